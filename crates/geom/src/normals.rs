//! Unit surface normals near given points, for checks that compare a cutting plane with
//! the surface it cuts (the flat-blade restriction of "Hot Blade Cuttings" §4).
//!
//! Entry point: [`SurfaceNormals::new`](crate::normals::SurfaceNormals::new), then
//! [`SurfaceNormals::normal_near`](crate::normals::SurfaceNormals::normal_near).
//!
//! Height fields give the exact normal of the graph above the point's `(x, y)`; meshes the
//! normal of the closest triangle; B-spline surfaces the normal of the closest triangle of
//! a fine parameter-grid triangulation. Normals are oriented with a non-negative `z`
//! (a facade's outward side, by convention) and `+x` for vertical ones.

use nalgebra::Vector3;

use crate::error::Result;
use crate::heightfield::HeightField;
use crate::index::TriangleIndex;
use crate::mesh::TriMesh;
use crate::surface::Surface;

/// Normal look-up for one surface.
pub struct SurfaceNormals<'s> {
    kind: Kind<'s>,
}

enum Kind<'s> {
    Graph(&'s HeightField),
    Mesh(&'s TriMesh, TriangleIndex<'s>),
    Owned(Box<TriMesh>),
}

impl<'s> SurfaceNormals<'s> {
    /// Prepares the look-up (builds a triangle index for meshes; a `grid × grid`
    /// triangulation for B-spline surfaces).
    ///
    /// # Errors
    /// Mesh errors when a B-spline surface cannot be triangulated.
    pub fn new(surface: &'s Surface, grid: usize) -> Result<Self> {
        let kind = match surface {
            Surface::HeightField(h) => Kind::Graph(h),
            Surface::Mesh(m) => Kind::Mesh(m, TriangleIndex::new(m)),
            Surface::Spline(s) => Kind::Owned(Box::new(
                crate::surface::spline_grid_mesh(s, grid.max(8))?.0,
            )),
        };
        Ok(Self { kind })
    }

    /// The unit normal of the surface at (or, for meshes, closest to) `p`.
    pub fn normal_near(&self, p: &Vector3<f64>) -> Vector3<f64> {
        let n = match &self.kind {
            Kind::Graph(h) => {
                let fx = h.expr().eval_along((p.x, p.y), (1.0, 0.0), 0.0).d1;
                let fy = h.expr().eval_along((p.x, p.y), (0.0, 1.0), 0.0).d1;
                Vector3::new(-fx, -fy, 1.0)
            }
            Kind::Mesh(m, index) => face_normal(m, index, p),
            Kind::Owned(m) => face_normal(m, &TriangleIndex::new(m), p),
        };
        orient(n)
    }

    /// Normals at many points (faster for B-spline surfaces: one index for all).
    pub fn normals_near(&self, points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
        match &self.kind {
            Kind::Owned(m) => {
                let index = TriangleIndex::new(m);
                points
                    .iter()
                    .map(|p| orient(face_normal(m, &index, p)))
                    .collect()
            }
            _ => points.iter().map(|p| self.normal_near(p)).collect(),
        }
    }
}

fn face_normal(m: &TriMesh, index: &TriangleIndex<'_>, p: &Vector3<f64>) -> Vector3<f64> {
    match index.closest_point(p) {
        Some(c) => {
            let [a, b, cc] = m.triangle(c.face);
            (b - a).cross(&(cc - a))
        }
        None => Vector3::z(),
    }
}

fn orient(n: Vector3<f64>) -> Vector3<f64> {
    let len = n.norm();
    if !(len > 0.0) || !len.is_finite() {
        return Vector3::z();
    }
    let n = n / len;
    if n.z < 0.0 || (n.z == 0.0 && n.x < 0.0) {
        -n
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Expr;

    #[test]
    fn graph_and_mesh_normals_agree_on_a_plane() {
        let h = HeightField::try_new(
            Expr::parse("0.5*x + 0.25*y").unwrap(),
            (0.0, 10.0),
            (0.0, 10.0),
        )
        .unwrap();
        let exact = Vector3::new(-0.5, -0.25, 1.0).normalize();
        let m = h.to_mesh(4, 4).unwrap();
        let sh = Surface::HeightField(h);
        let sm = Surface::Mesh(m);
        let p = Vector3::new(3.0, 4.0, 2.5);
        let n1 = SurfaceNormals::new(&sh, 0).unwrap().normal_near(&p);
        let n2 = SurfaceNormals::new(&sm, 0).unwrap().normal_near(&p);
        assert!((n1 - exact).norm() < 1e-12);
        assert!((n2 - exact).norm() < 1e-12);
    }
}
