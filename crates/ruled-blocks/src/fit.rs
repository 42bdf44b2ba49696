//! Eq. (4.1) of the thesis: the piecewise ruled surface `s` closest, in least squares, to a
//! region's samples `f_{i,j}` taken on a `(u_i, v_j)` grid,
//!
//! `min Σᵢ Σⱼ ‖f_{i,j} − s(u_i, v_j)‖²`,
//!
//! ch. 2's fit without its constraints. `s` has `strips + 1` rails — B-spline curves in `u`
//! of one degree and knot vector — joined by straight rulings in `v` (degree 1 in `v`,
//! [`geom::BSplineSurface::piecewise_ruled`]); neighbouring strips share their rail, so the
//! patch is C⁰ across its strips.
//!
//! The surface is a tensor product and the samples a full grid, so the least-squares
//! problem separates: with `B_v` (rows: `v_j`, columns: hat functions of the rails) and
//! `B_u` (rows: `u_i`, columns: B-spline basis functions), each coordinate's control grid
//! is `C = B_v⁺ F (B_u⁺)ᵀ` (pseudo-inverses by SVD). Our own: the problem is a few lines of
//! linear algebra on nalgebra; no fitting crate fits rulings to a grid.

use geom::bspline::{clamped_uniform_knots, nonzero_basis};
use geom::BSplineSurface;
use nalgebra::{DMatrix, Vector3};

/// Largest number of samples along `u` or `v`.
pub const MAX_SAMPLES_PER_AXIS: usize = 100_000;
/// Largest number of samples in a grid.
pub const MAX_SAMPLES: usize = 10_000_000;
/// Largest number of control points of a rail, and of strips.
pub const MAX_CONTROLS: usize = 1_000;
/// A basis matrix whose smallest singular value is below this share of its largest is
/// rank deficient: its samples do not pin every control point.
const RANK_TOLERANCE: f64 = 1e-10;

/// Samples of a region on a `(u, v)` grid.
#[derive(Debug, Clone, PartialEq)]
pub struct GridSamples {
    /// Parameters along the rails, strictly increasing.
    pub u: Vec<f64>,
    /// Parameters across the rails (along the rulings), strictly increasing.
    pub v: Vec<f64>,
    /// The points, row by row: `points[j * u.len() + i]` is `f(u_i, v_j)`.
    pub points: Vec<[f64; 3]>,
}

/// What to fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RuledFitParams {
    /// Ruled strips across the region (rails: one more), ≥ 1.
    pub strips: usize,
    /// Degree of the rails, ≥ 1.
    pub degree: usize,
    /// Control points of each rail, ≥ `degree + 1`.
    pub controls: usize,
}

/// A fitted piecewise ruled surface.
#[derive(Debug, Clone, PartialEq)]
pub struct RuledFit {
    /// The surface: degree `degree` in `u` over the samples' `u` range, degree 1 in `v`
    /// with its rails at `v` spread evenly over the samples' `v` range.
    pub surface: BSplineSurface,
    /// `|f_{i,j} − s(u_i, v_j)|` per sample, in the samples' order: the distance from each
    /// sample to the surface point of its own parameters (an upper bound on its distance
    /// to the surface).
    pub residuals: Vec<f64>,
    /// Root mean square of the residuals.
    pub rms: f64,
    /// The largest residual.
    pub max_residual: f64,
    /// Each sample's distance to the surface (its closest point, found from the sample's
    /// own parameters; never more than its residual), in the samples' order.
    pub distances: Vec<f64>,
    /// Root mean square of the distances.
    pub rms_distance: f64,
    /// The largest distance.
    pub max_distance: f64,
}

/// Most Gauss–Newton steps of a closest-point search.
pub const MAX_PROJECTION_STEPS: usize = 60;

