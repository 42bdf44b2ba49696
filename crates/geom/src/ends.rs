//! What the data say about the curvature at the ends of a sampled curve.
//!
//! A smoothing spline fitted to a polyline has, inside its first and last few segments,
//! curvature set by its penalty rather than by the points (the penalty pulls it towards
//! zero there). An inflection a few millimetres from a section's end is then lost. This
//! module reads the curvature at each end from a local cubic least-squares fit to the
//! last [`END_WINDOW`](crate::ends::END_WINDOW) points instead, with its standard error, so that
//! [`analyze_curve`](crate::analysis::analyze_curve) can restore an end inflection that the
//! data show and the spline does not.
//!
//! Written here rather than taken from a crate: it is a 4-parameter least-squares fit in a
//! local frame, and the point is its error estimate, which ties the decision to the data.

use nalgebra::{Matrix4, Vector2, Vector4};

/// Number of points the local fit at each end uses, at least.
pub const END_WINDOW: usize = 16;

/// The share of the curve's parameter length the local fit at an end spans when its
/// [`END_WINDOW`] points show no significant curvature (and it holds more of them).
pub const END_SPAN: f64 = 0.03;

/// The curvature at one end of a sampled curve, from a local cubic fit to its last points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndTrend {
    /// Signed curvature at the end point (the curve's orientation, first to last point).
    pub curvature: f64,
    /// Parameter distance from the end to where the local fit's curvature is zero, when
    /// that lies within the fitted points.
    pub zero_at: Option<f64>,
    /// Parameter length the local fit spans.
    pub window: f64,
    /// The standard error of `curvature`, from the fit's residuals.
    pub standard_error: f64,
}

/// How many standard errors the end curvature must lie from zero to count.
pub const SIGNIFICANCE: f64 = 3.0;

/// Curvature trends at the start and at the end of the open polyline `points` (parameters
/// `params`, e.g. chord length). `None` at an end when there are too few points, the
/// points fold back within the window, or the curvature there is not significantly
/// different from zero (the fit's residuals say how well it is known).
pub fn end_trends(points: &[Vector2<f64>], params: &[f64]) -> (Option<EndTrend>, Option<EndTrend>) {
    let n = points.len();
    if n < 2 * END_WINDOW || params.len() != n {
        return (None, None);
    }
    // END_WINDOW points; where their curvature is not significant, as many as lie within
    // END_SPAN of the curve's parameter length from the end (a fine polyline's 16 points
    // may span too little of the curve to show its curvature above their chordal noise),
    // at most n/4
    let total = params[n - 1] - params[0];
    let reach = END_SPAN * total;
    let cap = (n / 4).max(END_WINDOW);
    let wide0 = params
        .partition_point(|&t| t <= params[0] + reach)
        .clamp(END_WINDOW, cap);
    let wide1 = (n - params.partition_point(|&t| t < params[n - 1] - reach)).clamp(END_WINDOW, cap);
    // the wide window speaks only of a zero beyond the narrow one: nearer the end, the
    // narrow window's points saw nothing significant
    let narrow0 = params[END_WINDOW - 1] - params[0];
    let narrow1 = params[n - 1] - params[n - END_WINDOW];
    let start = local_fit(&points[..END_WINDOW], true)
        .map(|fit| (fit, END_WINDOW))
        .or_else(|| {
            local_fit(&points[..wide0], true)
                .filter(|f| wide0 > END_WINDOW && f.2.is_some_and(|z| z > narrow0))
                .map(|fit| (fit, wide0))
        })
        .map(|((k, se, zero, _), w)| EndTrend {
            curvature: k,
            zero_at: zero,
            window: params[w - 1] - params[0],
            standard_error: se,
        });
    let end = local_fit(&points[n - END_WINDOW..], false)
        .map(|fit| (fit, END_WINDOW))
        .or_else(|| {
            local_fit(&points[n - wide1..], false)
                .filter(|f| wide1 > END_WINDOW && f.2.is_some_and(|z| f.3 - z > narrow1))
                .map(|fit| (fit, wide1))
        })
        .map(|((k, se, zero, len), w)| EndTrend {
            curvature: k,
            zero_at: zero.map(|z| len - z),
            window: params[n - 1] - params[n - w],
            standard_error: se,
        });
    (start, end)
}

