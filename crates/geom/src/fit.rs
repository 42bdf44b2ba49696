//! Fitting B-spline curves to points: plain least squares on given knots and a smoothing
//! fit that meets an explicit tolerance.
//!
//! Entry points: [`fit_least_squares`](crate::fit::fit_least_squares), [`fit_smoothing`](crate::fit::fit_smoothing) with [`SmoothingParams`](crate::fit::SmoothingParams),
//! [`chord_length_params`](crate::fit::chord_length_params).
//!
//! The smoothing fit is a penalised spline (P-spline): many uniform knots and a penalty
//! `λ Σ |c_{i+2} − 2c_{i+1} + c_i|²` on the control polygon's second differences. The
//! largest `λ` whose RMS residual stays within the tolerance is found by bisection on
//! `log λ` such that no point is farther than the tolerance from the curve (at the point's
//! parameter), so the result is the smoothest curve of the family within the tolerance of
//! every point. A bound on the largest deviation, rather than the RMS, keeps the ends of the
//! curve honest: an RMS bound lets the penalty flatten the last few millimetres and lose
//! inflections there. This is what removes the false inflections that mesh noise
//! produces on nearly straight stretches, while the tolerance bounds how far the curve may
//! move away from the data.

use nalgebra::SVector;

use crate::banded::SymBand;
use crate::bspline::{basis_funs, clamped_uniform_knots, find_span, BSplineCurve};
use crate::error::{GeomError, Result};

/// Cumulative chord lengths of a polyline, starting at 0 (in the points' units).
///
/// ```
/// use geom::fit::chord_length_params;
/// use nalgebra::Vector2;
/// let pts = [Vector2::new(0.0, 0.0), Vector2::new(3.0, 4.0), Vector2::new(3.0, 5.0)];
/// assert_eq!(chord_length_params(&pts), vec![0.0, 5.0, 6.0]);
/// ```
pub fn chord_length_params<const D: usize>(points: &[SVector<f64, D>]) -> Vec<f64> {
    let mut t = Vec::with_capacity(points.len());
    let mut acc = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            acc += (p - points[i - 1]).norm();
        }
        t.push(acc);
    }
    t
}

fn check_points<const D: usize>(points: &[SVector<f64, D>], params: &[f64]) -> Result<()> {
    if points.len() != params.len() {
        return Err(GeomError::InvalidFit(format!(
            "{} points but {} parameters",
            points.len(),
            params.len()
        )));
    }
    if points.iter().any(|p| p.iter().any(|v| !v.is_finite()))
        || params.iter().any(|t| !t.is_finite())
    {
        return Err(GeomError::NonFinite {
            what: "a point or parameter to fit".into(),
        });
    }
    if params.windows(2).any(|w| w[1] < w[0]) {
        return Err(GeomError::InvalidFit(
            "parameters must be non-decreasing".into(),
        ));
    }
    Ok(())
}

/// The least-squares line `a + b·t` through the points at their parameters.
fn line_through<const D: usize>(
    points: &[SVector<f64, D>],
    params: &[f64],
) -> (SVector<f64, D>, SVector<f64, D>) {
    let m = points.len().max(1) as f64;
    let tm = params.iter().sum::<f64>() / m;
    let pm = points.iter().sum::<SVector<f64, D>>() / m;
    let (mut stt, mut stp) = (0.0, SVector::<f64, D>::zeros());
    for (p, &t) in points.iter().zip(params) {
        stt += (t - tm) * (t - tm);
        stp += (p - pm) * (t - tm);
    }
    let b = if stt > 0.0 {
        stp / stt
    } else {
        SVector::zeros()
    };
    (pm - b * tm, b)
}

/// Assembles `BᵀB + λ DᵀD` and `Bᵀy` and solves for the control points.
///
/// The points' least-squares line `a + b·t` is taken out first and put back into the
/// control points at their Greville abscissae `gᵢ` (`Σ gᵢ Nᵢ(t) = t`, and lines are the
/// penalty's null space, so the problem is the same): the system then solves for the
/// points' departure from a line, and its rounding scales with that departure, not with
/// the coordinates. A straight or planar stretch comes out straight to f64 rounding
/// however large `λ`, instead of wiggling by the solve's error (10⁻⁴ of the
/// coordinates at `λ` ~ 10⁸).
fn solve_penalised<const D: usize>(
    points: &[SVector<f64, D>],
    params: &[f64],
    degree: usize,
    knots: &[f64],
    n: usize,
    lambda: f64,
) -> Option<Vec<SVector<f64, D>>> {
    Penalised::new(points, params, degree, knots, n).solve(lambda)
}

