//! # hotblade — hot-blade rationalization ("Hot Blade Cuttings" §6–7, thesis §5.1)
//!
//! A surface is cut from a grid of foam blocks by a blade held by two robots; the blade is
//! always a planar elastica. [`rationalize`] turns the surface into what the cell cuts:
//!
//! 1. **Planes** ([`grid`]): `targets` planes per block, from its entry face to its exit
//!    face; neighbouring rows share the face plane. With a cutting-direction curve the
//!    planes follow it (thesis eq. 5.4).
//! 2. **Fits** ([`fit`]): every plane's section is clipped to a column of blocks and fitted
//!    by an elastica keeping its end points (and by default its length), warm-started from
//!    the previous plane's fit (§7) in sweeps; neighbouring columns clip at the same point
//!    of the same section, so their blades share end points (C⁰); with
//!    [`Continuity::C1`] the fits also keep the design's tangent there.
//! 3. **Splits**: a column whose fit breaks the tolerance is halved along the cut and
//!    refitted, up to `split_depth` times (§6).
//! 4. **Blades and poses**: each fit is extended along its own elastica to the blade's
//!    length; its two ends give the robots' targets ([`elastica::sweep::blade_pose`]).
//! 5. **Blocks** ([`block`]): the swept surface between targets interpolates the fits'
//!    parameters ([`elastica::sweep::interpolate`]) and is compared with the design on
//!    `refine` extra planes per gap; every production constraint gets a flag.
//!
//! Like the other algorithm crates it takes a parameter struct, reports progress through
//! a callback, returns a plain serde-able result and does no I/O.
//!
//! ```
//! use geom::expr::Expr;
//! use geom::heightfield::HeightField;
//! use geom::surface::Surface;
//!
//! // a gently curved panel, 1.2 m along the cut, 0.5 m across: two blocks of 600 mm
//! let z = Expr::parse("40*sin(y/150)").unwrap();
//! let surface = Surface::HeightField(HeightField::try_new(z, (0.0, 1200.0), (0.0, 500.0)).unwrap());
//! let params = hotblade::Params {
//!     block: [600.0, 600.0, 400.0],
//!     origin: Some([0.0, 0.0, -200.0]),
//!     targets: 5,
//!     ..hotblade::Params::default()
//! };
//! let cut = hotblade::rationalize(&surface, &params, &|_| {}).unwrap();
//! assert_eq!(cut.blocks.len(), 2);
//! // every block gets one blade pose per target plane, within the tolerance
//! assert!(cut.blocks.iter().all(|b| b.sections.len() == 5));
//! assert!(cut.summary.max_fit_distance < params.tolerance_max);
//! ```

/// Building a block from its fitted sections: swept surface, deviation, flags.
pub mod block;
/// Errors of a run.
pub mod error;
/// Fitting a column's sections: warm-started sweeps, C¹ tangents, blades and poses.
pub mod fit;
/// Block grid, cutting planes, clipping a section to a block.
pub mod grid;
/// The run: planes, sections, fits with splits, blocks, totals.
mod pipeline;
/// The result: blocks with their fitted sections, swept surfaces and report entries.
pub mod result;
/// Serializers for the geometry types of `geom` and `nalgebra`, which carry no serde.
mod ser;

use elastica::fit::FitConstraint;
use geom::surface::SectionParams;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use error::HotBladeError;
pub use fit::{make_blade, sweep_fits};
pub use grid::Clipped;
pub use pipeline::rationalize;
pub use result::{BlockResult, FittedSection, Rationalization};

/// Share of the largest-distance tolerance by which a parameter-interpolated curve of the
/// swept surface may stray from the pointwise blend of its two neighbouring fits before
/// the blend is refitted instead (see [`block`]).
pub const SWEEP_SHARE: f64 = 0.1;

/// Shortest design part fitted, as a share of the blade length: shorter parts (slivers
/// where a plane grazes the surface inside the block) get no blade pose and count as missing
/// sections, since extending a fit of a few millimetres to the whole blade is meaningless.
pub const SHORTEST_PART: f64 = 0.05;

/// Continuity of the rationalized surface across block faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
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
}

/// Parameters of [`rationalize`]. Lengths are in the surface's unit; the defaults are the
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
            blade: BladeLimits {
                length: 1000.0,
                max_curvature: 0.011,
                max_inflections: 2,
            },
            tolerance_rms: 0.5,
            tolerance_max: 2.0,
            sectioning: SectionParams::default(),
        }
    }
}

/// Progress of a run, reported through the callback (from worker threads too).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress<'a> {
    /// A step with `total` units of work begins.
    Start {
        /// What the step does.
        step: &'a str,
        /// Units of work.
        total: u64,
    },
    /// One unit of the current step is done.
    Tick,
    /// The current step is done.
    Finish,
}

/// The progress callback of [`rationalize`].
pub type ProgressFn<'a> = dyn Fn(Progress<'_>) + Sync + 'a;
