//! The initial guess of "Hot Blade Cuttings for the Building Industries" §5.1: local
//! tangent angle and curvature of the data, least-squares (λ₁, λ₂, α) in
//! κ = λ₂x − λ₁y + α (eq. 11), scale S = λ^{-1/2} and rotation φ from (λ₁, λ₂), the family
//! and k from the pendulum energy H = ½(Sκ)² − cos(θ − φ) of the normalized curve
//! (H = 2k² − 1 inflectional, H = 2/k² − 1 non-inflectional), s₀ from the start tangent
//! and curvature, ℓ = L/S.

use super::model::Data;
use crate::elliptic::Elliptic;
use crate::unit::Family;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// Tangent angle (unwrapped) and curvature at every data point.
pub(crate) struct Local {
    pub theta: Vec<f64>,
    pub kappa: Vec<f64>,
}

/// Local quadratic least-squares fits of x(s), y(s) over a window of neighbours.
pub(crate) fn local_geometry(data: &Data) -> Local {
    let n = data.p.len();
    let half = (n / 12).clamp(2, 25);
    let mut theta = Vec::with_capacity(n);
    let mut kappa = Vec::with_capacity(n);
    let mut prev = 0.0;
    for i in 0..n {
        let lo = i.saturating_sub(half);
        let hi = (i + half).min(n - 1);
        let (lo, hi) = if hi - lo < 2 * half.min((n - 1) / 2) {
            if lo == 0 {
                (0, (2 * half).min(n - 1))
            } else {
                ((n - 1).saturating_sub(2 * half), n - 1)
            }
        } else {
            (lo, hi)
        };
        let si = data.t[i] * data.length;
        // moments Σ dsᵏ (k ≤ 4) and Σ dsᵏ x, Σ dsᵏ y (k ≤ 2) of the window, in scalars
        let mut mo = [0.0f64; 5];
        let (mut bx, mut by) = ([0.0f64; 3], [0.0f64; 3]);
        for j in lo..=hi {
            let ds = data.t[j] * data.length - si;
            let ds2 = ds * ds;
            mo[0] += 1.0;
            mo[1] += ds;
            mo[2] += ds2;
            mo[3] += ds2 * ds;
            mo[4] += ds2 * ds2;
            let (x, y) = (data.p[j].re, data.p[j].im);
            bx[0] += x;
            bx[1] += ds * x;
            bx[2] += ds2 * x;
            by[0] += y;
            by[1] += ds * y;
            by[2] += ds2 * y;
        }
        let m = Matrix3::new(
            mo[0], mo[1], mo[2], mo[1], mo[2], mo[3], mo[2], mo[3], mo[4],
        );
        let (cx, cy) = match m.cholesky() {
            Some(ch) => (ch.solve(&Vector3::from(bx)), ch.solve(&Vector3::from(by))),
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        let (x1, y1, x2, y2) = (cx[1], cy[1], 2.0 * cx[2], 2.0 * cy[2]);
        let speed = x1.hypot(y1).max(1e-300);
        let mut th = y1.atan2(x1);
        if i > 0 {
            th += 2.0 * PI * ((prev - th) / (2.0 * PI)).round();
        }
        prev = th;
        theta.push(th);
        kappa.push((x1 * y2 - y1 * x2) / speed.powi(3));
    }
    Local { theta, kappa }
}

use geom::polyline::wrap_angle as wrap;

/// Weighted mean curvature: the circle guess.
pub(crate) fn mean_curvature(data: &Data, local: &Local) -> f64 {
    data.w.iter().zip(&local.kappa).map(|(w, k)| w * k).sum()
}

/// The elastica guess (family, [k, s₀, ℓ]), or `None` when λ ≈ 0 (line or circle).
pub(crate) fn elastica_guess(data: &Data, local: &Local) -> Option<(Family, [f64; 3])> {
    let n = data.p.len();
    let (mut xm, mut ym) = (0.0, 0.0);
    for i in 0..n {
        xm += data.w[i] * data.p[i].re;
        ym += data.w[i] * data.p[i].im;
    }
    let mut m = Matrix3::<f64>::zeros();
    let mut rhs = Vector3::<f64>::zeros();
    for i in 0..n {
        let v = Vector3::new(data.p[i].re - xm, -(data.p[i].im - ym), 1.0);
        m += v * v.transpose() * data.w[i];
        rhs += v * (local.kappa[i] * data.w[i]);
    }
    let sol = m.try_inverse()? * rhs;
    let (l2, l1) = (sol[0], sol[1]);
    let lambda = l1.hypot(l2);
    let len = data.length;
    if !(lambda * len * len > 1e-6) {
        return None;
    }
    let phi = l2.atan2(l1);
    let scale = 1.0 / lambda.sqrt();
    let energy: f64 = (0..n)
        .map(|i| {
            let tk = scale * local.kappa[i];
            data.w[i] * (0.5 * tk * tk - (local.theta[i] - phi).cos())
        })
        .sum();
    let l = len / scale;
    if energy < 1.0 {
        let k = ((energy + 1.0) / 2.0).max(0.0).sqrt().clamp(1e-3, 0.999);
        let ell = Elliptic::from_modulus(k).ok()?;
        let th = wrap(local.theta[0] - phi);
        let am = ((th / 2.0).sin() / k).atan2(scale * local.kappa[0] / (2.0 * k));
        Some((Family::Inflectional, [k, ell.f(am), l]))
    } else {
        let k = (2.0 / (energy + 1.0)).sqrt().clamp(1e-2, 0.999);
        let ell = Elliptic::from_modulus(k).ok()?;
        let turning: f64 = mean_curvature(data, local);
        if turning >= 0.0 {
            let am = wrap(local.theta[0] - phi) / 2.0;
            Some((Family::NonInflectional, [k, k * ell.f(am), l]))
        } else {
            // a right turn is the left-turning curve run backwards from the data's end
            let am = wrap(local.theta[n - 1] - phi) / 2.0;
            let s_end = k * ell.f(am);
            Some((Family::NonInflectional, [k, s_end + l, -l]))
        }
    }
}
