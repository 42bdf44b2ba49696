//! The model as a closed solid: a closed triangle mesh as it is, or an open height field
//! closed into a slab (its graph on top, vertical walls, a flat floor at `base`), so that
//! every later step sees one kind of model: a solid to keep.

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
    let mut v = Vec::with_capacity(2 * (nx + 1) * (ny + 1));
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
    let top = |i: usize, j: usize| (i * (ny + 1) + j) as u32;
    let n = v.len() as u32;
    // the floor: the same grid at `base`
    for i in 0..=nx {
        for j in 0..=ny {
            let (px, py) = at(i, j);
            v.push(Vector3::new(px, py, base));
        }
    }
    let bottom = |i: usize, j: usize| n + top(i, j);
    let mut f = Vec::with_capacity(4 * nx * ny + 4 * (nx + ny));
    for i in 0..nx {
        for j in 0..ny {
            f.push([top(i, j), top(i + 1, j), top(i + 1, j + 1)]);
            f.push([top(i, j), top(i + 1, j + 1), top(i, j + 1)]);
            f.push([bottom(i, j), bottom(i + 1, j + 1), bottom(i + 1, j)]);
            f.push([bottom(i, j), bottom(i, j + 1), bottom(i + 1, j + 1)]);
        }
    }
    // walls: the boundary walked counter-clockwise seen from above, each edge a quad down
    let mut ring: Vec<(usize, usize)> = (0..nx).map(|i| (i, 0)).collect();
    ring.extend((0..ny).map(|j| (nx, j)));
    ring.extend((1..=nx).rev().map(|i| (i, ny)));
    ring.extend((1..=ny).rev().map(|j| (0, j)));
    for k in 0..ring.len() {
        let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
        let (ta, tb) = (top(a.0, a.1), top(b.0, b.1));
        let (ba, bb) = (bottom(a.0, a.1), bottom(b.0, b.1));
        f.push([ba, bb, tb]);
        f.push([ba, tb, ta]);
    }
    TriMesh::try_new(v, f).map_err(|e| Error::Model(e.to_string()))
}