/// The distance from `p` to `surface` and the parameters of its closest point, searched
/// by Gauss–Newton steps from `start` within the surface's domain (at most
/// [`MAX_PROJECTION_STEPS`]; a step that does not bring the point closer is halved, so the
/// distance never exceeds `|p − s(start)|`).
///
/// ```
/// use geom::{BSplineCurve, BSplineSurface};
/// use nalgebra::Vector3;
/// use ruled_blocks::fit::closest_point;
/// // the unit square in z = 0 as a ruled surface
/// let line = |y: f64| BSplineCurve::clamped_uniform(1, vec![Vector3::new(0.0, y, 0.0), Vector3::new(1.0, y, 0.0)]);
/// let square = BSplineSurface::ruled(&line(1.0)?, &line(0.0)?)?;
/// let (d, (u, v)) = closest_point(&square, Vector3::new(0.25, 0.5, 0.75), (0.9, 0.1));
/// assert!((d - 0.75).abs() < 1e-12 && (u - 0.25).abs() < 1e-12 && (v - 0.5).abs() < 1e-12);
/// // beyond the edge: the distance to the edge
/// let (d, _) = closest_point(&square, Vector3::new(2.0, 0.5, 0.0), (0.5, 0.5));
/// assert!((d - 1.0).abs() < 1e-12);
/// # Ok::<(), geom::GeomError>(())
/// ```
pub fn closest_point(
    surface: &BSplineSurface,
    p: Vector3<f64>,
    start: (f64, f64),
) -> (f64, (f64, f64)) {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let clamp = |(u, v): (f64, f64)| (u.clamp(u0, u1), v.clamp(v0, v1));
    let mut at = clamp(start);
    let mut best = (p - surface.eval(at.0, at.1)).norm();
    let small = 1e-14 * ((u1 - u0) + (v1 - v0));
    for _ in 0..MAX_PROJECTION_STEPS {
        let (s, su, sv) = surface.partials(at.0, at.1);
        let r = p - s;
        // the normal equations of min |r − J δ|², J = [s_u s_v]
        let (a, b, c) = (su.dot(&su), su.dot(&sv), sv.dot(&sv));
        let (gu, gv) = (su.dot(&r), sv.dot(&r));
        let det = a * c - b * b;
        if !(det > 1e-300) {
            break;
        }
        let mut step = ((c * gu - b * gv) / det, (a * gv - b * gu) / det);
        let mut moved = false;
        for _ in 0..30 {
            let next = clamp((at.0 + step.0, at.1 + step.1));
            let d = (p - surface.eval(next.0, next.1)).norm();
            if d < best {
                moved = (next.0 - at.0).abs() + (next.1 - at.1).abs() > small;
                best = d;
                at = next;
                break;
            }
            step = (0.5 * step.0, 0.5 * step.1);
        }
        if !moved {
            break;
        }
    }
    (best, at)
}

/// Why a fit cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// The samples are not a grid of finite points on increasing parameters (named).
    #[error("samples: {0}")]
    Samples(String),
    /// A parameter is out of range (its field, and what is wrong).
    #[error("`{field}` {message}")]
    Params {
        /// The field of [`RuledFitParams`].
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The samples do not pin every control point: too few in some knot span.
    #[error("the samples along {axis} do not determine every control point (condition {condition:.3e}): sample more densely or ask for fewer {field}")]
    RankDeficient {
        /// `u` or `v`.
        axis: &'static str,
        /// The field to lower: `controls` or `strips`.
        field: &'static str,
        /// The basis matrix's smallest over largest singular value.
        condition: f64,
    },
}

fn check(samples: &GridSamples, p: &RuledFitParams) -> Result<(), FitError> {
    let (nu, nv) = (samples.u.len(), samples.v.len());
    let increasing =
        |t: &[f64]| t.iter().all(|x| x.is_finite()) && t.windows(2).all(|w| w[1] > w[0]);
    if !(2..=MAX_SAMPLES_PER_AXIS).contains(&nu) || !(2..=MAX_SAMPLES_PER_AXIS).contains(&nv) {
        return Err(FitError::Samples(format!(
            "{nu} × {nv} parameters: each axis needs 2–{MAX_SAMPLES_PER_AXIS}"
        )));
    }
    if nu * nv > MAX_SAMPLES {
        return Err(FitError::Samples(format!(
            "{nu} × {nv} samples: at most {MAX_SAMPLES}"
        )));
    }
    if !increasing(&samples.u) || !increasing(&samples.v) {
        return Err(FitError::Samples(
            "u and v must be finite and strictly increasing".into(),
        ));
    }
    if samples.points.len() != nu * nv {
        return Err(FitError::Samples(format!(
            "{} points for a {nu} × {nv} grid",
            samples.points.len()
        )));
    }
    if let Some(k) = samples
        .points
        .iter()
        .position(|q| q.iter().any(|x| !x.is_finite()))
    {
        return Err(FitError::Samples(format!("point {k} is not finite")));
    }
    let bad = |field, message: String| Err(FitError::Params { field, message });
    if !(1..=MAX_CONTROLS).contains(&p.strips) {
        return bad(
            "strips",
            format!("must be 1–{MAX_CONTROLS}, got {}", p.strips),
        );
    }
    if p.strips + 1 > nv {
        return bad(
            "strips",
            format!(
                "{} strips need {} samples across, got {nv}",
                p.strips,
                p.strips + 1
            ),
        );
    }
    if !(1..=5).contains(&p.degree) {
        return bad("degree", format!("must be 1–5, got {}", p.degree));
    }
    if !(p.degree + 1..=MAX_CONTROLS).contains(&p.controls) {
        return bad(
            "controls",
            format!(
                "must be {}–{MAX_CONTROLS} (degree + 1 or more), got {}",
                p.degree + 1,
                p.controls
            ),
        );
    }
    if p.controls > nu {
        return bad(
            "controls",
            format!(
                "{} control points need {} samples along, got {nu}",
                p.controls, p.controls
            ),
        );
    }
    Ok(())
}

