//! Fitting a planar curve by an elastica segment ("Hot Blade Cuttings for the Building
//! Industries" §5.1): minimise the squared L2 distance of eq. (9) between the curve and
//! the segment with points matched by arc length.
//!
//! The method:
//! 1. **Data.** Points with arc-length parameters (given, or the polyline's chord lengths),
//!    t = s/L, trapezoid weights in t so that the sum is the integral of eq. (9).
//! 2. **Variable projection.** A segment is `a·z(t; θ) + b` with complex a = S·e^{iφ} and
//!    b = x₀ + i y₀ (module `model`); for fixed θ = (k, s₀, ℓ) the optimal a, b are a
//!    weighted Procrustes solve (free) or fixed by the end points, so Levenberg–Marquardt
//!    (module `lm`) iterates on three parameters (two with a fixed length: ℓ is then solved from
//!    the length equation and eliminated by the implicit function theorem).
//! 3. **Initial guess** of §5.1 (module `guess`), or a warm start from a previous segment.
//! 4. **Lines and arcs** (λ = 0) are fitted as their own shapes (zero and one nonlinear
//!    parameter) and win when they fit as well, so they never appear as k → 0, S → ∞.
//! 5. **Self-consistent matching.** Chord lengths of sampled or noisy points are not the
//!    curve's arc length (noise of σ at spacing h inflates them by ~σ²/h²). After the
//!    arc-length-matched solve, module `odr` moves each point's parameter to its foot on the
//!    segment while refining the segment (Gauss–Newton on normal distances), so a point is
//!    finally matched with the arc length of its foot. This recovers exact elastica to
//!    rounding and removes the noise bias. Under end-point constraints the first and last
//!    point keep t = 0 and t = 1.
//! 6. **Two phases for speed.** Every candidate (line, arc, warm start, §5.1 guess, and for
//!    constrained fits the free fit's parameters) is first solved by arc-length matching on
//!    a 64-point subsample to a relative cost decrease of 1e-7; only the candidates within
//!    a factor 4 of the best (and one of several that met at the same minimum) are then
//!    refined orthogonally on all points. A constrained fit that stays poor (RMS above 3 %
//!    of the length) also starts from the refined free fit. Solves stop when the
//!    Gauss–Newton model predicts no worthwhile gain, or when they creep (see `lm::CREEP`).

// The solvers walk several parallel arrays (points, weights, parameters, Jacobian rows) by
// index; iterator zips of four slices read worse.
#![allow(clippy::needless_range_loop)]

/// The arc through a curve's end points that fits it best (the stable fallback of a blade).
mod arc;
/// The generic 7-parameter comparison baseline of the benchmarks.
pub mod baseline;
/// A fit described for a report: family, named parameters, quality, sampled curve.
pub mod describe;
mod error;
mod guess;
mod lm;
mod model;
mod odr;
mod tangents;

use crate::segment::{ElasticaParams, Segment};
use crate::unit::Family;
use model::{Data, Placement, Shape, C};

pub use arc::arc_through_ends;
pub use error::FitError;
pub use tangents::fit_with_end_tangents;

/// Which boundary data the fitted segment must reproduce exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FitConstraint {
    /// Nothing: the best segment in the L2 sense.
    #[default]
    Free,
    /// The first and last points are interpolated.
    EndPoints,
    /// End points interpolated and the length equal to the curve's (the skater-ramp
    /// setting of the hot-blade paper §7).
    EndPointsAndLength,
}

impl FitConstraint {
    /// The constraint of a fit whose ends must stay put (neighbouring blades meet there):
    /// `Free` becomes `EndPoints`, the others are kept.
    pub fn with_end_points(self) -> Self {
        match self {
            Self::Free => Self::EndPoints,
            other => other,
        }
    }
}

/// Options of [`fit_points`].
#[derive(Clone, Debug)]
pub struct FitParams {
    /// Boundary constraints.
    pub constraint: FitConstraint,
    /// Levenberg–Marquardt iterations per solve.
    pub max_iterations: usize,
    /// Iterations of the orthogonal refinement that makes the arc-length matching
    /// self-consistent (0 keeps the input's chord-length matching).
    pub refine_iterations: usize,
    /// Start from this segment (e.g. the fit of the neighbouring section) instead of the
    /// §5.1 guess; the guess is still tried when the warm start fails.
    pub warm_start: Option<Segment>,
    /// Consider straight lines and circular arcs.
    pub lines_and_arcs: bool,
}

impl Default for FitParams {
    fn default() -> Self {
        FitParams {
            constraint: FitConstraint::Free,
            max_iterations: 100,
            refine_iterations: 50,
            warm_start: None,
            lines_and_arcs: true,
        }
    }
}

/// A fitted segment and how well it fits.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FitResult {
    /// The segment; t = 0 and t = 1 are the feet of the first and last point.
    pub segment: Segment,
    /// Root-mean-square distance over arc length: √(∫|x − γ|² ds / L).
    pub rms: f64,
    /// Largest distance between a point and its matched point on the segment.
    pub max: f64,
    /// The L2 distance of eq. (9): √(∫|x − γ|² ds).
    pub l2: f64,
    /// Length of the input curve.
    pub input_length: f64,
    /// Levenberg–Marquardt iterations over all solves.
    pub iterations: usize,
    /// Whether the last solve met its convergence test.
    pub converged: bool,
    /// The parameter t of every input point on the segment.
    pub t: Vec<f64>,
}