/// The penalised least-squares system of [`solve_penalised`] with its data part assembled
/// once, so that a search over λ solves it again without reassembling (the same numbers,
/// added in the same order).
struct Penalised<const D: usize> {
    /// The straight line `a + b·t` the points are fitted about.
    line: (SVector<f64, D>, SVector<f64, D>),
    /// Greville abscissae of the control points.
    greville: Vec<f64>,
    /// `BᵀB` of the points about the line.
    data: SymBand,
    /// `Bᵀy`.
    rhs: Vec<[f64; D]>,
    n: usize,
}

impl<const D: usize> Penalised<D> {
    fn new(
        points: &[SVector<f64, D>],
        params: &[f64],
        degree: usize,
        knots: &[f64],
        n: usize,
    ) -> Self {
        let (a, b) = line_through(points, params);
        let greville: Vec<f64> = (0..n)
            .map(|i| knots[i + 1..=i + degree].iter().sum::<f64>() / degree.max(1) as f64)
            .collect();
        let band = degree.max(2);
        let mut data = SymBand::zeros(n, band);
        let mut rhs = vec![[0.0; D]; n];
        let mut basis = Vec::new();
        for (p, &t) in points.iter().zip(params) {
            let p = p - (a + b * t);
            let span = find_span(degree, knots, n, t);
            basis_funs(degree, knots, span, t, &mut basis);
            let first = span - degree;
            for (i, bi) in basis.iter().enumerate() {
                for (j, bj) in basis.iter().enumerate().skip(i) {
                    data.add(first + i, first + j, bi * bj);
                }
                for c in 0..D {
                    rhs[first + i][c] += bi * p[c];
                }
            }
        }
        Self {
            line: (a, b),
            greville,
            data,
            rhs,
            n,
        }
    }

    /// The control points at smoothing weight `lambda`.
    fn solve(&self, lambda: f64) -> Option<Vec<SVector<f64, D>>> {
        let n = self.n;
        let mut a = self.data.clone();
        if lambda > 0.0 && n >= 3 {
            // Second divided differences over the Greville abscissae gᵢ: their null space is
            // cᵢ = A + B·gᵢ, i.e. exactly the straight lines parameterised linearly (linear
            // precision), so a chord-length parameterised straight stretch is not penalised.
            let g = &self.greville;
            let mean = (g[n - 1] - g[0]) / (n - 1) as f64;
            for i in 0..n - 2 {
                let (h0, h1) = (
                    (g[i + 1] - g[i]).max(1e-300),
                    (g[i + 2] - g[i + 1]).max(1e-300),
                );
                let w = [mean / h0, -mean / h0 - mean / h1, mean / h1];
                for r in 0..3 {
                    for s in r..3 {
                        a.add(i + r, i + s, lambda * w[r] * w[s]);
                    }
                }
            }
        }
        // a tiny ridge keeps spans without data solvable; it does not change well-posed fits
        let scale = a.rows.iter().map(|r| r[0]).fold(0.0, f64::max).max(1.0);
        for i in 0..n {
            a.rows[i][0] += 1e-12 * scale;
        }
        let sol = a.solve(&self.rhs)?;
        let (la, lb) = self.line;
        Some(
            sol.into_iter()
                .map(SVector::<f64, D>::from)
                .zip(&self.greville)
                .map(|(c, &g)| c + la + lb * g)
                .collect(),
        )
    }
}

/// RMS residual, largest residual, and largest residual relative to each point's allowance.
fn residuals<const D: usize>(
    curve: &BSplineCurve<D>,
    points: &[SVector<f64, D>],
    params: &[f64],
    allow: &[f64],
) -> (f64, f64, f64) {
    let mut sum = 0.0;
    let mut max: f64 = 0.0;
    let mut ratio: f64 = 0.0;
    for ((p, &t), &a) in points.iter().zip(params).zip(allow) {
        let d = (curve.eval(t) - p).norm();
        sum += d * d;
        max = max.max(d);
        let r = if a > 0.0 {
            d / a
        } else if d > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        ratio = ratio.max(r);
    }
    ((sum / points.len() as f64).sqrt(), max, ratio)
}

