//! Planar cubic Bézier curves `B(t) = Σ bᵢ Bᵢ³(t)`, t ∈ [0, 1]: points, derivatives,
//! curvature, arc length (composite Gauss–Legendre, exact to rounding for the smooth
//! speed of a regular cubic), the end data an elastica must share with the curve, and the
//! angles of the control polygon ("Designing for Robotic Hot-Blade Cutting" fig. 12).

use crate::error::{DesignError, Result};

/// A planar cubic Bézier curve by its four control points.
///
/// ```
/// use design::Bezier;
/// // an arch over [0, 4], symmetric about x = 2
/// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] };
/// assert_eq!(b.point(0.0), b.p[0]);
/// assert_eq!(b.point(1.0), b.p[3]);
/// assert_eq!(b.point(0.5), [2.0, 1.5]); // (b₀ + 3b₁ + 3b₂ + b₃) / 8
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Bezier {
    /// Control points b₀, b₁, b₂, b₃.
    pub p: [[f64; 2]; 4],
}

/// Pieces and nodes of the arc-length quadrature.
const PIECES: usize = 64;
/// A Bézier's arc length tabulated at its panel ends ([`Bezier::arc_table`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ArcTable {
    bezier: Bezier,
    /// Arc length at `k / PIECES`, `k = 0..=PIECES`.
    cumulative: Vec<f64>,
}

impl ArcTable {
    /// The whole length.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let (length, table) = (b.length(), b.arc_table());
    /// assert!((table.length() - length).abs() < 1e-14 * length); // the same panels, to rounding
    /// // half the length lies on either side of the axis of symmetry
    /// let t = table.at_length(0.5 * length);
    /// assert!((t - 0.5).abs() < 1e-12);
    /// assert!((b.length_to(t) - 0.5 * length).abs() < 1e-12 * length);
    /// ```
    pub fn length(&self) -> f64 {
        self.cumulative[PIECES]
    }