/// Fit points whose arc-length parameters are the chord lengths of the polyline.
///
/// ```
/// use elastica::fit::{fit_points, FitParams};
/// use elastica::segment::Segment;
/// // a quarter circle of radius 2
/// let pts: Vec<[f64; 2]> = (0..50)
///     .map(|i| {
///         let a = std::f64::consts::FRAC_PI_2 * i as f64 / 49.0;
///         [2.0 * a.cos(), 2.0 * a.sin()]
///     })
///     .collect();
/// let fit = fit_points(&pts, &FitParams::default()).unwrap();
/// // exact to the grid the points are rounded to (`FIT_GRID` of the length, 3.4e-9 here)
/// assert!(fit.rms < 1e-8);
/// assert!(matches!(fit.segment, Segment::Arc { .. }));
/// ```
pub fn fit_points(points: &[[f64; 2]], params: &FitParams) -> Result<FitResult, FitError> {
    if let Some(i) = points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(FitError::NonFinite(i));
    }
    fit_points_with_arclength(points, &geom::polyline::chord_lengths(points), params)
}

/// Fit points with given arc-length parameters `s` (increasing; the length is
/// `s[last] − s[0]`, which is also the target length of
/// [`FitConstraint::EndPointsAndLength`]).
///
/// The fit is unit-free: the points are moved to their first point, divided by their
/// length and rounded to [`FIT_GRID`] before anything is solved, so every tolerance inside
/// is relative and a curve in metres fits as the same numbers, to the same segment, as
/// the curve in millimetres. The residuals (`rms`, `max`, `l2`) are measured to the points
/// as given.
///
/// ```
/// use elastica::{fit_points_with_arclength, ElasticaParams, Family, FitConstraint, FitParams, Segment};
/// // a non-inflectional elastica sampled unevenly, with its exact arc lengths
/// let truth = Segment::Elastica(ElasticaParams {
///     family: Family::NonInflectional, k: 0.8, s0: 0.2, l: 1.5,
///     scale: 50.0, phi: 0.0, x0: 0.0, y0: 0.0, one_minus_k: None,
/// });
/// let eval = truth.evaluator()?;
/// let t: Vec<f64> = (0..30).map(|i| (i as f64 / 29.0).powf(1.3)).collect();
/// let points: Vec<[f64; 2]> = t.iter().map(|&t| eval.eval(t).p).collect();
/// let s: Vec<f64> = t.iter().map(|t| t * truth.length()).collect();
/// let params = FitParams { constraint: FitConstraint::EndPointsAndLength, ..FitParams::default() };
/// let fit = fit_points_with_arclength(&points, &s, &params)?;
/// assert!(fit.max < 1e-6);
/// // the constraint holds: same ends, same length
/// assert!((fit.segment.length() - truth.length()).abs() < 1e-9);
/// let end = fit.segment.eval(1.0)?.p;
/// assert!((end[0] - points[29][0]).abs() < 1e-9 && (end[1] - points[29][1]).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_points_with_arclength(
    points: &[[f64; 2]],
    s: &[f64],
    params: &FitParams,
) -> Result<FitResult, FitError> {
    let Some(frame) = UnitFrame::of(points, s) else {
        return fit_in_frame(points, s, params, None);
    };
    let (p, t) = frame.points_to_unit(points, s);
    let warm_start = params.warm_start.as_ref().map(|w| frame.segment_to_unit(w));
    let exact = FitParams {
        warm_start,
        ..params.clone()
    };
    // the fit is made to the points rounded to the grid: the same numbers for the same
    // curve in any unit, so the same choices (candidates, thresholds, Levenberg–Marquardt's
    // path) and the same segment; its residuals are measured to the points as given
    let (pq, tq) = (quantize_points(&p), quantize_all(&t));
    let increasing = tq.windows(2).all(|w| w[1] > w[0]);
    let result = if increasing {
        let rounded = FitParams {
            warm_start: warm_start.map(quantize_segment),
            ..params.clone()
        };
        fit_in_frame(&pq, &tq, &rounded, Some(&p))?
    } else {
        fit_in_frame(&p, &t, &exact, None)?
    };
    Ok(frame.result_from_unit(result))
}

