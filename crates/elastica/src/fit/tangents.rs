//! Fits that also keep end tangents: the C¹ joints between neighbouring hot-blade pieces
//! ("Hot Blade Cuttings" §6). Starting from an end-point fit, the shape parameters
//! θ = (k, s₀, ℓ) of the elastica are moved by constrained Gauss–Newton steps (the KKT
//! system of the linearised least-squares problem with the linearised constraints) until
//! the tangent angles, and with a fixed length also the length, hold to rounding; the
//! placement keeps the end points exactly at every step. Written here because no crate
//! offers equality-constrained least squares on a 3-parameter closed-form curve.

use nalgebra::{DMatrix, DVector};

use super::{fit_points_with_arclength, FitConstraint, FitError, FitParams, FitResult};
use crate::segment::{ElasticaParams, Segment};
use crate::unit::Family;

/// Constraint residual that counts as met (radians, and relative length).
const TOLERANCE: f64 = 1e-11;

use geom::polyline::wrap_angle as wrap;

/// The two families as one chart: `q ∈ [0, 1]` is the inflectional elastica of modulus
/// `k = q`, `q ∈ (1, 2)` the non-inflectional one of modulus `k = 2 − q`. Both families are
/// the same curve at k = 1 (κ = 2 sech σ), so a solve can cross from one to the other.
fn chart(q: f64) -> Option<(Family, f64)> {
    if (0.0..=1.0).contains(&q) {
        Some((Family::Inflectional, q))
    } else if q > 1.0 && q < 2.0 {
        Some((Family::NonInflectional, 2.0 - q))
    } else {
        None
    }
}

/// The chart coordinate of a family and modulus.
fn chart_of(family: Family, k: f64) -> f64 {
    match family {
        Family::Inflectional => k,
        Family::NonInflectional => 2.0 - k,
    }
}

/// The segment of shape `theta` (chart coordinate, s₀, ℓ) placed so that it runs from `p0`
/// to `p1`.
fn placed(theta: &[f64; 3], p0: [f64; 2], p1: [f64; 2]) -> Option<Segment> {
    let (family, k) = chart(theta[0])?;
    Segment::elastica_between(family, k, theta[1], theta[2], p0, p1)
}

struct Problem<'a> {
    points: &'a [[f64; 2]],
    t: Vec<f64>,
    w: Vec<f64>,
    start: Option<f64>,
    end: Option<f64>,
    length: Option<f64>,
}

impl Problem<'_> {
    /// Jacobians of the residuals and constraints at θ: central differences, one-sided
    /// where a side leaves the valid range (k ∉ [0, 1]).
    fn jacobians(
        &self,
        theta: &[f64; 3],
        r: &[f64],
        c: &[f64],
    ) -> Option<(DMatrix<f64>, DMatrix<f64>)> {
        let mut jr = DMatrix::zeros(r.len(), 3);
        let mut jc = DMatrix::zeros(c.len(), 3);
        for k in 0..3 {
            let h = 1e-7 * (1.0 + theta[k].abs());
            let (mut tp, mut tm) = (*theta, *theta);
            tp[k] += h;
            tm[k] -= h;
            let (plus, minus) = (self.eval(&tp), self.eval(&tm));
            let ((rp, cp), (rm, cm), width) = match (plus, minus) {
                (Some((rp, cp, _)), Some((rm, cm, _))) => ((rp, cp), (rm, cm), 2.0 * h),
                (Some((rp, cp, _)), None) => ((rp, cp), (r.to_vec(), c.to_vec()), h),
                (None, Some((rm, cm, _))) => ((r.to_vec(), c.to_vec()), (rm, cm), h),
                (None, None) => return None,
            };
            for i in 0..r.len() {
                jr[(i, k)] = (rp[i] - rm[i]) / width;
            }
            for i in 0..c.len() {
                jc[(i, k)] = wrap(cp[i] - cm[i]) / width;
            }
        }
        Some((jr, jc))
    }

    /// Weighted residuals and constraint values at θ.
    fn eval(&self, theta: &[f64; 3]) -> Option<(Vec<f64>, Vec<f64>, Segment)> {
        let n = self.points.len();
        let seg = placed(theta, self.points[0], self.points[n - 1])?;
        let e = seg.evaluator().ok()?;
        let mut r = Vec::with_capacity(2 * n);
        for (i, q) in self.points.iter().enumerate() {
            let p = e.eval(self.t[i]).p;
            r.push(self.w[i] * (p[0] - q[0]));
            r.push(self.w[i] * (p[1] - q[1]));
        }
        let mut c = Vec::new();
        if let Some(a) = self.start {
            c.push(wrap(e.eval(0.0).angle - a));
        }
        if let Some(a) = self.end {
            c.push(wrap(e.eval(1.0).angle - a));
        }
        if let Some(l) = self.length {
            c.push(seg.length() / l - 1.0);
        }
        if r.iter().chain(&c).all(|v| v.is_finite()) {
            Some((r, c, seg))
        } else {
            None
        }
    }
}

