//! Triangle meshes: loading from OBJ (via `tobj`), validation, topology, area and volume.
//!
//! Entry points: [`TriMesh::load_obj`](crate::mesh::TriMesh::load_obj), [`TriMesh::try_new`](crate::mesh::TriMesh::try_new), [`TriMesh::topology`](crate::mesh::TriMesh::topology),
//! [`TriMesh::validate`](crate::mesh::TriMesh::validate), [`TriMesh::area`](crate::mesh::TriMesh::area), [`TriMesh::volume`](crate::mesh::TriMesh::volume).

use std::collections::HashMap;

use nalgebra::Vector3;

use crate::bbox::Aabb;
use crate::error::{GeomError, Result};

/// Outward-facing triangles of a box whose corners are numbered by bits (bit 0: +x,
/// bit 1: +y, bit 2: +z side), for boxes in a right-handed frame.
pub const BOX_FACES: [[u32; 3]; 12] = [
    [0, 2, 1],
    [1, 2, 3],
    [4, 5, 6],
    [5, 7, 6],
    [0, 1, 4],
    [1, 5, 4],
    [2, 6, 3],
    [3, 6, 7],
    [0, 4, 2],
    [2, 4, 6],
    [1, 3, 5],
    [3, 7, 5],
];

/// An indexed triangle mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    vertices: Vec<Vector3<f64>>,
    faces: Vec<[u32; 3]>,
}

/// Edge and component counts of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Topology {
    /// Distinct undirected edges.
    pub edges: usize,
    /// Edges used by exactly one face.
    pub boundary_edges: usize,
    /// Closed loops formed by the boundary edges.
    pub boundary_loops: usize,
    /// Edges used by three or more faces.
    pub nonmanifold_edges: usize,
    /// Faces with zero area (repeated or collinear vertices).
    pub degenerate_faces: usize,
    /// Connected components (through shared edges).
    pub components: usize,
}

/// A problem found by [`TriMesh::validate`] that does not stop the work.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshWarning {
    /// Zero-area faces; they are ignored by sectioning.
    DegenerateFaces(usize),
    /// The mesh has boundary edges (normal for a facade sheet; holes add loops).
    Open {
        /// Boundary edges.
        boundary_edges: usize,
        /// Boundary loops.
        boundary_loops: usize,
    },
    /// More than one connected piece.
    Components(usize),
}

impl std::fmt::Display for MeshWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::DegenerateFaces(n) => write!(f, "{n} degenerate (zero-area) face(s) ignored"),
            Self::Open {
                boundary_edges,
                boundary_loops,
            } => write!(
                f,
                "mesh is open: {boundary_edges} boundary edge(s) in {boundary_loops} loop(s)"
            ),
            Self::Components(n) => write!(f, "mesh has {n} connected components"),
        }
    }
}

impl TriMesh {
    /// A closed box from its eight corners (bit `k` of the index: the + side of axis `k`),
    /// with the faces of [`BOX_FACES`].
    ///
    /// # Errors
    /// A non-finite corner.
    ///
    /// ```
    /// use geom::bbox::Aabb;
    /// use geom::TriMesh;
    /// use nalgebra::Vector3;
    /// let b = Aabb { min: Vector3::new(0.0, 0.0, 0.0), max: Vector3::new(2.0, 3.0, 4.0) };
    /// let mesh = TriMesh::cuboid(b.corners())?;
    /// assert_eq!(mesh.faces().len(), 12);
    /// assert!((mesh.volume() - 24.0).abs() < 1e-12);
    /// assert!((mesh.area() - 52.0).abs() < 1e-12);
    /// assert!(mesh.validate(true)?.is_empty()); // closed, consistently oriented
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn cuboid(corners: [Vector3<f64>; 8]) -> Result<Self> {
        Self::try_new(corners.to_vec(), BOX_FACES.to_vec())
    }

