//! Errors of the design crate.

use thiserror::Error;

/// What can go wrong with a design curve or its elastica.
#[derive(Debug, Error, PartialEq)]
pub enum DesignError {
    /// A curve or boundary data that cannot define an elastica (named, with the reason).
    #[error("{0}")]
    Invalid(String),
    /// The boundary-value problem did not converge (with the residuals reached).
    #[error("no elastica meets the end data: residuals {0:?} after the Newton iterations")]
    NoConvergence([f64; 3]),
    /// An error of the elastica crate.
    #[error("{0}")]
    Elastica(String),
}

/// Result alias.
pub type Result<T, E = DesignError> = std::result::Result<T, E>;