/// Refits `fit` (an end-point fit of `points` with arc lengths `s`) so that the segment's
/// tangent angle is `start` at t = 0 and `end` at t = 1 (each optional), keeping the end
/// points, and the length when `constraint` is [`FitConstraint::EndPointsAndLength`].
///
/// Unit-free like [`fit_points_with_arclength`]: solved on the curve moved to unit size.
///
/// # Errors
/// [`FitError::Tangents`] when the constraints cannot be met from this start.
///
/// ```
/// use elastica::{fit_points_with_arclength, fit_with_end_tangents, FitConstraint, FitParams};
/// // the parabola y = x²/4 on [0, 1], with chord-length parameters
/// let points: Vec<[f64; 2]> = (0..40).map(|i| { let x = i as f64 / 39.0; [x, x * x / 4.0] }).collect();
/// let s = geom::polyline::chord_lengths(&points);
/// let params = FitParams { constraint: FitConstraint::EndPoints, ..FitParams::default() };
/// let fit = fit_points_with_arclength(&points, &s, &params)?;
/// // refit leaving horizontally and arriving with the parabola's slope 1/2
/// let (start, end) = (0.0, 0.5f64.atan());
/// let tangent = fit_with_end_tangents(&points, &s, &fit, None, Some(start), Some(end), FitConstraint::EndPoints)?;
/// let (a, b) = (tangent.segment.eval(0.0)?, tangent.segment.eval(1.0)?);
/// assert!((a.angle - start).abs() < 1e-9 && (b.angle - end).abs() < 1e-9);
/// assert!(a.p[0].abs() < 1e-9 && a.p[1].abs() < 1e-9);
/// assert!((b.p[0] - 1.0).abs() < 1e-9 && (b.p[1] - 0.25).abs() < 1e-9);
/// assert!(tangent.rms < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_with_end_tangents(
    points: &[[f64; 2]],
    s: &[f64],
    fit: &FitResult,
    warm: Option<&Segment>,
    start: Option<f64>,
    end: Option<f64>,
    constraint: FitConstraint,
) -> Result<FitResult, FitError> {
    let Some(frame) = super::UnitFrame::of(points, s) else {
        return tangents_in_frame(points, s, fit, warm, start, end, constraint);
    };
    let (p, t) = frame.points_to_unit(points, s);
    let fit = frame.result_to_unit(fit);
    let warm = warm.map(|w| frame.segment_to_unit(w));
    // as `fit_points_with_arclength`: solved on the points rounded to the grid (the same
    // numbers in any unit), the residuals measured to the points as given
    let (pq, tq) = (super::quantize_points(&p), super::quantize_all(&t));
    let r = if tq.windows(2).all(|w| w[1] > w[0]) {
        let q = |a: Option<f64>| a.map(super::quantize);
        let r = tangents_in_frame(
            &pq,
            &tq,
            &super::quantize_result(&fit),
            warm.map(super::quantize_segment).as_ref(),
            q(start),
            q(end),
            constraint,
        )?;
        // the constraints made exact again on the points and angles as given
        let length = t[t.len() - 1] - t[0];
        let ends = [p[0], p[p.len() - 1]];
        let exact = Problem {
            points: &ends,
            t: vec![0.0, 1.0],
            w: vec![0.0, 0.0],
            start,
            end,
            length: (constraint == FitConstraint::EndPointsAndLength).then_some(length),
        };
        let segment = constrained(&exact, &r.segment).unwrap_or_else(|| {
            let pinned = super::pinned(r.segment, &pq, &p);
            match constraint {
                FitConstraint::EndPointsAndLength => super::with_length(pinned, &p, length),
                _ => pinned,
            }
        });
        let r = FitResult { segment, ..r };
        super::remeasured(r, &p, &tq)?
    } else {
        tangents_in_frame(&p, &t, &fit, warm.as_ref(), start, end, constraint)?
    };
    Ok(frame.result_from_unit(r))
}

