//! The block grid of the hot-blade task, the cutting planes of each block (parallel, or
//! following a cutting-direction curve, thesis eq. 5.4), and the part of a section that a
//! block holds.
//!
//! Coordinates: the grid frame has axes `d` (the cutting direction, or the chord of the
//! cutting-direction curve), `u = normalize(ẑ × d)` and `v = d × u` ([`PlaneFrame`](geom::slice::PlaneFrame)); a
//! point's grid coordinates are `(d·p, u·p, v·p)`. Blocks are boxes of `size` (along
//! `d`, `u`, `v`) tiling the surface's extent from the grid origin.

use geom::planar::{ArcLength, PlanarCurve};
use geom::slice::PlaneFrame;
use geom::surface::Section;
use nalgebra::{Vector2, Vector3};

use crate::result::GridInfo;

/// The block grid.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Grid {
    /// Block axes.
    #[cfg_attr(feature = "serde", serde(serialize_with = "crate::ser::frame"))]
    pub frame: PlaneFrame,
    /// Grid coordinates of the grid's min corner.
    pub origin: [f64; 3],
    /// Block size along `d`, `u`, `v`.
    pub size: [f64; 3],
    /// Blocks along `d`.
    pub rows: usize,
    /// Blocks along `u`.
    pub cols: usize,
    /// Extent of the surface along `d`.
    pub extent_d: (f64, f64),
}

impl Grid {
    /// A grid covering `extent` (per axis, grid coordinates) from `origin` (the extent's
    /// min corner when `None`).
    pub fn new(
        frame: PlaneFrame,
        size: [f64; 3],
        extent: [(f64, f64); 3],
        origin: Option<[f64; 3]>,
    ) -> Self {
        let origin = origin.unwrap_or([extent[0].0, extent[1].0, extent[2].0]);
        let count = |i: usize| {
            let n = ((extent[i].1 - origin[i]) / size[i] - 1e-9).ceil();
            if n.is_finite() && n >= 1.0 {
                n as usize
            } else {
                1
            }
        };
        Self {
            frame,
            origin,
            size,
            rows: count(0),
            cols: count(1),
            extent_d: extent[0],
        }
    }

    /// `[lo, hi]` of row `r` along `d`.
    pub fn row_range(&self, r: usize) -> (f64, f64) {
        (
            self.origin[0] + r as f64 * self.size[0],
            self.origin[0] + (r + 1) as f64 * self.size[0],
        )
    }

    /// `[lo, hi]` of column `c` along `u`.
    pub fn col_range(&self, c: usize) -> (f64, f64) {
        (
            self.origin[1] + c as f64 * self.size[1],
            self.origin[1] + (c + 1) as f64 * self.size[1],
        )
    }

    /// Positions along `d` of the `n` target planes of row `r`: equally spaced from the
    /// block's entry face to its exit face, both clipped to the surface (moved inside it
    /// by a hair so that the end planes still cut it). Rows share their face planes
    /// bit for bit.
    pub fn row_planes(&self, r: usize, n: usize) -> Vec<f64> {
        let (lo, hi) = self.row_range(r);
        let eps = 1e-9 * (self.extent_d.1 - self.extent_d.0).abs().max(1e-300);
        let a = lo.max(self.extent_d.0 + eps);
        let b = hi.min(self.extent_d.1 - eps);
        let n = n.max(2);
        (0..n)
            .map(|j| {
                if j == 0 {
                    a
                } else if j == n - 1 {
                    b
                } else {
                    a + (b - a) * j as f64 / (n - 1) as f64
                }
            })
            .collect()
    }

    /// World position of grid coordinates.
    pub fn world(&self, c: [f64; 3]) -> Vector3<f64> {
        self.frame.normal * c[0] + self.frame.u * c[1] + self.frame.v * c[2]
    }