/// `fit` refined on the points as given, not rounded to [`FIT_GRID`]: one more solve
/// started from `fit.segment`. For exact data (points computed on an elastica) the
/// parameters then come out to the points' own precision instead of the grid's (~10⁻⁸
/// relative on gently bent shapes). The polished fit is kept only when it lies within
/// 1000 grid steps (~10⁻⁶ of the length) of `fit` and fits better; elsewhere (noisy data
/// in a flat valley, where a unit change could send the polish to another minimum) `fit`
/// is returned as it is. Not unit-invariant to the last digits where it applies, which is
/// why [`fit_points_with_arclength`] does not do it.
///
/// ```
/// use elastica::{fit_points_with_arclength, polish, ElasticaParams, Family, FitParams, Segment};
/// let truth = ElasticaParams { family: Family::Inflectional, k: 0.6, s0: 0.3, l: 2.5,
///     scale: 100.0, phi: 0.2, x0: 10.0, y0: -5.0, one_minus_k: None };
/// let seg = Segment::Elastica(truth);
/// let eval = seg.evaluator()?;
/// let points: Vec<[f64; 2]> = (0..200).map(|i| eval.eval(i as f64 / 199.0).p).collect();
/// let s: Vec<f64> = (0..200).map(|i| seg.length() * i as f64 / 199.0).collect();
/// let fit = fit_points_with_arclength(&points, &s, &FitParams::default())?;
/// let fine = polish(&points, &s, &fit, &FitParams::default())?;
/// let Segment::Elastica(p) = fine.segment else { panic!() };
/// assert!((p.k - 0.6).abs() < 1e-11 && (p.x0 - 10.0).abs() < 1e-9);
/// assert!(fine.rms <= fit.rms);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`fit_points_with_arclength`].
pub fn polish(
    points: &[[f64; 2]],
    s: &[f64],
    fit: &FitResult,
    params: &FitParams,
) -> Result<FitResult, FitError> {
    let Some(frame) = UnitFrame::of(points, s) else {
        return Ok(fit.clone());
    };
    let (p, t) = frame.points_to_unit(points, s);
    let warm = FitParams {
        warm_start: Some(frame.segment_to_unit(&fit.segment)),
        ..params.clone()
    };
    let fine = frame.result_from_unit(fit_in_frame(&p, &t, &warm, None)?);
    // kept only where it refines the grid's fit in place: on exact data the two lie within
    // the grid's reach of each other; where the polish wanders off along a flat valley
    // (noisy data near the separatrix) a unit change could send it elsewhere, and the
    // unit-invariant fit stands
    let close = within(&fit.segment, &fine.segment, POLISH_REACH * frame.scale);
    Ok(if close && fine.rms <= fit.rms {
        fine
    } else {
        fit.clone()
    })
}

/// How far, relative to the curve's length, a polished fit may lie from the grid's fit
/// and still replace it: 1000 grid steps.
const POLISH_REACH: f64 = 1000.0 * FIT_GRID;

/// Whether segments `a` and `b` lie within `d` of each other at 17 equal parameters.
fn within(a: &Segment, b: &Segment, d: f64) -> bool {
    let (Ok(ea), Ok(eb)) = (a.evaluator(), b.evaluator()) else {
        return false;
    };
    (0..=16).all(|i| {
        let t = i as f64 / 16.0;
        let (p, q) = (ea.eval(t).p, eb.eval(t).p);
        (p[0] - q[0]).hypot(p[1] - q[1]) <= d
    })
}

/// The grid, relative to a curve's length, its points and arc lengths are rounded to
/// before a fit makes its choices: 2⁻³⁰ ≈ 9·10⁻¹⁰, 0.6 µm on a 600 mm section.
///
/// A curve given in metres and in millimetres reaches the fit as numbers that differ in
/// their last bits (a section computed in either unit, a ÷1000 that rounds), and a fit near
/// a fold or a family boundary can follow either of two paths to different minima on such
/// a difference. Rounded to this grid, the two are the same numbers unless one of them
/// lies within a few ulps of a grid midpoint (a chance of ~10⁻⁶ per coordinate). The grid
/// is far below any tolerance of a cut. (Fitting the rounded points and then polishing on
/// the exact ones was tried: in the flat valleys of nearly separatrix elastica (k → 1) the
/// polish alone moved the two units' fits apart again, 0.5086 vs 0.5080 mm rms.)
pub const FIT_GRID: f64 = 1.0 / (1u64 << 30) as f64;

pub(crate) fn quantize(x: f64) -> f64 {
    geom::unit::snap(x, FIT_GRID)
}

pub(crate) fn quantize_all(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| quantize(x)).collect()
}

pub(crate) fn quantize_points(p: &[[f64; 2]]) -> Vec<[f64; 2]> {
    p.iter().map(|q| [quantize(q[0]), quantize(q[1])]).collect()
}

/// A warm start in the unit frame, every number rounded to the grid.
pub(crate) fn quantize_segment(seg: Segment) -> Segment {
    let q = quantize;
    match seg {
        Segment::Elastica(e) => Segment::Elastica(ElasticaParams {
            // the modulus is the rounded k's (a fit's segments carry no complement)
            one_minus_k: None,
            k: q(e.k),
            s0: q(e.s0),
            l: q(e.l),
            scale: q(e.scale),
            phi: q(e.phi),
            x0: q(e.x0),
            y0: q(e.y0),
            ..e
        }),
        Segment::Line {
            x0,
            y0,
            phi,
            length,
        } => Segment::Line {
            x0: q(x0),
            y0: q(y0),
            phi: q(phi),
            length: q(length),
        },
        Segment::Arc {
            x0,
            y0,
            phi,
            curvature,
            length,
        } => Segment::Arc {
            x0: q(x0),
            y0: q(y0),
            phi: q(phi),
            curvature: q(curvature),
            length: q(length),
        },
    }
}

