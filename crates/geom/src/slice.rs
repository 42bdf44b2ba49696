//! Sectioning by a family of parallel planes: the plane frame, slab-centre offsets, and
//! slicing a triangle mesh into ordered polylines.
//!
//! Entry points: [`PlaneFrame::from_direction`](crate::slice::PlaneFrame::from_direction), [`slab_centres`](crate::slice::slab_centres), [`slice_mesh`](crate::slice::slice_mesh).
//!
//! Plane coordinates: a section plane has normal `d` (the cutting direction); its in-plane
//! axes are `u = normalize(ẑ × d)` (horizontal) and `v = d × u` (up when `d` is horizontal),
//! so the default direction `+x` gives sections as curves in `(y, z)`.

use std::collections::HashMap;

use nalgebra::{Vector2, Vector3};

use crate::error::{GeomError, Result};
use crate::mesh::TriMesh;

/// An orthonormal frame `(u, v, d)` for planes normal to the cutting direction `d`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneFrame {
    /// Unit plane normal, the cutting direction.
    pub normal: Vector3<f64>,
    /// First in-plane axis (horizontal).
    pub u: Vector3<f64>,
    /// Second in-plane axis.
    pub v: Vector3<f64>,
}

impl PlaneFrame {
    /// The frame for cutting direction `d` (any length). For a vertical `d`, `u = x̂`.
    ///
    /// # Errors
    /// [`GeomError::ZeroDirection`] for a zero or non-finite vector.
    pub fn from_direction(d: Vector3<f64>) -> Result<Self> {
        let len = d.norm();
        if !(len > 0.0) || !len.is_finite() {
            return Err(GeomError::ZeroDirection);
        }
        let n = d / len;
        let h = Vector3::z().cross(&n);
        let u = if h.norm() > 1e-12 {
            h.normalize()
        } else {
            Vector3::x()
        };
        let v = n.cross(&u);
        Ok(Self { normal: n, u, v })
    }

    /// The plane that holds `points` best (least squares: its normal is the direction of
    /// least spread about their centroid), as a frame, the plane's offset along its
    /// normal, and the largest distance of a point from it. The normal is the one with
    /// its largest component positive, so the frame depends on the points only, not on
    /// their order; a vertical plane gets a horizontal `u` and an upward `v`.
    ///
    /// ```
    /// use geom::slice::PlaneFrame;
    /// use nalgebra::Vector3;
    /// // points of the plane y = 5, the x–z plane moved
    /// let pts: Vec<Vector3<f64>> = (0..10)
    ///     .map(|i| Vector3::new(i as f64, 5.0, (i as f64 * 0.7).sin()))
    ///     .collect();
    /// let (frame, offset, off) = PlaneFrame::fit_points(&pts)?;
    /// assert!((frame.normal - Vector3::y()).norm() < 1e-12);
    /// assert!((offset - 5.0).abs() < 1e-12 && off < 1e-12);
    /// let q = frame.to_plane(&pts[3]);
    /// assert!((frame.to_world(offset, &q) - pts[3]).norm() < 1e-12);
    /// # Ok::<(), geom::GeomError>(())
    /// ```
    ///
    /// # Errors
    /// [`GeomError::ZeroDirection`] for fewer than 2 distinct or non-finite points.
    pub fn fit_points(points: &[Vector3<f64>]) -> Result<(Self, f64, f64)> {
        if points.is_empty() || points.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(GeomError::ZeroDirection);
        }
        let c = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
        let mut cov = nalgebra::Matrix3::zeros();
        for p in points {
            let d = p - c;
            cov += d * d.transpose();
        }
        if !(cov.norm() > 0.0) || !cov.norm().is_finite() {
            return Err(GeomError::ZeroDirection);
        }
        let eig = nalgebra::SymmetricEigen::new(cov);
        let (i, _) =
            eig.eigenvalues
                .iter()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |best, (i, &l)| if l < best.1 { (i, l) } else { best },
                );
        let mut n: Vector3<f64> = eig.eigenvectors.column(i).into_owned();
        let largest = n
            .iter()
            .fold(0.0f64, |m, &x| if x.abs() > m.abs() { x } else { m });
        if largest < 0.0 {
            n = -n;
        }
        let frame = Self::from_direction(n)?;
        let offset = frame.normal.dot(&c);
        let off = points
            .iter()
            .map(|p| (frame.normal.dot(p) - offset).abs())
            .fold(0.0, f64::max);
        Ok((frame, offset, off))
    }

    /// Plane coordinates `(u·p, v·p)` of a world point.
    pub fn to_plane(&self, p: &Vector3<f64>) -> Vector2<f64> {
        Vector2::new(self.u.dot(p), self.v.dot(p))
    }

    /// The world point with plane coordinates `q` on the plane at `offset` along the normal.
    pub fn to_world(&self, offset: f64, q: &Vector2<f64>) -> Vector3<f64> {
        self.normal * offset + self.u * q.x + self.v * q.y
    }
}

