//! Discrete elastica ("Designing for Robotic Hot-Blade Cutting" §3.2, after Bruckstein et
//! al. 2001): a polyline of n equal segments between given end points, end tangents and
//! length that minimises the sum of squared turning angles.
//!
//! Unknowns are the segment directions θ₀ … θ_{n−1}; the turning angles are their
//! differences, with the end tangents as ghost directions θ_s, θ_e. The first and last turn
//! happen over half a segment, so they count twice — that keeps the discrete energy a
//! second-order approximation of ∫κ² ds and the vertices converge to the closed-form
//! elastica at O(h²). The end point is imposed by two equality constraints
//! `h Σ (cos θᵢ, sin θᵢ) = p_e − p_s`; the problem is solved by Newton's method on the
//! Lagrange (KKT) system with a merit-function line search, a direct solve instead of the
//! paper's two-loop gradient descent.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Boundary data and resolution of a discrete elastica.
#[derive(Clone, Debug)]
pub struct DiscreteParams {
    /// Number of equal segments (≥ 2).
    pub segments: usize,
    /// Start point.
    pub start: [f64; 2],
    /// Tangent angle at the start (radians).
    pub start_angle: f64,
    /// End point.
    pub end: [f64; 2],
    /// Tangent angle at the end (radians, unwrapped relative to the start).
    pub end_angle: f64,
    /// Curve length (> distance between the end points).
    pub length: f64,
    /// Newton iterations at most.
    pub max_iterations: usize,
}

/// A solved discrete elastica.
#[derive(Clone, Debug, Serialize)]
pub struct DiscreteElastica {
    /// The n + 1 vertices.
    pub points: Vec<[f64; 2]>,
    /// Direction of each segment.
    pub angles: Vec<f64>,
    /// Bending energy Σα²/h (approximates ∫κ² ds).
    pub energy: f64,
    /// Distance between the last vertex and the requested end point.
    pub end_error: f64,
    /// Newton iterations used.
    pub iterations: usize,
}

/// Why no discrete elastica was found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiscreteError {
    /// Bad input.
    #[error("invalid discrete elastica input: {0}")]
    Invalid(String),
    /// Newton's method did not reach the end point.
    #[error("no discrete elastica found: end point missed by {0}")]
    NotConverged(f64),
}

