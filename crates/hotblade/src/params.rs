//! The parameters of [`rationalize`](crate::rationalize), their defaults, and every check
//! a run makes on them ([`Params::problems`]), so a caller can validate before running.

use elastica::fit::FitConstraint;
use geom::surface::SectionParams;
use nalgebra::Vector3;

/// Continuity of the rationalized surface across block faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Continuity {
    /// Neighbouring blades share their end points.
    #[default]
    C0,
    /// Neighbouring blades share their end points and end tangents.
    C1,
}

/// What the blade takes, in the surface's length unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BladeLimits {
    /// Blade length.
    pub length: f64,
    /// Largest allowed |curvature|.
    pub max_curvature: f64,
    /// Most inflections a blade shape may have.
    pub max_inflections: u32,
    /// Most inflections the whole held blade may have, if limited (besides
    /// `max_inflections`).
    pub max_blade_inflections: Option<u32>,
    /// Least stability margin a held blade keeps ([`elastica::stability()`]; below it a
    /// blade is marginal).
    pub min_margin: f64,
}

impl BladeLimits {
    /// A blade of `length` bending to `max_curvature` with `max_inflections`, no separate
    /// limit on the whole blade's inflections, the default margin.
    pub fn new(length: f64, max_curvature: f64, max_inflections: u32) -> Self {
        BladeLimits {
            length,
            max_curvature,
            max_inflections,
            max_blade_inflections: None,
            min_margin: elastica::stability::MARGINAL,
        }
    }
}

/// Parameters of [`rationalize`](crate::rationalize). Lengths are in the surface's unit; the defaults are the
/// paper's cell in millimetres.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Block edge lengths along the cut, across it and along `v = d × u`.
    pub block: [f64; 3],
    /// World position of the grid's min corner; `None`: the surface's extent's min corner.
    pub origin: Option<[f64; 3]>,
    /// Unit cutting direction `d`; replaced by the curve's chord when `curve` is given.
    pub direction: Vector3<f64>,
    /// Plan points `(x, y)` of a cutting-direction curve the planes follow (eq. 5.4),
    /// strictly advancing along its chord; `None`: parallel planes normal to `direction`.
    pub curve: Option<Vec<(f64, f64)>>,
    /// Poses (target planes) per block, ≥ 2. Default 51.
    pub targets: usize,
    /// What each fit keeps: `EndPoints` or `EndPointsAndLength` (`Free` is taken as
    /// `EndPoints`: neighbouring blocks must meet). Default `EndPointsAndLength`.
    pub constraint: FitConstraint,
    /// Continuity across block faces. Default `C0`.
    pub continuity: Continuity,
    /// Largest number of halvings of a column over tolerance. Default 2.
    pub split_depth: u32,
    /// Fit samples per section. Default 100.
    pub samples: usize,
    /// Flat-blade limit: largest angle between a cutting plane and the surface normal,
    /// radians. Default π/6.
    pub max_plane_angle: f64,
    /// Extra planes between two targets on the deviation grid. Default 3.
    pub refine: usize,
    /// Points per curve on the deviation grid and in the meshes. Default 60.
    pub grid_points: usize,
    /// Blade limits. Default 1000 mm, 0.011 /mm, 2 inflections.
    pub blade: BladeLimits,
    /// RMS fit tolerance. Default 0.5 mm.
    pub tolerance_rms: f64,
    /// Largest-distance fit tolerance. Default 2 mm.
    pub tolerance_max: f64,
    /// Sectioning of polyline surfaces (`direction` and `count` are not used).
    pub sectioning: SectionParams,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            block: [600.0, 600.0, 600.0],
            origin: None,
            direction: Vector3::x(),
            curve: None,
            targets: 51,
            constraint: FitConstraint::EndPointsAndLength,
            continuity: Continuity::C0,
            split_depth: 2,
            samples: 100,
            max_plane_angle: std::f64::consts::FRAC_PI_6,
            refine: 3,
            grid_points: 60,
            blade: BladeLimits::new(1000.0, 0.011, 2),
            tolerance_rms: 0.5,
            tolerance_max: 2.0,
            sectioning: SectionParams::default(),
        }
    }
}

