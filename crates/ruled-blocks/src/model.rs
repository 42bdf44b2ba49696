//! The model as a closed solid: a closed triangle mesh as it is, or an open surface — a
//! height field, or a grid of points such as a sampled B-spline surface — closed into a
//! slab (the surface on top, vertical walls, a flat floor at `base`), so that every later
//! step sees one kind of model: a solid to keep.

use geom::heightfield::HeightField;
use geom::TriMesh;
use nalgebra::Vector3;

use crate::error::{Error, Result};

/// The closed slab under a height field: `nx × ny` cells of its graph on top, walls down to
/// `base` and the floor, outward-facing triangles.
///
/// # Errors
/// [`Error::Model`] when a height lies at or below `base`, is not finite, or the grid is
/// empty.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField};
/// use ruled_blocks::model::slab;
/// let hf = HeightField::try_new(Expr::parse("10 + x/10")?, (0.0, 100.0), (0.0, 50.0))?;
/// let solid = slab(&hf, 8, 4, 0.0)?;
/// // a closed solid under the graph: ∫∫ (10 + x/10) dx dy = 50 · (1000 + 500)
/// assert!((solid.volume() - 75_000.0).abs() < 1e-6);
/// assert!(solid.validate(true).is_ok());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn slab(hf: &HeightField, nx: usize, ny: usize, base: f64) -> Result<TriMesh> {
    if nx == 0 || ny == 0 {
        return Err(Error::Model(
            "a height field needs at least one cell per side".into(),
        ));
    }
    let (x, y) = (hf.x_range(), hf.y_range());
    let at = |i: usize, j: usize| {
        let px = x.0 + (x.1 - x.0) * i as f64 / nx as f64;
        let py = y.0 + (y.1 - y.0) * j as f64 / ny as f64;
        (px, py)
    };
    let mut v = Vec::with_capacity((nx + 1) * (ny + 1));
    for i in 0..=nx {
        for j in 0..=ny {
            let (px, py) = at(i, j);
            let z = hf.expr().eval(px, py);
            if !(z.is_finite() && z > base) {
                return Err(Error::Model(format!(
                    "the height at ({px}, {py}) is {z}: it must be finite and above the floor at {base}"
                )));
            }
            v.push(Vector3::new(px, py, z));
        }
    }
    slab_under(v, nx, ny, base)
}

/// The closed slab under an open surface given as a grid of points, `(nx + 1) × (ny + 1)`
/// of them, `i`-major (`top[i·(ny + 1) + j]`; a B-spline surface sampled over its
/// domain): the grid's triangles on top, its boundary walled straight down to the floor
/// `z = base`, the floor the top's shadow. The surface must be a graph over the xy-plane —
/// every cell's shadow turned the same way, the boundary's shadow not crossing itself — or
/// the slab would cut through itself; a grid turned clockwise seen from above is walked the
/// other way.
///
/// # Errors
/// [`Error::Model`] when the grid is empty or of the wrong size, a point is not finite or
/// not above `base`, or the surface is not a graph over the xy-plane (it folds over, stands
/// vertical, or its shadow overlaps itself).
///
/// ```
/// use nalgebra::Vector3;
/// use ruled_blocks::model::slab_under;
/// // a tilted square, 2 × 1 cells, listed so that it is clockwise seen from above
/// let top: Vec<_> = (0..=2)
///     .flat_map(|i| (0..=1).map(move |j| Vector3::new(j as f64, i as f64 / 2.0, 3.0 + j as f64)))
///     .collect();
/// let solid = slab_under(top, 2, 1, 0.0)?;
/// // ∫∫ (3 + x) over the unit square
/// assert!((solid.volume() - 3.5).abs() < 1e-12);
/// assert!(solid.validate(true).is_ok());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn slab_under(top: Vec<Vector3<f64>>, nx: usize, ny: usize, base: f64) -> Result<TriMesh> {
    if nx == 0 || ny == 0 || top.len() != (nx + 1) * (ny + 1) {
        return Err(Error::Model(format!(
            "a surface grid needs at least one cell per side and (nx + 1)·(ny + 1) points: {} for {nx} × {ny}",
            top.len()
        )));
    }
    if let Some(p) = top
        .iter()
        .find(|p| !(p.iter().all(|c| c.is_finite()) && p.z > base))
    {
        return Err(Error::Model(format!(
            "the surface point {p:?} must be finite and above the floor at {base}"
        )));
    }
    let shadow = |a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>| {
        ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2.0
    };
    let cell = |v: &[Vector3<f64>], ny: usize, i: usize, j: usize| {
        let at = |i: usize, j: usize| &v[i * (ny + 1) + j];
        [
            shadow(at(i, j), at(i + 1, j), at(i + 1, j + 1)),
            shadow(at(i, j), at(i + 1, j + 1), at(i, j + 1)),
        ]
    };
    let total: f64 = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| (i, j)))
        .flat_map(|(i, j)| cell(&top, ny, i, j))
        .sum();
    // a clockwise grid is walked transposed, which turns it counter-clockwise
    let (top, nx, ny) = if total < 0.0 {
        let t: Vec<Vector3<f64>> = (0..=ny)
            .flat_map(|j| (0..=nx).map(move |i| (i, j)))
            .map(|(i, j)| top[i * (ny + 1) + j])
            .collect();
        (t, ny, nx)
    } else {
        (top, nx, ny)
    };
    let min_area = total.abs() * 1e-12;
    for i in 0..nx {
        for j in 0..ny {
            if cell(&top, ny, i, j).iter().any(|&a| !(a > min_area)) {
                let p = top[i * (ny + 1) + j];
                return Err(Error::Model(format!(
                    "the surface is not a graph over the xy-plane: it folds over or stands vertical near ({:.6}, {:.6}, {:.6}); RuledBlocks closes an open surface by walls straight down (−z), so give it a surface that is one height per (x, y), or a closed mesh",
                    p.x, p.y, p.z
                )));
            }
        }
    }
    let ring = boundary(nx, ny);
    if let Some(k) = crossing(&ring, &|(i, j)| top[i * (ny + 1) + j]) {
        let (i, j) = ring[k];
        let p = top[i * (ny + 1) + j];
        return Err(Error::Model(format!(
            "the surface is not a graph over the xy-plane: its edge passes over itself near ({:.6}, {:.6}, {:.6})",
            p.x, p.y, p.z
        )));
    }
    let mut v = top;
    let n = v.len() as u32;
    let top_at = |i: usize, j: usize| (i * (ny + 1) + j) as u32;
    // the floor: the top's shadow at `base`
    for k in 0..n as usize {
        let p = v[k];
        v.push(Vector3::new(p.x, p.y, base));
    }
    let bottom = |i: usize, j: usize| n + top_at(i, j);
    let mut f = Vec::with_capacity(4 * nx * ny + 4 * (nx + ny));
    for i in 0..nx {
        for j in 0..ny {
            f.push([top_at(i, j), top_at(i + 1, j), top_at(i + 1, j + 1)]);
            f.push([top_at(i, j), top_at(i + 1, j + 1), top_at(i, j + 1)]);
            f.push([bottom(i, j), bottom(i + 1, j + 1), bottom(i + 1, j)]);
            f.push([bottom(i, j), bottom(i, j + 1), bottom(i + 1, j + 1)]);
        }
    }
    // walls: the boundary walked counter-clockwise seen from above, each edge a quad down
    for k in 0..ring.len() {
        let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
        let (ta, tb) = (top_at(a.0, a.1), top_at(b.0, b.1));
        let (ba, bb) = (bottom(a.0, a.1), bottom(b.0, b.1));
        f.push([ba, bb, tb]);
        f.push([ba, tb, ta]);
    }
    TriMesh::try_new(v, f).map_err(|e| Error::Model(e.to_string()))
}