    /// A mesh from vertices and triangles.
    ///
    /// # Errors
    /// [`GeomError::EmptyMesh`] without faces, [`GeomError::NonFinite`] for NaN coordinates,
    /// [`GeomError::BadIndex`] for out-of-range indices.
    ///
    /// ```
    /// use geom::TriMesh;
    /// use nalgebra::Vector3;
    /// // the corner tetrahedron of the unit cube, faces oriented outwards
    /// let v = vec![Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z()];
    /// let tet = TriMesh::try_new(v.clone(), vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// assert!((tet.volume() - 1.0 / 6.0).abs() < 1e-15);
    /// assert_eq!(tet.topology().boundary_edges, 0);
    /// // a face naming a vertex that does not exist is refused
    /// assert!(TriMesh::try_new(v, vec![[0, 1, 4]]).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn try_new(vertices: Vec<Vector3<f64>>, faces: Vec<[u32; 3]>) -> Result<Self> {
        if vertices.is_empty() || faces.is_empty() {
            return Err(GeomError::EmptyMesh(format!(
                "{} vertices, {} faces",
                vertices.len(),
                faces.len()
            )));
        }
        if let Some(i) = vertices
            .iter()
            .position(|v| v.iter().any(|c| !c.is_finite()))
        {
            return Err(GeomError::NonFinite {
                what: format!("vertex {} (1-based)", i + 1),
            });
        }
        for (fi, f) in faces.iter().enumerate() {
            for &v in f {
                if v as usize >= vertices.len() {
                    return Err(GeomError::BadIndex {
                        face: fi,
                        vertex: v as usize,
                        count: vertices.len(),
                    });
                }
            }
        }
        Ok(Self { vertices, faces })
    }

    /// Loads the triangles of every object in an OBJ file (polygons are fan-triangulated),
    /// coordinates read in `f64`.
    ///
    /// # Errors
    /// [`GeomError::MeshRead`] when the file is missing or malformed, and the errors of
    /// [`Self::try_new`].
    #[cfg(feature = "obj")]
    pub fn load_obj(path: &std::path::Path) -> Result<Self> {
        let opts = tobj::LoadOptions {
            triangulate: true,
            single_index: false,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _) = tobj::load_obj(path, &opts).map_err(|e| GeomError::MeshRead {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        for m in models {
            let base = vertices.len() as u32;
            let mesh = m.mesh;
            for p in mesh.positions.chunks_exact(3) {
                vertices.push(Vector3::new(p[0], p[1], p[2]));
            }
            for f in mesh.indices.chunks_exact(3) {
                if f[0] == f[1] || f[1] == f[2] || f[0] == f[2] {
                    return Err(GeomError::MeshRead {
                        path: path.to_path_buf(),
                        message: format!(
                            "face {} names one vertex twice ({} {} {}, 1-based): not a triangle",
                            faces.len() + 1,
                            base + f[0] + 1,
                            base + f[1] + 1,
                            base + f[2] + 1
                        ),
                    });
                }
                faces.push([base + f[0], base + f[1], base + f[2]]);
            }
        }
        Self::try_new(vertices, faces).map_err(|e| match e {
            GeomError::EmptyMesh(m) => GeomError::EmptyMesh(format!("{}: {m}", path.display())),
            other => other,
        })
    }

    /// Vertex positions.
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// Triangles as vertex indices.
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// The corners of face `f`.
    pub fn triangle(&self, f: usize) -> [Vector3<f64>; 3] {
        let [a, b, c] = self.faces[f];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// The step the vertex coordinates were written with: `10⁻ᵏ` for the least `k ≤ 12`
    /// such that every coordinate is a whole multiple of it (an OBJ file written with `k`
    /// decimals), or 0 when there is none (coordinates computed in binary floating point,
    /// precise to f64 rounding). Half of it is how far any vertex may lie from where its
    /// model put it: the file's precision.
    pub fn quantum(&self) -> f64 {
        'k: for k in 0..=12 {
            let scale = 10f64.powi(k);
            for p in &self.vertices {
                for &c in p.iter() {
                    let x = c * scale;
                    // x carries f64 rounding of |x|·2⁻⁵² from the decimal reading and the
                    // product; a whole multiple is within 10⁻³ of an integer
                    if (x - x.round()).abs() > 1e-3 + 4.0 * f64::EPSILON * x.abs() {
                        continue 'k;
                    }
                }
            }
            return 1.0 / scale;
        }
        0.0
    }

    /// Unit normal at every vertex: the area-weighted mean of its faces' normals (zero for
    /// a vertex of no face or of degenerate faces only).
    pub fn vertex_normals(&self) -> Vec<Vector3<f64>> {
        let mut n = vec![Vector3::zeros(); self.vertices.len()];
        for f in 0..self.faces.len() {
            let [a, b, c] = self.triangle(f);
            // the cross product's length is twice the area: area weighting for free
            let w = (b - a).cross(&(c - a));
            for &v in &self.faces[f] {
                n[v as usize] += w;
            }
        }
        for v in &mut n {
            let len = v.norm();
            if len > 0.0 && len.is_finite() {
                *v /= len;
            }
        }
        n
    }

    /// Bounding box of the vertices.
    pub fn aabb(&self) -> Aabb {
        Aabb::from_points(&self.vertices).unwrap_or(Aabb {
            min: Vector3::zeros(),
            max: Vector3::zeros(),
        })
    }

    /// Whether face `f` has zero area.
    pub fn is_degenerate(&self, f: usize) -> bool {
        let [a, b, c] = self.triangle(f);
        (b - a).cross(&(c - a)).norm_squared() == 0.0
    }

    /// Edge, boundary and component counts.
    pub fn topology(&self) -> Topology {
        let mut edge_faces: HashMap<(u32, u32), u32> = HashMap::new();
        let mut degenerate = 0;
        for (fi, f) in self.faces.iter().enumerate() {
            if self.is_degenerate(fi) {
                degenerate += 1;
            }
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                if a == b {
                    continue;
                }
                *edge_faces.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        let boundary: Vec<(u32, u32)> = edge_faces
            .iter()
            .filter(|(_, &c)| c == 1)
            .map(|(&e, _)| e)
            .collect();
        let nonmanifold = edge_faces.values().filter(|&&c| c > 2).count();
        // boundary loops: components of the boundary-edge graph
        let mut uf = UnionFind::new(self.vertices.len());
        for &(a, b) in &boundary {
            uf.union(a as usize, b as usize);
        }
        let mut roots: Vec<usize> = boundary.iter().map(|&(a, _)| uf.find(a as usize)).collect();
        roots.sort_unstable();
        roots.dedup();
        // face components through shared vertices of shared edges
        let mut uf2 = UnionFind::new(self.vertices.len());
        for f in &self.faces {
            uf2.union(f[0] as usize, f[1] as usize);
            uf2.union(f[1] as usize, f[2] as usize);
        }
        let mut comps: Vec<usize> = self.faces.iter().map(|f| uf2.find(f[0] as usize)).collect();
        comps.sort_unstable();
        comps.dedup();
        Topology {
            edges: edge_faces.len(),
            boundary_edges: boundary.len(),
            boundary_loops: roots.len(),
            nonmanifold_edges: nonmanifold,
            degenerate_faces: degenerate,
            components: comps.len(),
        }
    }

    /// Checks the mesh: non-manifold edges are an error, as are boundary edges when
    /// `require_closed`; degenerate faces, openness and several components are warnings.
    ///
    /// # Errors
    /// [`GeomError::NonManifold`], [`GeomError::OpenMesh`].
    pub fn validate(&self, require_closed: bool) -> Result<Vec<MeshWarning>> {
        let t = self.topology();
        if t.nonmanifold_edges > 0 {
            return Err(GeomError::NonManifold(t.nonmanifold_edges));
        }
        if require_closed && t.boundary_edges > 0 {
            return Err(GeomError::OpenMesh {
                boundary_edges: t.boundary_edges,
                boundary_loops: t.boundary_loops,
            });
        }
        let mut w = Vec::new();
        if t.degenerate_faces > 0 {
            w.push(MeshWarning::DegenerateFaces(t.degenerate_faces));
        }
        if t.boundary_edges > 0 {
            w.push(MeshWarning::Open {
                boundary_edges: t.boundary_edges,
                boundary_loops: t.boundary_loops,
            });
        }
        if t.components > 1 {
            w.push(MeshWarning::Components(t.components));
        }
        Ok(w)
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        (0..self.faces.len())
            .map(|f| {
                let [a, b, c] = self.triangle(f);
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .sum()
    }

    /// Signed enclosed volume by the divergence theorem (positive for a closed, outward
    /// oriented mesh; meaningless for an open one).
    pub fn volume(&self) -> f64 {
        (0..self.faces.len())
            .map(|f| {
                let [a, b, c] = self.triangle(f);
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum()
    }
}

struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
        }
    }
    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }
    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn cube() -> TriMesh {
        let v: Vec<Vector3<f64>> = (0..8)
            .map(|i| Vector3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let f = vec![
            [0, 2, 1],
            [1, 2, 3],
            [4, 5, 6],
            [5, 7, 6],
            [0, 1, 4],
            [1, 5, 4],
            [2, 6, 3],
            [3, 6, 7],
            [0, 4, 2],
            [2, 4, 6],
            [1, 3, 5],
            [3, 7, 5],
        ];
        TriMesh::try_new(v, f).unwrap()
    }

    #[test]
    fn cube_measures() {
        let c = cube();
        assert!((c.volume() - 1.0).abs() < 1e-12);
        assert!((c.area() - 6.0).abs() < 1e-12);
        let t = c.topology();
        assert_eq!(
            (t.edges, t.boundary_edges, t.nonmanifold_edges, t.components),
            (18, 0, 0, 1)
        );
        assert!(c.validate(true).unwrap().is_empty());
    }

    #[test]
    fn open_mesh_is_reported() {
        let c = cube();
        let open = TriMesh::try_new(c.vertices().to_vec(), c.faces()[2..].to_vec()).unwrap();
        assert!(matches!(
            open.validate(true),
            Err(GeomError::OpenMesh {
                boundary_loops: 1,
                ..
            })
        ));
        let w = open.validate(false).unwrap();
        assert!(matches!(
            w[0],
            MeshWarning::Open {
                boundary_edges: 4,
                boundary_loops: 1
            }
        ));
    }

    #[test]
    fn bad_meshes_are_errors() {
        assert!(matches!(
            TriMesh::try_new(vec![], vec![]),
            Err(GeomError::EmptyMesh(_))
        ));
        let v = vec![
            Vector3::new(0.0, 0.0, f64::NAN),
            Vector3::zeros(),
            Vector3::x(),
        ];
        assert!(matches!(
            TriMesh::try_new(v, vec![[0, 1, 2]]),
            Err(GeomError::NonFinite { .. })
        ));
        let v = vec![Vector3::zeros(), Vector3::x(), Vector3::y()];
        assert!(matches!(
            TriMesh::try_new(v, vec![[0, 1, 3]]),
            Err(GeomError::BadIndex { .. })
        ));
    }

    #[cfg(feature = "obj")]
    #[test]
    fn a_missing_obj_file_is_an_error() {
        assert!(matches!(
            TriMesh::load_obj(std::path::Path::new("/nonexistent/x.obj")),
            Err(GeomError::MeshRead { .. })
        ));
    }

    #[test]
    fn nonmanifold_is_an_error() {
        let v = vec![
            Vector3::zeros(),
            Vector3::x(),
            Vector3::y(),
            Vector3::z(),
            -Vector3::y(),
        ];
        let m = TriMesh::try_new(v, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap();
        assert!(matches!(m.validate(false), Err(GeomError::NonManifold(1))));
    }
}
