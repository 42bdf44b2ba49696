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
//! Nearly straight curves (slack within `NEAR_STRAIGHT` = 5 % of the chord; issue 37) are
//! solved first by Levenberg–Marquardt on the pendulum data `(κ₀, λ₁, λ₂)` with the closed
//! form as the exact integrator (`pendulum::segment_of_pendulum`): those data stay well
//! conditioned down to a straight line, where `(k, s₀, ℓ)` do not (the window shrinks to a
//! point of the normalized curve or its modulus tends to 1). Under a strong pull, where
//! shooting amplifies its errors like `e^{√λ L}`, the result is polished about the
//! pendulum's top (`taut`), with `1 − k` kept to full precision
//! (`ElasticaParams::one_minus_k`); near a buckling load, in `(q, s₀, ℓ)` with wide
//! differences, and where Newton stalls there with the end short of the chord by a
//! buckled mode's slack, `λ₁` is followed alone towards tension to where the end meets
//! the chord (`pendulum::along_tension`) and Newton restarted. A curve whose slack is below [`crate::bvp::STRAIGHT_SLACK`] and whose
//! tangents lie within [`crate::bvp::STRAIGHT_ANGLE`] of its chord is a line.
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

use crate::bezier::wrap;
use crate::error::{DesignError, Result};

mod pendulum;
mod taut;
use pendulum::{
    along_tension, closed_form_starts, discrete_pendulum, newton_pendulum, pendulum_of, shoot_from,
};

/// The data an elastica must meet.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
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
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
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
/// Largest residual norm of an accepted solution. Newton reaches 10⁻¹³ on most data; on
/// nearly straight curves close to a buckling load the slack hardly moves with the shape
/// and the length's residual can stall near 10⁻⁹.
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
    if !(chord > 0.0) || !(d.length >= chord * (1.0 - STRAIGHT_SLACK)) {
        return Err(DesignError::Invalid(format!(
            "the length {} is shorter than the distance {chord} between the end points",
            d.length
        )));
    }
    Ok(chord)
}

/// Slack (length over chord − 1) below which, with end tangents within
/// [`STRAIGHT_ANGLE`] of the chord, a curve is straight: rounding of the length and the
/// chord (≈ 10⁻¹⁶) cannot tell it from a line.
pub const STRAIGHT_SLACK: f64 = 1e-13;
/// Largest angle (radians) between a straight curve's end tangents and its chord. A
/// Bézier with slack [`STRAIGHT_SLACK`] has end tangents about 10⁻⁶ off its chord, and
/// a line instead of its elastica lies within 10⁻⁷ of its length of it.
pub const STRAIGHT_ANGLE: f64 = 2e-6;

/// The line of `d` when its data are straight ([`STRAIGHT_SLACK`], [`STRAIGHT_ANGLE`]):
/// from the start along the chord, the chord long.
fn straight(d: &EndData, chord: f64) -> Option<Solution> {
    let turn = (d.end[1] - d.start[1]).atan2(d.end[0] - d.start[0]);
    let a = wrap(d.start_angle - turn);
    let b = a + (d.end_angle - d.start_angle);
    let slack = d.length / chord - 1.0;
    let flat = slack <= STRAIGHT_SLACK && a.abs() <= STRAIGHT_ANGLE && b.abs() <= STRAIGHT_ANGLE;
    flat.then(|| Solution {
        segment: Segment::Line {
            x0: d.start[0],
            y0: d.start[1],
            phi: turn,
            length: chord,
        },
        residuals: [a, b - a, chord / d.length - 1.0],
        discrete_distance: 0.0,
        iterations: 0,
    })
}

/// The segment of shape `x = (k, s₀, ℓ)` between the end points, and its residuals.
fn residuals(d: &EndData, family: Family, x: [f64; 3]) -> Option<(Segment, [f64; 3])> {
    segment_residuals(
        d,
        Segment::elastica_between(family, x[0], x[1], x[2], d.start, d.end)?,
    )
}