pub use geom::ParamProblem;

impl Params {
    /// Every rule [`rationalize`](crate::rationalize) checks that the parameters break,
    /// one problem per rule (none: it runs).
    pub fn problems(&self) -> Vec<ParamProblem> {
        let mut out = Vec::new();
        let mut bad = |field: &'static str, message: String| {
            out.push(ParamProblem {
                field,
                index: None,
                message,
            });
        };
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !self.block.iter().all(|&v| positive(v)) {
            bad(
                "block",
                format!("edges must be positive and finite, got {:?}", self.block),
            );
        }
        if self
            .origin
            .is_some_and(|o| !o.iter().all(|v| v.is_finite()))
        {
            bad("origin", format!("must be finite, got {:?}", self.origin));
        }
        let d = self.direction;
        if !(d.iter().all(|v| v.is_finite()) && d.norm() > 0.0) {
            bad(
                "direction",
                format!("must be a finite non-zero vector, got {:?}", d.as_slice()),
            );
        }
        if let Some(curve) = &self.curve {
            if let Err(m) = curve_chord(curve) {
                bad("curve", m);
            }
        }
        let mut range = |field: &'static str, v: usize, lo: usize, hi: usize| {
            if !(lo..=hi).contains(&v) {
                bad(field, format!("must be {lo}–{hi}, got {v}"));
            }
        };
        range("targets", self.targets, 2, 10_000);
        range("split_depth", self.split_depth as usize, 0, 8);
        range("samples", self.samples, 8, 100_000);
        range("refine", self.refine, 0, 100);
        range("grid_points", self.grid_points, 2, 100_000);
        let angle = self.max_plane_angle;
        if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&angle) {
            bad(
                "max_plane_angle",
                format!("must be in [0, π/2], got {angle}"),
            );
        }
        let b = &self.blade;
        if !(positive(b.length) && positive(b.max_curvature)) {
            bad(
                "blade",
                format!(
                    "length and max_curvature must be positive, got {:?} and {:?}",
                    b.length, b.max_curvature
                ),
            );
        }
        if !(positive(self.tolerance_rms) && positive(self.tolerance_max)) {
            bad(
                "tolerance",
                format!(
                    "rms and max must be positive, got {:?} and {:?}",
                    self.tolerance_rms, self.tolerance_max
                ),
            );
        }
        out
    }
}

/// The unit chord of a cutting-direction curve (plan points `(x, y)`), checking that it
/// has at least 2 finite points and that every point advances along the chord from the
/// first point to the last (else planes would cross).
///
/// # Errors
/// What is wrong with the curve.
pub fn curve_chord(curve: &[(f64, f64)]) -> Result<Vector3<f64>, String> {
    if curve.len() < 2 {
        return Err(format!("needs at least 2 points, got {}", curve.len()));
    }
    if let Some(i) = curve
        .iter()
        .position(|p| !p.0.is_finite() || !p.1.is_finite())
    {
        return Err(format!("point {i} is not finite"));
    }
    let (a, b) = (curve[0], curve[curve.len() - 1]);
    let chord = Vector3::new(b.0 - a.0, b.1 - a.1, 0.0);
    if !(chord.norm() > 0.0) {
        return Err("the first and last points coincide".into());
    }
    let d = chord.normalize();
    for i in 1..curve.len() {
        let step = (curve[i].0 - curve[i - 1].0) * d.x + (curve[i].1 - curve[i - 1].1) * d.y;
        if !(step > 0.0) {
            return Err(format!(
                "point {i} does not advance along the chord from the first to the last point (planes would cross)"
            ));
        }
    }
    Ok(d)
}