/// The similarity that takes a curve to unit size: `p ↦ (p − origin)/scale`, `scale` the
/// curve's length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct UnitFrame {
    origin: [f64; 2],
    scale: f64,
}

impl UnitFrame {
    /// The frame of points with arc lengths `s`; `None` when the length is not a positive
    /// finite number or the first point is not finite (the fit then reports the problem).
    pub(crate) fn of(points: &[[f64; 2]], s: &[f64]) -> Option<Self> {
        let (first, last) = (*s.first()?, *s.last()?);
        let length = last - first;
        let origin = *points.first()?;
        if !(length.is_finite() && length > 0.0 && origin[0].is_finite() && origin[1].is_finite()) {
            return None;
        }
        Some(Self {
            origin,
            scale: length,
        })
    }
    /// Points and arc lengths in the frame.
    pub(crate) fn points_to_unit(
        &self,
        points: &[[f64; 2]],
        s: &[f64],
    ) -> (Vec<[f64; 2]>, Vec<f64>) {
        let inv = 1.0 / self.scale;
        let p = points
            .iter()
            .map(|q| [(q[0] - self.origin[0]) * inv, (q[1] - self.origin[1]) * inv])
            .collect();
        let t = s.iter().map(|v| (v - s[0]) * inv).collect();
        (p, t)
    }

    /// A segment in the frame.
    pub(crate) fn segment_to_unit(&self, seg: &Segment) -> Segment {
        let inv = 1.0 / self.scale;
        seg.similar(inv, [-self.origin[0] * inv, -self.origin[1] * inv])
    }

    /// A fit in the frame, in the original coordinates (lengths ×scale, l2 ×scale^1.5).
    pub(crate) fn result_from_unit(&self, r: FitResult) -> FitResult {
        let c = self.scale;
        FitResult {
            segment: r.segment.similar(c, self.origin),
            rms: r.rms * c,
            max: r.max * c,
            l2: r.l2 * c * c.sqrt(),
            input_length: r.input_length * c,
            ..r
        }
    }

    /// A fit in original coordinates, in the frame.
    pub(crate) fn result_to_unit(&self, r: &FitResult) -> FitResult {
        let inv = 1.0 / self.scale;
        FitResult {
            segment: self.segment_to_unit(&r.segment),
            rms: r.rms * inv,
            max: r.max * inv,
            l2: r.l2 * inv * inv.sqrt(),
            input_length: r.input_length * inv,
            ..r.clone()
        }
    }
}

/// [`fit_points_with_arclength`] in the coordinates given; with `exact`, the points as
/// given of which `points` are rounded, to which the residuals are measured.
fn fit_in_frame(
    points: &[[f64; 2]],
    s: &[f64],
    params: &FitParams,
    exact: Option<&[[f64; 2]]>,
) -> Result<FitResult, FitError> {
    let (data, placement, fixed_length) = checked_data(points, s, params)?;
    let input_length = data.length;
    let (mut best, iterations) = fit_data(data, placement, fixed_length, params)?;
    if let Some(p) = exact {
        if placement == Placement::EndPoints {
            best.segment = pinned(best.segment, points, p);
            if fixed_length {
                best.segment = with_length(best.segment, p, s[s.len() - 1] - s[0]);
            }
        }
        // the feet found for the rounded points are within the grid of the exact ones'
        best.data.p = p.iter().map(|q| C::new(q[0], q[1])).collect();
    }
    finish(best, iterations, input_length)
}

/// A segment through the end points of `exact` (as [`pinned`] leaves it), its shape moved
/// by the least change of (k, s₀, ℓ) (an arc's curvature) that makes its length `length`
/// again: pinning scaled it by up to the rounding of the far end over the chord, and a
/// length-keeping fit keeps both to rounding. Unchanged when that does not converge.
pub(crate) fn with_length(seg: Segment, exact: &[[f64; 2]], length: f64) -> Segment {
    let (Some(p0), Some(p1)) = (exact.first(), exact.last()) else {
        return seg;
    };
    let (p0, p1) = (C::new(p0[0], p0[1]), C::new(p1[0], p1[1]));
    let chord = p1 - p0;
    let rho = chord.norm() / length;
    if !(rho > 0.0 && rho < 1.0 && length.is_finite()) {
        return seg;
    }
    match seg {
        Segment::Elastica(e) => {
            let data = Data {
                p: vec![p0, p1],
                w: vec![0.5, 0.5],
                t: vec![0.0, 1.0],
                length,
            };
            let Some(th) = model::feasible_start(e.family, [e.k, e.s0, e.l], &data) else {
                return seg;
            };
            let Ok(unit) = crate::unit::UnitElastica::new(e.family, th[0]) else {
                return seg;
            };
            let (f0, f1) = (unit.eval(th[1]).p, unit.eval(th[1] + th[2]).p);
            let dz = C::new(f1[0] - f0[0], f1[1] - f0[1]);
            if dz.norm() == 0.0 {
                return seg;
            }
            let a = chord / dz;
            let b = p0 - a * C::new(f0[0], f0[1]);
            Segment::Elastica(ElasticaParams {
                one_minus_k: None,
                k: th[0],
                s0: th[1],
                l: th[2],
                scale: a.norm(),
                phi: a.arg(),
                x0: b.re,
                y0: b.im,
                ..e
            })
        }
        Segment::Arc { curvature, .. } => {
            let kappa = curvature.signum() * 2.0 * arc_half_turn(rho) / length;
            Segment::Arc {
                x0: p0.re,
                y0: p0.im,
                phi: chord.arg() - 0.5 * kappa * length,
                curvature: kappa,
                length,
            }
        }
        Segment::Line { .. } => seg,
    }
}

