//! One section checked while it is drawn (thesis §5.1): a designer drags a control point
//! and asks whether the blade can cut the curve. The points are read as a sectioned
//! polyline is read (a smoothing spline through them,
//! [`Section::from_points`](geom::surface::Section::from_points)), analysed
//! for length, inflections and curvature as the `Analyze` task analyses its sections (at
//! the caller's number of curvature samples: [`default_samples`](crate::check::default_samples)
//! reads fewer than the task's 2000, to answer within a millisecond), and
//! fitted by one elastica ([`elastica::fit_points`]), whose distance from the points is
//! held to the tolerance; the elastica is then extended to the blade's length where along
//! it the blade holds its shape best ([`elastica::stability()`]), as the segmentation places
//! its pieces.
//!
//! Entry point: [`check_section`](crate::check::check_section).

use elastica::{fit_points, FitParams, FitResult};
use geom::analysis::analyze_curve;
use geom::fit::SmoothingParams;
use geom::surface::Section;
use nalgebra::Vector2;

use crate::survey::{violations, SurveyParams, Violation};
use crate::SegError;

/// Curvature samples of the sign test (eq. 5.2) for a section of `n` points, when the
/// caller does not choose: two per point, 64 to 2000 (the `Analyze` task reads 2000 per
/// section, whatever its length). The smoothing spline through `n` points has about `n/2`
/// cubic spans, so this reads every span at least 4 times, while a dragged curve is
/// checked within a millisecond.
pub fn default_samples(n: usize) -> usize {
    (2 * n).clamp(64, 2000)
}

/// Parameters of [`check_section`].
#[derive(Debug, Clone, PartialEq)]
pub struct CheckParams {
    /// The constraints and the curve analysis, as the `Analyze` task sets them (`block`
    /// is not used).
    pub survey: SurveyParams,
    /// Largest distance between a point and the smoothing spline read through the
    /// points (≥ 0), in the points' units.
    pub smoothing: f64,
    /// RMS distance allowed between the points and their elastica (> 0).
    pub rms: f64,
    /// Largest distance allowed between a point and its elastica (> 0).
    pub max: f64,
    /// The least stability margin the blade keeps (`elastica::stability::MARGINAL` by
    /// default).
    pub min_margin: f64,
}

/// A point on the checked section.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct CheckPoint {
    /// Arc length from the first point.
    pub s: f64,
    /// Position.
    pub point: [f64; 2],
    /// Signed curvature (left turn positive).
    pub curvature: f64,
}

/// What [`check_section`] found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SectionCheck {
    /// Arc length of the section.
    pub length: f64,
    /// Its inflections, in order.
    pub inflections: Vec<CheckPoint>,
    /// Where its |curvature| is largest.
    pub max_abs_curvature: CheckPoint,
    /// Inflections dropped as noise (see [`crate::survey::SectionReport`]).
    pub suppressed_inflections: usize,
    /// RMS distance of the smoothing spline from the points.
    pub smoothing_rms: f64,
    /// The production constraints it breaks: length, inflections, curvature.
    pub violations: Vec<Violation>,
    /// The elastica fitted to the points, or why none could be.
    pub elastica: Result<FitResult, String>,
    /// The elastica lies within the tolerance of the points (RMS and largest distance).
    pub fit_ok: bool,
    /// The elastica extended to the blade's length, at the place along the blade (of
    /// every sixteenth of the extension, the middle first) where it holds its shape best:
    /// its stability, inflections and loads per EI. `None` without an elastica or when
    /// the section is longer than the blade.
    pub blade: Option<elastica::Blade>,
    /// No constraint broken, the elastica within tolerance and its blade holding its
    /// shape: one blade cuts it.
    pub cuttable: bool,
}

