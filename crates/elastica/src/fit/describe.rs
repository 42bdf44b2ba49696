//! Fits described as plain, serializable data: the segment's family and named parameters,
//! its quality, inflection points and the curve sampled; one input curve with its fit or
//! why it could not be fitted; and totals over many curves.
//!
//! Entry points: [`CurveFit::new`](crate::fit::describe::CurveFit::new),
//! [`FitSummary::of`](crate::fit::describe::FitSummary::of).

use super::{FitError, FitResult};
use crate::elliptic::EllipticError;
use crate::segment::Segment;
use crate::unit::Family;

/// Points of the fitted segment a description holds.
pub const FITTED_SAMPLES: usize = 400;

/// Totals over many fitted curves.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct FitSummary {
    /// Curves read.
    pub curves: usize,
    /// Curves that could not be fitted (see their `error`).
    pub failed: usize,
    /// Fits that are straight lines.
    pub lines: usize,
    /// Fits that are circular arcs.
    pub arcs: usize,
    /// Fits that are inflectional elastica.
    pub inflectional: usize,
    /// Fits that are non-inflectional elastica.
    pub noninflectional: usize,
    /// Largest RMS distance over the curves.
    pub max_rms: f64,
    /// Median RMS distance over the curves.
    pub median_rms: f64,
    /// Largest distance between a point and its match on the fit, over all curves.
    pub max_distance: f64,
}

/// One curve and its fit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct CurveFit {
    /// The curve's id (from the input file; `section <plane>.<piece>` for sections).
    pub id: String,
    /// Number of input points.
    pub points: usize,
    /// Length of the input polyline (sections: of the section curve).
    pub input_length: f64,
    /// Why the curve could not be fitted; absent when it was.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub error: Option<String>,
    /// The fit; absent when the curve could not be fitted.
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub fit: Option<FittedCurve>,
}

/// A fitted segment with its quality and geometry.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct FittedCurve {
    /// `line`, `arc`, `inflectional` or `noninflectional`.
    pub family: String,
    /// The segment's parameters. Elastica: the papers' `k`, `s0`, `l`, `S`, `phi`, `x0`,
    /// `y0` (the point at t ∈ [0, 1] is S·R(φ)·f(s₀ + ℓt) + (x₀, y₀); ℓ < 0 runs the
    /// normalized curve backwards). Line: `x0`, `y0`, `phi`, `length`. Arc: `x0`, `y0`,
    /// `phi` (start tangent angle), `curvature` (signed, left positive), `length`.
    pub parameters: std::collections::BTreeMap<String, f64>,
    /// Root-mean-square distance over arc length between the curve and the fit, √(∫|x − γ|² ds / L).
    pub rms: f64,
    /// Largest distance between an input point and its matched point on the fit.
    pub max: f64,
    /// Length of the fitted segment.
    pub length: f64,
    /// Number of inflection points of the fitted segment.
    pub inflections: usize,
    /// The inflection points of the fitted segment.
    pub inflection_points: Vec<[f64; 2]>,
    /// Largest |curvature| along the fitted segment.
    pub max_abs_curvature: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Whether the last solve met its convergence test.
    pub converged: bool,
    /// The fitted segment sampled at 400 points equally spaced in arc length.
    pub fitted: Vec<[f64; 2]>,
}

impl CurveFit {
    /// Curve `id` of `points` points and length `input_length`, with its fit (or why not).
    pub fn new(
        id: impl Into<String>,
        points: usize,
        input_length: f64,
        fit: &Result<FitResult, FitError>,
    ) -> Self {
        let fitted = fit
            .as_ref()
            .map_err(|e| e.to_string())
            .and_then(|f| FittedCurve::of(f).map_err(|e| e.to_string()));
        let (fit, error) = match fitted {
            Ok(f) => (Some(f), None),
            Err(e) => (None, Some(e)),
        };
        CurveFit {
            id: id.into(),
            points,
            input_length,
            error,
            fit,
        }
    }
}