/// Sagitta of the polyline at each point: `h·θ/8` with `h` the mean of the two adjacent
/// segment lengths and `θ` the turning angle there (the ends copy their neighbours). For a
/// polyline that samples a smooth curve with spacing `h` this is the chordal error `κh²/8`.
pub fn polyline_sagitta<const D: usize>(points: &[SVector<f64, D>]) -> Vec<f64> {
    let n = points.len();
    let mut out = vec![0.0; n];
    for i in 1..n.saturating_sub(1) {
        let a = points[i] - points[i - 1];
        let b = points[i + 1] - points[i];
        let (la, lb) = (a.norm(), b.norm());
        if la > 0.0 && lb > 0.0 {
            let cos = (a.dot(&b) / (la * lb)).clamp(-1.0, 1.0);
            out[i] = 0.5 * (la + lb) * cos.acos() / 8.0;
        }
    }
    if n >= 3 {
        out[0] = out[1];
        out[n - 1] = out[n - 2];
    }
    out
}

/// Least-squares fit of a degree-`degree` B-spline with the given knot vector to points with
/// parameters `params` (minimises `Σ |s(tⱼ) − pⱼ|²`).
///
/// # Errors
/// [`GeomError::InvalidFit`] for mismatched or too few points, or when the system is singular
/// (a knot span with no data); [`GeomError::InvalidSpline`] for a bad knot vector.
///
/// ```
/// use geom::bspline::clamped_uniform_knots;
/// use geom::fit::fit_least_squares;
/// use nalgebra::Vector2;
/// // a cubic polynomial lies in the space of cubic splines: the fit reproduces it
/// let f = |t: f64| Vector2::new(t, t * t * t - t);
/// let params: Vec<f64> = (0..20).map(|i| i as f64 / 19.0).collect();
/// let points: Vec<_> = params.iter().map(|&t| f(t)).collect();
/// let curve = fit_least_squares(&points, &params, 3, clamped_uniform_knots(3, 6, 0.0, 1.0))?;
/// for t in [0.0, 0.37, 0.81, 1.0] {
///     assert!((curve.eval(t) - f(t)).norm() < 1e-12);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_least_squares<const D: usize>(
    points: &[SVector<f64, D>],
    params: &[f64],
    degree: usize,
    knots: Vec<f64>,
) -> Result<BSplineCurve<D>> {
    check_points(points, params)?;
    let n = knots.len().saturating_sub(degree + 1);
    crate::bspline::check_knots(degree, &knots, n)?;
    if points.len() < n {
        return Err(GeomError::InvalidFit(format!(
            "{} points cannot determine {n} control points",
            points.len()
        )));
    }
    let control = solve_penalised(points, params, degree, &knots, n, 0.0)
        .ok_or_else(|| GeomError::InvalidFit("singular least-squares system".into()))?;
    BSplineCurve::try_new(degree, knots, control)
}

/// Parameters of [`fit_smoothing`].
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothingParams {
    /// Spline degree (3 gives continuous curvature).
    pub degree: usize,
    /// Largest allowed distance between a point and the curve at the point's parameter, in
    /// the points' units. Must be ≥ 0.
    pub tolerance: f64,
    /// Upper bound on the number of control points (the fit uses about one per two points).
    pub max_control: usize,
    /// Treat the points as a chordal polyline (a mesh section): each point may then deviate
    /// by `max(tolerance, its sagitta)` (see [`polyline_sagitta`]), because a point on a
    /// facet is only known to within the facet's distance from the true surface.
    pub chordal: bool,
}

impl Default for SmoothingParams {
    fn default() -> Self {
        Self {
            degree: 3,
            tolerance: 1e-3,
            max_control: 400,
            chordal: false,
        }
    }
}

/// The result of [`fit_smoothing`].
#[derive(Debug, Clone)]
pub struct SplineFit<const D: usize> {
    /// The fitted curve; its parameter is the points' chord-length parameter.
    pub curve: BSplineCurve<D>,
    /// RMS residual at the points.
    pub rms: f64,
    /// Largest residual at a point.
    pub max_error: f64,
    /// The smoothing weight used (relative to the data term; 0 = plain least squares).
    pub lambda: f64,
    /// How far each point is known to lie from the true curve, whatever the tolerance: the
    /// larger of its chordal sagitta (with `chordal`) and its known deviation (0 for exact
    /// points). A wiggle of the curve smaller than the data's own error is not in the data
    /// ([`crate::significance`]).
    pub precision: Vec<f64>,
}