/// A segment through the first and last of the rounded points `rounded`, moved by the
/// similarity that takes those two to the first and last of `exact`: an end-point fit
/// keeps the end points as given (neighbouring pieces and blocks meet exactly), at the cost
/// of a change of scale and angle within the grid.
pub(crate) fn pinned(seg: Segment, rounded: &[[f64; 2]], exact: &[[f64; 2]]) -> Segment {
    let c = |p: &[f64; 2]| C::new(p[0], p[1]);
    let (Some(q0), Some(q1), Some(p0), Some(p1)) =
        (rounded.first(), rounded.last(), exact.first(), exact.last())
    else {
        return seg;
    };
    let dq = c(q1) - c(q0);
    if dq.norm() == 0.0 {
        return seg;
    }
    let a = (c(p1) - c(p0)) / dq;
    let b = c(p0) - a * c(q0);
    if !(a.re.is_finite() && a.im.is_finite() && b.re.is_finite() && b.im.is_finite()) {
        return seg;
    }
    seg.mapped([a.re, a.im], [b.re, b.im])
}

/// The data of a fit, checked, with its placement and whether it keeps its length.
fn checked_data(
    points: &[[f64; 2]],
    s: &[f64],
    params: &FitParams,
) -> Result<(Data, Placement, bool), FitError> {
    let n = points.len();
    if n < 3 {
        return Err(FitError::TooFewPoints(n));
    }
    if s.len() != n {
        return Err(FitError::LengthMismatch {
            points: n,
            lengths: s.len(),
        });
    }
    for i in 0..n {
        if !(points[i][0].is_finite() && points[i][1].is_finite() && s[i].is_finite()) {
            return Err(FitError::NonFinite(i));
        }
        if i > 0 && !(s[i] > s[i - 1]) {
            return Err(FitError::NotIncreasing(i));
        }
    }
    let length = s[n - 1] - s[0];
    let t: Vec<f64> = s.iter().map(|v| (v - s[0]) / length).collect();
    let data = Data {
        p: points.iter().map(|p| C::new(p[0], p[1])).collect(),
        w: model::trapezoid_weights(&t),
        t,
        length,
    };
    let chord = (data.p[n - 1] - data.p[0]).norm();
    let placement = match params.constraint {
        FitConstraint::Free => Placement::Free,
        _ => {
            if chord <= 1e-12 * length {
                return Err(FitError::ClosedCurve);
            }
            Placement::EndPoints
        }
    };
    let fixed_length = params.constraint == FitConstraint::EndPointsAndLength;
    // a straight curve's rounded points can be a grid step longer than their arc length
    if fixed_length && chord > length * (1.0 + 4.0 * FIT_GRID) {
        return Err(FitError::LengthBelowChord { length, chord });
    }
    Ok((data, placement, fixed_length))
}

/// Fit a planar curve (e.g. a `geom` B-spline section) sampled at `samples` points of equal
/// arc length.
///
/// ```
/// use elastica::{fit_curve, FitParams, Segment};
/// use geom::planar::{Jet2, PlanarCurve};
/// use nalgebra::Vector2;
///
/// // a third of a circle of radius 50
/// struct Circle;
/// impl PlanarCurve for Circle {
///     fn domain(&self) -> (f64, f64) {
///         (0.0, 2.0 * std::f64::consts::FRAC_PI_3)
///     }
///     fn jet(&self, t: f64) -> Jet2 {
///         let (s, c) = t.sin_cos();
///         Jet2 {
///             p: Vector2::new(50.0 * c, 50.0 * s),
///             d1: Vector2::new(-50.0 * s, 50.0 * c),
///             d2: Vector2::new(-50.0 * c, -50.0 * s),
///         }
///     }
/// }
/// let fit = fit_curve(&Circle, 40, &FitParams::default())?;
/// let Segment::Arc { curvature, length, .. } = fit.segment else {
///     panic!("expected an arc, got a {}", fit.segment.kind());
/// };
/// assert!((curvature - 1.0 / 50.0).abs() < 1e-9);
/// assert!((length - 100.0 * std::f64::consts::FRAC_PI_3).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_curve(
    curve: &dyn geom::planar::PlanarCurve,
    samples: usize,
    params: &FitParams,
) -> Result<FitResult, FitError> {
    let samples = samples.max(3);
    let arc = geom::planar::ArcLength::new(curve, 4 * samples);
    let total = arc.length();
    let mut pts = Vec::with_capacity(samples);
    let mut s = Vec::with_capacity(samples);
    for i in 0..samples {
        let si = total * i as f64 / (samples - 1) as f64;
        let p = curve.point(arc.t_at(curve, si));
        pts.push([p[0], p[1]]);
        s.push(si);
    }
    fit_points_with_arclength(&pts, &s, params)
}