/// [`fit_with_end_tangents`] in the coordinates given.
fn tangents_in_frame(
    points: &[[f64; 2]],
    s: &[f64],
    fit: &FitResult,
    warm: Option<&Segment>,
    start: Option<f64>,
    end: Option<f64>,
    constraint: FitConstraint,
) -> Result<FitResult, FitError> {
    if start.is_none() && end.is_none() {
        return Ok(fit.clone());
    }
    let n = points.len();
    let total = s.last().copied().unwrap_or(0.0);
    if n < 3 || s.len() != n || !(total > 0.0) {
        return Err(FitError::TooFewPoints(n));
    }
    // starts: the neighbour's solution (already close to meeting similar constraints),
    // the end-point fit, and — lines and arcs have too few parameters for four boundary
    // conditions — the best elastica
    let mut bases: Vec<ElasticaParams> = Vec::new();
    if let Some(Segment::Elastica(p)) = warm {
        bases.push(*p);
    }
    if let Segment::Elastica(p) = fit.segment {
        bases.push(p);
    }
    let mut last_err = FitError::Tangents("no elastica start".into());
    let mut best: Option<FitResult> = None;
    for round in 0..2 {
        for base in &bases {
            match refine_from(
                points,
                s,
                total,
                *base,
                start,
                end,
                constraint,
                fit.iterations,
            ) {
                Ok(r) => {
                    if best.as_ref().is_none_or(|b| r.l2 < b.l2) {
                        best = Some(r);
                    }
                }
                Err(e) => last_err = e,
            }
        }
        if best.is_some() || round == 1 {
            break;
        }
        let refit = fit_points_with_arclength(
            points,
            s,
            &FitParams {
                constraint,
                lines_and_arcs: false,
                ..FitParams::default()
            },
        )?;
        bases.clear();
        if let Segment::Elastica(p) = refit.segment {
            bases.push(p);
        }
    }
    best.ok_or(last_err)
}

/// The elastica `seg` moved by minimum-norm Newton steps on the constraints alone until
/// they hold to [`TOLERANCE`] on `problem` (its end points, angles and length); `None` for
/// a line or an arc, or when the steps stop short.
fn constrained(problem: &Problem, seg: &Segment) -> Option<Segment> {
    let Segment::Elastica(e) = seg else {
        return None;
    };
    let mut theta = [chart_of(e.family, e.k), e.s0, e.l];
    let (mut r, mut c, mut out) = problem.eval(&theta)?;
    let worst = |c: &[f64]| c.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for _ in 0..30 {
        if worst(&c) <= TOLERANCE {
            break;
        }
        let (_, jc) = problem.jacobians(&theta, &r, &c)?;
        let y = (&jc * jc.transpose())
            .lu()
            .solve(&DVector::from_vec(c.clone()))?;
        let step = -(jc.transpose() * y);
        // the full step, else halved until the constraints shrink
        let mut next = None;
        let mut alpha = 1.0;
        for _ in 0..20 {
            let mut tn = theta;
            for k in 0..3 {
                tn[k] += alpha * step[k];
            }
            if let Some((rn, cn, sn)) = problem.eval(&tn) {
                if worst(&cn) < worst(&c) {
                    next = Some((tn, rn, cn, sn));
                    break;
                }
            }
            alpha *= 0.5;
        }
        let Some(n) = next else {
            break;
        };
        (theta, r, c, out) = n;
    }
    (worst(&c) <= 10.0 * TOLERANCE).then_some(out)
}

