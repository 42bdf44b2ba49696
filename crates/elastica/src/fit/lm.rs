//! A small Levenberg–Marquardt loop on the (at most three) nonlinear parameters of a
//! [`Shape`], with the placement a, b solved in closed form at every trial point.
//!
//! Written here rather than taken from the `levenberg-marquardt` crate: that crate is built
//! on nalgebra 0.34 (the workspace uses 0.35), and variable projection needs control over
//! the residual evaluation that a generic problem trait hides.

use super::model::{cost, feasible_start, jacobian, place, plausible, Data, Placement, Shape, C};
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// Outcome of one solve.
#[derive(Clone, Debug)]
pub(crate) struct Solved {
    pub theta: [f64; 3],
    pub l: f64,
    pub a: C,
    pub b: C,
    pub cost: f64,
    pub iterations: usize,
    pub converged: bool,
}

/// Minimise the weighted squared distance over θ starting at `theta0`; stop after two
/// accepted steps in a row that lower the cost by less than the relative `tol`, or after
/// [`CREEP_STEPS`] that lower it by less than [`CREEP`].
pub(crate) fn solve(
    shape: &Shape,
    theta0: [f64; 3],
    data: &Data,
    placement: Placement,
    max_iterations: usize,
    tol: f64,
) -> Option<Solved> {
    let dims = shape.dims();
    let l_sign = if theta0[2] < 0.0 { -1.0 } else { 1.0 };
    let mut theta = theta0;
    shape.clamp(&mut theta, l_sign);
    let mut ev = match shape.eval(&theta, data, theta0[2]) {
        Some(ev) => ev,
        None => {
            // a length-keeping start where the length cannot be matched: moved to the
            // nearest start where it can
            let Shape::Elastica {
                family,
                fixed_length: true,
            } = *shape
            else {
                return None;
            };
            theta = feasible_start(family, theta, data)?;
            shape.clamp(&mut theta, l_sign);
            shape.eval(&theta, data, theta[2])?
        }
    };
    let (mut a, mut b) = place(&ev.z, data, placement)?;
    if !plausible(shape, &theta, ev.l, a, data) {
        return None;
    }
    let mut f = cost(&ev.z, a, b, data);
    let floor = (1e-15 * data.length).powi(2);
    let mut out = Solved {
        theta,
        l: ev.l,
        a,
        b,
        cost: f,
        iterations: 0,
        converged: dims == 0 || f <= floor,
    };
    if out.converged {
        return Some(out);
    }
    let mut mu = 1e-3;
    let mut stall = 0;
    let mut creeping = 0;
    for it in 1..=max_iterations {
        let jac = jacobian(&ev, a, data, placement, dims);
        let mut h = Matrix3::<f64>::zeros();
        let mut g = Vector3::<f64>::zeros();
        for (i, ji) in jac.iter().enumerate() {
            let r = a * ev.z[i] + b - data.p[i];
            let w = data.w[i];
            for j in 0..dims {
                g[j] += w * (ji[j].conj() * r).re;
                for k in j..dims {
                    h[(j, k)] += w * (ji[j].conj() * ji[k]).re;
                }
            }
        }
        symmetrize_and_pad(&mut h, dims);
        if predicted_gain(&h, &g, dims) <= tol * f + floor {
            // even the full Gauss–Newton step would gain nothing worth a trial
            out.converged = true;
            break;
        }
        let mut accepted = false;
        for _ in 0..MAX_TRIALS {
            let Some(step) = damped_step(&h, &g, dims, mu) else {
                mu *= 10.0;
                continue;
            };
            let mut trial = theta;
            for j in 0..dims {
                trial[j] += step[j];
            }
            shape.clamp(&mut trial, l_sign);
            let Some(ev_t) = shape.eval(&trial, data, ev.l) else {
                mu *= 4.0;
                continue;
            };
            let Some((at, bt)) = place(&ev_t.z, data, placement) else {
                mu *= 4.0;
                continue;
            };
            let ft = cost(&ev_t.z, at, bt, data);
            if ft.is_finite() && ft < f && plausible(shape, &trial, ev_t.l, at, data) {
                let drop = (f - ft) / f;
                let moved =
                    (0..dims).any(|j| (trial[j] - theta[j]).abs() > 1e-13 * (1.0 + theta[j].abs()));
                theta = trial;
                ev = ev_t;
                a = at;
                b = bt;
                f = ft;
                mu = (mu / 3.0).max(1e-15);
                accepted = true;
                stall = if drop < tol || !moved { stall + 1 } else { 0 };
                creeping = if drop < CREEP { creeping + 1 } else { 0 };
                break;
            }
            mu *= 4.0;
            if mu > 1e16 {
                break;
            }
        }
        out = Solved {
            theta,
            l: ev.l,
            a,
            b,
            cost: f,
            iterations: it,
            converged: false,
        };
        if f <= floor || stall >= 2 || !accepted || creeping >= CREEP_STEPS {
            // no downhill step even with heavy damping: a (local) minimum to rounding
            out.converged = true;
            break;
        }
    }
    Some(out)
}

/// Relative decrease per step that counts as creeping: on noisy data the parameters can
/// sit in a long flat valley (e.g. a nearly circular elastica) where Levenberg–Marquardt
/// gains a fraction of a percent of the cost over dozens of steps. A solve stops after
/// [`CREEP_STEPS`] such steps in a row; the cost is then within ~0.1 % of the valley's
/// floor, far below the noise. Fits to exact data converge fast and never creep.
pub(crate) const CREEP: f64 = 1e-4;
/// Consecutive creeping steps that end a solve.
pub(crate) const CREEP_STEPS: usize = 3;

/// Rejected trial steps (damping ×4 each) after which an iteration gives up.
pub(crate) const MAX_TRIALS: usize = 16;

/// The cost decrease the undamped Gauss–Newton step predicts, gᵀH⁻¹g for the cost
/// Σ w|r|² with g = Jᵀ W r and H = Jᵀ W J (a tiny damping where H is singular).
pub(crate) fn predicted_gain<const N: usize>(
    h: &SMatrix<f64, N, N>,
    g: &SVector<f64, N>,
    dims: usize,
) -> f64 {
    [0.0, 1e-12, 1e-8]
        .iter()
        .find_map(|&mu| damped_step(h, g, dims, mu))
        .map_or(f64::INFINITY, |step| -g.dot(&step))
}

/// Fill the lower triangle of a normal matrix built upper-only and put 1 on the diagonal of
/// the unused trailing parameters, so a fixed-size solve works for any `dims ≤ N`.
pub(crate) fn symmetrize_and_pad<const N: usize>(h: &mut SMatrix<f64, N, N>, dims: usize) {
    for j in 0..N {
        for k in 0..j {
            h[(j, k)] = h[(k, j)];
        }
        if j >= dims {
            h[(j, j)] = 1.0;
        }
    }
}

/// The Levenberg–Marquardt step (H + μ diag H) δ = −g, or `None` when not positive definite.
pub(crate) fn damped_step<const N: usize>(
    h: &SMatrix<f64, N, N>,
    g: &SVector<f64, N>,
    dims: usize,
    mu: f64,
) -> Option<SVector<f64, N>> {
    let mut damped = *h;
    for j in 0..dims {
        damped[(j, j)] += mu * h[(j, j)].max(1e-300);
    }
    damped.cholesky().map(|c| c.solve(&(-g)))
}