/// The basis matrix of `n` B-spline functions of `degree` on `knots` at `t`.
fn basis_matrix(t: &[f64], degree: usize, knots: &[f64], n: usize) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(t.len(), n);
    for (r, &x) in t.iter().enumerate() {
        let (first, values) = nonzero_basis(degree, knots, n, x);
        for (k, b) in values.into_iter().enumerate() {
            m[(r, first + k)] = b;
        }
    }
    m
}

/// The pseudo-inverse of a full-column-rank basis matrix.
fn pseudo_inverse(
    m: DMatrix<f64>,
    axis: &'static str,
    field: &'static str,
) -> Result<DMatrix<f64>, FitError> {
    let svd = m.svd(true, true);
    let s = &svd.singular_values;
    let (lo, hi) = (s.min(), s.max());
    let condition = if hi > 0.0 { lo / hi } else { 0.0 };
    if !(condition > RANK_TOLERANCE) {
        return Err(FitError::RankDeficient {
            axis,
            field,
            condition,
        });
    }
    svd.pseudo_inverse(RANK_TOLERANCE * hi)
        .map_err(|_| FitError::RankDeficient {
            axis,
            field,
            condition,
        })
}

/// Fits the piecewise ruled surface of `params` to `samples` (eq. 4.1).
///
/// # Errors
/// [`FitError::Samples`] for samples that are not a finite grid on increasing parameters,
/// [`FitError::Params`] for parameters out of range, [`FitError::RankDeficient`] when the
/// samples leave a control point free.
///
/// ```
/// use ruled_blocks::fit::{fit_piecewise_ruled, GridSamples, RuledFitParams};
/// // a quarter cylinder of radius 2 and height 1: straight along v, so one strip is
/// // exact across; along u the cubic rails approximate the circle
/// let u: Vec<f64> = (0..40).map(|i| i as f64 / 39.0).collect();
/// let v = vec![0.0, 0.5, 1.0];
/// let points = v
///     .iter()
///     .flat_map(|&z| u.iter().map(move |&t| {
///         let a = t * std::f64::consts::FRAC_PI_2;
///         [2.0 * a.cos(), 2.0 * a.sin(), z]
///     }))
///     .collect();
/// let samples = GridSamples { u, v, points };
/// let fit = fit_piecewise_ruled(&samples, &RuledFitParams { strips: 1, degree: 3, controls: 6 })?;
/// assert!(fit.max_residual < 1e-3 * 2.0 && fit.rms <= fit.max_residual); // within 0.1 % of the radius
/// // asking for more control points than samples along u is refused
/// assert!(fit_piecewise_ruled(&samples, &RuledFitParams { strips: 1, degree: 3, controls: 41 }).is_err());
/// # Ok::<(), ruled_blocks::fit::FitError>(())
/// ```
pub fn fit_piecewise_ruled(
    samples: &GridSamples,
    params: &RuledFitParams,
) -> Result<RuledFit, FitError> {
    let (surface, residuals) = fit_surface(samples, params)?;
    Ok(measure(samples, surface, residuals))
}

