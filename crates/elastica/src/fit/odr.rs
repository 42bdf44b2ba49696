//! Orthogonal refinement of a fit: the parameters of the data points move to their feet on
//! the segment while Levenberg–Marquardt moves the segment, i.e. Gauss–Newton on the
//! distances along the normals (the tangential components are taken up by the parameters,
//! which eliminates them exactly to first order). This is what makes the arc-length
//! matching self-consistent: the matched parameter of a point is its arc length along the
//! fitted curve, which recovers sampled exact elastica to rounding and removes the bias of
//! chord lengths on noisy points. Converges quadratically for small residuals, where
//! alternating "fit, then re-foot" converges only linearly.

use super::lm::{
    damped_step, predicted_gain, symmetrize_and_pad, Solved, CREEP, CREEP_STEPS, MAX_TRIALS,
};
use super::model::{jacobian, place, plausible, Data, Placement, Shape, ShapeEval, C};
use nalgebra::{SMatrix, SVector};

type M7 = SMatrix<f64, 7, 7>;
type V7 = SVector<f64, 7>;

/// Relative cost decrease below which the refinement has converged.
const TOL: f64 = 1e-10;
/// Scalar residuals with their direction: the normal distance for interior points (their
/// feet move), both coordinates for the first and last point (their parameters stay at 0 and
/// 1 and pin down where the segment starts and ends). Returns (value, direction, weight)
/// triples and the Gauss–Newton foot steps of the interior points.
#[allow(clippy::type_complexity)]
fn residuals(ev: &ShapeEval, a: C, b: C, data: &Data) -> (Vec<(f64, C, f64, usize)>, Vec<f64>) {
    let n = ev.z.len();
    let mut out = Vec::with_capacity(n + 2);
    let mut shift = vec![0.0; n];
    for i in 0..n {
        let r = a * ev.z[i] + b - data.p[i];
        let w = data.w[i];
        if i == 0 || i == n - 1 {
            out.push((r.re, C::new(1.0, 0.0), w, i));
            out.push((r.im, C::new(0.0, 1.0), w, i));
            continue;
        }
        let g = a * ev.dzdt[i];
        let speed = g.norm().max(1e-300);
        let tau = g / speed;
        let nrm = C::new(-tau.im, tau.re);
        out.push(((nrm.conj() * r).re, nrm, w, i));
        shift[i] = -(tau.conj() * r).re / speed;
    }
    (out, shift)
}

fn weighted_sq(res: &[(f64, C, f64, usize)]) -> f64 {
    res.iter().map(|(d, _, w, _)| w * d * d).sum()
}

/// The Gauss–Newton normal equations `(H, g)` of the weighted normal distances `res` at the
/// segment `ev` placed by `a`: over the shape's `dims` parameters, and with a free
/// placement also over `a` and `b` (raw derivatives a·∂z/∂θ, then z, iz, 1, i).
fn normal_equations(
    res: &[(f64, C, f64, usize)],
    ev: &ShapeEval,
    a: C,
    data: &Data,
    placement: Placement,
    dims: usize,
) -> (M7, V7) {
    let free = placement == Placement::Free;
    let nparams = if free { dims + 4 } else { dims };
    let theta_cols = if free {
        None
    } else {
        Some(jacobian(ev, a, data, placement, dims))
    };
    let mut h = M7::zeros();
    let mut g = V7::zeros();
    for &(d, dir, w, i) in res {
        let nc = dir.conj();
        let mut row = [0.0; 7];
        match &theta_cols {
            Some(j) => {
                for k in 0..dims {
                    row[k] = (nc * j[i][k]).re;
                }
            }
            None => {
                for k in 0..dims {
                    row[k] = (nc * a * ev.dz[i][k]).re;
                }
                let z = ev.z[i];
                row[dims] = (nc * z).re;
                row[dims + 1] = (nc * C::new(-z.im, z.re)).re;
                row[dims + 2] = nc.re;
                row[dims + 3] = (nc * C::new(0.0, 1.0)).re;
            }
        }
        for j in 0..nparams {
            g[j] += w * row[j] * d;
            for k in j..nparams {
                h[(j, k)] += w * row[j] * row[k];
            }
        }
    }
    symmetrize_and_pad(&mut h, nparams);
    (h, g)
}