/// Relative cost decrease below which Levenberg–Marquardt has converged.
const LM_TOL: f64 = 1e-12;
/// The same before the orthogonal refinement, which finishes the job.
const LM_TOL_BEFORE_REFINE: f64 = 1e-7;
/// Points of the subsample the candidates are first solved on.
const LM_POINTS: usize = 64;
/// Candidates whose first solve costs more than this multiple of the best are not refined.
const REFINE_WITHIN: f64 = 4.0;
/// RMS distance, relative to the length, above which a constrained fit also tries the
/// refined free fit as its start.
const POOR_FIT: f64 = 3e-2;
/// RMS distance, relative to the length, below which the guess's constrained fit is taken
/// as close enough to skip the free-fit start: 6 µm on a 600 mm blade section. (At 1e-3
/// the hot-blade facade job kept fixed-length arcs 0.6 mm off sections that an elastica
/// fits to 0.003 mm; the stricter value costs ≤ 5 % on the shared curves' benchmark.)
const GOOD_FIT: f64 = 1e-5;

/// A candidate shape with its start.
#[derive(Clone)]
struct Candidate {
    shape: Shape,
    theta: [f64; 3],
}

/// One fitted candidate.
struct Fitted {
    segment: Segment,
    cost: f64,
    data: Data,
    iterations: usize,
    converged: bool,
}

fn theta_of(seg: &Segment, fixed_length: bool) -> Option<Candidate> {
    match *seg {
        Segment::Elastica(p) => Some(Candidate {
            shape: Shape::Elastica {
                family: p.family,
                fixed_length,
            },
            theta: [p.k, p.s0, p.l],
        }),
        _ => None,
    }
}

/// The starts of a fit: a line and an arc (when allowed; a length-keeping arc only when one
/// of the data's length fits), the warm start, and the elastica guessed from the data's
/// local geometry, which is also returned.
fn candidates(
    data: &Data,
    fixed_length: bool,
    params: &FitParams,
) -> (Vec<Candidate>, Option<(Family, [f64; 3])>) {
    let local = guess::local_geometry(data);
    let mut candidates = Vec::new();
    if params.lines_and_arcs {
        if !fixed_length || model::chord_ratio(data) >= 1.0 - 4.0 * FIT_GRID {
            candidates.push(Candidate {
                shape: Shape::Line,
                theta: [0.0; 3],
            });
        }
        if !fixed_length {
            candidates.push(Candidate {
                shape: Shape::Circle { fixed: false },
                theta: [guess::mean_curvature(data, &local), 0.0, 0.0],
            });
        } else if let Some(kappa) = arc_curvature_for_length(data, &local) {
            candidates.push(Candidate {
                shape: Shape::Circle { fixed: true },
                theta: [kappa, 0.0, 0.0],
            });
        }
    }
    if let Some(c) = params
        .warm_start
        .as_ref()
        .and_then(|s| theta_of(s, fixed_length))
    {
        candidates.push(c);
    }
    let guess = guess::elastica_guess(data, &local);
    if let Some((family, theta)) = guess {
        candidates.push(Candidate {
            shape: Shape::Elastica {
                family,
                fixed_length,
            },
            theta,
        });
    }
    (candidates, guess)
}

/// Phase 2: the candidates solved in phase 1 within reach of the best, simplest first,
/// refined on all points; a later one must beat the best so far clearly, so a straight
/// section stays a line and a circular one an arc. Adds the iterations spent.
fn refine_solved(
    solved: &[(Candidate, lm::Solved)],
    data: &Data,
    placement: Placement,
    params: &FitParams,
    floor: f64,
    iterations: &mut usize,
) -> Option<Fitted> {
    let best_cost = solved
        .iter()
        .map(|(_, s)| s.cost)
        .fold(f64::INFINITY, f64::min);
    let mut best: Option<Fitted> = None;
    let mut done: Vec<(&Shape, &lm::Solved)> = Vec::new();
    for (c, s) in solved.iter() {
        if s.cost > REFINE_WITHIN * best_cost + floor {
            continue;
        }
        // two elastica starts that met in phase 1 need one refinement
        if matches!(c.shape, Shape::Elastica { .. })
            && done
                .iter()
                .any(|(shape, d)| same_minimum(shape, d, &c.shape, s))
        {
            continue;
        }
        done.push((&c.shape, s));
        if let Some(f) = run(c, s.clone(), data, placement, params) {
            *iterations += f.iterations;
            if !loops_between_points(&f.segment, data) {
                keep_better(&mut best, f, floor);
            }
        }
    }
    best
}

