//! 3D convex hull by the quickhull method.
//!
//! Entry point: [`convex_hull`](crate::hull::convex_hull). Written here because no well-kept pure-Rust crate offers a
//! 3D hull without pulling in a physics engine; the algorithm is short and the block
//! segmentation needs it on every block.
//!
//! Whether a point is outside a face is decided by Shewchuk's exact orientation predicate
//! (the `robust` crate), not by a rounded distance: on nearly coplanar or collinear points
//! (a box's corners, points on its edges, many duplicates) a rounded test lets a sliver
//! face with a noisy plane judge points inside that are outside, and the "hull" then
//! leaves points out by a good part of its size. Rounded distances only pick which outside
//! point is added next, and refuse input that is coplanar within `1e-10 ×` its extent.

use std::collections::HashMap;

use nalgebra::Vector3;

use crate::error::{GeomError, Result};
use crate::mesh::TriMesh;

struct Face {
    v: [usize; 3],
    n: Vector3<f64>,
    d: f64,
    outside: Vec<usize>,
    alive: bool,
}

impl Face {
    fn new(pts: &[Vector3<f64>], v: [usize; 3]) -> Self {
        let n = (pts[v[1]] - pts[v[0]]).cross(&(pts[v[2]] - pts[v[0]]));
        let n = n / n.norm().max(f64::MIN_POSITIVE);
        Self {
            v,
            n,
            d: n.dot(&pts[v[0]]),
            outside: Vec::new(),
            alive: true,
        }
    }
    fn dist(&self, p: &Vector3<f64>) -> f64 {
        self.n.dot(p) - self.d
    }
    /// Whether `p` lies strictly outside the face's plane (exactly: the sign of the
    /// orientation determinant of its corners and `p`).
    fn outside(&self, pts: &[Vector3<f64>], p: &Vector3<f64>) -> bool {
        let c = |q: &Vector3<f64>| robust::Coord3D {
            x: q.x,
            y: q.y,
            z: q.z,
        };
        let [a, b, d] = self.v.map(|i| c(&pts[i]));
        robust::orient3d(a, b, d, c(p)) < 0.0
    }
}

/// The convex hull of a point set as a closed, outward-oriented triangle mesh (only the
/// hull's vertices are kept). Every point lies inside or on every face's plane, exactly
/// (a face's plane through its three corners, as the orientation predicate sees it).
///
/// # Errors
/// [`GeomError::NonFinite`] for NaN points, [`GeomError::Unsupported`] for fewer than four
/// points or points that are all coplanar.
///
/// ```
/// use geom::hull::convex_hull;
/// use nalgebra::Vector3;
/// // the unit cube's corners and a point inside: the hull keeps the corners only
/// let mut pts: Vec<_> = (0..8)
///     .map(|i| Vector3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
///     .collect();
/// pts.push(Vector3::new(0.5, 0.5, 0.5));
/// let hull = convex_hull(&pts)?;
/// assert_eq!(hull.vertices().len(), 8);
/// assert!((hull.volume() - 1.0).abs() < 1e-12);
/// assert!((hull.area() - 6.0).abs() < 1e-12);
/// // coplanar points have no hull
/// assert!(convex_hull(&pts[..4]).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn convex_hull(points: &[Vector3<f64>]) -> Result<TriMesh> {
    if points.iter().any(|p| p.iter().any(|v| !v.is_finite())) {
        return Err(GeomError::NonFinite {
            what: "a hull point".into(),
        });
    }
    let degenerate =
        || GeomError::Unsupported("convex hull of fewer than four non-coplanar points".into());
    if points.len() < 4 {
        return Err(degenerate());
    }
    let extent = crate::bbox::Aabb::from_points(points)
        .map(|b| b.size().norm())
        .unwrap_or(0.0);
    let eps = 1e-10 * extent.max(f64::MIN_POSITIVE);

    let [i0, i1, i2, i3] = initial_tetrahedron(points, eps).ok_or_else(degenerate)?;
    let mut faces: Vec<Face> = Vec::new();
    // each face turned so that the opposite corner is inside it (exactly)
    for (tri, opposite) in [
        ([i0, i1, i2], i3),
        ([i0, i1, i3], i2),
        ([i0, i2, i3], i1),
        ([i1, i2, i3], i0),
    ] {
        let mut f = Face::new(points, tri);
        if f.outside(points, &points[opposite]) {
            f = Face::new(points, [tri[0], tri[2], tri[1]]);
        }
        faces.push(f);
    }
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for k in 0..3 {
            edges.insert((f.v[k], f.v[(k + 1) % 3]), fi);
        }
    }
    for (pi, p) in points.iter().enumerate() {
        if [i0, i1, i2, i3].contains(&pi) {
            continue;
        }
        if let Some(f) = faces.iter_mut().find(|f| f.outside(points, p)) {
            f.outside.push(pi);
        }
    }

    let mut stack: Vec<usize> = (0..faces.len()).collect();
    while let Some(fi) = stack.pop() {
        if !faces[fi].alive || faces[fi].outside.is_empty() {
            continue;
        }
        let eye = *faces[fi]
            .outside
            .iter()
            .max_by(|&&a, &&b| {
                faces[fi]
                    .dist(&points[a])
                    .total_cmp(&faces[fi].dist(&points[b]))
            })
            .unwrap_or(&faces[fi].outside[0]);
        let ep = points[eye];
        let (visible, horizon) = visible_and_horizon(&faces, &edges, fi, points, &ep);
        let mut orphans = Vec::new();
        for &f in &visible {
            faces[f].alive = false;
            orphans.append(&mut faces[f].outside);
            let v = faces[f].v;
            for e in 0..3 {
                edges.remove(&(v[e], v[(e + 1) % 3]));
            }
        }
        let first_new = faces.len();
        for (a, b) in horizon {
            let nf = faces.len();
            faces.push(Face::new(points, [a, b, eye]));
            for (x, y) in [(a, b), (b, eye), (eye, a)] {
                edges.insert((x, y), nf);
            }
        }
        for p in orphans {
            if p == eye {
                continue;
            }
            if let Some(f) = faces[first_new..]
                .iter_mut()
                .find(|f| f.outside(points, &points[p]))
            {
                f.outside.push(p);
            }
        }
        stack.extend(first_new..faces.len());
    }

    compact(&faces, points)
}