/// Refine `s` (from an arc-length-matched solve on `data`) orthogonally; updates `data.t`.
pub(crate) fn refine(
    shape: &Shape,
    mut s: Solved,
    data: &mut Data,
    placement: Placement,
    max_iterations: usize,
) -> Solved {
    let dims = shape.dims();
    let free = placement == Placement::Free;
    let nparams = if free { dims + 4 } else { dims };
    if nparams == 0 {
        // a line through fixed end points: only the feet move
        if let Some(ev) = shape.eval(&s.theta, data, s.l) {
            let (_, shift) = residuals(&ev, s.a, s.b, data);
            move_feet(data, &shift);
        }
        return s;
    }
    let l_sign = if s.theta[2] < 0.0 || s.l < 0.0 {
        -1.0
    } else {
        1.0
    };
    let Some(mut ev) = shape.eval(&s.theta, data, s.l) else {
        return s;
    };
    let floor = (1e-15 * data.length).powi(2);
    let mut mu = 1e-4;
    let mut small_steps = 0;
    let mut creeping = 0;
    for _ in 0..max_iterations {
        let (res, shift) = residuals(&ev, s.a, s.b, data);
        let f = weighted_sq(&res);
        s.cost = f;
        if f <= floor {
            s.converged = true;
            move_feet(data, &shift);
            break;
        }
        let (h, g) = normal_equations(&res, &ev, s.a, data, placement, dims);
        let done = predicted_gain(&h, &g, nparams) <= TOL * f + floor;
        // the feet move with the current segment before the step is tried
        move_feet(data, &shift);
        let mut accepted = false;
        for _ in 0..if done { 0 } else { MAX_TRIALS } {
            let Some(step) = damped_step(&h, &g, nparams, mu) else {
                mu *= 10.0;
                continue;
            };
            let mut theta = s.theta;
            for k in 0..dims {
                theta[k] += step[k];
            }
            shape.clamp(&mut theta, l_sign);
            let Some(ev_t) = shape.eval(&theta, data, s.l) else {
                mu *= 4.0;
                continue;
            };
            let (a, b) = if free {
                (
                    s.a + C::new(step[dims], step[dims + 1]),
                    s.b + C::new(step[dims + 2], step[dims + 3]),
                )
            } else {
                match place(&ev_t.z, data, placement) {
                    Some(ab) => ab,
                    None => {
                        mu *= 4.0;
                        continue;
                    }
                }
            };
            let (rt, _) = residuals(&ev_t, a, b, data);
            let ft = weighted_sq(&rt);
            if ft.is_finite() && ft < f && plausible(shape, &theta, ev_t.l, a, data) {
                let rel = (f - ft) / f;
                s.theta = theta;
                s.l = ev_t.l;
                s.a = a;
                s.b = b;
                s.cost = ft;
                s.iterations += 1;
                ev = ev_t;
                mu = (mu / 5.0).max(1e-15);
                accepted = true;
                small_steps = if rel < TOL { small_steps + 1 } else { 0 };
                creeping = if rel < CREEP { creeping + 1 } else { 0 };
                break;
            }
            mu *= 5.0;
            if mu > 1e16 {
                break;
            }
        }
        if !accepted || small_steps >= 2 || creeping >= CREEP_STEPS {
            // re-evaluate at the moved feet for the final numbers
            if let Some(e) = shape.eval(&s.theta, data, s.l) {
                let (r, shift) = residuals(&e, s.a, s.b, data);
                s.cost = weighted_sq(&r);
                move_feet(data, &shift);
            }
            s.converged = true;
            break;
        }
    }
    s
}

/// Apply the foot steps of the interior points (the first and last keep t = 0 and 1); a step
/// that would reorder the points is not taken.
fn move_feet(data: &mut Data, shift: &[f64]) {
    let old = data.t.clone();
    for (t, s) in data.t.iter_mut().zip(shift) {
        *t += s;
    }
    if data.t.windows(2).any(|w| !(w[1] > w[0])) {
        data.t = old;
    }
}