    /// The grid as the report gives it.
    pub fn info(&self) -> GridInfo {
        let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
        GridInfo {
            axis_d: arr(&self.frame.normal),
            axis_u: arr(&self.frame.u),
            axis_v: arr(&self.frame.v),
            size: self.size,
            origin: arr(&self.world(self.origin)),
            rows: self.rows,
            columns: self.cols,
        }
    }
}

/// A cutting plane: its frame and offset along the frame's normal.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Plane {
    /// In-plane axes and normal.
    #[cfg_attr(feature = "serde", serde(serialize_with = "crate::ser::frame"))]
    pub frame: PlaneFrame,
    /// Offset along the normal.
    pub offset: f64,
}

/// Where the cutting planes go: parallel to the grid's `d`, or following a plan curve.
#[derive(Debug, Clone)]
pub enum Planes {
    /// Planes normal to `d`.
    Parallel(PlaneFrame),
    /// Planes through the points of a curve, normal to its horizontal tangent.
    Curve(CurvePlanes),
}

impl Planes {
    /// The plane at position `a` along `d`.
    pub fn at(&self, a: f64) -> Plane {
        match self {
            Self::Parallel(f) => Plane {
                frame: *f,
                offset: a,
            },
            Self::Curve(c) => c.at(a),
        }
    }
}

/// A cutting-direction curve in grid coordinates: lateral offset `w(a)` along `u` as a
/// natural cubic spline through the plan points (the curve advances along `d`).
#[derive(Debug, Clone)]
pub struct CurvePlanes {
    grid: PlaneFrame,
    a: Vec<f64>,
    w: Vec<f64>,
    m: Vec<f64>,
}

impl CurvePlanes {
    /// The curve through `points` (plan `(x, y)`, strictly advancing along `grid.normal`).
    pub fn new(grid: PlaneFrame, points: &[(f64, f64)]) -> Self {
        let a: Vec<f64> = points
            .iter()
            .map(|p| grid.normal.x * p.0 + grid.normal.y * p.1)
            .collect();
        let w: Vec<f64> = points
            .iter()
            .map(|p| grid.u.x * p.0 + grid.u.y * p.1)
            .collect();
        let m = natural_second_derivatives(&a, &w);
        Self { grid, a, w, m }
    }

    /// `w(a)` and `w'(a)` (linear continuation beyond the ends).
    fn eval(&self, x: f64) -> (f64, f64) {
        let n = self.a.len();
        if n < 2 {
            return (self.w.first().copied().unwrap_or(0.0), 0.0);
        }
        let slope_end = |i: usize, j: usize| {
            let h = self.a[j] - self.a[i];
            (self.w[j] - self.w[i]) / h - h * (2.0 * self.m[i] + self.m[j]) / 6.0
        };
        if x <= self.a[0] {
            let s = slope_end(0, 1);
            return (self.w[0] + s * (x - self.a[0]), s);
        }
        if x >= self.a[n - 1] {
            let h = self.a[n - 1] - self.a[n - 2];
            let s = (self.w[n - 1] - self.w[n - 2]) / h
                + h * (self.m[n - 2] + 2.0 * self.m[n - 1]) / 6.0;
            return (self.w[n - 1] + s * (x - self.a[n - 1]), s);
        }
        let i = match self.a.binary_search_by(|v| v.total_cmp(&x)) {
            Ok(i) => i.min(n - 2),
            Err(i) => i - 1,
        };
        let h = self.a[i + 1] - self.a[i];
        let (t0, t1) = (self.a[i + 1] - x, x - self.a[i]);
        let (m0, m1) = (self.m[i], self.m[i + 1]);
        let value = m0 * t0.powi(3) / (6.0 * h)
            + m1 * t1.powi(3) / (6.0 * h)
            + (self.w[i] / h - m0 * h / 6.0) * t0
            + (self.w[i + 1] / h - m1 * h / 6.0) * t1;
        let slope = -m0 * t0 * t0 / (2.0 * h) + m1 * t1 * t1 / (2.0 * h)
            - (self.w[i] / h - m0 * h / 6.0)
            + (self.w[i + 1] / h - m1 * h / 6.0);
        (value, slope)
    }

