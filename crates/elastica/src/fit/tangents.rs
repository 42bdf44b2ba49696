//! Fits that also keep end tangents: the C¹ joints between neighbouring hot-blade pieces
//! ("Hot Blade Cuttings" §6). Starting from an end-point fit, the shape parameters
//! θ = (k, s₀, ℓ) of the elastica are moved by constrained Gauss–Newton steps (the KKT
//! system of the linearised least-squares problem with the linearised constraints) until
//! the tangent angles, and with a fixed length also the length, hold to rounding; the
//! placement keeps the end points exactly at every step. Written here because no crate
//! offers equality-constrained least squares on a 3-parameter closed-form curve.

use nalgebra::{DMatrix, DVector};

use super::{fit_points_with_arclength, FitConstraint, FitError, FitParams, FitResult};
use crate::segment::Segment;
use crate::unit::Family;

/// Constraint residual that counts as met (radians, and relative length).
const TOLERANCE: f64 = 1e-11;

fn wrap(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    a - (a / tau).round() * tau
}

/// The segment of shape `theta` placed so that it runs from `p0` to `p1`.
fn placed(family: Family, theta: &[f64; 3], p0: [f64; 2], p1: [f64; 2]) -> Option<Segment> {
    Segment::elastica_between(family, theta[0], theta[1], theta[2], p0, p1)
}

struct Problem<'a> {
    family: Family,
    points: &'a [[f64; 2]],
    t: Vec<f64>,
    w: Vec<f64>,
    start: Option<f64>,
    end: Option<f64>,
    length: Option<f64>,
}

impl Problem<'_> {
    /// Weighted residuals and constraint values at θ.
    fn eval(&self, theta: &[f64; 3]) -> Option<(Vec<f64>, Vec<f64>, Segment)> {
        let n = self.points.len();
        let seg = placed(self.family, theta, self.points[0], self.points[n - 1])?;
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
/// # Errors
/// [`FitError::NotConverged`] when the constraints cannot be met from this start.
pub fn fit_with_end_tangents(
    points: &[[f64; 2]],
    s: &[f64],
    fit: &FitResult,
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
    // lines and arcs have too few parameters for four boundary conditions: start from
    // the best elastica instead
    let base = match fit.segment {
        Segment::Elastica(p) => p,
        _ => {
            let refit = fit_points_with_arclength(
                points,
                s,
                &FitParams {
                    constraint,
                    lines_and_arcs: false,
                    ..FitParams::default()
                },
            )?;
            match refit.segment {
                Segment::Elastica(p) => p,
                _ => return Err(FitError::Tangents("no elastica start".into())),
            }
        }
    };
    let t: Vec<f64> = s.iter().map(|v| v / total).collect();
    let tw = super::model::trapezoid_weights(&t);
    let problem = Problem {
        family: base.family,
        points,
        t: t.clone(),
        w: tw.iter().map(|v| (v * total).sqrt()).collect(),
        start,
        end,
        length: (constraint == FitConstraint::EndPointsAndLength).then_some(total),
    };
    let mut theta = [base.k, base.s0, base.l];
    let (mut r, mut c, mut seg) = problem
        .eval(&theta)
        .ok_or_else(|| FitError::Tangents("invalid start".into()))?;
    let mut iterations = 0;
    for _ in 0..100 {
        iterations += 1;
        let m = c.len();
        // Jacobians by central differences
        let mut jr = DMatrix::zeros(r.len(), 3);
        let mut jc = DMatrix::zeros(m, 3);
        for k in 0..3 {
            let h = 1e-7 * (1.0 + theta[k].abs());
            let (mut tp, mut tm) = (theta, theta);
            tp[k] += h;
            tm[k] -= h;
            let (Some((rp, cp, _)), Some((rm, cm, _))) = (problem.eval(&tp), problem.eval(&tm))
            else {
                return Err(FitError::Tangents("the shape left the valid range".into()));
            };
            for i in 0..r.len() {
                jr[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
            }
            for i in 0..m {
                jc[(i, k)] = wrap(cp[i] - cm[i]) / (2.0 * h);
            }
        }
        // KKT: [JᵀJ + μI, Cᵀ; C, 0] [Δ; λ] = [−Jᵀr; −c]
        let rv = DVector::from_vec(r.clone());
        let jtj = jr.transpose() * &jr;
        let g = jr.transpose() * rv;
        let mu = 1e-12 * (1.0 + jtj.diagonal().amax());
        let mut kkt = DMatrix::zeros(3 + m, 3 + m);
        let mut rhs = DVector::zeros(3 + m);
        for i in 0..3 {
            for j in 0..3 {
                kkt[(i, j)] = jtj[(i, j)] + if i == j { mu } else { 0.0 };
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
            return Err(FitError::Tangents("singular constraints".into()));
        };
        // backtrack on the merit ‖c‖ first, the cost second
        let viol = |c: &[f64]| c.iter().map(|v| v * v).sum::<f64>().sqrt();
        let cost = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
        let (v0, f0) = (viol(&c), cost(&r));
        let mut alpha = 1.0;
        let mut moved = false;
        for _ in 0..30 {
            let mut tn = theta;
            for k in 0..3 {
                tn[k] += alpha * step[k];
            }
            if let Some((rn, cn, sn)) = problem.eval(&tn) {
                let (v1, f1) = (viol(&cn), cost(&rn));
                if v1 < v0 * (1.0 - 1e-4 * alpha) || (v1 <= v0.max(TOLERANCE) && f1 <= f0) {
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
        let done = viol(&c) <= TOLERANCE;
        let small = (0..3).all(|k| (alpha * step[k]).abs() <= 1e-12 * (1.0 + theta[k].abs()));
        if done && (small || !moved) {
            break;
        }
        if !moved {
            break;
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
        iterations: fit.iterations + iterations,
        converged: true,
        t,
    })
}
