//! Errors of the pre-cut optimization.

use thiserror::Error;

/// What can go wrong in a pre-cut.
#[derive(Debug, Error)]
pub enum PreCutError {
    /// A parameter is out of range (named, with the reason).
    #[error("invalid parameter `{name}`: {reason}")]
    InvalidParameter {
        /// The parameter.
        name: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// The surface does not lie in the block or has no part over it.
    #[error("surface and block: {0}")]
    Placement(String),
    /// The QP solver failed.
    #[error("the QP solver stopped with status {status} (direction {direction}, round {round})")]
    Solver {
        /// Solver status as text.
        status: String,
        /// Direction index.
        direction: usize,
        /// Assignment round.
        round: usize,
    },
    /// The solution violates the no-over-cut constraint after every exchange round.
    #[error("no over-cut could not be verified: a design point lies {excess:.3e} above cut {leg} of direction {direction} (tolerance {tolerance:.3e})")]
    NotVerified {
        /// Direction index.
        direction: usize,
        /// Leg (cut) index.
        leg: usize,
        /// Height of the design point above the cut.
        excess: f64,
        /// Allowed excess.
        tolerance: f64,
    },
    /// A wire program leaves the machine's travel.
    #[error("{program}: axis {axis} goes to {value:.3} mm, outside the machine's travel {min}..{max} mm (spanning {:.3}..{:.3} mm on {axis})", extent.0, extent.1)]
    OutOfTravel {
        /// The program: `direction D cut C`.
        program: String,
        /// The axis letter.
        axis: char,
        /// The coordinate out of travel, mm.
        value: f64,
        /// The axis's least travel, mm.
        min: f64,
        /// The axis's greatest travel, mm.
        max: f64,
        /// The program's range on the axis, mm.
        extent: (f64, f64),
    },
    /// A geometry error from `geom`.
    #[error(transparent)]
    Geom(#[from] geom::GeomError),
}

/// Result alias.
pub type Result<T, E = PreCutError> = std::result::Result<T, E>;
