//! The elastica with given end points, end tangent angles and length: a boundary-value
//! problem ("Designing for Robotic Hot-Blade Cutting" §4, the elastica of a Bézier).
//!
//! Solved in closed form. A shape `(family, k, s₀, ℓ)` of the normalized elastica is
//! moved by the similarity that puts its ends on the given end points
//! (`Segment::elastica_between`), so the end points hold exactly; what remains are three
//! dimensionless equations — the start tangent against the given one, the total turning,
//! the length over the chord — in the three unknowns `(k, s₀, ℓ)`, solved by damped Newton
//! with a central-difference Jacobian. The start comes from the discrete elastica of the
//! same data ([`elastica::discrete`]) fitted by the closed form with its end points and
//! length ([`elastica::fit`]); the discrete curve is also the cross-check, to its O(h²).
//! Our own solver: the elastica crate fits points, not boundary data.
//!
//! Near the separatrix (k → 1, where the two families meet and the quarter period grows
//! without bound) the fitted start can fall on the wrong side; then the pendulum equation
//! is solved by shooting in (κ₀, λ₁, λ₂), which has no such singularity, and gives the
//! family, the modulus and the normalized length of the closed form exactly.
//!
//! Known limit (issue 22 in progress). Measured on random Béziers with a unit chord:
//! - legs 0.2–0.7 of the chord, end tangents 10°–60° and −40°–60°: 3000 of 3000 solved,
//!   each with its end data to 1e-9;
//! - legs down to 0.15, tangents to 85°: 1.5 % are not solved (`NoConvergence`), because
//!   neither start converges.

use elastica::discrete::{discrete_elastica, DiscreteParams};
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams, FitResult};
use elastica::segment::{ElasticaParams, Segment};
use elastica::unit::Family;
use serde::Serialize;

use crate::bezier::wrap;
use crate::error::{DesignError, Result};

/// The data an elastica must meet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EndData {
    /// Start point.
    pub start: [f64; 2],
    /// Tangent angle at the start, radians.
    pub start_angle: f64,
    /// End point.
    pub end: [f64; 2],
    /// Tangent angle at the end, radians, unwrapped along the curve (start angle plus the
    /// total turning).
    pub end_angle: f64,
    /// Length (> the distance between the end points).
    pub length: f64,
}

/// The solved elastica.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Solution {
    /// The closed-form segment, t ∈ [0, 1] from the start to the end.
    pub segment: Segment,
    /// Residuals: start angle (rad), total turning (rad), length relative to the given.
    pub residuals: [f64; 3],
    /// Largest distance between the discrete elastica's vertices and the closed form at
    /// the same arc length (the discretization's error, O(h²)).
    pub discrete_distance: f64,
    /// Newton iterations.
    pub iterations: usize,
}

/// Segments of the discrete elastica that starts and checks the solve.
pub const DISCRETE_SEGMENTS: usize = 64;
/// Largest Newton iterations.
const MAX_NEWTON: usize = 60;
/// Convergence of the residuals (radians and relative length).
const TOLERANCE: f64 = 1e-13;
/// Largest residual norm of an accepted solution. Newton reaches 10⁻¹³ but on nearly
/// taut curves (a blade under tension: length within 10⁻³ of the chord), whose modulus is
/// within 10⁻⁸ of 1 and so is represented in `f64` to only eight or nine digits of 1 − k;
/// there the residuals stall near 10⁻⁹.
pub const ACCEPT: f64 = 1e-8;

fn check(d: &EndData) -> Result<f64> {
    let finite = [
        d.start[0],
        d.start[1],
        d.end[0],
        d.end[1],
        d.start_angle,
        d.end_angle,
        d.length,
    ]
    .iter()
    .all(|v| v.is_finite());
    if !finite {
        return Err(DesignError::Invalid("end data not finite".into()));
    }
    let chord = (d.end[0] - d.start[0]).hypot(d.end[1] - d.start[1]);
    if !(chord > 0.0) || !(d.length > chord * (1.0 + 1e-12)) {
        return Err(DesignError::Invalid(format!(
            "the length {} must exceed the distance {chord} between the end points (a straight curve is a line, not a bent blade)",
            d.length
        )));
    }
    Ok(chord)
}