/// The constrained Gauss–Newton solve from one start.
#[allow(clippy::too_many_arguments)]
fn refine_from(
    points: &[[f64; 2]],
    s: &[f64],
    total: f64,
    base: ElasticaParams,
    start: Option<f64>,
    end: Option<f64>,
    constraint: FitConstraint,
    prior_iterations: usize,
) -> Result<FitResult, FitError> {
    let t: Vec<f64> = s.iter().map(|v| v / total).collect();
    let tw = super::model::trapezoid_weights(&t);
    let problem = Problem {
        points,
        t: t.clone(),
        w: tw.iter().map(|v| (v * total).sqrt()).collect(),
        start,
        end,
        length: (constraint == FitConstraint::EndPointsAndLength).then_some(total),
    };
    let mut theta = [chart_of(base.family, base.k), base.s0, base.l];
    let (mut r, mut c, mut seg) = problem
        .eval(&theta)
        .ok_or_else(|| FitError::Tangents("invalid start".into()))?;
    let mut iterations = 0;
    let mut mu = 1e-12;
    let viol = |c: &[f64]| c.iter().map(|v| v * v).sum::<f64>().sqrt();
    let cost = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    for _ in 0..100 {
        iterations += 1;
        let m = c.len();
        let Some((jr, jc)) = problem.jacobians(&theta, &r, &c) else {
            return Err(FitError::Tangents("the shape left the valid range".into()));
        };
        // KKT: [JᵀJ + μI, Cᵀ; C, 0] [Δ; λ] = [−Jᵀr; −c]
        let rv = DVector::from_vec(r.clone());
        let jtj = jr.transpose() * &jr;
        let g = jr.transpose() * rv;
        let scale = 1.0 + jtj.diagonal().amax();
        // Levenberg–Marquardt damping on the least-squares part: as μ grows the step tends
        // to the minimum-norm step onto the linearised constraints
        let (v0, f0) = (viol(&c), cost(&r));
        let mut moved = false;
        let mut last_step = [0.0; 3];
        for _ in 0..40 {
            let mut kkt = DMatrix::zeros(3 + m, 3 + m);
            let mut rhs = DVector::zeros(3 + m);
            for i in 0..3 {
                for j in 0..3 {
                    kkt[(i, j)] = jtj[(i, j)] + if i == j { mu * scale } else { 0.0 };
                }
                rhs[i] = -g[i];
            }
            for i in 0..m {
                for j in 0..3 {
                    kkt[(3 + i, j)] = jc[(i, j)];
                    kkt[(j, 3 + i)] = jc[(i, j)];
                }
                rhs[3 + i] = -c[i];
            }
            let Some(step) = kkt.lu().solve(&rhs) else {
                mu *= 4.0;
                continue;
            };
            // backtrack along the step (needed when the constraints fix all three parameters
            // and μ has no effect)
            let mut alpha = 1.0;
            for _ in 0..24 {
                let mut tn = theta;
                for k in 0..3 {
                    tn[k] += alpha * step[k];
                    last_step[k] = alpha * step[k];
                }
                if let Some((rn, cn, sn)) = problem.eval(&tn) {
                    let (v1, f1) = (viol(&cn), cost(&rn));
                    let better = if v0 > TOLERANCE {
                        v1 < v0 * (1.0 - 1e-4 * alpha) || (v1 < v0 && f1 <= f0)
                    } else {
                        v1 <= TOLERANCE && f1 < f0
                    };
                    if better {
                        theta = tn;
                        r = rn;
                        c = cn;
                        seg = sn;
                        moved = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if moved {
                mu = (mu / 10.0).max(1e-12);
                break;
            }
            mu *= 10.0;
            if mu > 1e12 {
                break;
            }
        }
        let done = viol(&c) <= TOLERANCE;
        let small = (0..3).all(|k| last_step[k].abs() <= 1e-12 * (1.0 + theta[k].abs()));
        if done && (small || !moved) {
            break;
        }
        if !moved {
            break;
        }
    }
    // finish on the constraints alone: minimum-norm Newton steps Δ = −Cᵀ(CCᵀ)⁻¹c
    for _ in 0..30 {
        if c.iter().all(|v| v.abs() <= TOLERANCE) {
            break;
        }
        let Some((_, jc)) = problem.jacobians(&theta, &r, &c) else {
            break;
        };
        let cct = &jc * jc.transpose();
        let Some(y) = cct.lu().solve(&DVector::from_vec(c.clone())) else {
            break;
        };
        let step = -(jc.transpose() * y);
        let mut tn = theta;
        for k in 0..3 {
            tn[k] += step[k];
        }
        match problem.eval(&tn) {
            Some((rn, cn, sn))
                if cn.iter().map(|v| v.abs()).fold(0.0, f64::max)
                    < c.iter().map(|v| v.abs()).fold(0.0, f64::max) =>
            {
                theta = tn;
                r = rn;
                c = cn;
                seg = sn;
            }
            _ => break,
        }
    }
    if let Some(v) = c.iter().find(|v| v.abs() > TOLERANCE * 10.0) {
        return Err(FitError::Tangents(format!("residual {v:e}")));
    }
    // distances with arc-length matching
    let e = seg
        .evaluator()
        .map_err(|e| FitError::Tangents(e.to_string()))?;
    let d: Vec<f64> = points
        .iter()
        .zip(&t)
        .map(|(q, &ti)| {
            let p = e.eval(ti).p;
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .collect();
    let l2sq: f64 = d.iter().zip(&tw).map(|(di, wi)| di * di * wi * total).sum();
    Ok(FitResult {
        segment: seg,
        rms: (l2sq / total).sqrt(),
        max: d.iter().copied().fold(0.0, f64::max),
        l2: l2sq.sqrt(),
        input_length: total,
        iterations: prior_iterations + iterations,
        converged: true,
        t,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::fit_points;

    fn sample(seg: &Segment, n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
        let pts = seg.sample(n).unwrap();
        let s = (0..n)
            .map(|i| seg.length() * i as f64 / (n - 1) as f64)
            .collect();
        (pts, s)
    }

    #[test]
    fn end_tangents_are_kept_to_rounding() {
        let seg = Segment::elastica_between(
            Family::Inflectional,
            0.4,
            0.3,
            0.9,
            [0.0, 0.0],
            [600.0, 20.0],
        )
        .unwrap();
        let (pts, s) = sample(&seg, 100);
        for constraint in [FitConstraint::EndPoints, FitConstraint::EndPointsAndLength] {
            let fit = fit_points_with_arclength(
                &pts,
                &s,
                &FitParams {
                    constraint,
                    ..FitParams::default()
                },
            )
            .unwrap();
            let e = seg.evaluator().unwrap();
            let (a0, a1) = (e.eval(0.0).angle, e.eval(1.0).angle);
            for (start, end) in [
                (Some(a0 + 0.01), None),
                (None, Some(a1 - 0.02)),
                (Some(a0 - 0.01), Some(a1 + 0.01)),
            ] {
                let r = fit_with_end_tangents(&pts, &s, &fit, None, start, end, constraint)
                    .unwrap_or_else(|e| panic!("{constraint:?} {start:?} {end:?} {a0} {a1}: {e}"));
                let f = r.segment.evaluator().unwrap();
                // solved on the unit frame's grid, then made exact on the constraints
                let tol = 1e-9;
                for (want, t) in [(start, 0.0), (end, 1.0)] {
                    if let Some(a) = want {
                        let err = wrap(f.eval(t).angle - a).abs();
                        assert!(err < tol, "{constraint:?} t = {t}: {err:e}");
                    }
                }
                let (p0, p1) = (f.eval(0.0).p, f.eval(1.0).p);
                assert!((p0[0] - pts[0][0]).hypot(p0[1] - pts[0][1]) < 1e-9);
                assert!((p1[0] - pts[99][0]).hypot(p1[1] - pts[99][1]) < 1e-9);
                if constraint == FitConstraint::EndPointsAndLength {
                    assert!((r.segment.length() / s[99] - 1.0).abs() < 1e-9);
                }
                assert!(r.max < 10.0, "{}", r.max);
            }
        }
        let _ = fit_points;
    }
}
