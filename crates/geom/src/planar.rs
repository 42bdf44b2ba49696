//! Planar curves: the [`PlanarCurve`](crate::planar::PlanarCurve) capability trait,
//! signed curvature (eq. 1.8), arc length and arc-length reparameterisation.
//!
//! Entry points: [`PlanarCurve`](crate::planar::PlanarCurve) (implemented by
//! [`SplineCurve2`](crate::planar::SplineCurve2) and by height-field sections),
//! [`signed_curvature`](crate::planar::signed_curvature),
//! [`ArcLength`](crate::planar::ArcLength). Inflections and curvature maxima are in
//! [`crate::analysis`].

use nalgebra::Vector2;

use crate::bspline::BSplineCurve;

/// Position and first two derivatives of a planar curve at one parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet2 {
    /// Point `c(t)`.
    pub p: Vector2<f64>,
    /// First derivative `c'(t)`.
    pub d1: Vector2<f64>,
    /// Second derivative `c''(t)`.
    pub d2: Vector2<f64>,
}

/// A regular parametric planar curve with two derivatives.
pub trait PlanarCurve {
    /// Parameter domain `[a, b]`, `a < b`.
    fn domain(&self) -> (f64, f64);
    /// Point and derivatives at `t`.
    fn jet(&self, t: f64) -> Jet2;
    /// The point at `t`.
    fn point(&self, t: f64) -> Vector2<f64> {
        self.jet(t).p
    }
    /// The first derivative at `t` (what arc length needs): `jet(t).d1`, which a curve may
    /// compute alone, faster.
    fn velocity(&self, t: f64) -> Vector2<f64> {
        self.jet(t).d1
    }
}

/// Signed curvature `det(c', c'') / |c'|³` (eq. 1.8); left turns are positive. Zero where the
/// curve is not regular (`c' = 0`).
pub fn signed_curvature(j: &Jet2) -> f64 {
    let speed = j.d1.norm();
    if speed <= f64::MIN_POSITIVE.sqrt() {
        return 0.0;
    }
    let k = (j.d1.x * j.d2.y - j.d1.y * j.d2.x) / (speed * speed * speed);
    if k.is_finite() {
        k
    } else {
        0.0
    }
}

/// A planar B-spline curve with its derivative curves precomputed.
#[derive(Debug, Clone)]
pub struct SplineCurve2 {
    curve: BSplineCurve<2>,
    d1: BSplineCurve<2>,
    d2: BSplineCurve<2>,
}

impl SplineCurve2 {
    /// Wraps a planar B-spline.
    pub fn new(curve: BSplineCurve<2>) -> Self {
        let d1 = curve.derivative();
        let d2 = d1.derivative();
        Self { curve, d1, d2 }
    }

    /// The underlying B-spline.
    pub fn spline(&self) -> &BSplineCurve<2> {
        &self.curve
    }
}

impl PlanarCurve for SplineCurve2 {
    fn domain(&self) -> (f64, f64) {
        self.curve.domain()
    }
    fn jet(&self, t: f64) -> Jet2 {
        Jet2 {
            p: self.curve.eval(t),
            d1: self.d1.eval(t),
            d2: self.d2.eval(t),
        }
    }
    fn velocity(&self, t: f64) -> Vector2<f64> {
        self.d1.eval(t)
    }
}

/// Cumulative arc length of a curve, tabulated by 5-point Gauss–Legendre quadrature on
/// `pieces` equal parameter intervals; `s(t)` and its inverse `t(s)` are then evaluated by
/// local quadrature and Newton steps, so the table only brackets.
#[derive(Debug, Clone)]
pub struct ArcLength {
    ts: Vec<f64>,
    ss: Vec<f64>,
}

const GL_X: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683,
    0.0,
    0.538_469_310_105_683,
    0.906_179_845_938_664,
];
const GL_W: [f64; 5] = [
    0.236_926_885_056_189,
    0.478_628_670_499_366,
    0.568_888_888_888_889,
    0.478_628_670_499_366,
    0.236_926_885_056_189,
];

fn gauss_length(curve: &dyn PlanarCurve, a: f64, b: f64) -> f64 {
    let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
    GL_X.iter()
        .zip(GL_W)
        .map(|(x, w)| w * curve.velocity(m + h * x).norm())
        .sum::<f64>()
        * h
}

