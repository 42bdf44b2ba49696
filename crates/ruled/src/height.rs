//! The design surface as a height function `z = f(x, y)` (its upper envelope), which is
//! all a pre-cut needs: the thesis orients the surface so its outward normal is roughly
//! +z, and a wire never reaches below the highest sheet anyway.
//!
//! Height fields are evaluated exactly; meshes (and B-spline surfaces, tessellated on a
//! fine parameter grid) by the highest triangle over the point, found through a uniform
//! grid of triangle footprints (written here: a 2D column query is all that is needed and
//! the R*-tree in `geom::index` answers 3D boxes).

use geom::heightfield::HeightField;
use geom::mesh::TriMesh;
use geom::surface::Surface;
use nalgebra::{Vector2, Vector3};

use crate::error::{PreCutError, Result};
use crate::unit::{round, UnitFrame};

/// Parameter samples per side when a B-spline surface is tessellated.
pub const SPLINE_GRID: usize = 256;

/// `z = f(x, y)`, the highest point of the design surface over `(x, y)`.
#[derive(Debug, Clone)]
pub enum Height {
    /// Exact height field.
    Field(HeightField),
    /// A triangle mesh with a column index.
    Mesh(MeshHeight),
    /// An exact height field seen in a block's unit frame: evaluated at the model point,
    /// the height mapped to the frame and rounded ([`crate::unit::height`]).
    FieldInFrame {
        /// The height field (model units).
        field: HeightField,
        /// The frame.
        frame: UnitFrame,
        /// The field's `x` and `y` ranges in the frame, rounded: a point's coverage is
        /// decided on the frame's numbers, the same in any unit.
        range: [(f64, f64); 2],
    },
}

impl Height {
    /// The height function of a surface.
    ///
    /// # Errors
    /// [`PreCutError::Geom`] when a spline cannot be tessellated;
    /// [`PreCutError::Placement`] for a mesh without a triangle of positive footprint.
    pub fn new(surface: &Surface) -> Result<Self> {
        match surface {
            Surface::HeightField(h) => Ok(Self::Field(h.clone())),
            Surface::Mesh(m) => Ok(Self::Mesh(MeshHeight::new(m)?)),
            Surface::Spline(s) => Ok(Self::Mesh(MeshHeight::new(&s.to_mesh(SPLINE_GRID)?)?)),
        }
    }

    /// `f(x, y)`, or `None` where the surface is not over `(x, y)`.
    pub fn at(&self, x: f64, y: f64) -> Option<f64> {
        match self {
            Self::Field(h) => {
                let ((x0, x1), (y0, y1)) = (h.x_range(), h.y_range());
                (x >= x0 && x <= x1 && y >= y0 && y <= y1).then(|| h.expr().eval(x, y))
            }
            Self::Mesh(m) => m.at(x, y),
            Self::FieldInFrame {
                field,
                frame,
                range: [(x0, x1), (y0, y1)],
            } => {
                if !(x >= *x0 && x <= *x1 && y >= *y0 && y <= *y1) {
                    return None;
                }
                let p = frame.to_model(Vector3::new(x, y, 0.0));
                let ((a0, a1), (b0, b1)) = (field.x_range(), field.y_range());
                let z = field.expr().eval(p.x.clamp(a0, a1), p.y.clamp(b0, b1));
                Some(round((z - frame.origin.z) / frame.scale))
            }
        }
    }
}

/// Highest-triangle queries over a mesh's `xy` footprint.
#[derive(Debug, Clone)]
pub struct MeshHeight {
    triangles: Vec<[Vector3<f64>; 3]>,
    lo: Vector2<f64>,
    cell: Vector2<f64>,
    n: [usize; 2],
    /// Triangle ids per cell, row-major.
    cells: Vec<Vec<u32>>,
}

