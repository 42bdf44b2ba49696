//! Height fields `z = f(x, y)` over a rectangle, sectioned analytically.
//!
//! Entry points: [`HeightField::try_new`](crate::heightfield::HeightField::try_new), [`HeightField::section`](crate::heightfield::HeightField::section), [`HeightField::to_mesh`](crate::heightfield::HeightField::to_mesh),
//! and [`GraphCurve`](crate::heightfield::GraphCurve), the exact section curve.

use std::sync::Arc;

use nalgebra::{Vector2, Vector3};

use crate::bbox::Aabb;
use crate::error::{GeomError, Result};
use crate::expr::Expr;
use crate::mesh::TriMesh;
use crate::planar::{Jet2, PlanarCurve};
use crate::slice::PlaneFrame;

/// Samples per side used to bound the height range (`z` is not bounded analytically).
pub const Z_RANGE_SAMPLES: usize = 257;

/// `z = f(x, y)` on `[x0, x1] × [y0, y1]`.
#[derive(Debug, Clone)]
pub struct HeightField {
    expr: Arc<Expr>,
    x: (f64, f64),
    y: (f64, f64),
    /// The bounding box, computed once ([`HeightField::aabb`]): a height field is
    /// immutable, and its box is asked for by every task, often many times.
    bounds: Aabb,
}

impl HeightField {
    /// A height field; the expression must be finite on a
    /// [`Z_RANGE_SAMPLES`]² grid over the rectangle.
    ///
    /// # Errors
    /// [`GeomError::InvalidDomain`] for an empty rectangle; [`GeomError::NonFinite`] when `f`
    /// is NaN or infinite at a grid point (reported with the point).
    pub fn try_new(expr: Expr, x: (f64, f64), y: (f64, f64)) -> Result<Self> {
        for (name, (a, b)) in [("x", x), ("y", y)] {
            if !(a.is_finite() && b.is_finite() && b > a) {
                return Err(GeomError::InvalidDomain(format!(
                    "{name} range ({a}, {b}) must be finite with min < max"
                )));
            }
        }
        let mut h = Self {
            expr: Arc::new(expr),
            x,
            y,
            bounds: Aabb {
                min: Vector3::zeros(),
                max: Vector3::zeros(),
            },
        };
        h.bounds = h.sampled_aabb()?;
        Ok(h)
    }

    fn grid_point(&self, i: usize, j: usize, n: usize) -> (f64, f64) {
        (
            self.x.0 + (self.x.1 - self.x.0) * i as f64 / n as f64,
            self.y.0 + (self.y.1 - self.y.0) * j as f64 / n as f64,
        )
    }

    /// The expression.
    pub fn expr(&self) -> &Expr {
        &self.expr
    }

    /// `x` range.
    pub fn x_range(&self) -> (f64, f64) {
        self.x
    }

    /// `y` range.
    pub fn y_range(&self) -> (f64, f64) {
        self.y
    }

    /// Bounding box; `z` from a [`Z_RANGE_SAMPLES`]² sample grid, its extremes polished
    /// by Newton steps in the cells around them (exact at smooth interior or edge extrema).
    pub fn aabb(&self) -> Aabb {
        self.bounds
    }

    /// [`Self::aabb`], computed: every grid sample checked finite.
    fn sampled_aabb(&self) -> Result<Aabb> {
        let n = Z_RANGE_SAMPLES - 1;
        let (mut lo, mut hi) = ((f64::INFINITY, 0, 0), (f64::NEG_INFINITY, 0, 0));
        for i in 0..=n {
            for j in 0..=n {
                let (px, py) = self.grid_point(i, j, n);
                let z = self.expr.eval(px, py);
                if !z.is_finite() {
                    return Err(GeomError::NonFinite {
                        what: format!("z = {} at (x, y) = ({px}, {py})", self.expr.source()),
                    });
                }
                if z < lo.0 {
                    lo = (z, i, j);
                }
                if z > hi.0 {
                    hi = (z, i, j);
                }
            }
        }
        // the sampled extremes miss the true ones by O(h²·f''): polish each inside the
        // cells around its sample
        let lo = self.polish_extreme(lo, n, 1.0);
        let hi = -self.polish_extreme((-hi.0, hi.1, hi.2), n, -1.0);
        Ok(Aabb {
            min: Vector3::new(self.x.0, self.y.0, lo),
            max: Vector3::new(self.x.1, self.y.1, hi),
        })
    }