impl ArcLength {
    /// Tabulates the arc length with `pieces` intervals (at least 1).
    pub fn new(curve: &dyn PlanarCurve, pieces: usize) -> Self {
        let (a, b) = curve.domain();
        Self::between(curve, a, b, pieces)
    }

    /// Tabulates the arc length of the part `[a, b]` of the curve's domain only (`s = 0` at
    /// `a`; `s_at` and `t_at` clamp to that part), with `pieces` intervals (at least 1).
    pub fn between(curve: &dyn PlanarCurve, a: f64, b: f64, pieces: usize) -> Self {
        let pieces = pieces.max(1);
        let mut ts = Vec::with_capacity(pieces + 1);
        let mut ss = Vec::with_capacity(pieces + 1);
        let mut acc = 0.0;
        ts.push(a);
        ss.push(0.0);
        for k in 1..=pieces {
            let t0 = a + (b - a) * (k - 1) as f64 / pieces as f64;
            let t1 = a + (b - a) * k as f64 / pieces as f64;
            acc += gauss_length(curve, t0, t1);
            ts.push(t1);
            ss.push(acc);
        }
        Self { ts, ss }
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        self.ss.last().copied().unwrap_or(0.0)
    }

    /// Arc length from the start to parameter `t`.
    pub fn s_at(&self, curve: &dyn PlanarCurve, t: f64) -> f64 {
        let t = t.clamp(self.ts[0], self.ts[self.ts.len() - 1]);
        let i = match self.ts.binary_search_by(|x| x.total_cmp(&t)) {
            Ok(i) => return self.ss[i],
            Err(i) => i.saturating_sub(1).min(self.ts.len() - 2),
        };
        self.ss[i] + gauss_length(curve, self.ts[i], t)
    }

    /// The parameter at arc length `s` (clamped to `[0, length]`): the arc-length
    /// reparameterisation `t(s)`.
    pub fn t_at(&self, curve: &dyn PlanarCurve, s: f64) -> f64 {
        let s = s.clamp(0.0, self.length());
        let i = match self.ss.binary_search_by(|x| x.total_cmp(&s)) {
            Ok(i) => return self.ts[i],
            Err(i) => i.saturating_sub(1).min(self.ss.len() - 2),
        };
        let (t0, t1) = (self.ts[i], self.ts[i + 1]);
        let (s0, s1) = (self.ss[i], self.ss[i + 1]);
        let mut t = if s1 > s0 {
            t0 + (t1 - t0) * (s - s0) / (s1 - s0)
        } else {
            t0
        };
        for _ in 0..8 {
            let err = s0 + gauss_length(curve, t0, t) - s;
            let speed = curve.velocity(t).norm();
            if speed <= 0.0 {
                break;
            }
            let next = (t - err / speed).clamp(t0, t1);
            if (next - t).abs() <= 1e-15 * (1.0 + t.abs()) {
                t = next;
                break;
            }
            t = next;
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Circle of radius 3 on [0, 2]: arc length 3t.
    struct Circle;
    impl PlanarCurve for Circle {
        fn domain(&self) -> (f64, f64) {
            (0.0, 2.0)
        }
        fn jet(&self, t: f64) -> Jet2 {
            let (s, c) = t.sin_cos();
            Jet2 {
                p: Vector2::new(3.0 * c, 3.0 * s),
                d1: Vector2::new(-3.0 * s, 3.0 * c),
                d2: Vector2::new(-3.0 * c, -3.0 * s),
            }
        }
    }

    #[test]
    fn arc_length_of_the_whole_curve_and_of_a_part() {
        let whole = ArcLength::new(&Circle, 16);
        assert!((whole.length() - 6.0).abs() < 1e-13);
        assert!((whole.s_at(&Circle, 0.7) - 2.1).abs() < 1e-13);
        let part = ArcLength::between(&Circle, 0.5, 1.25, 8);
        assert!((part.length() - 2.25).abs() < 1e-13);
        assert!((part.s_at(&Circle, 1.0) - 1.5).abs() < 1e-13);
        assert!((part.t_at(&Circle, 1.5) - 1.0).abs() < 1e-13);
        // clamped to the part
        assert_eq!(part.s_at(&Circle, 0.1), 0.0);
        assert!((part.t_at(&Circle, 9.0) - 1.25).abs() < 1e-15);
    }
}
