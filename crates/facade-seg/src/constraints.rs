use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams};

use crate::section::PreparedSection;
use crate::SegError;

/// The production constraints of §5.1 (lengths in the facade's units).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Constraints {
    /// Block size: along the cut, across it (`u`), and along `v`.
    pub block: [f64; 3],
    /// The blade's cutting length: no section part may be longer (§5.1.1).
    pub blade_length: f64,
    /// Largest |curvature| the blade takes without permanent deformation (§5.1.4).
    pub max_curvature: f64,
    /// Most inflections a section part may have (§5.1.3; the thesis uses 2).
    pub max_inflections: u32,
    /// RMS distance allowed between a part and its elastica (§5.1.2).
    pub tolerance_rms: f64,
    /// Largest distance allowed between a part and its elastica.
    pub tolerance_max: f64,
}

impl Constraints {
    /// Checks that every size and tolerance is a positive finite number and that a part may
    /// hold at least one inflection.
    ///
    /// # Errors
    /// [`SegError::Invalid`] naming the field.
    pub fn validate(&self) -> Result<(), SegError> {
        let positive = [
            ("block.size.0", self.block[0]),
            ("block.size.1", self.block[1]),
            ("block.size.2", self.block[2]),
            ("blade length", self.blade_length),
            ("max curvature", self.max_curvature),
            ("tolerance rms", self.tolerance_rms),
            ("tolerance max", self.tolerance_max),
        ];
        for (what, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(SegError::Invalid {
                    what: what.into(),
                    message: format!("must be a positive number, got {v}"),
                });
            }
        }
        if self.max_inflections == 0 {
            return Err(SegError::Invalid {
                what: "max inflections".into(),
                message: "must be at least 1 for segmentation: parts meet between inflections, never exactly on one, so a section with an inflection cannot be split into parts without any".into(),
            });
        }
        Ok(())
    }
}

/// An elastica fitted to a part (end points kept, as the hot blade's pieces meet).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct FitCheck {
    /// RMS distance from the part to the elastica.
    pub rms: f64,
    /// Largest distance.
    pub max: f64,
    /// Inflections of the elastica.
    pub inflections: usize,
    /// Largest |curvature| of the elastica.
    pub max_abs_curvature: f64,
}

/// What one section part measures against the constraints.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PartCheck {
    /// Arc length of the part.
    pub length: f64,
    /// Extent across the facade (`u`).
    pub u_extent: f64,
    /// Extent along `v`.
    pub v_extent: f64,
    /// Inflections of the design inside the part.
    pub inflections: usize,
    /// Largest |curvature| of the design in the part.
    pub max_abs_curvature: f64,
    /// The elastica fit, when asked for (and found).
    pub fit: Option<FitCheck>,
}

/// Per-constraint verdicts (true = met).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Verdicts {
    /// No part longer than the blade, and the piece fits its block (§5.1.1).
    pub dimension: bool,
    /// Every part's elastica within both tolerances (§5.1.2); `None` when not fitted.
    pub approximation: Option<bool>,
    /// No part with more than `max_inflections` inflections, in the design or in its
    /// elastica (§5.1.3).
    pub shape: bool,
    /// No part (design or elastica) bending beyond `max_curvature` (§5.1.4).
    pub blade_strain: bool,
    /// Every blade the piece is cut with holds its shape: a stable equilibrium by at least
    /// the stated margin ([`elastica::stability()`]), within the blade's inflection limit
    /// when one is set, and carried from each plane's shape to the next's without snapping
    /// (rationalized runs; true otherwise). The seed's "instability of the blade due to
    /// multiple inflection points", measured.
    pub stability: bool,
}

impl Verdicts {
    /// All met (an unfitted approximation counts as met).
    pub fn all(&self) -> bool {
        self.dimension
            && self.approximation != Some(false)
            && self.shape
            && self.blade_strain
            && self.stability
    }
}

impl PartCheck {
    /// Measures the part `[s0, s1]` of `sec`; with `fit`, fits an elastica through its end
    /// points on `samples` points.
    pub fn of(sec: &PreparedSection, s0: f64, s1: f64, samples: usize, fit: bool) -> Self {
        let (pts, ss) = sec.samples(s0, s1, samples);
        let extent = |k: usize| {
            let (lo, hi) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p[k]), b.max(p[k]))
                });
            hi - lo
        };
        let fit = if fit && s1 - s0 > 0.0 {
            fit_points_with_arclength(
                &pts,
                &ss,
                &FitParams {
                    constraint: FitConstraint::EndPoints,
                    ..FitParams::default()
                },
            )
            .ok()
            .map(|f| FitCheck {
                rms: f.rms,
                max: f.max,
                inflections: f
                    .segment
                    .inflections()
                    .map(|v| v.len())
                    .unwrap_or(usize::MAX),
                max_abs_curvature: f.segment.max_abs_curvature().unwrap_or(f64::INFINITY),
            })
        } else {
            None
        };
        Self {
            length: s1 - s0,
            u_extent: extent(0),
            v_extent: extent(1),
            inflections: sec.inflections_in(s0, s1),
            max_abs_curvature: sec.max_abs_curvature(s0, s1, samples),
            fit,
        }
    }

    /// The verdicts of this part alone (the block check here is the part's own extent).
    pub fn verdicts(&self, c: &Constraints, fitted: bool) -> Verdicts {
        let max_infl = c.max_inflections as usize;
        Verdicts {
            dimension: self.length <= c.blade_length * (1.0 + 1e-12)
                && self.u_extent <= c.block[1] * (1.0 + 1e-12)
                && self.v_extent <= c.block[2] * (1.0 + 1e-12),
            approximation: fitted.then(|| {
                self.fit
                    .is_some_and(|f| f.rms <= c.tolerance_rms && f.max <= c.tolerance_max)
            }),
            shape: self.inflections <= max_infl
                && self.fit.is_none_or(|f| f.inflections <= max_infl),
            blade_strain: self.max_abs_curvature <= c.max_curvature
                && self
                    .fit
                    .is_none_or(|f| f.max_abs_curvature <= c.max_curvature),
            stability: true,
        }
    }
}