    /// Lowers `sign · f` (given as `(value, i, j)` at grid sample `(i, j)` of an `n`-cell grid)
    /// by alternating one-dimensional Newton steps along x and y, each kept inside the cells
    /// next to the sample and taken only when it lowers the value. Returns the lowest
    /// `sign · f` found (never above the sample's).
    fn polish_extreme(&self, (best, i, j): (f64, usize, usize), n: usize, sign: f64) -> f64 {
        let (x0, y0) = self.grid_point(i.saturating_sub(1), j.saturating_sub(1), n);
        let (x1, y1) = self.grid_point((i + 1).min(n), (j + 1).min(n), n);
        let (mut px, mut py) = self.grid_point(i, j, n);
        let mut best = best;
        for _ in 0..20 {
            let before = best;
            for (dir, lo, hi) in [
                ((1.0, 0.0), x0 - px, x1 - px),
                ((0.0, 1.0), y0 - py, y1 - py),
            ] {
                let jet = self.expr.eval_along((px, py), dir, 0.0);
                let (d1, d2) = (sign * jet.d1, sign * jet.d2);
                let t = if d2 > 0.0 {
                    (-d1 / d2).clamp(lo, hi)
                } else if d1 > 0.0 {
                    lo
                } else {
                    hi
                };
                let (qx, qy) = (px + t * dir.0, py + t * dir.1);
                let v = sign * self.expr.eval(qx, qy);
                if v < best {
                    best = v;
                    (px, py) = (qx, qy);
                }
            }
            if !(best < before) {
                break;
            }
        }
        best
    }

