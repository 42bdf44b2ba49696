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
//! use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
//! use hotblade::{rationalize, Params};
//!
//! // a gently curved panel, 1.2 m along the cut, 0.5 m across: two blocks of 600 mm
//! let z = Expr::parse("40*sin(y/150)")?;
//! let surface = Surface::HeightField(HeightField::try_new(z, (0.0, 1200.0), (0.0, 500.0))?);
//! let params = Params {
//!     block: [600.0, 600.0, 400.0],
//!     origin: Some([0.0, 0.0, -200.0]),
//!     targets: 5,
//!     ..Params::default()
//! };
//! let cut = rationalize(&surface, &params, &|_| {})?;
//! assert_eq!(cut.blocks.len(), 2);
//! // every block gets one blade pose per target plane, within the tolerance
//! assert!(cut.blocks.iter().all(|b| b.sections.len() == 5));
//! assert!(cut.summary.max_fit_distance < params.tolerance_max);
//! // each fitted section is extended along its elastica to the whole blade
//! for s in cut.blocks.iter().flat_map(|b| &b.sections) {
//!     assert!((s.blade.segment.length() - params.blade.length).abs() < 1e-6);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// Building a block from its fitted sections: swept surface, deviation, flags.
pub mod block;
/// Errors of a run.
pub mod error;
/// Fitting a column's sections: warm-started sweeps, C¹ tangents, blades and poses.
pub mod fit;
/// Block grid, cutting planes, clipping a section to a block.
pub mod grid;
/// The parameters and their checks.
mod params;
/// The run: planes, sections, fits with splits, blocks, totals.
mod pipeline;
/// The result: blocks with their fitted sections, swept surfaces and report entries.
pub mod result;
/// Serializers for the geometry types of `geom` and `nalgebra`, which carry no serde.
#[cfg(feature = "serde")]
mod ser;

pub use error::HotBladeError;
pub use fit::{make_blade, sweep_fits, SweepError};
pub use grid::Clipped;
pub use params::{curve_chord, BladeLimits, Continuity, ParamProblem, Params};
pub use pipeline::{rationalize, run_size, RunSize, MAX_BLOCKS, MAX_PLANES};
pub use result::{BlockResult, FittedSection, Rationalization};

/// Share of the largest-distance tolerance by which a parameter-interpolated curve of the
/// swept surface may stray from the pointwise blend of its two neighbouring fits before
/// the blend is refitted instead (see [`block`]).
pub const SWEEP_SHARE: f64 = 0.1;

/// Shortest design part fitted, as a share of the blade length: shorter parts (slivers
/// where a plane grazes the surface inside the block) get no blade pose and count as missing
/// sections, since extending a fit of a few millimetres to the whole blade is meaningless.
pub const SHORTEST_PART: f64 = 0.05;

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