/// The residuals of [`residuals`] of a segment between `d`'s end points.
fn segment_residuals(d: &EndData, seg: Segment) -> Option<(Segment, [f64; 3])> {
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
fn newton(
    d: &EndData,
    family: Family,
    x: [f64; 3],
    step: f64,
) -> Option<(Segment, [f64; 3], usize)> {
    let res = |y: [f64; 3]| residuals(d, family, [from_q(y[0]), y[1], y[2]]);
    let y = [to_q(x[0].clamp(1e-9, 1.0)), x[1], x[2]];
    damped_newton(&res, y, [to_q(1e-9), 40.0], step)
}

/// The central-difference Jacobian of `res` at `y` (residuals `r` there), with step
/// `step(yⱼ)` per unknown; one-sided where a neighbour holds no curve, `None` where
/// neither does.
fn jacobian(
    res: &dyn Fn([f64; 3]) -> Option<[f64; 3]>,
    y: [f64; 3],
    r: [f64; 3],
    step: &dyn Fn(f64) -> f64,
) -> Option<nalgebra::Matrix3<f64>> {
    let mut jac = nalgebra::Matrix3::zeros();
    for j in 0..3 {
        let h = step(y[j]);
        let (mut up, mut down) = (y, y);
        up[j] += h;
        down[j] -= h;
        let (ru, rd, width) = match (res(up), res(down)) {
            (Some(u), Some(v)) => (u, v, 2.0 * h),
            (Some(u), None) => (u, r, h),
            (None, Some(v)) => (r, v, h),
            (None, None) => return None,
        };
        for i in 0..3 {
            jac[(i, j)] = (ru[i] - rd[i]) / width;
        }
    }
    Some(jac)
}

/// A residual map of three unknowns: the segment and its residuals, `None` where the
/// unknowns hold no curve.
type ResidualMap<'a> = dyn Fn([f64; 3]) -> Option<(Segment, [f64; 3])> + 'a;

/// Damped Newton with a central-difference Jacobian (steps `step·max(|yⱼ|, 10⁻³)`) on
/// `res` from `y`, the first unknown kept in `range`: the segment, its residuals and the
/// iterations when they fall to [`TOLERANCE`], or stall at most at [`ACCEPT`].
fn damped_newton(
    res: &ResidualMap,
    mut y: [f64; 3],
    range: [f64; 2],
    step: f64,
) -> Option<(Segment, [f64; 3], usize)> {
    let (mut seg, mut r) = res(y)?;
    for it in 0..MAX_NEWTON {
        if norm(&r) <= TOLERANCE {
            return Some((seg, r, it));
        }
        let jac = jacobian(&|x| res(x).map(|v| v.1), y, r, &|v| {
            step * v.abs().max(1e-3)
        })?;
        let dy = jac.lu().solve(&nalgebra::Vector3::from(r))?;
        let mut w = 1.0;
        let mut accepted = false;
        for _ in 0..30 {
            let mut trial = [y[0] - w * dy[0], y[1] - w * dy[1], y[2] - w * dy[2]];
            trial[0] = trial[0].clamp(range[0], range[1]);
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
    if let Some(line) = straight(d, chord) {
        return Ok(line);
    }
    if !(d.length > chord) {
        return Err(DesignError::Invalid(format!(
            "the length {} is the distance between the end points, but their tangents are not along it: no curve meets them",
            d.length
        )));
    }
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
    // the discrete elastica on DISCRETE_SEGMENTS, else on 2× or 1.5× as many: its Newton
    // can stall a hair short of its tolerance on nearly straight, nearly buckling data
    let discrete_on = |segments, max_iterations| {
        discrete_elastica(&DiscreteParams {
            segments,
            start: d.start,
            start_angle: d.start_angle,
            end: d.end,
            end_angle: d.end_angle,
            length: d.length,
            max_iterations,
        })
    };
    let discrete = discrete_on(DISCRETE_SEGMENTS, 200)
        .or_else(|_| discrete_on(2 * DISCRETE_SEGMENTS, 1000))
        .or_else(|_| discrete_on(3 * DISCRETE_SEGMENTS / 2, 1000))
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    let segments = discrete.angles.len();
    let h = d.length / segments as f64;
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
    // nearly straight: Newton on the pendulum data, which stay well conditioned as the
    // angles vanish (the closed form's (k, s₀, ℓ) do not)
    if d.length - 1.0 <= NEAR_STRAIGHT {
        if let Some(u) = discrete_pendulum(d, &discrete) {
            if let Some((seg, _, it)) = newton_pendulum(d, u, TOLERANCE) {
                done = keep(standard(d, &seg).map(|(s, r)| (s, r, it)));
                // under tension the pendulum's shooting amplifies its errors like
                // e^{√λ L}: solved again about the top
                if !done {
                    done = keep(taut::newton_taut(d, &seg));
                }
                // near a buckling load, where λ₁ creeps: polished in (k, s₀, ℓ), with
                // differences wide enough to see the slack
                // (not near the separatrix: (q, s₀, ℓ) would drop the exact 1 − k)
                if let (
                    false,
                    Segment::Elastica(
                        p @ ElasticaParams {
                            one_minus_k: None, ..
                        },
                    ),
                ) = (done, seg)
                {
                    done = keep(newton(d, p.family, [p.k, p.s0, p.l], WIDE_STEP));
                }
                // stalled near a buckling load, the end short of the chord by a buckled
                // mode's slack: λ₁ followed towards tension to where it meets it
                if !done {
                    let start = pendulum_of(&seg).and_then(|u| along_tension(d, u));
                    if let Some((seg, _, it)) = start.and_then(|u| newton_pendulum(d, u, TOLERANCE))
                    {
                        done = keep(standard(d, &seg).map(|(s, r)| (s, r, it)));
                    }
                }
            }
        }
    }
    if !done {
        if let Ok(FitResult {
            segment:
                Segment::Elastica(ElasticaParams {
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
                if keep(newton(d, f, x0, NARROW_STEP)) {
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
                        if keep(newton(d, f, x0, NARROW_STEP)) {
                            break 'starts;
                        }
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
            let p = e.eval(i as f64 / segments as f64).p;
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

/// Relative step of the Jacobian's differences in Newton on `(q, s₀, ℓ)`.
const NARROW_STEP: f64 = 1e-7;
/// The same for nearly straight curves, whose slack moves with the shape only at second
/// order in the angles: wider, to see it above rounding.
const WIDE_STEP: f64 = 1e-4;

/// Below this slack (length over chord − 1) the solve starts with Newton on the pendulum
/// data ([`pendulum::newton_pendulum`]).
const NEAR_STRAIGHT: f64 = 0.05;

/// A segment's residuals as [`residuals`] gives them: an elastica moved so that its ends
/// are `d`'s; an arc (no force) when its end misses `d`'s by at most [`ACCEPT`].
fn standard(d: &EndData, seg: &Segment) -> Option<(Segment, [f64; 3])> {
    if let Segment::Elastica(_) = seg {
        return segment_residuals(d, seg.with_ends(d.start, d.end)?);
    }
    let e = seg.evaluator().ok()?;
    let (a, b) = (e.eval(0.0), e.eval(1.0));
    let miss = (b.p[0] - d.end[0]).hypot(b.p[1] - d.end[1]) / d.length;
    let r = [
        wrap(a.angle - d.start_angle),
        (b.angle - a.angle) - (d.end_angle - d.start_angle),
        seg.length() / d.length - 1.0,
    ];
    (miss <= ACCEPT && r.iter().all(|v| v.is_finite())).then_some((*seg, r))
}

fn other(f: Family) -> Family {
    match f {
        Family::Inflectional => Family::NonInflectional,
        Family::NonInflectional => Family::Inflectional,
    }
}
