//! The comparison baseline of the benchmarks: a generic least-squares fit of all seven
//! parameters (k, s₀, ℓ, S, φ, x₀, y₀) by Levenberg–Marquardt with a forward-difference
//! Jacobian, from the same §5.1 initial guess and with the same arc-length matching (chord
//! lengths, trapezoid weights), and nothing else: no variable projection, no analytic
//! derivatives, no line or arc candidates, no orthogonal refinement. This is what a
//! straightforward implementation of "Hot Blade Cuttings" §5.1 looks like; it exists so that
//! `BENCHMARKS.md` can say how much the method of [`crate::fit::fit_points`] gains.

use super::model::{place, trapezoid_weights, Data, Placement, C};
use super::{guess, FitError, FitResult};
use crate::segment::{ElasticaParams, ElasticaSegment, Segment};
use nalgebra::{SMatrix, SVector};

type M7 = SMatrix<f64, 7, 7>;
type V7 = SVector<f64, 7>;

/// Fit points (matched by chord length) by a generic 7-parameter Levenberg–Marquardt solve
/// from the §5.1 guess. Fails with [`FitError::Failed`] where the guess finds no elastica
/// (λ ≈ 0: lines and circles) or the solve diverges.
///
/// ```
/// use elastica::fit::baseline::fit_points_baseline;
/// // a piece of a parabola
/// let pts: Vec<[f64; 2]> = (0..50).map(|i| {
///     let x = i as f64 / 49.0;
///     [x, 0.3 * x * x]
/// }).collect();
/// let fit = fit_points_baseline(&pts, 200).unwrap();
/// assert!(fit.rms < 1e-3);
/// ```
pub fn fit_points_baseline(
    points: &[[f64; 2]],
    max_iterations: usize,
) -> Result<FitResult, FitError> {
    let n = points.len();
    if n < 3 {
        return Err(FitError::TooFewPoints(n));
    }
    let mut s = vec![0.0; n];
    for i in 0..n {
        if !(points[i][0].is_finite() && points[i][1].is_finite()) {
            return Err(FitError::NonFinite(i));
        }
        if i > 0 {
            let d = (points[i][0] - points[i - 1][0]).hypot(points[i][1] - points[i - 1][1]);
            if !(d > 0.0) {
                return Err(FitError::NotIncreasing(i));
            }
            s[i] = s[i - 1] + d;
        }
    }
    let length = s[n - 1];
    let t: Vec<f64> = s.iter().map(|v| v / length).collect();
    let data = Data {
        p: points.iter().map(|p| C::new(p[0], p[1])).collect(),
        w: trapezoid_weights(&t),
        t,
        length,
    };
    let local = guess::local_geometry(&data);
    let (family, theta) = guess::elastica_guess(&data, &local)
        .ok_or_else(|| FitError::Failed("the guess found no elastica (line or circle)".into()))?;
    let unit = crate::unit::UnitElastica::new(family, theta[0])
        .map_err(|e| FitError::Failed(e.to_string()))?;
    let z: Vec<C> = data
        .t
        .iter()
        .map(|&t| {
            let p = unit.eval(theta[1] + theta[2] * t).p;
            C::new(p[0], p[1])
        })
        .collect();
    let (a, b) = place(&z, &data, Placement::Free)
        .ok_or_else(|| FitError::Failed("degenerate guess".into()))?;
    let mut x = V7::from([theta[0], theta[1], theta[2], a.norm(), a.arg(), b.re, b.im]);
    let params = |x: &V7| ElasticaParams {
        one_minus_k: None,
        family,
        k: x[0],
        s0: x[1],
        l: x[2],
        scale: x[3],
        phi: x[4],
        x0: x[5],
        y0: x[6],
    };
    let residuals = |x: &V7| -> Option<Vec<f64>> {
        let seg = ElasticaSegment::new(params(x)).ok()?;
        let mut r = Vec::with_capacity(2 * n);
        for i in 0..n {
            let q = seg.eval(data.t[i]).p;
            let sw = data.w[i].sqrt();
            r.push(sw * (q[0] - data.p[i].re));
            r.push(sw * (q[1] - data.p[i].im));
        }
        Some(r)
    };
    let sq = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut r = residuals(&x).ok_or_else(|| FitError::Failed("guess outside the domain".into()))?;
    let mut f = sq(&r);
    let mut mu = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    for _ in 0..max_iterations {
        iterations += 1;
        // forward-difference Jacobian, one extra residual evaluation per parameter
        let mut jac = vec![[0.0; 7]; 2 * n];
        for j in 0..7 {
            let h = 1e-7 * x[j].abs().max(1.0);
            // forward step, or backward where the forward one leaves the domain (k ≤ 1)
            let (rs, step) = [h, -h]
                .iter()
                .find_map(|&step| {
                    let mut xs = x;
                    xs[j] += step;
                    residuals(&xs).map(|rs| (rs, step))
                })
                .ok_or_else(|| FitError::Failed("Jacobian outside the domain".into()))?;
            for i in 0..2 * n {
                jac[i][j] = (rs[i] - r[i]) / step;
            }
        }
        let mut h = M7::zeros();
        let mut g = V7::zeros();
        for (ji, ri) in jac.iter().zip(&r) {
            for a in 0..7 {
                g[a] += ji[a] * ri;
                for b in 0..7 {
                    h[(a, b)] += ji[a] * ji[b];
                }
            }
        }
        let mut accepted = false;
        for _ in 0..20 {
            let mut d = h;
            for a in 0..7 {
                d[(a, a)] += mu * h[(a, a)].max(1e-300);
            }
            let Some(step) = d.cholesky().map(|c| c.solve(&(-g))) else {
                mu *= 10.0;
                continue;
            };
            let xt = x + step;
            match residuals(&xt) {
                Some(rt) if sq(&rt) < f => {
                    let ft = sq(&rt);
                    converged = (f - ft) <= 1e-12 * f;
                    x = xt;
                    r = rt;
                    f = ft;
                    mu = (mu / 3.0).max(1e-15);
                    accepted = true;
                    break;
                }
                _ => mu *= 4.0,
            }
        }
        if !accepted || converged {
            converged = true;
            break;
        }
    }
    let seg = ElasticaSegment::new(params(&x)).map_err(|e| FitError::Failed(e.to_string()))?;
    let mut max: f64 = 0.0;
    for i in 0..n {
        let q = seg.eval(data.t[i]).p;
        max = max.max((q[0] - data.p[i].re).hypot(q[1] - data.p[i].im));
    }
    Ok(FitResult {
        segment: Segment::Elastica(params(&x)),
        rms: f.sqrt(),
        max,
        l2: (f * length).sqrt(),
        input_length: length,
        iterations,
        converged,
        t: data.t,
    })
}