/// Smoothing spline through `points` (parameters by chord length when `params` is `None`):
/// the smoothest P-spline whose largest residual is at most `params.tolerance`. When even
/// the least-squares spline misses the tolerance, that spline is returned and its
/// `max_error` says so.
///
/// # Errors
/// [`GeomError::InvalidFit`] for fewer than two distinct points or mismatched input;
/// [`GeomError::NonFinite`] for NaN input; a negative or NaN tolerance.
///
/// # Example
/// ```
/// use geom::fit::{fit_smoothing, SmoothingParams};
/// use nalgebra::Vector2;
/// let pts: Vec<_> = (0..50).map(|i| Vector2::new(i as f64, (i as f64 / 8.0).sin())).collect();
/// let fit = fit_smoothing(&pts, None, &SmoothingParams { tolerance: 0.01, ..Default::default() }).unwrap();
/// assert!(fit.rms <= 0.01 + 1e-9);
/// ```
pub fn fit_smoothing<const D: usize>(
    points: &[SVector<f64, D>],
    params: Option<&[f64]>,
    opts: &SmoothingParams,
) -> Result<SplineFit<D>> {
    fit_smoothing_allowing(points, params, opts, None)
}

/// [`fit_smoothing`] where point `i` may also deviate by `known[i]` (how far it is known
/// to lie from the true curve, e.g. a mesh facet's distance from the surface it
/// approximates); the allowance at each point is the largest of the tolerance, the
/// chordal sagitta (with `opts.chordal`) and `known[i]`.
///
/// # Errors
/// As [`fit_smoothing`]; `known` of another length than `points`.
///
/// ```
/// use geom::fit::{fit_smoothing_allowing, SmoothingParams};
/// use nalgebra::Vector2;
/// // points known to lie up to 0.05 off the true curve may deviate that much from the fit
/// let pts: Vec<_> = (0..40).map(|i| Vector2::new(i as f64, (i as f64 / 6.0).sin())).collect();
/// let known = vec![0.05; pts.len()];
/// let opts = SmoothingParams { tolerance: 1e-3, ..SmoothingParams::default() };
/// let fit = fit_smoothing_allowing(&pts, None, &opts, Some(&known))?;
/// assert!(fit.max_error <= 0.05 + 1e-9);
/// // one allowance per point is required
/// assert!(fit_smoothing_allowing(&pts, None, &opts, Some(&known[1..])).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_smoothing_allowing<const D: usize>(
    points: &[SVector<f64, D>],
    params: Option<&[f64]>,
    opts: &SmoothingParams,
    known: Option<&[f64]>,
) -> Result<SplineFit<D>> {
    if known.is_some_and(|k| k.len() != points.len()) {
        return Err(GeomError::InvalidFit(
            "one known deviation per point needed".into(),
        ));
    }
    // fitted about the first point, so a model far from the origin (coordinates near 10⁶)
    // loses no digits in the normal equations; the control points are moved back after
    let centre = points
        .first()
        .copied()
        .filter(|c| c.iter().all(|v| v.is_finite()))
        .unwrap_or_else(SVector::zeros);
    let local: Vec<SVector<f64, D>> = points.iter().map(|p| p - centre).collect();
    let fit = fit_smoothing_at_origin(&local, params, opts, known)?;
    let control: Vec<SVector<f64, D>> = fit
        .curve
        .control_points()
        .iter()
        .map(|c| c + centre)
        .collect();
    Ok(SplineFit {
        curve: BSplineCurve::try_new(fit.curve.degree(), fit.curve.knots().to_vec(), control)?,
        ..fit
    })
}