/// Whether `segment` bends far more than the points it was fitted to could show: its
/// largest |κ| above a hundred times the data's own (the largest turning between
/// consecutive segments of the polyline over their mean length) plus a hundred over its
/// length. Near k = 1 an elastica can hide a small loop between two samples; its residuals
/// at the points are then tiny while the blade it stands for would be torn. Such a
/// candidate is not a fit of these points (a line or arc, or another elastica, is).
fn loops_between_points(segment: &Segment, data: &Data) -> bool {
    if !matches!(segment, Segment::Elastica(_)) {
        return false;
    }
    let p = &data.p;
    let mut kappa: f64 = 0.0;
    for w in p.windows(3) {
        let (a, b) = ((w[1] - w[0]), (w[2] - w[1]));
        let (la, lb) = (a.norm(), b.norm());
        if la > 0.0 && lb > 0.0 {
            let turn = (a.re * b.im - a.im * b.re)
                .atan2(a.re * b.re + a.im * b.im)
                .abs();
            kappa = kappa.max(turn / (0.5 * (la + lb)));
        }
    }
    let limit = 100.0 * kappa + 100.0 / data.length;
    segment.max_abs_curvature().is_ok_and(|k| k > limit)
}

fn fit_data(
    data: Data,
    placement: Placement,
    fixed_length: bool,
    params: &FitParams,
) -> Result<(Fitted, usize), FitError> {
    // the arc-length-matched solves of all candidates run on a subsample; only the
    // promising candidates are then refined on all points. The guesses use all points:
    // their local curvature estimates average the noise over more neighbours.
    let sub = data.subsample(LM_POINTS);
    let (candidates, guess) = candidates(&data, fixed_length, params);

    // phase 1: every candidate solved by arc-length matching on the subsample
    let mut iterations = 0;
    let phase1 = |c: Candidate, iterations: &mut usize| {
        let s = lm::solve(
            &c.shape,
            c.theta,
            &sub,
            placement,
            params.max_iterations,
            LM_TOL_BEFORE_REFINE,
        )?;
        *iterations += s.iterations;
        Some((c, s))
    };
    let mut solved: Vec<(Candidate, lm::Solved)> = candidates
        .into_iter()
        .filter_map(|c| phase1(c, &mut iterations))
        .collect();
    let elastica_cost = solved
        .iter()
        .filter(|(c, _)| matches!(c.shape, Shape::Elastica { .. }))
        .map(|(_, s)| s.cost)
        .fold(f64::INFINITY, f64::min);
    if let Some((family, theta)) = guess {
        if placement != Placement::Free
            && params.warm_start.is_none()
            && !(elastica_cost <= (GOOD_FIT * data.length).powi(2))
        {
            // the guess did not lead to a close constrained fit: also start from the free
            // fit, which is close to it and robust to find
            let free = Shape::Elastica {
                family,
                fixed_length: false,
            };
            if let Some(f) = lm::solve(
                &free,
                theta,
                &sub,
                Placement::Free,
                params.max_iterations,
                LM_TOL_BEFORE_REFINE,
            ) {
                iterations += f.iterations;
                let c = Candidate {
                    shape: Shape::Elastica {
                        family,
                        fixed_length,
                    },
                    theta: f.theta,
                };
                // before the guess's own candidate: refined first on a tie
                let at = solved
                    .iter()
                    .position(|(c, _)| matches!(c.shape, Shape::Elastica { .. }))
                    .unwrap_or(solved.len());
                if let Some(cs) = phase1(c, &mut iterations) {
                    solved.insert(at, cs);
                }
            }
        }
    }
    // costs within the rounding of the points to the grid are equal
    let floor = (FIT_GRID * data.length).powi(2);
    let mut best = refine_solved(&solved, &data, placement, params, floor, &mut iterations);
    let poor = best
        .as_ref()
        .is_none_or(|b| b.cost > (POOR_FIT * data.length).powi(2));
    if placement != Placement::Free && params.warm_start.is_none() && poor {
        // A poor constrained fit (a curve far from any elastica): on such curves the
        // refined free fit can lead to a better minimum than the quick free start.
        let free = FitParams {
            constraint: FitConstraint::Free,
            lines_and_arcs: false,
            ..params.clone()
        };
        if let Some(c) = fit_data(data.clone(), Placement::Free, false, &free)
            .ok()
            .and_then(|(f, _)| theta_of(&f.segment, fixed_length))
        {
            if let Some(f) =
                phase1(c, &mut iterations).and_then(|(c, s)| run(&c, s, &data, placement, params))
            {
                iterations += f.iterations;
                keep_better(&mut best, f, floor);
            }
        }
    }
    let best = best.ok_or_else(|| FitError::Failed("every candidate diverged".into()))?;
    Ok((best, iterations))
}

/// Replace `best` by `f` when `f` is clearly better (by a relative 1e-6 and `floor`).
fn keep_better(best: &mut Option<Fitted>, f: Fitted, floor: f64) {
    let better = match best {
        None => true,
        Some(b) => f.cost < b.cost * (1.0 - 1e-6) - floor,
    };
    if better {
        *best = Some(f);
    }
}