impl FittedCurve {
    /// The description of fit `f`.
    ///
    /// # Errors
    /// When the segment cannot be evaluated (parameters outside the elliptic functions'
    /// domain).
    ///
    /// ```
    /// use elastica::fit::describe::{FittedCurve, FITTED_SAMPLES};
    /// use elastica::{fit_points, FitParams, Segment};
    /// let line = Segment::Line { x0: 0.0, y0: 0.0, phi: 0.5, length: 10.0 };
    /// let fit = fit_points(&line.sample(20)?, &FitParams::default())?;
    /// let d = FittedCurve::of(&fit)?;
    /// assert_eq!(d.family, "line");
    /// assert_eq!((d.inflections, d.max_abs_curvature), (0, 0.0));
    /// assert!((d.length - 10.0).abs() < 1e-6);
    /// assert_eq!(d.fitted.len(), FITTED_SAMPLES);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of(f: &FitResult) -> Result<Self, EllipticError> {
        let seg = &f.segment;
        let (family, parameters) = parameters(seg);
        let inflections = seg.inflections()?;
        let eval = seg.evaluator()?;
        Ok(FittedCurve {
            family: family.into(),
            parameters,
            rms: f.rms,
            max: f.max,
            length: seg.length(),
            inflections: inflections.len(),
            inflection_points: inflections.iter().map(|&t| eval.eval(t).p).collect(),
            max_abs_curvature: seg.max_abs_curvature()?,
            iterations: f.iterations,
            converged: f.converged,
            fitted: seg.sample(FITTED_SAMPLES)?,
        })
    }
}

/// The segment's family name and its parameters by name.
fn parameters(seg: &Segment) -> (&'static str, std::collections::BTreeMap<String, f64>) {
    let p = |pairs: &[(&str, f64)]| pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    match *seg {
        Segment::Elastica(e) => (
            match e.family {
                Family::Inflectional => "inflectional",
                Family::NonInflectional => "noninflectional",
            },
            p(&[
                ("k", e.k),
                ("s0", e.s0),
                ("l", e.l),
                ("S", e.scale),
                ("phi", e.phi),
                ("x0", e.x0),
                ("y0", e.y0),
            ]),
        ),
        Segment::Line {
            x0,
            y0,
            phi,
            length,
        } => (
            "line",
            p(&[("x0", x0), ("y0", y0), ("phi", phi), ("length", length)]),
        ),
        Segment::Arc {
            x0,
            y0,
            phi,
            curvature,
            length,
        } => (
            "arc",
            p(&[
                ("x0", x0),
                ("y0", y0),
                ("phi", phi),
                ("curvature", curvature),
                ("length", length),
            ]),
        ),
    }
}

impl FitSummary {
    /// Totals over `entries`: families, RMS median and largest, largest distance.
    pub fn of(entries: &[CurveFit]) -> Self {
        let fits: Vec<&FittedCurve> = entries.iter().filter_map(|e| e.fit.as_ref()).collect();
        let count = |family: &str| fits.iter().filter(|f| f.family == family).count();
        let mut rms: Vec<f64> = fits.iter().map(|f| f.rms).collect();
        rms.sort_by(f64::total_cmp);
        let median_rms = match rms.len() {
            0 => 0.0,
            n if n % 2 == 1 => rms[n / 2],
            n => 0.5 * (rms[n / 2 - 1] + rms[n / 2]),
        };
        FitSummary {
            curves: entries.len(),
            failed: entries.len() - fits.len(),
            lines: count("line"),
            arcs: count("arc"),
            inflectional: count("inflectional"),
            noninflectional: count("noninflectional"),
            max_rms: rms.last().copied().unwrap_or(0.0),
            median_rms,
            max_distance: fits.iter().map(|f| f.max).fold(0.0, f64::max),
        }
    }
}