/// Checks one planar section given as points: the §5.1 production constraints (length,
/// inflections, curvature) and how close one elastica comes.
///
/// ```
/// use facade_seg::check::{check_section, CheckParams};
/// use facade_seg::survey::SurveyParams;
/// // 200 points on a gentle arch 600 mm wide
/// let pts: Vec<[f64; 2]> = (0..200).map(|i| {
///     let x = 600.0 * i as f64 / 199.0;
///     [x, 60.0 * (std::f64::consts::PI * x / 600.0).sin()]
/// }).collect();
/// let params = CheckParams {
///     survey: SurveyParams {
///         curve: Default::default(),
///         blade_length: 1000.0,
///         max_curvature: 0.01,
///         max_inflections: 2,
///         block: None,
///     },
///     smoothing: 0.05,
///     rms: 0.5,
///     max: 2.0,
///     min_margin: 0.05,
/// };
/// let c = check_section(&pts, &params)?;
/// assert!(c.violations.is_empty() && c.inflections.is_empty());
/// assert!(c.fit_ok && c.cuttable);
/// // the arch extended to the 1000 mm blade holds its shape
/// let blade = c.blade.unwrap();
/// assert!(blade.stability_ok && blade.stability.margin > 0.5);
/// # Ok::<(), facade_seg::SegError>(())
/// ```
///
/// # Errors
/// [`SegError::Invalid`] for fewer than 3 distinct points (a repeated consecutive point
/// counts once, for the analysis and the fit alike), non-finite coordinates or
/// tolerances; [`SegError::Section`] when the curve cannot be analysed.
pub fn check_section(points: &[[f64; 2]], params: &CheckParams) -> Result<SectionCheck, SegError> {
    let invalid = |what: &str, message: String| SegError::Invalid {
        what: what.into(),
        message,
    };
    if let Some(i) = points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(invalid("points", format!("point {i} is not finite")));
    }
    for (what, v, zero_ok) in [
        ("smoothing", params.smoothing, true),
        ("rms", params.rms, false),
        ("max", params.max, false),
    ] {
        if !(v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0))) {
            return Err(invalid(
                what,
                format!("must be a positive number, got {v:?}"),
            ));
        }
    }
    let distinct = distinct(points);
    // the fit sees the same points as the analysis: a repeated vertex would stop its arc
    // length from increasing
    let cleaned: Vec<[f64; 2]> = distinct.iter().map(|p| [p.x, p.y]).collect();
    if distinct.len() < 3 {
        return Err(invalid(
            "points",
            format!(
                "a section needs at least 3 distinct points, got {}",
                distinct.len()
            ),
        ));
    }
    let closed = distinct.len() > 3 && distinct.first() == distinct.last();
    let smoothing = SmoothingParams {
        degree: 3,
        tolerance: params.smoothing,
        max_control: 400,
        chordal: false,
    };
    let section_error = |e: geom::GeomError| SegError::Section {
        index: 0,
        message: e.to_string(),
    };
    let section =
        Section::from_points(distinct, None, closed, &smoothing).map_err(section_error)?;
    let analysis = analyze_curve(
        &section.curve,
        &section.analysis_params(&params.survey.curve),
    )
    .map_err(section_error)?;
    let point = |p: &geom::analysis::CurvePoint| CheckPoint {
        s: p.s,
        point: [p.point.x, p.point.y],
        curvature: p.curvature,
    };
    let violations = violations(&analysis, &params.survey);
    let elastica = fit_points(&cleaned, &FitParams::default()).map_err(|e| e.to_string());
    let fit_ok = elastica
        .as_ref()
        .is_ok_and(|f| f.rms <= params.rms && f.max <= params.max);
    let blade = elastica
        .as_ref()
        .ok()
        .and_then(|f| held_blade(&f.segment, params));
    let holds = blade.as_ref().is_none_or(|b| b.stability_ok);
    Ok(SectionCheck {
        length: analysis.length,
        inflections: analysis.inflections.iter().map(point).collect(),
        max_abs_curvature: point(&analysis.max_abs_curvature),
        suppressed_inflections: analysis.suppressed_inflections,
        smoothing_rms: section.fit_rms,
        cuttable: fit_ok && violations.is_empty() && holds,
        violations,
        elastica,
        fit_ok,
        blade,
    })
}

/// `segment` extended to the blade at the place along it where the blade holds best: the
/// middle when it holds there, else the largest margin of every sixteenth of the
/// extension.
fn held_blade(segment: &elastica::Segment, params: &CheckParams) -> Option<elastica::Blade> {
    let length = params.survey.blade_length;
    if !(segment.length() <= length) {
        return None;
    }
    let at = |share: f64| {
        elastica::extend_to_blade(
            segment,
            &elastica::BladeParams {
                lead_in_share: share,
                stability: elastica::StabilityParams {
                    marginal: params.min_margin,
                    ..Default::default()
                },
                ..elastica::BladeParams::new(length)
            },
        )
        .ok()
    };
    let middle = at(0.5)?;
    if middle.stability_ok {
        return Some(middle);
    }
    let n = elastica::clearance::FINE_SHARES;
    (0..=n)
        .filter_map(|k| at(k as f64 / n as f64))
        .chain(std::iter::once(middle))
        .max_by(|a, b| a.stability.margin.total_cmp(&b.stability.margin))
}

/// The points without consecutive repeats: a point within 10⁻¹² of the points' extent of
/// the one before (a CAD polyline's repeated vertex) is dropped. Relative to the extent,
/// so a section in metres or at 10³⁰⁰ keeps the same points as in millimetres.
fn distinct(points: &[[f64; 2]]) -> Vec<Vector2<f64>> {
    let first = points
        .first()
        .map_or(Vector2::zeros(), |p| Vector2::new(p[0], p[1]));
    // the extent by coordinates, so it does not overflow where the points are finite
    let gap = |a: &Vector2<f64>, b: &Vector2<f64>| (a.x - b.x).abs().max((a.y - b.y).abs());
    let extent = points
        .iter()
        .map(|p| gap(&Vector2::new(p[0], p[1]), &first))
        .fold(0.0, f64::max);
    let mut out: Vec<Vector2<f64>> = Vec::with_capacity(points.len());
    for p in points {
        let x = Vector2::new(p[0], p[1]);
        match out.last() {
            Some(l) if gap(l, &x) <= 1e-12 * extent => {}
            _ => out.push(x),
        }
    }
    out
}
