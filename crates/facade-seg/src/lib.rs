//! # facade-seg — segmenting facades for hot-blade cutting (thesis ch. 5)
//!
//! A facade is cut by a hot blade from blocks; where a block's sections break a
//! production constraint (§5.1: dimensions, approximation, shape, blade strain) the facade
//! is segmented into pieces. This crate takes the facade's sections (from
//! [`geom::surface::Surface::sections`]) and the constraints, and returns pieces: per
//! section the part each piece holds, the block it is cut from, and a verdict per
//! constraint.

/// Sections seen across the facade (`u` ↔ arc length, curvature, inflections).
mod across;
/// The production constraints of §5.1 and their checks on one section part.
pub mod constraints;
/// Why a segmentation failed.
pub mod error;
/// The inflection-points algorithm (§5.2).
pub mod inflection;
/// The longest-elastica algorithm (§5.4).
pub mod longest;
/// Pieces, blocks and seams: what every algorithm returns.
pub mod piece;
/// Rationalizing a piece: its parts fitted by elastica, extended to the blade, posed.
pub mod rationalize;
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
