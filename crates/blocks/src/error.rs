/// Why a block segmentation could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BlockError {
    /// A parameter out of range.
    #[error("invalid {what}: {message}")]
    Invalid {
        /// The offending field.
        what: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// The model is not a closed mesh with a volume, or has no samples.
    #[error("unusable model: {0}")]
    Model(String),
    /// The sampling would exceed the sample cap (block too small for the model).
    #[error("{samples} samples needed, more than the cap of {cap}: use a larger block or a coarser sample spacing")]
    TooManySamples {
        /// Samples the model would need.
        samples: usize,
        /// The cap.
        cap: usize,
    },
}

/// Result with [`BlockError`].
pub type Result<T> = std::result::Result<T, BlockError>;
