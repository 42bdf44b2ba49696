//! Errors of the robot cell.

use thiserror::Error;

/// What can go wrong with a robot model or a pose.
#[derive(Debug, Error, PartialEq)]
pub enum CellError {
    /// A model parameter is out of range (named, with the reason).
    #[error("robot model {model}: `{name}` {reason}")]
    InvalidModel {
        /// The model's name.
        model: String,
        /// The parameter.
        name: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// A blade pose or motion that cannot be held or planned.
    #[error("{0}")]
    Blade(String),
    /// Joint values or a pose that are not finite.
    #[error("{0} is not finite")]
    NotFinite(&'static str),
}

/// Result alias.
pub type Result<T, E = CellError> = std::result::Result<T, E>;