/// Offsets of `n` planes at the centres of `n` equal slabs of `[lo, hi]`.
pub fn slab_centres(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| lo + (hi - lo) * (i as f64 + 0.5) / n as f64)
        .collect()
}

/// A point where the plane crosses the mesh edge `a → b`, at `lerp(a, b, s)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// First vertex (the smaller index).
    pub a: u32,
    /// Second vertex.
    pub b: u32,
    /// Position along the edge, in `[0, 1]`.
    pub s: f64,
}

/// Largest angle between the vertex normals of one mesh edge taken for the bending of a
/// smooth surface (≈ 17°); beyond it the edge crosses a crease.
pub const MAX_FACET_BEND: f64 = 0.3;

/// One connected piece of a mesh section: crossings in order along the piece.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Edge crossings in order.
    pub crossings: Vec<Crossing>,
    /// Whether the piece is a closed loop (first and last crossing are joined).
    pub closed: bool,
}

impl Chain {
    /// How far each crossing may lie from the smooth surface the mesh approximates: on an
    /// edge of length `L` whose vertex normals differ by the angle `θ`, the surface bends
    /// by about `θ/L`, so the edge (a chord) is off it by `s(1−s)·L·θ/2` at the crossing's
    /// share `s` — the facet error a smoothing fit should not follow (`normals`: one unit
    /// normal per vertex, [`TriMesh::vertex_normals`]). Edges whose normals differ by more
    /// than [`MAX_FACET_BEND`] cross a crease of the design, not a facet of a smooth
    /// surface: they count that much only; a vertex without a normal counts nothing.
    pub fn facet_deviation(&self, mesh: &TriMesh, normals: &[Vector3<f64>]) -> Vec<f64> {
        let v = mesh.vertices();
        self.crossings
            .iter()
            .map(|c| {
                let (a, b) = (c.a as usize, c.b as usize);
                let (na, nb) = (normals[a], normals[b]);
                if na.norm_squared() == 0.0 || nb.norm_squared() == 0.0 {
                    return 0.0;
                }
                let length = (v[b] - v[a]).norm();
                let bend = na.dot(&nb).clamp(-1.0, 1.0).acos().min(MAX_FACET_BEND);
                let d = c.s * (1.0 - c.s) * length * bend / 2.0;
                if d.is_finite() {
                    d
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// World positions of the crossings.
    pub fn points(&self, mesh: &TriMesh) -> Vec<Vector3<f64>> {
        let v = mesh.vertices();
        self.crossings
            .iter()
            .map(|c| v[c.a as usize] * (1.0 - c.s) + v[c.b as usize] * c.s)
            .collect()
    }
}

/// Slices `mesh` with the plane `normal · p = offset`. Vertices exactly on the plane count
/// as on its positive side, so every crossing lies on an edge with a strict sign change and
/// neighbouring triangles share crossings exactly. Degenerate faces are skipped. Chains come
/// in the order of their lowest face index.
///
/// ```
/// use geom::bbox::Aabb;
/// use geom::slice::slice_mesh;
/// use geom::TriMesh;
/// use nalgebra::Vector3;
/// let cube = TriMesh::cuboid(Aabb { min: Vector3::zeros(), max: Vector3::new(1.0, 1.0, 1.0) }.corners())?;
/// // halfway up, the cube's section is one closed loop of its side faces' edges
/// let chains = slice_mesh(&cube, &Vector3::z(), 0.5);
/// assert_eq!(chains.len(), 1);
/// assert!(chains[0].closed);
/// assert!(chains[0].points(&cube).iter().all(|p| (p.z - 0.5).abs() < 1e-15));
/// // above the cube: nothing
/// assert!(slice_mesh(&cube, &Vector3::z(), 2.0).is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn slice_mesh(mesh: &TriMesh, normal: &Vector3<f64>, offset: f64) -> Vec<Chain> {
    let verts = mesh.vertices();
    let dist: Vec<f64> = verts.iter().map(|p| normal.dot(p) - offset).collect();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    // segments as pairs of edge keys
    let mut segs: Vec<[(u32, u32); 2]> = Vec::new();
    for (fi, f) in mesh.faces().iter().enumerate() {
        let pos = f.map(|v| dist[v as usize] >= 0.0);
        if pos[0] == pos[1] && pos[1] == pos[2] {
            continue;
        }
        if mesh.is_degenerate(fi) {
            continue;
        }
        let mut ends = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            if pos[k] != pos[(k + 1) % 3] {
                ends.push(key(a, b));
            }
        }
        if ends.len() == 2 {
            segs.push([ends[0], ends[1]]);
        }
    }
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (i, s) in segs.iter().enumerate() {
        for e in s {
            by_edge.entry(*e).or_default().push(i);
        }
    }
    let crossing = |(a, b): (u32, u32)| {
        let (da, db) = (dist[a as usize], dist[b as usize]);
        let s = if da != db {
            (da / (da - db)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        Crossing { a, b, s }
    };
    let mut used = vec![false; segs.len()];
    let mut chains = Vec::new();
    // walk from open ends first (edges with a single segment), then loops
    let starts: Vec<(usize, (u32, u32))> = segs
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.iter().map(move |e| (i, *e)))
        .filter(|(_, e)| by_edge[e].len() == 1)
        .chain(segs.iter().enumerate().map(|(i, s)| (i, s[0])))
        .collect();
    for (start, start_edge) in starts {
        if used[start] {
            continue;
        }
        let open = by_edge[&start_edge].len() == 1;
        let mut edges = vec![start_edge];
        let mut seg = start;
        let mut at = start_edge;
        let mut closed = false;
        loop {
            used[seg] = true;
            let s = segs[seg];
            let next_edge = if s[0] == at { s[1] } else { s[0] };
            if next_edge == start_edge && !open {
                closed = true;
                break;
            }
            edges.push(next_edge);
            at = next_edge;
            match by_edge[&at].iter().find(|&&o| !used[o]) {
                Some(&o) => seg = o,
                None => break,
            }
        }
        chains.push(Chain {
            crossings: edges.into_iter().map(crossing).collect(),
            closed,
        });
    }
    chains
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_default_is_yz() {
        let f = PlaneFrame::from_direction(Vector3::new(2.0, 0.0, 0.0)).unwrap();
        assert_eq!(f.u, Vector3::y());
        assert_eq!(f.v, Vector3::z());
        let g = PlaneFrame::from_direction(Vector3::new(1.0, 2.0, 0.5)).unwrap();
        assert!((g.u.cross(&g.v) - g.normal).norm() < 1e-12);
        let p = Vector3::new(0.3, -2.0, 5.0);
        let q = g.to_plane(&p);
        assert!((g.to_world(g.normal.dot(&p), &q) - p).norm() < 1e-12);
        assert!(PlaneFrame::from_direction(Vector3::zeros()).is_err());
        let v = PlaneFrame::from_direction(Vector3::z()).unwrap();
        assert_eq!(v.u, Vector3::x());
    }

    #[test]
    fn slab_centres_are_centred() {
        assert_eq!(slab_centres(0.0, 10.0, 5), vec![1.0, 3.0, 5.0, 7.0, 9.0]);
    }

    #[test]
    fn cube_section_is_a_closed_square() {
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
        let m = TriMesh::try_new(v, f).unwrap();
        let chains = slice_mesh(&m, &Vector3::x(), 0.5);
        assert_eq!(chains.len(), 1);
        assert!(chains[0].closed);
        let pts = chains[0].points(&m);
        let mut perim = 0.0;
        for i in 0..pts.len() {
            perim += (pts[(i + 1) % pts.len()] - pts[i]).norm();
        }
        assert!((perim - 4.0).abs() < 1e-12);
    }
}
