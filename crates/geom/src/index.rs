//! A spatial index over a mesh's triangles (an R*-tree from `rstar`) for point and box
//! queries.
//!
//! Entry points: [`TriangleIndex::new`](crate::index::TriangleIndex::new), [`TriangleIndex::closest_point`](crate::index::TriangleIndex::closest_point),
//! [`TriangleIndex::triangles_in`](crate::index::TriangleIndex::triangles_in).

use nalgebra::Vector3;
use rstar::{primitives::GeomWithData, primitives::Rectangle, RTree, AABB};

use crate::bbox::Aabb;
use crate::mesh::TriMesh;

type Entry = GeomWithData<Rectangle<[f64; 3]>, usize>;

/// R*-tree of triangle bounding boxes.
pub struct TriangleIndex<'m> {
    mesh: &'m TriMesh,
    tree: RTree<Entry>,
}

/// Result of [`TriangleIndex::closest_point`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoint {
    /// Face index.
    pub face: usize,
    /// Closest point on that face.
    pub point: Vector3<f64>,
    /// Distance from the query point.
    pub distance: f64,
}

/// Closest point to `p` on triangle `abc` (Ericson, *Real-Time Collision Detection* §5.1.5).
pub fn closest_point_on_triangle(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> Vector3<f64> {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

impl<'m> TriangleIndex<'m> {
    /// Builds the index (bulk loading).
    pub fn new(mesh: &'m TriMesh) -> Self {
        let entries = (0..mesh.faces().len())
            .map(|f| {
                let [a, b, c] = mesh.triangle(f);
                let lo = a.inf(&b).inf(&c);
                let hi = a.sup(&b).sup(&c);
                GeomWithData::new(
                    Rectangle::from_corners([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]),
                    f,
                )
            })
            .collect();
        Self {
            mesh,
            tree: RTree::bulk_load(entries),
        }
    }

    /// Faces whose bounding boxes meet `b`, in increasing face order.
    pub fn triangles_in(&self, b: &Aabb) -> Vec<usize> {
        let env = AABB::from_corners([b.min.x, b.min.y, b.min.z], [b.max.x, b.max.y, b.max.z]);
        let mut v: Vec<usize> = self
            .tree
            .locate_in_envelope_intersecting(env)
            .map(|e| e.data)
            .collect();
        v.sort_unstable();
        v
    }

    /// The closest point of the mesh to `p` (ties broken by the lower face index).
    pub fn closest_point(&self, p: &Vector3<f64>) -> Option<ClosestPoint> {
        let mut best: Option<ClosestPoint> = None;
        // boxes come in order of increasing box distance; stop once a box is farther than the best hit
        for (e, d2) in self
            .tree
            .nearest_neighbor_iter_with_distance_2([p.x, p.y, p.z])
        {
            if let Some(b) = best {
                if d2 > b.distance * b.distance {
                    break;
                }
            }
            let [a, bb, c] = self.mesh.triangle(e.data);
            let q = closest_point_on_triangle(p, &a, &bb, &c);
            let d = (q - p).norm();
            let better = match best {
                None => true,
                Some(b) => d < b.distance || (d == b.distance && e.data < b.face),
            };
            if better {
                best = Some(ClosestPoint {
                    face: e.data,
                    point: q,
                    distance: d,
                });
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_matches_brute_force() {
        // a bumpy grid
        let n = 12;
        let mut v = Vec::new();
        for i in 0..n {
            for j in 0..n {
                v.push(Vector3::new(
                    i as f64,
                    j as f64,
                    ((i * 7 + j * 3) % 5) as f64 * 0.2,
                ));
            }
        }
        let mut f = Vec::new();
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                let a = (i * n + j) as u32;
                f.push([a, a + n as u32, a + 1]);
                f.push([a + 1, a + n as u32, a + n as u32 + 1]);
            }
        }
        let m = TriMesh::try_new(v, f).unwrap();
        let idx = TriangleIndex::new(&m);
        for k in 0..50 {
            let p = Vector3::new(
                (k * 37 % 130) as f64 / 10.0 - 0.5,
                (k * 53 % 120) as f64 / 10.0,
                (k % 7) as f64 - 2.0,
            );
            let got = idx.closest_point(&p).unwrap();
            let brute = (0..m.faces().len())
                .map(|fi| {
                    let [a, b, c] = m.triangle(fi);
                    (closest_point_on_triangle(&p, &a, &b, &c) - p).norm()
                })
                .fold(f64::INFINITY, f64::min);
            assert!((got.distance - brute).abs() < 1e-12);
        }
        let hits = idx.triangles_in(&Aabb {
            min: Vector3::new(0.1, 0.1, -1.0),
            max: Vector3::new(0.9, 0.9, 1.0),
        });
        assert_eq!(hits, vec![0, 1]);
    }
}
