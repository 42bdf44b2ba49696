//! The circular arc (or straight line) through a curve's two end points that fits its
//! points best: the simplest blade shape, a stable equilibrium carrying no force. A fit
//! may prefer an elastica that follows noise or a slight wave more closely and whose
//! extension to the blade's length then waves too (many inflections, unstable); where the
//! arc is within the tolerance, the blade can take it instead.

use super::FitResult;
use crate::segment::Segment;

/// Largest turning of the arc between the ends, radians.
const MAX_TURN: f64 = 3.0;

/// |distance| of the point `(x, y)` (chord frame: the ends at `(±c/2, 0)`) from the
/// circle through the ends that turns by `tau` between them, exact as `tau → 0`.
fn distance(x: f64, y: f64, c: f64, tau: f64) -> f64 {
    let a = 0.5 * c;
    let kappa = 2.0 * (0.5 * tau).sin() / c;
    let g = kappa * (x * x + y * y - a * a) - 2.0 * y * (0.5 * tau).cos();
    g.abs() / (1.0 + (1.0 + kappa * g).max(0.0).sqrt())
}

/// The arc through `points`' first and last point (turning at most 3 rad between them)
/// whose distances to the points are least in the mean square, as a [`FitResult`]; its
/// `rms` weighs the points by their spacing along `s` (the points' arc lengths), `max` is
/// the largest distance. `None` for fewer than 2 points, coincident ends or values that
/// are not finite.
///
/// ```
/// use elastica::fit::arc_through_ends;
/// use elastica::Segment;
/// // points on a circle of radius 5 through (0, 0) and (6, 0), bulging down
/// let pts: Vec<[f64; 2]> = (0..=20)
///     .map(|i| {
///         let a = -0.6435 + 1.287 * i as f64 / 20.0;
///         [3.0 + 5.0 * a.sin(), 4.0 - 5.0 * a.cos()]
///     })
///     .collect();
/// let s: Vec<f64> = (0..=20).map(|i| 5.0 * 1.287 * i as f64 / 20.0).collect();
/// let fit = arc_through_ends(&pts, &s).unwrap();
/// let Segment::Arc { curvature, .. } = fit.segment else { panic!() };
/// assert!((curvature - 0.2).abs() < 1e-4 && fit.max < 1e-3);
/// ```
pub fn arc_through_ends(points: &[[f64; 2]], s: &[f64]) -> Option<FitResult> {
    let n = points.len();
    if n < 2 || s.len() != n {
        return None;
    }
    let (p0, p1) = (points[0], points[n - 1]);
    let (dx, dy) = (p1[0] - p0[0], p1[1] - p0[1]);
    let c = dx.hypot(dy);
    if !(c > 0.0 && c.is_finite() && points.iter().flatten().all(|v| v.is_finite())) {
        return None;
    }
    let (ux, uy) = (dx / c, dy / c);
    let mid = [0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1])];
    let local: Vec<(f64, f64)> = points
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - mid[0], p[1] - mid[1]);
            (x * ux + y * uy, -x * uy + y * ux)
        })
        .collect();
    // weights: each point's share of the arc length (trapezoid)
    let total = s[n - 1] - s[0];
    let weight: Vec<f64> = (0..n)
        .map(|i| {
            let lo = if i > 0 { s[i] - s[i - 1] } else { 0.0 };
            let hi = if i + 1 < n { s[i + 1] - s[i] } else { 0.0 };
            0.5 * (lo + hi).max(0.0)
        })
        .collect();
    let wsum: f64 = weight.iter().sum();
    let wsum = if wsum > 0.0 { wsum } else { 1.0 };
    let cost = |tau: f64| -> f64 {
        local
            .iter()
            .zip(&weight)
            .map(|(&(x, y), w)| w * distance(x, y, c, tau).powi(2))
            .sum::<f64>()
            / wsum
    };
    // the turning of the circle through the ends and the middle point, then golden
    // section about it (a bounded number of steps)
    let (xm, ym) = local[n / 2];
    let start = {
        // the circle through (±a, 0) and (xm, ym) has its centre at (0, y_c), y_c =
        // (xm² + ym² − a²)/2ym, and turns by τ with tan(τ/2) = a/y_c between the ends
        let a = 0.5 * c;
        let den = xm * xm + ym * ym - a * a;
        let half = if den != 0.0 {
            (2.0 * a * ym / den).atan()
        } else {
            -std::f64::consts::FRAC_PI_2 * ym.signum()
        };
        (2.0 * half).clamp(-MAX_TURN, MAX_TURN)
    };
    let (mut lo, mut hi) = ((start - 0.5).max(-MAX_TURN), (start + 0.5).min(MAX_TURN));
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut fa, mut fb) = (cost(a), cost(b));
    for _ in 0..80 {
        if fa < fb {
            hi = b;
            (b, fb) = (a, fa);
            a = hi - r * (hi - lo);
            fa = cost(a);
        } else {
            lo = a;
            (a, fa) = (b, fb);
            b = lo + r * (hi - lo);
            fb = cost(b);
        }
    }
    let tau = 0.5 * (lo + hi);
    let kappa = 2.0 * (0.5 * tau).sin() / c;
    let half = 0.5 * tau;
    let length = if half.abs() < 1e-8 {
        c
    } else {
        c * half / half.sin()
    };
    let phi = uy.atan2(ux) - half;
    let segment = if tau == 0.0 {
        Segment::Line {
            x0: p0[0],
            y0: p0[1],
            phi,
            length,
        }
    } else {
        Segment::Arc {
            x0: p0[0],
            y0: p0[1],
            phi,
            curvature: kappa,
            length,
        }
    };
    let rms = cost(tau).sqrt();
    let max = local
        .iter()
        .map(|&(x, y)| distance(x, y, c, tau))
        .fold(0.0, f64::max);
    let t = local
        .iter()
        .map(|&(x, _)| ((x + 0.5 * c) / c).clamp(0.0, 1.0))
        .collect();
    Some(FitResult {
        segment,
        rms,
        max,
        l2: rms * total.max(0.0).sqrt(),
        input_length: total,
        iterations: 0,
        converged: true,
        t,
    })
}