/// [`fit_smoothing`] of points near the origin.
fn fit_smoothing_at_origin<const D: usize>(
    points: &[SVector<f64, D>],
    params: Option<&[f64]>,
    opts: &SmoothingParams,
    known: Option<&[f64]>,
) -> Result<SplineFit<D>> {
    if !(opts.tolerance >= 0.0) || !opts.tolerance.is_finite() {
        return Err(GeomError::InvalidFit(format!(
            "tolerance must be a finite number ≥ 0, got {:?}",
            opts.tolerance
        )));
    }
    let owned;
    let params = match params {
        Some(p) => p,
        None => {
            owned = chord_length_params(points);
            &owned
        }
    };
    check_points(points, params)?;
    let m = points.len();
    let (a, b) = (params[0], params[m - 1]);
    if m < 2 || !(b > a) {
        return Err(GeomError::InvalidFit(
            "need at least two distinct points".into(),
        ));
    }
    let degree = opts.degree.clamp(1, 5).min(m - 1).max(1);
    let n = (m / 2)
        .clamp(degree + 1, opts.max_control.max(degree + 1))
        .min(m.max(degree + 1));
    let knots = clamped_uniform_knots(degree, n, a, b);
    // each point's own error: its chordal sagitta and its known deviation
    let mut precision: Vec<f64> = if opts.chordal {
        polyline_sagitta(points)
    } else {
        vec![0.0; m]
    };
    if let Some(k) = known {
        for (p, k) in precision.iter_mut().zip(k) {
            if k.is_finite() {
                *p = p.max(*k);
            }
        }
    }
    let allow: Vec<f64> = precision.iter().map(|p| p.max(opts.tolerance)).collect();

    let system = Penalised::new(points, params, degree, &knots, n);
    // Scale λ so that it is dimensionless: data term ~ m, penalty term ~ n.
    let unit = m as f64 / n as f64;
    let fit_at = |log_lambda: f64| -> Option<(BSplineCurve<D>, f64, f64, f64)> {
        let lambda = if log_lambda.is_finite() {
            unit * 10f64.powf(log_lambda)
        } else {
            0.0
        };
        let control = system.solve(lambda)?;
        let curve = BSplineCurve::try_new(degree, knots.clone(), control).ok()?;
        let (rms, max, ratio) = residuals(&curve, points, params, &allow);
        Some((curve, rms, max, ratio))
    };
    let singular = || GeomError::InvalidFit("singular smoothing system".into());

    let (lo_curve, lo_rms, lo_max, lo_ratio) = fit_at(-8.0).ok_or_else(singular)?;
    if lo_ratio > 1.0 {
        return Ok(SplineFit {
            curve: lo_curve,
            rms: lo_rms,
            max_error: lo_max,
            lambda: unit * 1e-8,
            precision: precision.clone(),
        });
    }
    let hi = 8.0;
    if let Some((curve, rms, max, ratio)) = fit_at(hi) {
        if ratio <= 1.0 {
            return Ok(SplineFit {
                curve,
                rms,
                max_error: max,
                lambda: unit * 10f64.powf(hi),
                precision: precision.clone(),
            });
        }
    }
    let (mut lo, mut hi) = (-8.0, hi);
    let mut best = (lo_curve, lo_rms, lo_max, lo);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        match fit_at(mid) {
            Some((c, rms, max, ratio)) if ratio <= 1.0 => {
                best = (c, rms, max, mid);
                lo = mid;
            }
            _ => hi = mid,
        }
        if hi - lo < 0.02 {
            break;
        }
    }
    Ok(SplineFit {
        curve: best.0,
        rms: best.1,
        max_error: best.2,
        lambda: unit * 10f64.powf(best.3),
        precision: precision.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    #[test]
    fn least_squares_reproduces_a_spline() {
        let ctrl: Vec<_> = [(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.0), (6.0, 1.0)]
            .iter()
            .map(|&(x, y)| Vector2::new(x, y))
            .collect();
        let c = BSplineCurve::clamped_uniform(3, ctrl.clone()).unwrap();
        let ts: Vec<f64> = (0..40).map(|i| i as f64 / 39.0).collect();
        let pts: Vec<_> = ts.iter().map(|&t| c.eval(t)).collect();
        let f = fit_least_squares(&pts, &ts, 3, c.knots().to_vec()).unwrap();
        for (a, b) in f.control_points().iter().zip(&ctrl) {
            assert!((a - b).norm() < 1e-8);
        }
    }

    #[test]
    fn smoothing_meets_tolerance_and_straightens_noise() {
        // a straight line with deterministic "noise"
        let pts: Vec<_> = (0..200)
            .map(|i| {
                let x = i as f64;
                Vector2::new(x, 0.05 * ((i * 7919 % 13) as f64 / 13.0 - 0.5))
            })
            .collect();
        let fit = fit_smoothing(
            &pts,
            None,
            &SmoothingParams {
                tolerance: 0.05,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(fit.rms <= 0.05);
        // the fitted curve is nearly straight: tiny curvature everywhere
        let d1 = fit.curve.derivative();
        let d2 = d1.derivative();
        let (a, b) = fit.curve.domain();
        for k in 0..=100 {
            let t = a + (b - a) * k as f64 / 100.0;
            let (u, v) = (d1.eval(t), d2.eval(t));
            let kappa = (u.x * v.y - u.y * v.x) / u.norm().powi(3);
            assert!(kappa.abs() < 1e-5, "t={t}: {kappa}");
        }
    }

    #[test]
    fn rejects_bad_tolerance_and_nan() {
        let pts = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(2.0, 0.0),
        ];
        assert!(fit_smoothing(
            &pts,
            None,
            &SmoothingParams {
                tolerance: -1.0,
                ..Default::default()
            }
        )
        .is_err());
        let bad = vec![Vector2::new(0.0, 0.0), Vector2::new(f64::NAN, 0.0)];
        assert!(fit_smoothing(&bad, None, &SmoothingParams::default()).is_err());
        let same = vec![Vector2::new(1.0, 1.0); 4];
        assert!(fit_smoothing(&same, None, &SmoothingParams::default()).is_err());
    }
}
