//! The hot blade: a fitted segment continued along its own elastica to the blade's length,
//! so that it covers the section with lead-in and lead-out on both sides, and the data the
//! two robots need — the blade ends' positions and end-tangent angles ("Robotic Hot-Blade
//! Cutting" §4) — with the checks that keep the blade safe: max |κ| against the limit the
//! blade tolerates, the number of inflections on the whole blade, and whether the held
//! blade is a stable equilibrium ([`crate::stability()`]).

use crate::elliptic::EllipticError;
use crate::segment::Segment;
use crate::stability::{stability, Class, Stability, StabilityError, StabilityParams};

/// How to extend a segment to a blade.
#[derive(Clone, Debug)]
pub struct BladeParams {
    /// Physical blade length (same units as the segment).
    pub length: f64,
    /// Share of the extra length placed before t = 0 (0.5 centres the section on the blade).
    pub lead_in_share: f64,
    /// Largest |curvature| the blade may take, if limited.
    pub max_curvature: Option<f64>,
    /// Largest number of inflections on the blade, if limited.
    pub max_inflections: Option<usize>,
    /// How the blade's stability is judged (the margin below which it is marginal).
    pub stability: StabilityParams,
}

impl BladeParams {
    /// A blade of `length`, section centred, no limits.
    pub fn new(length: f64) -> Self {
        BladeParams {
            length,
            lead_in_share: 0.5,
            max_curvature: None,
            max_inflections: None,
            stability: StabilityParams::default(),
        }
    }
}

/// One end of the blade.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BladeEnd {
    /// Position.
    pub position: [f64; 2],
    /// Unit tangent pointing along the blade from its start to its end.
    pub tangent: [f64; 2],
    /// Tangent angle (radians).
    pub angle: f64,
}

/// A blade shape with its robot data and checks.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Blade {
    /// The whole blade as a segment (t = 0 and t = 1 are the held ends).
    pub segment: Segment,
    /// Length added before the section.
    pub lead_in: f64,
    /// Length added after the section.
    pub lead_out: f64,
    /// Start and end of the blade.
    pub ends: [BladeEnd; 2],
    /// Largest |curvature| anywhere on the blade.
    pub max_abs_curvature: f64,
    /// Inflections on the whole blade.
    pub inflections: usize,
    /// max |κ| within the limit (true when there is none).
    pub curvature_ok: bool,
    /// Inflection count within the limit (true when there is none).
    pub inflections_ok: bool,
    /// The held blade's stability: margin, class, total turning, end loads per EI.
    pub stability: Stability,
    /// The blade is a stable equilibrium by at least the stated margin
    /// ([`Class::Stable`]).
    pub stability_ok: bool,
}

/// Why a blade could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BladeError {
    /// The blade is shorter than the section it must cut.
    #[error("the blade ({blade}) is shorter than the section ({section})")]
    TooShort {
        /// Blade length.
        blade: f64,
        /// Section length.
        section: f64,
    },
    /// A parameter is not finite or out of range.
    #[error("invalid blade parameter: {0}")]
    Invalid(String),
    /// The segment's parameters are invalid.
    #[error(transparent)]
    Segment(#[from] EllipticError),
    /// The blade's stability could not be assessed.
    #[error(transparent)]
    Stability(#[from] StabilityError),
}

/// Extend `section` to the blade's length and check it.
///
/// ```
/// use elastica::blade::{extend_to_blade, BladeParams};
/// use elastica::segment::Segment;
/// let arc = Segment::Arc { x0: 0.0, y0: 0.0, phi: 0.0, curvature: 0.5, length: 1.0 };
/// let blade = extend_to_blade(&arc, &BladeParams::new(2.0)).unwrap();
/// assert!((blade.segment.length() - 2.0).abs() < 1e-12);
/// assert!((blade.lead_in - 0.5).abs() < 1e-12);
/// assert_eq!(blade.inflections, 0);
/// // an arc holds: stable, no force on the holders
/// assert!(blade.stability_ok && blade.stability.loads.force == 0.0);
/// ```
pub fn extend_to_blade(section: &Segment, params: &BladeParams) -> Result<Blade, BladeError> {
    if !(params.length > 0.0) || !params.length.is_finite() {
        return Err(BladeError::Invalid(format!(
            "length must be a positive number, got {:?}",
            params.length
        )));
    }
    if !(0.0..=1.0).contains(&params.lead_in_share) {
        return Err(BladeError::Invalid(format!(
            "lead_in_share must be in [0, 1], got {:?}",
            params.lead_in_share
        )));
    }
    let section_length = section.length();
    if params.length < section_length * (1.0 - 1e-12) {
        return Err(BladeError::TooShort {
            blade: params.length,
            section: section_length,
        });
    }
    let extra = (params.length - section_length).max(0.0);
    let lead_in = extra * params.lead_in_share;
    let lead_out = extra - lead_in;
    let segment = section.extended(lead_in, lead_out);
    let eval = segment.evaluator()?;
    let end = |t: f64| {
        let p = eval.eval(t);
        BladeEnd {
            position: p.p,
            tangent: p.tangent,
            angle: p.angle,
        }
    };
    let max_abs_curvature = segment.max_abs_curvature()?;
    let inflections = segment.inflections()?.len();
    let stability = stability(&segment, &params.stability)?;
    Ok(Blade {
        stability_ok: stability.class == Class::Stable,
        stability,
        ends: [end(0.0), end(1.0)],
        curvature_ok: params
            .max_curvature
            .is_none_or(|limit| max_abs_curvature <= limit),
        inflections_ok: params
            .max_inflections
            .is_none_or(|limit| inflections <= limit),
        segment,
        lead_in,
        lead_out,
        max_abs_curvature,
        inflections,
    })
}