impl MeshHeight {
    /// Indexes the triangles with a positive `xy` footprint (vertical ones never are the
    /// highest point strictly inside a column).
    ///
    /// # Errors
    /// [`PreCutError::Placement`] when no triangle has a footprint.
    pub fn new(mesh: &TriMesh) -> Result<Self> {
        let triangles: Vec<[Vector3<f64>; 3]> = (0..mesh.faces().len())
            .map(|f| mesh.triangle(f))
            .filter(|t| signed_area(t).abs() > 0.0)
            .collect();
        if triangles.is_empty() {
            return Err(PreCutError::Placement(
                "the mesh has no triangle that is not vertical".into(),
            ));
        }
        let aabb = mesh.aabb();
        let lo = aabb.min.xy();
        let size = (aabb.max.xy() - lo).map(|s| s.max(1e-12));
        let side = ((triangles.len() as f64).sqrt().ceil() as usize).clamp(1, 512);
        let n = [side, side];
        let cell = Vector2::new(size.x / side as f64, size.y / side as f64);
        let mut cells = vec![Vec::new(); side * side];
        for (id, t) in triangles.iter().enumerate() {
            let (a, b) = footprint(t);
            let (i0, j0) = (
                index(a.x, lo.x, cell.x, side),
                index(a.y, lo.y, cell.y, side),
            );
            let (i1, j1) = (
                index(b.x, lo.x, cell.x, side),
                index(b.y, lo.y, cell.y, side),
            );
            for i in i0..=i1 {
                for j in j0..=j1 {
                    cells[i * side + j].push(id as u32);
                }
            }
        }
        Ok(Self {
            triangles,
            lo,
            cell,
            n,
            cells,
        })
    }

    /// The highest triangle point over `(x, y)` (points on an edge count for both sides).
    pub fn at(&self, x: f64, y: f64) -> Option<f64> {
        let i = ((x - self.lo.x) / self.cell.x).floor();
        let j = ((y - self.lo.y) / self.cell.y).floor();
        // Points exactly on the far border belong to the last cell.
        let clamp = |v: f64, n: usize| -> Option<usize> {
            if v < -1e-9 || v > n as f64 + 1e-9 {
                None
            } else {
                Some((v.max(0.0) as usize).min(n - 1))
            }
        };
        let (i, j) = (clamp(i, self.n[0])?, clamp(j, self.n[1])?);
        let p = Vector2::new(x, y);
        let mut best: Option<f64> = None;
        for &id in &self.cells[i * self.n[1] + j] {
            if let Some(z) = height_in(&self.triangles[id as usize], &p) {
                best = Some(best.map_or(z, |b: f64| b.max(z)));
            }
        }
        best
    }
}

fn index(v: f64, lo: f64, cell: f64, n: usize) -> usize {
    (((v - lo) / cell).floor().max(0.0) as usize).min(n - 1)
}

fn footprint(t: &[Vector3<f64>; 3]) -> (Vector2<f64>, Vector2<f64>) {
    let a = t[0].xy().inf(&t[1].xy()).inf(&t[2].xy());
    let b = t[0].xy().sup(&t[1].xy()).sup(&t[2].xy());
    (a, b)
}

fn signed_area(t: &[Vector3<f64>; 3]) -> f64 {
    let (a, b, c) = (t[0].xy(), t[1].xy(), t[2].xy());
    (b - a).perp(&(c - a)) / 2.0
}

/// Height of the triangle's plane at `p` when `p` is in its footprint (with a relative
/// tolerance on the barycentric coordinates so shared edges are never missed).
fn height_in(t: &[Vector3<f64>; 3], p: &Vector2<f64>) -> Option<f64> {
    let (a, b, c) = (t[0].xy(), t[1].xy(), t[2].xy());
    let d = (b - a).perp(&(c - a));
    let l1 = (p - a).perp(&(c - a)) / d;
    let l2 = (b - a).perp(&(p - a)) / d;
    let l0 = 1.0 - l1 - l2;
    let eps = 1e-12;
    (l0 >= -eps && l1 >= -eps && l2 >= -eps).then(|| l0 * t[0].z + l1 * t[1].z + l2 * t[2].z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_height_of_two_triangles_is_exact() {
        // The plane z = 1 + x + 2y over the unit square, as two triangles.
        let z = |x: f64, y: f64| 1.0 + x + 2.0 * y;
        let v = vec![
            Vector3::new(0.0, 0.0, z(0.0, 0.0)),
            Vector3::new(1.0, 0.0, z(1.0, 0.0)),
            Vector3::new(1.0, 1.0, z(1.0, 1.0)),
            Vector3::new(0.0, 1.0, z(0.0, 1.0)),
        ];
        let mesh = TriMesh::try_new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        let h = MeshHeight::new(&mesh).unwrap();
        for (x, y) in [(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (1.0, 1.0), (0.99, 0.01)] {
            let got = h.at(x, y).unwrap();
            assert!((got - z(x, y)).abs() < 1e-12, "({x}, {y}): {got}");
        }
        assert!(h.at(1.5, 0.5).is_none());
        assert!(h.at(-0.1, 0.5).is_none());
    }
}