    /// The vertical plane through the curve's point at `a`, normal to its tangent.
    pub fn at(&self, a: f64) -> Plane {
        let (w, dw) = self.eval(a);
        let p = self.grid.normal * a + self.grid.u * w;
        let n = (self.grid.normal + self.grid.u * dw).normalize();
        // `from_direction` only fails for a zero vector; n is a unit vector here
        let frame = PlaneFrame::from_direction(n).unwrap_or(self.grid);
        Plane {
            frame,
            offset: frame.normal.dot(&p),
        }
    }
}

/// Second derivatives of the natural cubic spline through `(x, y)` (Thomas algorithm).
fn natural_second_derivatives(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut m = vec![0.0; n];
    if n < 3 {
        return m;
    }
    let mut c = vec![0.0; n];
    let mut d = vec![0.0; n];
    for i in 1..n - 1 {
        let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let a = h0 / 6.0;
        let b = (h0 + h1) / 3.0;
        let cc = h1 / 6.0;
        let r = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
        let denom = b - a * c[i - 1];
        c[i] = cc / denom;
        d[i] = (r - a * d[i - 1]) / denom;
    }
    for i in (1..n - 1).rev() {
        m[i] = d[i] - c[i] * m[i + 1];
    }
    m
}

/// The part of a section inside a block's `u` range, sampled equally in arc length.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Clipped {
    /// Sample points in plane coordinates.
    pub points: Vec<[f64; 2]>,
    /// Arc length of each sample from the first.
    pub s: Vec<f64>,
    /// Design length of the part.
    pub length: f64,
    /// Tangent angles of the design section at the part's start and end (plane
    /// coordinates, direction of increasing arc length).
    pub end_angles: [f64; 2],
}

/// Parameter samples used to find where a section enters and leaves a `u` range; fixed so
/// that two neighbouring blocks find their shared end bit for bit.
const CLIP_SAMPLES: usize = 1024;