/// Cubic fit η(ξ) over the window's chord frame. Returns the curvature at the first
/// (`at_start`) or last point and its standard error, the chord distance ξ of the
/// curvature's zero from the window's first point (if inside the window) and the window's
/// chord length.
fn local_fit(w: &[Vector2<f64>], at_start: bool) -> Option<(f64, f64, Option<f64>, f64)> {
    let (first, last) = (w.first()?, w.last()?);
    let chord = last - first;
    let len = chord.norm();
    if !(len > 0.0) || !len.is_finite() {
        return None;
    }
    let d = chord / len;
    let nrm = Vector2::new(-d.y, d.x);
    let uv: Vec<(f64, f64)> = w
        .iter()
        .map(|p| ((p - first).dot(&d) / len, (p - first).dot(&nrm) / len))
        .collect();
    // the window must be a graph over its chord: no step back along it (a slice through
    // a mesh's vertex region may give crossings a hair out of order, 10⁻⁹ of the window;
    // those are not a fold)
    if uv.windows(2).any(|q| !(q[1].0 > q[0].0 - 1e-6)) {
        return None;
    }
    let mut ata = Matrix4::zeros();
    let mut atb = Vector4::zeros();
    for &(u, v) in &uv {
        let row = Vector4::new(1.0, u, u * u, u * u * u);
        ata += row * row.transpose();
        atb += row * v;
    }
    let inv = ata.try_inverse()?;
    let c = inv * atb;
    let rss: f64 = uv
        .iter()
        .map(|&(u, v)| {
            let r = v - (c[0] + c[1] * u + c[2] * u * u + c[3] * u * u * u);
            r * r
        })
        .sum();
    let dof = (uv.len() - 4) as f64;
    let s2 = rss / dof;
    let ue = if at_start { 0.0 } else { uv[uv.len() - 1].0 };
    // η'' (in window units) at the end, its variance, and the curvature
    let g = Vector4::new(0.0, 0.0, 2.0, 6.0 * ue);
    let second = g.dot(&c);
    let var = s2 * (g.transpose() * inv * g)[0];
    let slope = c[1] + 2.0 * c[2] * ue + 3.0 * c[3] * ue * ue;
    let kappa_unit = second / (1.0 + slope * slope).powf(1.5);
    // significant against the residuals, and above rounding of the unit-scaled fit
    if !(second.abs() > SIGNIFICANCE * var.max(0.0).sqrt()) || !(second.abs() > 1e-9) {
        return None;
    }
    let zero = (c[3] != 0.0)
        .then(|| -c[2] / (3.0 * c[3]))
        .filter(|u| *u > 0.0 && *u < uv[uv.len() - 1].0)
        .map(|u| u * len);
    let se = var.max(0.0).sqrt() / (1.0 + slope * slope).powf(1.5) / len;
    Some((kappa_unit / len, se, zero, len))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y = x³ − a x: curvature 6x/(…) changes sign at x = 0.
    fn cubic(x0: f64, x1: f64, n: usize) -> (Vec<Vector2<f64>>, Vec<f64>) {
        let pts: Vec<Vector2<f64>> = (0..n)
            .map(|i| {
                let x = x0 + (x1 - x0) * i as f64 / (n - 1) as f64;
                Vector2::new(x, 0.3 * x * x * x - 0.2 * x)
            })
            .collect();
        let t = crate::fit::chord_length_params(&pts);
        (pts, t)
    }

    #[test]
    fn finds_the_sign_and_zero_of_the_curvature_at_both_ends() {
        // inflection at x = 0, inside the first window; the end is far from it
        let (p, t) = cubic(-0.004, 2.0, 4000);
        let (s, e) = end_trends(&p, &t);
        let s = s.unwrap();
        assert!(s.curvature < 0.0, "{s:?}");
        // the zero's distance along the window's chord: 0.004 along x, slope ≈ −0.2
        let z = s.zero_at.unwrap();
        let want = 0.004 * (1.0f64 + 0.04).sqrt();
        assert!((z - want).abs() < 1e-3 * want, "{z} vs {want}");
        let e = e.unwrap();
        assert!(e.curvature > 0.0 && e.zero_at.is_none(), "{e:?}");
        // exact: κ = y''/(1+y'²)^1.5 at x = 2
        let (d1, d2) = (0.9 * 4.0 - 0.2, 1.8 * 2.0);
        let k = d2 / (1.0f64 + d1 * d1).powf(1.5);
        assert!((e.curvature - k).abs() < 1e-3 * k, "{} vs {k}", e.curvature);
    }

    #[test]
    fn a_straight_line_has_no_trend_and_reversal_flips_the_sign() {
        let pts: Vec<Vector2<f64>> = (0..40)
            .map(|i| Vector2::new(i as f64, 2.0 * i as f64))
            .collect();
        let t = crate::fit::chord_length_params(&pts);
        assert_eq!(end_trends(&pts, &t), (None, None));
        let (p, t) = cubic(0.5, 2.0, 100);
        let (s, _) = end_trends(&p, &t);
        let rev: Vec<_> = p.iter().rev().copied().collect();
        let (_, e) = end_trends(&rev, &crate::fit::chord_length_params(&rev));
        let (s, e) = (s.unwrap(), e.unwrap());
        assert!((s.curvature + e.curvature).abs() < 1e-9 * s.curvature.abs());
    }

    #[test]
    fn curvature_scales_with_units_and_ignores_rigid_motion() {
        let (p, t) = cubic(-0.004, 2.0, 4000);
        let (s0, e0) = end_trends(&p, &t);
        let (s0, e0) = (s0.unwrap(), e0.unwrap());
        let (c, sn) = (0.6f64.cos(), 0.6f64.sin());
        for scale in [1e-3, 1.0, 1e3] {
            let q: Vec<Vector2<f64>> = p
                .iter()
                .map(|v| {
                    scale * Vector2::new(c * v.x - sn * v.y, sn * v.x + c * v.y)
                        + Vector2::new(7.0, -3.0) * scale
                })
                .collect();
            let (s, e) = end_trends(&q, &crate::fit::chord_length_params(&q));
            let (s, e) = (s.unwrap(), e.unwrap());
            for (a, b) in [(s, s0), (e, e0)] {
                assert!((a.curvature * scale - b.curvature).abs() < 1e-6 * b.curvature.abs());
                assert!((a.window / scale - b.window).abs() < 1e-9 * b.window);
            }
            let z = s.zero_at.unwrap() / scale;
            assert!((z - s0.zero_at.unwrap()).abs() < 1e-6 * z);
        }
    }

    #[test]
    fn too_few_points_say_nothing() {
        let (p, t) = cubic(-1.0, 1.0, 2 * END_WINDOW - 1);
        assert_eq!(end_trends(&p, &t), (None, None));
    }
}
