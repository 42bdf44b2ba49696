//! Errors of the rationalization and the block plan.

use thiserror::Error;

/// Why a rationalization or a block plan could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The model is not a closed solid, or has no section to fit.
    #[error("model: {0}")]
    Model(String),
    /// A parameter is out of range; `field` names it.
    #[error("{field}: {message}")]
    Params {
        /// The parameter.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// A region's least-squares fit failed.
    #[error("fit of region {region}: {source}")]
    Fit {
        /// The region.
        region: usize,
        /// Why.
        source: crate::fit::FitError,
    },
    /// The block segmentation failed.
    #[error("blocks: {0}")]
    Blocks(String),
}

/// Result of this crate.
pub type Result<T> = std::result::Result<T, Error>;