/// Whether two phase-1 elastica solutions are the same minimum: same family and costs
/// equal to 1e-4 (phase 1 stops at a relative cost decrease of 1e-7, where the parameters
/// along a flat direction can still differ in their third digit).
fn same_minimum(sa: &Shape, a: &lm::Solved, sb: &Shape, b: &lm::Solved) -> bool {
    let family = |s: &Shape| match s {
        Shape::Elastica { family, .. } => Some(*family),
        _ => None,
    };
    family(sa).is_some()
        && family(sa) == family(sb)
        && (a.cost - b.cost).abs() <= 1e-4 * a.cost.max(b.cost)
}

/// Half the turning x = κL/2 ∈ (0, π) of an arc whose chord is `rho` of its length:
/// sinc(x) = ρ by bisection (sinc decreases on (0, π)).
fn arc_half_turn(rho: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, std::f64::consts::PI);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if crate::segment::sinc(mid) > rho {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Curvature of the arc with the data's end points and length (sign from the data).
fn arc_curvature_for_length(data: &Data, local: &guess::Local) -> Option<f64> {
    let rho = model::chord_ratio(data);
    if rho >= 1.0 {
        return Some(0.0);
    }
    let lo = arc_half_turn(rho);
    let sign = if guess::mean_curvature(data, local) < 0.0 {
        -1.0
    } else {
        1.0
    };
    Some(sign * 2.0 * lo / data.length)
}

/// Finish one candidate from its phase-1 solution: refine it orthogonally on all points
/// (or, without refinement, solve it again on all points by arc-length matching), then map
/// the feet of the first and last point to t = 0 and t = 1.
fn run(
    c: &Candidate,
    start: lm::Solved,
    data: &Data,
    placement: Placement,
    params: &FitParams,
) -> Option<Fitted> {
    let mut data = data.clone();
    let before = start.iterations;
    let solved = if params.refine_iterations > 0 {
        odr::refine(
            &c.shape,
            start,
            &mut data,
            placement,
            params.refine_iterations,
        )
    } else {
        let mut s = lm::solve(
            &c.shape,
            start.theta,
            &data,
            placement,
            params.max_iterations,
            LM_TOL,
        )?;
        s.iterations += before;
        s
    };
    // phase-1 iterations are already counted
    let iterations = solved.iterations - before;
    let seg = c
        .shape
        .segment(&solved.theta, solved.l, solved.a, solved.b, data.length);
    let n = data.t.len();
    let (t0, t1) = (data.t[0], data.t[n - 1]);
    let span = t1 - t0;
    if !(span > 0.0) {
        return None;
    }
    let len = seg.length();
    let segment = if (t0 != 0.0 || t1 != 1.0) && len > 0.0 {
        seg.extended(-t0 * len, (t1 - 1.0) * len)
    } else {
        seg
    };
    for t in data.t.iter_mut() {
        *t = (*t - t0) / span;
    }
    Some(Fitted {
        segment,
        cost: solved.cost,
        data,
        iterations,
        converged: solved.converged,
    })
}

fn finish(best: Fitted, iterations: usize, input_length: f64) -> Result<FitResult, FitError> {
    let data = &best.data;
    let eval = best
        .segment
        .evaluator()
        .map_err(|e| FitError::Failed(e.to_string()))?;
    let mut max: f64 = 0.0;
    let mut sum = 0.0;
    for i in 0..data.t.len() {
        let q = eval.eval(data.t[i]).p;
        let d = (q[0] - data.p[i].re).hypot(q[1] - data.p[i].im);
        max = max.max(d);
        sum += data.w[i] * d * d;
    }
    Ok(FitResult {
        segment: best.segment,
        rms: sum.sqrt(),
        max,
        l2: (sum * input_length).sqrt(),
        input_length,
        iterations,
        converged: best.converged,
        t: data.t.clone(),
    })
}

/// `r` (a fit of the rounded points of a curve with arc-length parameters `t` on [0, 1])
/// with its residuals measured to `points`, the points as given.
pub(crate) fn remeasured(
    r: FitResult,
    points: &[[f64; 2]],
    t: &[f64],
) -> Result<FitResult, FitError> {
    let data = Data {
        p: points.iter().map(|q| C::new(q[0], q[1])).collect(),
        w: model::trapezoid_weights(t),
        t: r.t.clone(),
        length: r.input_length,
    };
    let best = Fitted {
        segment: r.segment,
        cost: 0.0,
        data,
        iterations: r.iterations,
        converged: r.converged,
    };
    finish(best, r.iterations, r.input_length)
}

/// A fit in the unit frame with every number rounded to the grid (a start or a baseline
/// of a refit).
pub(crate) fn quantize_result(r: &FitResult) -> FitResult {
    FitResult {
        segment: quantize_segment(r.segment),
        rms: quantize(r.rms),
        max: quantize(r.max),
        l2: quantize(r.l2),
        input_length: quantize(r.input_length),
        t: quantize_all(&r.t),
        ..r.clone()
    }
}

/// Family and modulus of a fitted elastica, for reports.
pub fn family_of(seg: &Segment) -> Option<Family> {
    match seg {
        Segment::Elastica(p) => Some(p.family),
        _ => None,
    }
}
