//! # ruled_blocks — segmentation versus rationalization (thesis ch. 4)
//!
//! A model that is not ruled, larger than one block, made of blocks a hot wire can cut
//! with no milling, as close to the model as possible and C⁰ between blocks. The thesis'
//! strategy: rationalize the whole model by piecewise ruled surfaces first, then segment
//! the rationalized model into blocks, so that the look does not depend on where the
//! blocks fall.
//!
//! This crate is being built up (issue 39). It has so far:
//! - [`fit`]: eq. (4.1), the least-squares piecewise ruled surface through a region's
//!   samples on a `(u, v)` grid — rails in `u`, straight rulings between neighbouring
//!   rails — with each sample's residual and its distance to the surface (closest point,
//!   [`fit::closest_point`]), their RMS and largest.
//!
//! Like the other algorithm crates it does no I/O and prints nothing. It is unit-free:
//! every length of a result scales with the input.
//!
//! ```
//! use ruled_blocks::fit::{fit_piecewise_ruled, GridSamples, RuledFitParams};
//!
//! // a hyperbolic paraboloid z = x·y is ruled: its fit is exact
//! let (nu, nv) = (12, 9);
//! let u: Vec<f64> = (0..nu).map(|i| i as f64 / (nu - 1) as f64).collect();
//! let v: Vec<f64> = (0..nv).map(|j| j as f64 / (nv - 1) as f64).collect();
//! let points = v.iter().flat_map(|&y| u.iter().map(move |&x| [x, y, x * y])).collect();
//! let samples = GridSamples { u, v, points };
//! let fit = fit_piecewise_ruled(&samples, &RuledFitParams { strips: 1, degree: 3, controls: 4 })?;
//! assert!(fit.max_residual < 1e-12);
//! # Ok::<(), ruled_blocks::fit::FitError>(())
//! ```

/// The two strategies side by side: seams' gaps and ruling jumps, deviation, material, cuts.
pub mod compare;
/// Cuttability per block and the strip cuts.
pub mod cuts;
/// Errors.
pub mod error;
/// Eq. (4.1): the least-squares piecewise ruled surface through gridded samples.
pub mod fit;
/// Blocks cut to their hulls: planar cuts, added material.
pub mod hull;
/// Wire paths of the cuts on a 4-axis hot-wire machine, the block mounted in its frame.
pub mod machine;
/// The model as a closed solid (height fields closed into slabs).
pub mod model;
/// The per-block strategy: segment first, then rationalize each block on its own.
pub mod per_block;
/// The whole chain: rationalize, segment, plan the cuts.
pub mod plan;
/// Regions (tubes of loops) and their ruled fits.
pub mod regions;
/// Sections of the model: loops with their corners.
pub mod sections;
/// Sharing the blocks' overlaps where that lowers what their hulls add (fig. 4.4).
pub mod share;
/// The rationalized solid, its strips' rulings, inside and depth queries.
pub mod solid;
/// The unit frame every step computes in.
pub mod unit;

pub use error::{Error, Result};
pub use plan::{run, Deviation, Params, Progress, RegionResult, RuledBlocks, SegmentationSummary};