/// The least-squares surface of [`fit_piecewise_ruled`] and each sample's residual,
/// without the closest-point distances (the costly part).
///
/// # Errors
/// As [`fit_piecewise_ruled`].
pub fn fit_surface(
    samples: &GridSamples,
    params: &RuledFitParams,
) -> Result<(BSplineSurface, Vec<f64>), FitError> {
    check(samples, params)?;
    let (nu, nv) = (samples.u.len(), samples.v.len());
    let (v0, v1) = (samples.v[0], samples.v[nv - 1]);
    let rails = params.strips + 1;
    let knots_u = averaged_knots(&samples.u, params.degree, params.controls);
    let knots_v = clamped_uniform_knots(1, rails, v0, v1);
    let pu = pseudo_inverse(
        basis_matrix(&samples.u, params.degree, &knots_u, params.controls),
        "u",
        "controls",
    )?;
    let pv = pseudo_inverse(basis_matrix(&samples.v, 1, &knots_v, rails), "v", "strips")?;
    // C = B_v⁺ F (B_u⁺)ᵀ per coordinate: rails × controls
    let coordinate = |c: usize| {
        let f = DMatrix::from_fn(nv, nu, |j, i| samples.points[j * nu + i][c]);
        &pv * f * pu.transpose()
    };
    let grids = [coordinate(0), coordinate(1), coordinate(2)];
    let mut control = Vec::with_capacity(params.controls * rails);
    for i in 0..params.controls {
        for j in 0..rails {
            control.push(Vector3::new(
                grids[0][(j, i)],
                grids[1][(j, i)],
                grids[2][(j, i)],
            ));
        }
    }
    let surface = BSplineSurface::try_new(
        (params.degree, 1),
        knots_u,
        knots_v,
        (params.controls, rails),
        control,
    )
    .map_err(|e| FitError::Samples(format!("the fitted surface: {e}")))?;
    let residuals: Vec<f64> = samples
        .v
        .iter()
        .enumerate()
        .flat_map(|(j, &v)| {
            let s = &surface;
            samples.u.iter().enumerate().map(move |(i, &u)| {
                (Vector3::from(samples.points[j * nu + i]) - s.eval(u, v)).norm()
            })
        })
        .collect();
    Ok((surface, residuals))
}

/// The fit of `surface` to `samples` with their `residuals`: each sample's distance to the
/// surface, RMS and largest of both.
pub fn measure(samples: &GridSamples, surface: BSplineSurface, residuals: Vec<f64>) -> RuledFit {
    let distances: Vec<f64> = samples
        .v
        .iter()
        .flat_map(|&v| samples.u.iter().map(move |&u| (u, v)))
        .zip(&samples.points)
        .map(|(at, q)| closest_point(&surface, Vector3::from(*q), at).0)
        .collect();
    let (rms, max_residual) = rms_and_max(&residuals);
    let (rms_distance, max_distance) = rms_and_max(&distances);
    RuledFit {
        surface,
        residuals,
        rms,
        max_residual,
        distances,
        rms_distance,
        max_distance,
    }
}

/// Clamped knots for a least-squares fit of `n` control points of degree `p` through
/// samples at `u` (increasing): the inner knots placed among the samples (Piegl & Tiller,
/// *The NURBS Book*, eq. 9.69), so that every knot span holds samples (the
/// Schoenberg–Whitney condition); evenly spread samples give evenly spread knots.
fn averaged_knots(u: &[f64], p: usize, n: usize) -> Vec<f64> {
    let m = u.len() - 1;
    let (u0, u1) = (u[0], u[m]);
    let mut k = vec![u0; p + 1];
    let d = (m + 1) as f64 / (n - p) as f64;
    for j in 1..(n - p) {
        let x = j as f64 * d;
        let i = (x.floor() as usize).clamp(1, m);
        let a = x - i as f64;
        k.push((1.0 - a) * u[i - 1] + a * u[i]);
    }
    k.extend(std::iter::repeat_n(u1, p + 1));
    k
}

/// Root mean square and largest of `values` (not empty).
fn rms_and_max(values: &[f64]) -> (f64, f64) {
    let rms = (values.iter().map(|r| r * r).sum::<f64>() / values.len() as f64).sqrt();
    (rms, values.iter().copied().fold(0.0, f64::max))
}
