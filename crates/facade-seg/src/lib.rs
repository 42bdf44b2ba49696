//! # facade-seg — segmenting facades for hot-blade cutting (thesis ch. 5)
//!
//! A facade is cut by a hot blade from blocks; where a block's sections break a
//! production constraint (§5.1: dimensions, approximation, shape, blade strain) the facade
//! is segmented into pieces. This crate takes the facade's sections (from
//! [`geom::surface::Surface::sections`]) and the constraints, and returns pieces: per
//! section the part each piece holds, the block it is cut from, and a verdict per
//! constraint.
//!
//! - The algorithms: [`inflection::inflection_points`] (§5.2), [`trace::trace`] (§5.3),
//!   [`longest::longest_elastica`] (§5.4), each returning a [`Segmentation`].
//! - [`rationalize::pose_pieces`]: every piece's parts fitted by elastica with the
//!   `hotblade` fit sweeps, extended to the blade and posed for the two robots;
//!   [`report::summarize`] folds those fits into each piece's verdicts and counts.
//! - [`survey::survey`]: every section checked against §5.1 before anything is cut.
//!
//! ```
//! use facade_seg::{inflection_points, Constraints, Facade, InflectionParams};
//! use geom::expr::Expr;
//! use geom::heightfield::HeightField;
//! use geom::surface::{SectionParams, Surface};
//!
//! // a wavy facade, an inflection every ~470 mm across the cut, 6 sections along it
//! let z = Expr::parse("60*sin(y/150)")?;
//! let surface = Surface::HeightField(HeightField::try_new(z, (0.0, 600.0), (0.0, 1800.0))?);
//! let (frame, sections) = surface
//!     .sections(&SectionParams { count: 6, ..SectionParams::default() }, &|| {})?;
//! let facade = Facade::new(frame, &sections)?;
//! let c = Constraints {
//!     block: [600.0, 600.0, 400.0],
//!     blade_length: 800.0,
//!     max_curvature: 0.011,
//!     max_inflections: 2,
//!     tolerance_rms: 0.5,
//!     tolerance_max: 2.0,
//! };
//! let seg = inflection_points(&facade, &c, &InflectionParams::default(), &|| {})?;
//! // every part of every piece holds at most two inflections
//! assert!(seg.pieces.iter().all(|p| p.verdicts.shape));
//! assert!(seg.pieces.len() > 1);
//! // and every section is shared out whole: the parts on it add up to its length
//! for (j, section) in facade.sections.iter().enumerate() {
//!     let held: f64 = seg.pieces.iter().flat_map(|p| &p.parts)
//!         .filter(|q| q.plane == j)
//!         .map(|q| q.s[1] - q.s[0])
//!         .sum();
//!     assert!((held - section.length).abs() < 1e-6);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// Sections seen across the facade (`u` ↔ arc length, curvature, inflections).
mod across;
/// One section checked against the production constraints and fitted, while it is drawn.
pub mod check;
/// The production constraints of §5.1 and their checks on one section part.
pub mod constraints;
/// Why a segmentation failed.
pub mod error;
/// A piece's block against its blades: its section on a plane, slid to clear the holders.
pub mod holders;
/// The inflection-points algorithm (§5.2).
pub mod inflection;
/// The longest-elastica algorithm (§5.4).
pub mod longest;
/// Pieces, blocks and seams: what every algorithm returns.
pub mod piece;
/// Rationalizing a piece: its parts fitted by elastica, extended to the blade, posed.
pub mod rationalize;
/// Refinement after any algorithm: failing pieces split until they hold or cannot shrink.
pub mod refine;
/// What a run reports per piece (blade fits folded into the verdicts), and the counts.
pub mod report;
/// Sections prepared for segmentation: arc length, inflections, sampling.
pub mod section;
/// The survey before cutting (§5.1): every section checked against the constraints.
pub mod survey;
/// The trace algorithm (§5.3).
pub mod trace;

pub use constraints::Constraints;
pub use error::SegError;
pub use piece::{Piece, PiecePart, Segmentation};
pub use section::Facade;

pub use inflection::{inflection_points, InflectionParams};
pub use longest::{longest_elastica, LongestParams};
pub use rationalize::{pose_pieces, RationalizeParams};
pub use refine::{refine, RefineParams};
pub use trace::{trace, TraceParams};
