//! A small Levenberg–Marquardt loop on the (at most three) nonlinear parameters of a
//! [`Shape`], with the placement a, b solved in closed form at every trial point.
//!
//! Written here rather than taken from the `levenberg-marquardt` crate: that crate is built
//! on nalgebra 0.34 (the workspace uses 0.35), and variable projection needs control over
//! the residual evaluation that a generic problem trait hides.

use super::model::{cost, jacobian, place, plausible, Data, Placement, Shape, C};
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

/// Minimise the weighted squared distance over θ starting at `theta0`.
pub(crate) fn solve(
    shape: &Shape,
    theta0: [f64; 3],
    data: &Data,
    placement: Placement,
    max_iterations: usize,
) -> Option<Solved> {
    let dims = shape.dims();
    let l_sign = if theta0[2] < 0.0 { -1.0 } else { 1.0 };
    let mut theta = theta0;
    shape.clamp(&mut theta, l_sign);
    let mut ev = shape.eval(&theta, data, theta0[2])?;
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
        let mut accepted = false;
        for _ in 0..30 {
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
                stall = if drop < 1e-12 || !moved { stall + 1 } else { 0 };
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
        if f <= floor || stall >= 2 || !accepted {
            // no downhill step even with heavy damping: a (local) minimum to rounding
            out.converged = true;
            break;
        }
    }
    Some(out)
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