/// The grid's boundary, counter-clockwise in `(i, j)`.
fn boundary(nx: usize, ny: usize) -> Vec<(usize, usize)> {
    let mut ring: Vec<(usize, usize)> = (0..nx).map(|i| (i, 0)).collect();
    ring.extend((0..ny).map(|j| (nx, j)));
    ring.extend((1..=nx).rev().map(|i| (i, ny)));
    ring.extend((1..=ny).rev().map(|j| (0, j)));
    ring
}

/// The first edge of the closed `ring` whose shadow (xy) crosses the shadow of another edge
/// that does not share a corner with it, if any (all pairs: the ring has `2(nx + ny)`
/// edges).
fn crossing(
    ring: &[(usize, usize)],
    point: &dyn Fn((usize, usize)) -> Vector3<f64>,
) -> Option<usize> {
    let m = ring.len();
    let seg = |k: usize| (point(ring[k]), point(ring[(k + 1) % m]));
    let orient = |a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>| {
        (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)
    };
    for k in 0..m {
        let (a, b) = seg(k);
        for l in k + 2..m {
            if (l + 1) % m == k {
                continue;
            }
            let (c, d) = seg(l);
            let (o1, o2) = (orient(&a, &b, &c), orient(&a, &b, &d));
            let (o3, o4) = (orient(&c, &d, &a), orient(&c, &d, &b));
            if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                return Some(k);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An annulus wound `turns` times, `n` cells around and one across, at height 1.
    fn wound(turns: f64, n: usize) -> Vec<Vector3<f64>> {
        (0..=n)
            .flat_map(|i| {
                let t = turns * std::f64::consts::TAU * i as f64 / n as f64;
                [1.0, 2.0].map(|r| Vector3::new(r * t.cos(), r * t.sin(), 1.0))
            })
            .collect()
    }

    #[test]
    fn a_surface_whose_shadow_overlaps_itself_is_refused() {
        // three quarters of a turn is a graph; a turn and a tenth overlaps itself
        let ok = slab_under(wound(0.75, 30), 30, 1, 0.0).unwrap();
        let ring = 0.75 * std::f64::consts::PI * (4.0 - 1.0);
        // the polygonal annulus holds a little less than the round one
        assert!(
            ok.volume() < ring && ok.volume() > 0.99 * ring,
            "{}",
            ok.volume()
        );
        assert!(ok.validate(true).is_ok());
        let e = slab_under(wound(1.1, 44), 44, 1, 0.0).unwrap_err();
        assert!(e.to_string().contains("passes over itself"), "{e}");
    }

    #[test]
    fn a_fold_and_a_point_under_the_floor_are_refused() {
        let mut top = wound(0.5, 10);
        top[8].x = -top[8].x; // pulls one point across: a cell turns over
        let e = slab_under(top, 10, 1, 0.0).unwrap_err();
        assert!(e.to_string().contains("folds over"), "{e}");
        let e = slab_under(wound(0.5, 10), 10, 1, 1.0).unwrap_err();
        assert!(e.to_string().contains("above the floor"), "{e}");
        assert!(slab_under(Vec::new(), 0, 1, 0.0).is_err());
    }
}