/// The segment of shape `x = (k, s₀, ℓ)` between the end points, and its residuals.
fn residuals(d: &EndData, family: Family, x: [f64; 3]) -> Option<(Segment, [f64; 3])> {
    let seg = Segment::elastica_between(family, x[0], x[1], x[2], d.start, d.end)?;
    let e = seg.evaluator().ok()?;
    let (a, b) = (e.eval(0.0), e.eval(1.0));
    let r = [
        wrap(a.angle - d.start_angle),
        (b.angle - a.angle) - (d.end_angle - d.start_angle),
        seg.length() / d.length - 1.0,
    ];
    r.iter().all(|v| v.is_finite()).then_some((seg, r))
}

fn norm(r: &[f64; 3]) -> f64 {
    r.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The modulus as Newton sees it: q = −ln(1 − k), so that shapes near the separatrix
/// (k → 1, where the quarter period grows like ln(4/√(1 − k²))) are as well scaled as the
/// others.
fn to_q(k: f64) -> f64 {
    -(1.0 - k).max(1e-17).ln()
}

fn from_q(q: f64) -> f64 {
    1.0 - (-q).exp()
}

/// Damped Newton on `(k, s₀, ℓ)` from `x` (in `(q, s₀, ℓ)`, see [`to_q`]).
fn newton(d: &EndData, family: Family, x: [f64; 3]) -> Option<(Segment, [f64; 3], usize)> {
    let res = |y: [f64; 3]| residuals(d, family, [from_q(y[0]), y[1], y[2]]);
    let mut y = [to_q(x[0].clamp(1e-9, 1.0)), x[1], x[2]];
    let (mut seg, mut r) = res(y)?;
    for it in 0..MAX_NEWTON {
        if norm(&r) <= TOLERANCE {
            return Some((seg, r, it));
        }
        let mut jac = nalgebra::Matrix3::zeros();
        for j in 0..3 {
            let h = 1e-7 * y[j].abs().max(1e-3);
            let (mut up, mut down) = (y, y);
            up[j] += h;
            down[j] -= h;
            // one-sided where a neighbour holds no curve
            let (ru, rd, width) = match (res(up), res(down)) {
                (Some(u), Some(v)) => (u.1, v.1, 2.0 * h),
                (Some(u), None) => (u.1, r, h),
                (None, Some(v)) => (r, v.1, h),
                (None, None) => return None,
            };
            for i in 0..3 {
                jac[(i, j)] = (ru[i] - rd[i]) / width;
            }
        }
        let step = jac.lu().solve(&nalgebra::Vector3::from(r))?;
        let mut w = 1.0;
        let mut accepted = false;
        for _ in 0..30 {
            let mut trial = [y[0] - w * step[0], y[1] - w * step[1], y[2] - w * step[2]];
            trial[0] = trial[0].clamp(to_q(1e-9), 40.0);
            if let Some((s, rt)) = res(trial) {
                if norm(&rt) < norm(&r) {
                    (y, seg, r, accepted) = (trial, s, rt, true);
                    break;
                }
            }
            w *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    (norm(&r) <= ACCEPT).then_some((seg, r, MAX_NEWTON))
}

/// Steps of the shooting integration (RK4; its error, O(h⁴), is far below the
/// tolerances on a unit chord).
const SHOOT_STEPS: usize = 2000;
/// Residual at which shooting stops: its solution only starts the closed form's Newton,
/// which converges from far rougher starts.
const SHOOT_ENOUGH: f64 = 1e-6;

/// The end of the elastica from the start of `d` with start curvature `u[0]` and
/// multipliers `(λ₁, λ₂) = (u[1], u[2])` (θ'' = λ₂ cos θ − λ₁ sin θ, "Hot Blade Cuttings"
/// eq. 3), integrated over the length: `(x, y, θ)`.
fn shoot_end(d: &EndData, u: [f64; 3]) -> [f64; 3] {
    let f = |y: [f64; 4]| {
        let (s, c) = y[2].sin_cos();
        [c, s, y[3], u[2] * c - u[1] * s]
    };
    let h = d.length / SHOOT_STEPS as f64;
    let mut y = [d.start[0], d.start[1], d.start_angle, u[0]];
    let add = |a: [f64; 4], b: [f64; 4], w: f64| std::array::from_fn(|i| a[i] + w * b[i]);
    for _ in 0..SHOOT_STEPS {
        let k1 = f(y);
        let k2 = f(add(y, k1, 0.5 * h));
        let k3 = f(add(y, k2, 0.5 * h));
        let k4 = f(add(y, k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    [y[0], y[1], y[2]]
}

/// The start curvature and the multipliers `(κ₀, λ₁, λ₂)` of the discrete elastica, from
/// the eq. (11) fit κ = λ₂x − λ₁y + α of its turning angles: the pendulum data of the
/// solution to the discretization's error.
fn discrete_pendulum(
    d: &EndData,
    discrete: &elastica::discrete::DiscreteElastica,
) -> Option<[f64; 3]> {
    let h = d.length / DISCRETE_SEGMENTS as f64;
    let (mut a, mut b) = (nalgebra::Matrix3::zeros(), nalgebra::Vector3::zeros());
    for j in 1..discrete.angles.len() {
        let p = discrete.points[j];
        let v = nalgebra::Vector3::new(p[0] - d.start[0], -(p[1] - d.start[1]), 1.0);
        a += v * v.transpose();
        b += v * ((discrete.angles[j] - discrete.angles[j - 1]) / h);
    }
    let g = a.lu().solve(&b)?;
    Some([g[2], g[1], g[0]])
}

/// The pendulum data `(κ₀, λ₁, λ₂)` of a closed-form segment: θ'' = −λ sin(θ − φ) with
/// λ = 1/S² and φ the segment's rotation (turned by π when it runs backwards).
fn pendulum_of(seg: &Segment) -> Option<[f64; 3]> {
    let Segment::Elastica(p) = seg else {
        return None;
    };
    let e = seg.evaluator().ok()?;
    let lambda = 1.0 / (p.scale * p.scale);
    let phi = p.phi + if p.l < 0.0 { std::f64::consts::PI } else { 0.0 };
    Some([
        e.eval(0.0).curvature,
        lambda * phi.cos(),
        lambda * phi.sin(),
    ])
}

/// [`shoot`] from `u`: Levenberg–Marquardt on the end point and the end angle.
fn shoot_from(d: &EndData, mut u: [f64; 3]) -> Option<[f64; 3]> {
    let res = |u: [f64; 3]| {
        let e = shoot_end(d, u);
        [e[0] - d.end[0], e[1] - d.end[1], e[2] - d.end_angle]
    };
    // Levenberg–Marquardt: robust from a rough start
    let mut r = res(u);
    let mut mu = 1e-3;
    for _ in 0..200 {
        if norm(&r) <= SHOOT_ENOUGH {
            return Some(u);
        }
        let mut jac = nalgebra::Matrix3::zeros();
        for j in 0..3 {
            let e = 1e-7 * u[j].abs().max(1.0);
            let (mut up, mut down) = (u, u);
            up[j] += e;
            down[j] -= e;
            let (ru, rd) = (res(up), res(down));
            for i in 0..3 {
                jac[(i, j)] = (ru[i] - rd[i]) / (2.0 * e);
            }
        }
        let jt = jac.transpose();
        let (jtj, jtr) = (jt * jac, jt * nalgebra::Vector3::from(r));
        let mut accepted = false;
        for _ in 0..40 {
            let m = jtj + nalgebra::Matrix3::identity() * (mu * jtj.diagonal().max().max(1e-300));
            if let Some(step) = m.lu().solve(&jtr) {
                let trial = [u[0] - step[0], u[1] - step[1], u[2] - step[2]];
                let rt = res(trial);
                if rt.iter().all(|v| v.is_finite()) && norm(&rt) < norm(&r) {
                    (u, r, accepted) = (trial, rt, true);
                    mu = (mu / 3.0).max(1e-15);
                    break;
                }
            }
            mu *= 4.0;
        }
        if !accepted {
            break;
        }
    }
    // a start for the closed form's Newton, which polishes it
    (norm(&r) <= 1e-4).then_some(u)
}

/// Closed-form starts from the shooting solution `u = (κ₀, λ₁, λ₂)`: the family and
/// modulus from the pendulum's first integral (κ²/2 − λ cos(θ − φ) constant, so
/// k̂² = (κ₀²/(2λ) − cos(θ₀ − φ) + 1)/2; inflectional when k̂ < 1, else modulus 1/k̂), the
/// normalized length √λ·L, and the start on the normalized curve searched on a grid for
/// the smallest residual, both ways along it.
fn closed_form_starts(d: &EndData, u: [f64; 3]) -> Vec<(Family, [f64; 3])> {
    let lambda = u[1].hypot(u[2]);
    if !(lambda > 1e-12) {
        return Vec::new();
    }
    let phi = u[2].atan2(u[1]);
    let khat2 = (u[0] * u[0] / (2.0 * lambda) - (d.start_angle - phi).cos() + 1.0) / 2.0;
    let (family, k) = if khat2 < 1.0 {
        (Family::Inflectional, khat2.max(0.0).sqrt())
    } else {
        (Family::NonInflectional, 1.0 / khat2.sqrt())
    };
    let k = k.clamp(1e-9, 1.0);
    let l = lambda.sqrt() * d.length;
    // near the separatrix, the other family's neighbour too
    let mut shapes = vec![(family, k)];
    if k > 0.999 {
        shapes.push((other(family), k));
    }
    let mut out = Vec::new();
    for (family, k) in shapes {
        let mut best: Option<(f64, [f64; 3])> = None;
        // a grid of s₀ ∈ [−80, 80] spaced 0.2 (a normalized curve's features are about
        // 1 long), then two finer grids about the best
        let (mut centre, mut half, steps) = (0.0, 80.0, 800);
        for _ in 0..3 {
            for sign in [1.0, -1.0] {
                for i in 0..=steps {
                    let s0 = centre - half + 2.0 * half * i as f64 / steps as f64;
                    let x = [k, s0, sign * l];
                    if let Some((_, r)) = residuals(d, family, x) {
                        if best.is_none_or(|b| norm(&r) < b.0) {
                            best = Some((norm(&r), x));
                        }
                    }
                }
            }
            let Some(b) = best else { break };
            (centre, half) = (b.1[1], 4.0 * half / steps as f64);
        }
        out.extend(best.map(|b| (family, b.1)));
    }
    out
}

/// The elastica of `d`.
///
/// ```
/// use design::bvp::{solve, EndData};
/// let d = EndData { start: [0.0, 0.0], start_angle: 0.4, end: [10.0, 0.0],
///     end_angle: -0.4, length: 10.5 };
/// let s = solve(&d).unwrap();
/// assert!(s.residuals.iter().all(|r| r.abs() < 1e-10));
/// assert!(s.discrete_distance < 1e-2);
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] for data that admit no bent elastica (not finite, length not
/// above the chord); [`DesignError::NoConvergence`] when Newton finds none.
pub fn solve(d: &EndData) -> Result<Solution> {
    let chord = check(d)?;
    // solved on the data moved to the unit chord from (0, 0) to (1, 0): the same numbers
    // wherever the curve lies and whatever its size, then mapped back
    let a = [d.end[0] - d.start[0], d.end[1] - d.start[1]];
    let turn = a[1].atan2(a[0]);
    let unit = EndData {
        start: [0.0, 0.0],
        start_angle: d.start_angle - turn,
        end: [1.0, 0.0],
        end_angle: d.end_angle - turn,
        length: d.length / chord,
    };
    let s = solve_unit(&unit)?;
    Ok(Solution {
        segment: s.segment.mapped(a, d.start),
        discrete_distance: s.discrete_distance * chord,
        ..s
    })
}

/// [`solve`] on a unit chord from (0, 0) to (1, 0).
fn solve_unit(d: &EndData) -> Result<Solution> {
    let discrete = discrete_elastica(&DiscreteParams {
        segments: DISCRETE_SEGMENTS,
        start: d.start,
        start_angle: d.start_angle,
        end: d.end,
        end_angle: d.end_angle,
        length: d.length,
        max_iterations: 200,
    })
    .map_err(|e| DesignError::Elastica(e.to_string()))?;
    let h = d.length / DISCRETE_SEGMENTS as f64;
    let s: Vec<f64> = (0..discrete.points.len()).map(|i| i as f64 * h).collect();
    let fit = fit_points_with_arclength(
        &discrete.points,
        &s,
        &FitParams {
            constraint: FitConstraint::EndPointsAndLength,
            lines_and_arcs: false,
            ..FitParams::default()
        },
    );
    let mut best: Option<(Segment, [f64; 3], usize)> = None;
    let mut keep = |found: Option<(Segment, [f64; 3], usize)>| {
        if let Some(found) = found {
            if best.as_ref().is_none_or(|b| norm(&found.1) < norm(&b.1)) {
                best = Some(found);
            }
        }
        best.as_ref().is_some_and(|b| norm(&b.1) <= TOLERANCE)
    };
    let mut done = false;
    if let Ok(FitResult {
        segment: Segment::Elastica(ElasticaParams {
            family, k, s0, l, ..
        }),
        ..
    }) = fit
    {
        // the fit's shape first; near the separatrix (k → 1, where the families meet)
        // the solution may be of the other family, with a similar shape
        let starts = [
            (family, k),
            (other(family), k),
            (other(family), 0.99),
            (other(family), 0.9),
            (family, 0.9),
        ];
        for (f, k) in starts {
            let x0 = [k.clamp(1e-9, 1.0), s0, l];
            if keep(newton(d, f, x0)) {
                done = true;
                break;
            }
        }
    }
    // the fit failed or its start led nowhere: the shooting solution gives the family,
    // the modulus and the length exactly, the grid the start
    if !done {
        // the discrete elastica's pendulum data first (close, and cheap); else shooting
        // (single shooting crawls under tension, where the end is exponentially
        // sensitive to the start) from the fitted closed form's, then from the discrete's
        let fitted = fit.as_ref().ok().and_then(|f| pendulum_of(&f.segment));
        let discrete_u = discrete_pendulum(d, &discrete);
        'starts: for which in 0..3 {
            let start = match which {
                0 => discrete_u,
                1 => fitted.and_then(|u| shoot_from(d, u)),
                _ => discrete_u.and_then(|u| shoot_from(d, u)),
            };
            if let Some(u) = start {
                for (f, x0) in closed_form_starts(d, u) {
                    if keep(newton(d, f, x0)) {
                        break 'starts;
                    }
                }
            }
        }
    }
    let Some((segment, r, iterations)) = best else {
        return Err(DesignError::NoConvergence([f64::NAN; 3]));
    };
    if norm(&r) > ACCEPT {
        return Err(DesignError::NoConvergence(r));
    }
    let e = segment
        .evaluator()
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    let discrete_distance = discrete
        .points
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let p = e.eval(i as f64 / DISCRETE_SEGMENTS as f64).p;
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(0.0, f64::max);
    Ok(Solution {
        segment,
        residuals: r,
        discrete_distance,
        iterations,
    })
}

fn other(f: Family) -> Family {
    match f {
        Family::Inflectional => Family::NonInflectional,
        Family::NonInflectional => Family::Inflectional,
    }
}