    /// The exact section by the plane `frame.normal · p = offset`, or `None` when the plane
    /// misses the rectangle.
    ///
    /// # Errors
    /// [`GeomError::Unsupported`] when the cutting direction is not horizontal (a tilted
    /// plane's section of a graph is not a graph over the plane's `u` axis).
    ///
    /// ```
    /// use geom::planar::PlanarCurve;
    /// use geom::{Expr, HeightField, PlaneFrame};
    /// use nalgebra::Vector3;
    /// let hf = HeightField::try_new(Expr::parse("x*y")?, (0.0, 2.0), (0.0, 1.0))?;
    /// let frame = PlaneFrame::from_direction(Vector3::x())?;
    /// // the plane x = 1.5 cuts the graph in the line z = 1.5·y, y ∈ [0, 1]
    /// let curve = hf.section(&frame, 1.5)?.ok_or("no section")?;
    /// let end = curve.point(curve.domain().1);
    /// assert!((end.x - 1.0).abs() < 1e-12 && (end.y - 1.5).abs() < 1e-12);
    /// // x = 3 misses the rectangle; a vertical cutting direction is not supported
    /// assert!(hf.section(&frame, 3.0)?.is_none());
    /// assert!(hf.section(&PlaneFrame::from_direction(Vector3::z())?, 0.5).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn section(&self, frame: &PlaneFrame, offset: f64) -> Result<Option<GraphCurve>> {
        if frame.normal.z.abs() > 1e-12 {
            return Err(GeomError::Unsupported(
                "height fields are sectioned analytically only for horizontal cutting directions (direction z = 0)".into(),
            ));
        }
        let o = (frame.normal.x * offset, frame.normal.y * offset);
        let u = (frame.u.x, frame.u.y);
        let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
        for (ok, uk, (lo, hi)) in [(o.0, u.0, self.x), (o.1, u.1, self.y)] {
            if uk.abs() < 1e-15 {
                if ok < lo || ok > hi {
                    return Ok(None);
                }
            } else {
                let (a, b) = ((lo - ok) / uk, (hi - ok) / uk);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        if !(t1 > t0) {
            return Ok(None);
        }
        Ok(Some(GraphCurve {
            expr: Arc::clone(&self.expr),
            origin: o,
            dir: u,
            t: (t0, t1),
        }))
    }

    /// A triangulated grid of `nx × ny` cells over the rectangle (for export and tests).
    ///
    /// # Errors
    /// [`GeomError::InvalidDomain`] for zero cells.
    pub fn to_mesh(&self, nx: usize, ny: usize) -> Result<TriMesh> {
        if nx == 0 || ny == 0 {
            return Err(GeomError::InvalidDomain(
                "a height-field mesh needs at least one cell per side".into(),
            ));
        }
        let mut v = Vec::with_capacity((nx + 1) * (ny + 1));
        for i in 0..=nx {
            for j in 0..=ny {
                let px = self.x.0 + (self.x.1 - self.x.0) * i as f64 / nx as f64;
                let py = self.y.0 + (self.y.1 - self.y.0) * j as f64 / ny as f64;
                v.push(Vector3::new(px, py, self.expr.eval(px, py)));
            }
        }
        let mut f = Vec::with_capacity(2 * nx * ny);
        let w = (ny + 1) as u32;
        for i in 0..nx as u32 {
            for j in 0..ny as u32 {
                let a = i * w + j;
                f.push([a, a + w, a + w + 1]);
                f.push([a, a + w + 1, a + 1]);
            }
        }
        TriMesh::try_new(v, f)
    }
}

/// The exact section of a height field: the graph `t ↦ (t, f(o + t·u))` in plane
/// coordinates, with `f`'s derivatives along the section computed exactly.
#[derive(Debug, Clone)]
pub struct GraphCurve {
    expr: Arc<Expr>,
    origin: (f64, f64),
    dir: (f64, f64),
    t: (f64, f64),
}

impl PlanarCurve for GraphCurve {
    fn domain(&self) -> (f64, f64) {
        self.t
    }
    fn jet(&self, t: f64) -> Jet2 {
        let j = self.expr.eval_along(self.origin, self.dir, t);
        Jet2 {
            p: Vector2::new(t, j.v),
            d1: Vector2::new(1.0, j.d1),
            d2: Vector2::new(0.0, j.d2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounding_box_heights_are_the_true_extremes_between_samples() {
        // interior maximum between grid samples; minimum on an edge (y = 0 and y = 1200)
        let h = HeightField::try_new(
            Expr::parse("150 + 40*sin(x/350) - 0.0001*(y - 600)*(y - 600)").unwrap(),
            (0.0, 1800.0),
            (0.0, 1200.0),
        )
        .unwrap();
        let b = h.aabb();
        assert!((b.min.z - 74.0).abs() < 1e-9, "{}", b.min.z);
        assert!((b.max.z - 190.0).abs() < 1e-9, "{}", b.max.z);
        let p = HeightField::try_new(
            Expr::parse("-(x - 0.31371)^2 - (y - 0.77713)^2").unwrap(),
            (0.0, 1.0),
            (0.0, 1.0),
        )
        .unwrap();
        assert!(p.aabb().max.z.abs() < 1e-15, "{}", p.aabb().max.z);
    }

    #[test]
    fn section_along_x_is_graph_in_y() {
        let h = HeightField::try_new(Expr::parse("x + y*y").unwrap(), (0.0, 10.0), (-1.0, 2.0))
            .unwrap();
        let f = PlaneFrame::from_direction(Vector3::x()).unwrap();
        let c = h.section(&f, 3.0).unwrap().unwrap();
        assert_eq!(c.domain(), (-1.0, 2.0));
        let j = c.jet(1.5);
        assert_eq!(j.p, Vector2::new(1.5, 3.0 + 2.25));
        assert_eq!(j.d2.y, 2.0);
        assert!(h.section(&f, 11.0).unwrap().is_none());
        let tilted = PlaneFrame::from_direction(Vector3::new(1.0, 0.0, 1.0)).unwrap();
        assert!(h.section(&tilted, 1.0).is_err());
    }

    #[test]
    fn diagonal_section_is_clipped() {
        let h = HeightField::try_new(Expr::parse("0").unwrap(), (0.0, 1.0), (0.0, 1.0)).unwrap();
        let f = PlaneFrame::from_direction(Vector3::new(1.0, 1.0, 0.0)).unwrap();
        let c = h.section(&f, 0.5_f64.sqrt()).unwrap().unwrap();
        let (a, b) = c.domain();
        assert!((b - a - 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn non_finite_expression_is_rejected() {
        let e = HeightField::try_new(Expr::parse("sqrt(x)").unwrap(), (-1.0, 1.0), (0.0, 1.0));
        assert!(matches!(e, Err(GeomError::NonFinite { .. })));
        assert!(HeightField::try_new(Expr::parse("x").unwrap(), (1.0, 1.0), (0.0, 1.0)).is_err());
    }
}
