//! How close a cubic Bézier is to the elastica with its end points, end tangents and
//! length ("Designing for Robotic Hot-Blade Cutting" §4, fig. 12): the deviation at equal
//! arc length, the elastica's largest curvature and inflections, and the residual of the
//! affine curvature law of an elastica, κ = λ₂x − λ₁y + α ("Hot Blade Cuttings" eq. 11),
//! fitted on the Bézier by least squares — zero for an elastica, so a cheap predictor of
//! the deviation before any elastica is solved.

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

use crate::bezier::Bezier;
use crate::bvp::{solve, EndData};
use crate::error::{DesignError, Result};
use elastica::segment::Segment;

/// Samples along the curve for the deviation and the eq. (11) fit.
pub const SAMPLES: usize = 200;

/// A Bézier against its elastica.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Proxy {
    /// The elastica, t ∈ [0, 1] from b₀ to b₃.
    pub elastica: Segment,
    /// The Bézier's length.
    pub length: f64,
    /// Largest distance between the two curves at the same arc length.
    pub max_deviation: f64,
    /// Root mean square of that distance over arc length.
    pub rms_deviation: f64,
    /// Distance between the elastica's ends and b₀, b₃ (the larger).
    pub end_point_error: f64,
    /// Difference of the end tangent angles (the larger), radians.
    pub end_angle_error: f64,
    /// The elastica's length against the Bézier's, relative.
    pub relative_length_error: f64,
    /// The elastica's largest |κ|.
    pub max_curvature: f64,
    /// The elastica's inflections inside (0, 1).
    pub inflections: usize,
    /// RMS residual of κ ≈ λ₂x − λ₁y + α fitted on the Bézier, times its length
    /// (dimensionless).
    pub eq11_residual: f64,
    /// The interior angles of the control polygon, degrees.
    pub polygon_angles_deg: [f64; 2],
    /// The discrete elastica's largest distance from the closed form.
    pub discrete_distance: f64,
}

/// The Bézier's end data.
///
/// # Errors
/// [`DesignError::Invalid`] for coincident control points.
pub fn end_data(b: &Bezier) -> Result<EndData> {
    Ok(EndData {
        start: b.p[0],
        start_angle: b.start_angle()?,
        end: b.p[3],
        end_angle: b.end_angle_unwrapped()?,
        length: b.length(),
    })
}

/// The eq. (11) residual of `b`: κ fitted by λ₂x − λ₁y + α over [`SAMPLES`] points evenly
/// spaced in arc length (coordinates about their centroid), the RMS residual times the
/// length.
pub fn eq11_residual(b: &Bezier) -> f64 {
    let length = b.length();
    let rows: Vec<([f64; 2], f64)> = (0..=SAMPLES)
        .map(|i| {
            let t = b.at_length(length * i as f64 / SAMPLES as f64);
            (b.point(t), b.curvature(t))
        })
        .collect();
    affine_curvature_residual(&rows, length)
}

/// The eq. (11) residual of a curve of `length` sampled at `rows` (point, curvature),
/// evenly along it: κ fitted by λ₂x − λ₁y + α by least squares (coordinates about their
/// centroid), the RMS residual times the length. NaN when the fit is singular.
pub fn affine_curvature_residual(rows: &[([f64; 2], f64)], length: f64) -> f64 {
    let n = rows.len() as f64;
    let c = rows
        .iter()
        .fold([0.0, 0.0], |c, (p, _)| [c[0] + p[0] / n, c[1] + p[1] / n]);
    let (mut a, mut y) = (Matrix3::zeros(), Vector3::zeros());
    for (p, k) in rows {
        let v = Vector3::new(p[0] - c[0], -(p[1] - c[1]), 1.0);
        a += v * v.transpose();
        y += v * *k;
    }
    let Some(x) = a.lu().solve(&y) else {
        return f64::NAN;
    };
    let ss: f64 = rows
        .iter()
        .map(|(p, k)| {
            let fit = x[0] * (p[0] - c[0]) - x[1] * (p[1] - c[1]) + x[2];
            (k - fit).powi(2)
        })
        .sum();
    (ss / n).sqrt() * length
}

/// The Bézier `b` against its elastica.
///
/// # Errors
/// [`DesignError::Invalid`] for a degenerate Bézier (collapsed, straight); the errors of
/// [`solve`].
pub fn proxy(b: &Bezier) -> Result<Proxy> {
    let d = end_data(b)?;
    let sol = solve(&d)?;
    let e = sol
        .segment
        .evaluator()
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    let (mut max, mut ss) = (0.0f64, 0.0);
    for i in 0..=SAMPLES {
        let w = i as f64 / SAMPLES as f64;
        let p = b.point(b.at_length(d.length * w));
        let q = e.eval(w).p;
        let dist = (p[0] - q[0]).hypot(p[1] - q[1]);
        max = max.max(dist);
        // trapezoid weights over arc length
        let weight = if i == 0 || i == SAMPLES { 0.5 } else { 1.0 };
        ss += weight * dist * dist / SAMPLES as f64;
    }
    let (a, z) = (e.eval(0.0), e.eval(1.0));
    let gap = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
    let inflections = sol
        .segment
        .inflections()
        .map_err(|e| DesignError::Elastica(e.to_string()))?
        .len();
    let max_curvature = sol
        .segment
        .max_abs_curvature()
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    Ok(Proxy {
        elastica: sol.segment,
        length: d.length,
        max_deviation: max,
        rms_deviation: ss.sqrt(),
        end_point_error: gap(a.p, d.start).max(gap(z.p, d.end)),
        end_angle_error: crate::bezier::wrap(a.angle - d.start_angle)
            .abs()
            .max(crate::bezier::wrap(z.angle - d.end_angle).abs()),
        relative_length_error: sol.segment.length() / d.length - 1.0,
        max_curvature,
        inflections,
        eq11_residual: eq11_residual(b),
        polygon_angles_deg: b.polygon_angles().map(f64::to_degrees),
        discrete_distance: sol.discrete_distance,
    })
}