/// Four points spanning a tetrahedron, from the extreme points: the lowest x, the farthest
/// from it, the farthest from their line, the farthest from their plane. `None` when the
/// points are collinear or coplanar (within `eps`).
fn initial_tetrahedron(points: &[Vector3<f64>], eps: f64) -> Option<[usize; 4]> {
    let by = |f: &dyn Fn(&Vector3<f64>) -> f64| {
        let mut best = 0;
        for (i, p) in points.iter().enumerate() {
            if f(p) > f(&points[best]) {
                best = i;
            }
        }
        best
    };
    let i0 = by(&|p| -p.x);
    let i1 = by(&|p| (p - points[i0]).norm_squared());
    let line = points[i1] - points[i0];
    let i2 = by(&|p| (p - points[i0]).cross(&line).norm_squared());
    let nrm = line.cross(&(points[i2] - points[i0]));
    if nrm.norm() <= eps * line.norm() {
        return None;
    }
    let i3 = by(&|p| (p - points[i0]).dot(&nrm).abs());
    if (points[i3] - points[i0]).dot(&nrm).abs() <= eps * nrm.norm() {
        return None;
    }
    Some([i0, i1, i2, i3])
}

/// The faces visible from `ep` (flood fill from face `fi` over shared edges) and the
/// horizon: the edges of visible faces whose twin face is not visible.
fn visible_and_horizon(
    faces: &[Face],
    edges: &HashMap<(usize, usize), usize>,
    fi: usize,
    points: &[Vector3<f64>],
    ep: &Vector3<f64>,
) -> (Vec<usize>, Vec<(usize, usize)>) {
    let mut visible = vec![fi];
    let mut seen = std::collections::HashSet::from([fi]);
    let mut k = 0;
    while k < visible.len() {
        let f = visible[k];
        k += 1;
        let v = faces[f].v;
        for e in 0..3 {
            if let Some(&g) = edges.get(&(v[(e + 1) % 3], v[e])) {
                if !seen.contains(&g) && faces[g].outside(points, ep) {
                    seen.insert(g);
                    visible.push(g);
                }
            }
        }
    }
    let mut horizon = Vec::new();
    for &f in &visible {
        let v = faces[f].v;
        for e in 0..3 {
            let (a, b) = (v[e], v[(e + 1) % 3]);
            match edges.get(&(b, a)) {
                Some(g) if seen.contains(g) => {}
                _ => horizon.push((a, b)),
            }
        }
    }
    (visible, horizon)
}

/// The live faces as a mesh holding only their vertices, numbered in order of first use.
fn compact(faces: &[Face], points: &[Vector3<f64>]) -> Result<TriMesh> {
    let mut map: HashMap<usize, u32> = HashMap::new();
    let mut verts = Vec::new();
    let mut tris = Vec::new();
    for f in faces.iter().filter(|f| f.alive) {
        let mut t = [0u32; 3];
        for (k, &v) in f.v.iter().enumerate() {
            t[k] = *map.entry(v).or_insert_with(|| {
                verts.push(points[v]);
                (verts.len() - 1) as u32
            });
        }
        tris.push(t);
    }
    TriMesh::try_new(verts, tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_with_interior_points() {
        let mut pts: Vec<Vector3<f64>> = (0..8)
            .map(|i| Vector3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let mut s = 12345u64;
        for _ in 0..500 {
            let mut r = || {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 11) as f64 / (1u64 << 53) as f64
            };
            pts.push(Vector3::new(r(), r(), r()));
        }
        let h = convex_hull(&pts).unwrap();
        assert!((h.volume() - 1.0).abs() < 1e-9, "{}", h.volume());
        assert!((h.area() - 6.0).abs() < 1e-9);
        let t = h.topology();
        assert_eq!((t.boundary_edges, t.nonmanifold_edges), (0, 0));
    }

    #[test]
    fn coplanar_is_an_error() {
        let pts: Vec<_> = (0..10)
            .map(|i| Vector3::new(i as f64, (i * i) as f64, 0.0))
            .collect();
        assert!(convex_hull(&pts).is_err());
        assert!(convex_hull(&pts[..3]).is_err());
    }
}