/// Parameters `[ta, tb]` of the part of `section` (on `plane`) whose grid `u` lies in
/// `range`: the first entry to the last exit when the section leaves the range in between.
/// `None` when no part is inside.
fn crossing(
    section: &Section,
    plane: &Plane,
    grid_u: &Vector3<f64>,
    range: (f64, f64),
) -> Option<(f64, f64)> {
    let curve = &section.curve;
    let (t0, t1) = curve.domain();
    let u_of = |t: f64| {
        let q = curve.point(t);
        grid_u.dot(&plane.frame.to_world(plane.offset, &q))
    };
    let ts: Vec<f64> = (0..=CLIP_SAMPLES)
        .map(|i| t0 + (t1 - t0) * i as f64 / CLIP_SAMPLES as f64)
        .collect();
    let us: Vec<f64> = ts.iter().map(|&t| u_of(t)).collect();
    let inside = |u: f64| u >= range.0 && u <= range.1;
    let first = us.iter().position(|&u| inside(u))?;
    let last = us.iter().rposition(|&u| inside(u))?;
    // the crossing of level `x` in [ta, tb] (u − x changes sign there)
    let cross = |ta: f64, tb: f64, x: f64| {
        // a sample exactly on the level is the crossing (both neighbours count it inside)
        if u_of(ta) == x {
            return ta;
        }
        if u_of(tb) == x {
            return tb;
        }
        let below = u_of(ta) < x;
        let (mut lo, mut hi) = (ta, tb);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if (u_of(mid) < x) == below {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let level = |u: f64| if u < range.0 { range.0 } else { range.1 };
    let ta = if first > 0 {
        cross(ts[first - 1], ts[first], level(us[first - 1]))
    } else {
        t0
    };
    let tb = if last < CLIP_SAMPLES {
        cross(ts[last], ts[last + 1], level(us[last + 1]))
    } else {
        t1
    };
    (tb > ta).then_some((ta, tb))
}

/// The part of `section` (on `plane`) whose grid `u` lies in `range`, sampled at `n`
/// points equally spaced in arc length; the first entry to the last exit when the section
/// leaves the range in between. `None` when no part is inside.
pub fn clip(
    section: &Section,
    plane: &Plane,
    grid_u: &Vector3<f64>,
    range: (f64, f64),
    n: usize,
) -> Option<Clipped> {
    let (ta, tb) = crossing(section, plane, grid_u, range)?;
    let curve = &section.curve;
    // the arc length of the part only: the section may run across many blocks
    let arc = ArcLength::between(curve, ta, tb, 4 * n.max(64));
    let length = arc.length();
    if !(length > 0.0) {
        return None;
    }
    let n = n.max(3);
    let mut points = Vec::with_capacity(n);
    let mut s = Vec::with_capacity(n);
    for i in 0..n {
        let t = if i == 0 {
            ta
        } else if i == n - 1 {
            tb
        } else {
            arc.t_at(curve, length * i as f64 / (n - 1) as f64)
        };
        let q: Vector2<f64> = curve.point(t);
        points.push([q.x, q.y]);
        s.push(if i == n - 1 {
            length
        } else {
            length * i as f64 / (n - 1) as f64
        });
    }
    let angle = |t: f64| {
        let d = curve.jet(t).d1;
        d.y.atan2(d.x)
    };
    Some(Clipped {
        points,
        s,
        length,
        end_angles: [angle(ta), angle(tb)],
    })
}

/// The same part as [`clip`] as a polyline of `n` points equally spaced in the curve's
/// parameter (no arc-length table): the dense design curve the deviation is measured
/// against.
pub fn clip_polyline(
    section: &Section,
    plane: &Plane,
    grid_u: &Vector3<f64>,
    range: (f64, f64),
    n: usize,
) -> Option<Vec<[f64; 2]>> {
    let (ta, tb) = crossing(section, plane, grid_u, range)?;
    let n = n.max(2);
    Some(
        (0..n)
            .map(|i| {
                let t = if i == n - 1 {
                    tb
                } else {
                    ta + (tb - ta) * i as f64 / (n - 1) as f64
                };
                let q = section.curve.point(t);
                [q.x, q.y]
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn natural_spline_reproduces_a_line_and_interpolates() {
        let frame = PlaneFrame::from_direction(Vector3::x()).unwrap();
        let c = CurvePlanes::new(frame, &[(0.0, 0.0), (100.0, 50.0), (200.0, 100.0)]);
        let (w, dw) = c.eval(150.0);
        assert!((w - 75.0).abs() < 1e-12 && (dw - 0.5).abs() < 1e-12);
        let c = CurvePlanes::new(
            frame,
            &[(0.0, 0.0), (100.0, 50.0), (200.0, 0.0), (300.0, 10.0)],
        );
        for (x, y) in [(0.0, 0.0), (100.0, 50.0), (200.0, 0.0), (300.0, 10.0)] {
            assert!((c.eval(x).0 - y).abs() < 1e-9);
        }
        // the slope matches a central difference
        let h = 1e-4;
        let fd = (c.eval(130.0 + h).0 - c.eval(130.0 - h).0) / (2.0 * h);
        assert!((fd - c.eval(130.0).1).abs() < 1e-7);
    }

    #[test]
    fn rows_share_face_planes() {
        let frame = PlaneFrame::from_direction(Vector3::x()).unwrap();
        let g = Grid::new(
            frame,
            [600.0, 600.0, 600.0],
            [(0.0, 1500.0), (0.0, 1000.0), (-100.0, 100.0)],
            None,
        );
        assert_eq!((g.rows, g.cols), (3, 2));
        let r0 = g.row_planes(0, 5);
        let r1 = g.row_planes(1, 5);
        assert_eq!(r0[4], r1[0]);
        assert!(r0[0] > 0.0 && r0[0] < 1e-5);
        let r2 = g.row_planes(2, 5);
        assert!(r2[4] < 1500.0 && r2[4] > 1500.0 - 1e-5);
    }
}