/// Solve for the discrete elastica.
///
/// ```
/// use elastica::discrete::{discrete_elastica, DiscreteParams};
/// // a symmetric arch: 1 unit wide, 1.2 long, leaving at +30° and arriving at −30°
/// let a = 30f64.to_radians();
/// let d = discrete_elastica(&DiscreteParams {
///     segments: 32, start: [0.0, 0.0], start_angle: a, end: [1.0, 0.0], end_angle: -a,
///     length: 1.2, max_iterations: 50,
/// }).unwrap();
/// assert!(d.end_error < 1e-12);
/// assert!((d.points[16][0] - 0.5).abs() < 1e-12); // symmetric
/// ```
pub fn discrete_elastica(p: &DiscreteParams) -> Result<DiscreteElastica, DiscreteError> {
    let n = p.segments;
    let finite = p.start.iter().chain(&p.end).all(|v| v.is_finite())
        && p.start_angle.is_finite()
        && p.end_angle.is_finite()
        && p.length.is_finite();
    if !finite {
        return Err(DiscreteError::Invalid("inputs must be finite".into()));
    }
    if n < 2 {
        return Err(DiscreteError::Invalid(format!(
            "need ≥ 2 segments, got {n}"
        )));
    }
    let dx = p.end[0] - p.start[0];
    let dy = p.end[1] - p.start[1];
    let chord = dx.hypot(dy);
    if !(p.length > chord) {
        return Err(DiscreteError::Invalid(format!(
            "length {} must exceed the chord {chord}",
            p.length
        )));
    }
    let h = p.length / n as f64;
    // start: a quadratic angle profile whose mean direction points along the chord
    let (ts, te) = (p.start_angle, p.end_angle);
    let chord_angle = ts
        + (dy.atan2(dx) - ts + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    let mut theta: Vec<f64> = (0..n)
        .map(|i| {
            let u = (i as f64 + 0.5) / n as f64;
            // Bernstein blend: ts, 3·mid-correction, te so the average is the chord angle
            let mid = (4.0 * chord_angle - ts - te) / 2.0;
            ts * (1.0 - u).powi(2) + 2.0 * mid * u * (1.0 - u) + te * u * u
        })
        .collect();
    let mut mu = [0.0f64; 2];
    let weights = |i: usize| if i == 0 || i == n { 2.0 } else { 1.0 };
    // gradient of E·h = Σ wᵢ αᵢ² with α₀ = θ₀ − θs, αᵢ = θᵢ − θᵢ₋₁, αₙ = θe − θₙ₋₁
    let alphas = |th: &[f64]| -> Vec<f64> {
        (0..=n)
            .map(|i| {
                if i == 0 {
                    th[0] - ts
                } else if i == n {
                    te - th[n - 1]
                } else {
                    th[i] - th[i - 1]
                }
            })
            .collect()
    };
    let residual = |th: &[f64], mu: &[f64; 2]| -> (DVector<f64>, f64) {
        let a = alphas(th);
        let mut r = DVector::zeros(n + 2);
        for i in 0..n {
            // ∂/∂θᵢ: from αᵢ (+) and αᵢ₊₁ (−)
            let g = 2.0 * (weights(i) * a[i] - weights(i + 1) * a[i + 1]);
            r[i] = g - mu[0] * h * th[i].sin() + mu[1] * h * th[i].cos();
        }
        let cx: f64 = th.iter().map(|t| h * t.cos()).sum::<f64>() - dx;
        let cy: f64 = th.iter().map(|t| h * t.sin()).sum::<f64>() - dy;
        r[n] = cx;
        r[n + 1] = cy;
        (r, cx.hypot(cy))
    };
    let mut iterations = 0;
    let (mut r, mut end_err) = residual(&theta, &mu);
    for it in 0..p.max_iterations {
        iterations = it;
        let rn = r.norm();
        if rn < 1e-13 * (1.0 + p.length) {
            break;
        }
        let mut k = DMatrix::<f64>::zeros(n + 2, n + 2);
        for i in 0..n {
            let (s, c) = theta[i].sin_cos();
            k[(i, i)] = 2.0 * (weights(i) + weights(i + 1)) - mu[0] * h * c - mu[1] * h * s;
            if i + 1 < n {
                k[(i, i + 1)] = -2.0 * weights(i + 1);
                k[(i + 1, i)] = -2.0 * weights(i + 1);
            }
            k[(i, n)] = -h * s;
            k[(n, i)] = -h * s;
            k[(i, n + 1)] = h * c;
            k[(n + 1, i)] = h * c;
        }
        let Some(step) = k.lu().solve(&(-&r)) else {
            break;
        };
        // backtracking on the KKT residual norm
        let mut lambda = 1.0;
        let mut improved = false;
        for _ in 0..30 {
            let th: Vec<f64> = (0..n).map(|i| theta[i] + lambda * step[i]).collect();
            let m = [mu[0] + lambda * step[n], mu[1] + lambda * step[n + 1]];
            let (rt, et) = residual(&th, &m);
            if rt.norm() < (1.0 - 1e-4 * lambda) * rn || rt.norm() < 1e-13 {
                theta = th;
                mu = m;
                r = rt;
                end_err = et;
                improved = true;
                break;
            }
            lambda *= 0.5;
        }
        if !improved {
            break;
        }
        iterations = it + 1;
    }
    if !(end_err < 1e-9 * p.length) {
        return Err(DiscreteError::NotConverged(end_err));
    }
    let mut points = Vec::with_capacity(n + 1);
    let mut q = p.start;
    points.push(q);
    for t in &theta {
        q = [q[0] + h * t.cos(), q[1] + h * t.sin()];
        points.push(q);
    }
    let a = alphas(&theta);
    let energy = (0..=n).map(|i| weights(i) * a[i] * a[i]).sum::<f64>() / h;
    Ok(DiscreteElastica {
        points,
        angles: theta,
        energy,
        end_error: end_err,
        iterations,
    })
}