    /// The parameter at arc length `s` from the start (`s` clamped to the curve): its
    /// panel from the table, then Newton on the panel's own Gauss rule, bisection
    /// safeguarded, to `1e-14` of the length.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let t = b.arc_table().at_length(1.0);
    /// assert!((b.length_to(t) - 1.0).abs() < 1e-12);
    /// assert_eq!(b.arc_table().at_length(-1.0), 0.0); // clamped to the curve
    /// ```
    pub fn at_length(&self, s: f64) -> f64 {
        let total = self.length();
        let s = s.clamp(0.0, total);
        let k = self.cumulative.partition_point(|&c| c < s).clamp(1, PIECES) - 1;
        let (t0, base) = (k as f64 / PIECES as f64, self.cumulative[k]);
        let (mut lo, mut hi) = (t0, (k + 1) as f64 / PIECES as f64);
        let span = self.cumulative[k + 1] - base;
        let mut t = if span > 0.0 {
            t0 + (hi - t0) * (s - base) / span
        } else {
            t0
        };
        for _ in 0..60 {
            let f = base + self.bezier.length_between(t0, t) - s;
            if f.abs() <= 1e-14 * total {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let d = self.bezier.d1(t);
            let next = t - f / d[0].hypot(d[1]);
            t = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
        }
        t
    }
}

/// Gauss–Legendre nodes and weights on [−1, 1], 5 points.
pub(crate) const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

fn lerp(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

impl Bezier {
    /// The point at `t` (de Casteljau).
    pub fn point(&self, t: f64) -> [f64; 2] {
        let [a, b, c, d] = self.p;
        let (ab, bc, cd) = (lerp(a, b, t), lerp(b, c, t), lerp(c, d, t));
        lerp(lerp(ab, bc, t), lerp(bc, cd, t), t)
    }

    /// The first derivative at `t`.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// assert_eq!(b.d1(0.0), [3.0, 6.0]); // 3 (b₁ − b₀)
    /// assert_eq!(b.d1(1.0), [3.0, -6.0]); // 3 (b₃ − b₂)
    /// ```
    pub fn d1(&self, t: f64) -> [f64; 2] {
        let [a, b, c, d] = self.p;
        let (u, v, w) = (sub(b, a), sub(c, b), sub(d, c));
        let q = lerp(lerp(u, v, t), lerp(v, w, t), t);
        [3.0 * q[0], 3.0 * q[1]]
    }

    /// The second derivative at `t`.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// assert_eq!(b.d2(0.0), [6.0, -12.0]); // 6 (b₀ − 2b₁ + b₂)
    /// assert_eq!(b.d2(0.5), [0.0, -12.0]);
    /// ```
    pub fn d2(&self, t: f64) -> [f64; 2] {
        let [a, b, c, d] = self.p;
        let u = [a[0] - 2.0 * b[0] + c[0], a[1] - 2.0 * b[1] + c[1]];
        let v = [b[0] - 2.0 * c[0] + d[0], b[1] - 2.0 * c[1] + d[1]];
        let q = lerp(u, v, t);
        [6.0 * q[0], 6.0 * q[1]]
    }

    /// The signed curvature at `t` (positive turns left); `NaN` where the speed vanishes.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// // at its top the arch runs along x at speed 4.5 and turns right: κ = −12 / 4.5²
    /// assert!((b.curvature(0.5) + 12.0 / 4.5f64.powi(2)).abs() < 1e-12);
    /// let line = Bezier { p: [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]] };
    /// assert_eq!(line.curvature(0.3), 0.0);
    /// ```
    pub fn curvature(&self, t: f64) -> f64 {
        let (d, dd) = (self.d1(t), self.d2(t));
        let speed = d[0].hypot(d[1]);
        (d[0] * dd[1] - d[1] * dd[0]) / (speed * speed * speed)
    }

    /// Arc length from 0 to `t`.
    ///
    /// ```
    /// use design::Bezier;
    /// // a line whose control points bunch up towards the end: its speed varies, its length
    /// // does not
    /// let line = Bezier { p: [[0.0, 0.0], [2.0, 0.0], [2.5, 0.0], [3.0, 0.0]] };
    /// assert!((line.length() - 3.0).abs() < 1e-12);
    /// assert!((line.length_to(0.5) - line.point(0.5)[0]).abs() < 1e-12);
    /// ```
    pub fn length_to(&self, t: f64) -> f64 {
        let n = ((PIECES as f64 * t.abs()).ceil() as usize).max(1);
        let h = t / n as f64;
        let mut s = 0.0;
        for i in 0..n {
            let mid = (i as f64 + 0.5) * h;
            for (x, w) in GAUSS {
                let d = self.d1(mid + 0.5 * h * x);
                s += w * d[0].hypot(d[1]);
            }
        }
        0.5 * h * s
    }

    /// The whole length.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let polygon = 2.0 * 5f64.sqrt() + 2.0;
    /// assert!(b.length() > 4.0 && b.length() < polygon); // between its chord and its polygon
    /// ```
    pub fn length(&self) -> f64 {
        self.length_to(1.0)
    }

    /// The arc length between parameters `a` and `b` by one 5-point Gauss–Legendre rule
    /// (accurate on an interval no wider than one of the [`PIECES`] panels).
    fn length_between(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = 0.0;
        for (x, w) in GAUSS {
            let d = self.d1(mid + half * x);
            s += w * d[0].hypot(d[1]);
        }
        half * s
    }

    /// The cumulative arc length at the panel ends `k / PIECES`, for sampling the curve at
    /// many arc lengths ([`ArcTable::at_length`]): built once, each lookup then costs a
    /// few Gauss rules on one panel instead of integrating from the start each time.
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let table = b.arc_table();
    /// for s in [0.5, 1.0, 2.5] {
    ///     assert!((b.length_to(table.at_length(s)) - s).abs() < 1e-12);
    /// }
    /// ```
    pub fn arc_table(&self) -> ArcTable {
        let mut cumulative = Vec::with_capacity(PIECES + 1);
        cumulative.push(0.0);
        for k in 0..PIECES {
            let (a, b) = (k as f64 / PIECES as f64, (k + 1) as f64 / PIECES as f64);
            cumulative.push(cumulative[k] + self.length_between(a, b));
        }
        ArcTable {
            bezier: *self,
            cumulative,
        }
    }

    /// The parameter at arc length `s` from the start (Newton on the length, bisection
    /// safeguarded; `s` clamped to the curve).
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let t = b.at_length(1.0);
    /// assert!((b.length_to(t) - 1.0).abs() < 1e-12);
    /// assert!((b.at_length(0.5 * b.length()) - 0.5).abs() < 1e-12); // the symmetric middle
    /// ```
    pub fn at_length(&self, s: f64) -> f64 {
        let total = self.length();
        let s = s.clamp(0.0, total);
        let (mut lo, mut hi, mut t) = (0.0f64, 1.0f64, s / total.max(f64::MIN_POSITIVE));
        for _ in 0..60 {
            let f = self.length_to(t) - s;
            if f.abs() <= 1e-14 * total {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let d = self.d1(t);
            let next = t - f / d[0].hypot(d[1]);
            t = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
        }
        t
    }

    /// Tangent angle at the start: the direction of the first leg (or of the next nonzero
    /// one when legs collapse).
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// assert_eq!(b.start_angle()?, 2f64.atan2(1.0));
    /// // a collapsed first leg: the direction towards b₂
    /// let c = Bezier { p: [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0], [2.0, 0.0]] };
    /// assert_eq!(c.start_angle()?, std::f64::consts::FRAC_PI_4);
    /// assert!(Bezier { p: [[1.0, 1.0]; 4] }.start_angle().is_err());
    /// # Ok::<(), design::DesignError>(())
    /// ```
    ///
    /// # Errors
    /// [`DesignError::Invalid`] when all control points coincide.
    pub fn start_angle(&self) -> Result<f64> {
        let [a, b, c, d] = self.p;
        first_direction(&[sub(b, a), sub(c, a), sub(d, a)])
    }

    /// Tangent angle at the end: the direction of the last leg (or of the previous nonzero
    /// one).
    ///
    /// ```
    /// use design::Bezier;
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// assert_eq!(b.end_angle()?, (-2f64).atan2(1.0));
    /// # Ok::<(), design::DesignError>(())
    /// ```
    ///
    /// # Errors
    /// [`DesignError::Invalid`] when all control points coincide.
    pub fn end_angle(&self) -> Result<f64> {
        let [a, b, c, d] = self.p;
        first_direction(&[sub(d, c), sub(d, b), sub(d, a)])
    }

    /// The end tangent angle unwrapped along the curve: the start angle plus the total
    /// turning ∫κ ds, so that a curve turning by more than π keeps its true turn.
    ///
    /// ```
    /// use design::Bezier;
    /// use std::f64::consts::TAU;
    /// // a hook turning left by more than half a turn: the end leg points back and down
    /// let hook = Bezier { p: [[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 1.0]] };
    /// let (wrapped, unwrapped) = (hook.end_angle()?, hook.end_angle_unwrapped()?);
    /// assert!(wrapped < 0.0);
    /// assert!((unwrapped - (wrapped + TAU)).abs() < 1e-12);
    /// # Ok::<(), design::DesignError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Bezier::start_angle`].
    pub fn end_angle_unwrapped(&self) -> Result<f64> {
        let (a0, a1) = (self.start_angle()?, self.end_angle()?);
        let n = 256;
        let mut turn = 0.0;
        let mut previous = a0;
        for i in 1..=n {
            let t = i as f64 / n as f64;
            let d = self.d1(t);
            let a = if i == n || d[0].hypot(d[1]) == 0.0 {
                a1
            } else {
                d[1].atan2(d[0])
            };
            turn += wrap(a - previous);
            previous = a;
        }
        Ok(a0 + turn)
    }

    /// The interior angles of the control polygon at b₁ and b₂, radians in [0, π] (π: the
    /// legs in line; small: an acute, folded polygon); `NaN` at a collapsed leg.
    ///
    /// ```
    /// use design::Bezier;
    /// use std::f64::consts::PI;
    /// let line = Bezier { p: [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]] };
    /// assert_eq!(line.polygon_angles(), [PI, PI]);
    /// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
    /// let a = (-1.0 / 5f64.sqrt()).acos(); // between the legs (−1, −2) and (2, 0)
    /// assert!(b.polygon_angles().iter().all(|x| (x - a).abs() < 1e-12));
    /// ```
    pub fn polygon_angles(&self) -> [f64; 2] {
        let [a, b, c, d] = self.p;
        let angle = |u: [f64; 2], v: [f64; 2]| {
            let (nu, nv) = (u[0].hypot(u[1]), v[0].hypot(v[1]));
            ((u[0] * v[0] + u[1] * v[1]) / (nu * nv))
                .clamp(-1.0, 1.0)
                .acos()
        };
        [angle(sub(a, b), sub(c, b)), angle(sub(b, c), sub(d, c))]
    }
}

/// The angle of the first vector in `v` that is not zero.
fn first_direction(v: &[[f64; 2]]) -> Result<f64> {
    v.iter()
        .find(|d| d[0].hypot(d[1]) > 0.0)
        .map(|d| d[1].atan2(d[0]))
        .ok_or_else(|| DesignError::Invalid("the Bézier's control points coincide".into()))
}

/// An angle less whole turns, within (−π, π] ([`geom::polyline::principal_angle`]).
pub use geom::polyline::principal_angle as wrap;
