//! The error type of fitting.

/// Why a fit could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// Fewer than 3 points.
    #[error("a curve needs at least 3 points to fit, got {0}")]
    TooFewPoints(usize),
    /// A coordinate or arc length is NaN or infinite.
    #[error("point {0} is not finite")]
    NonFinite(usize),
    /// Arc-length parameters must increase strictly.
    #[error("arc length does not increase at point {0} (repeated or reversed points)")]
    NotIncreasing(usize),
    /// The arc-length list does not match the points.
    #[error("{points} points but {lengths} arc-length values")]
    LengthMismatch {
        /// Number of points.
        points: usize,
        /// Number of arc-length values.
        lengths: usize,
    },
    /// With a fixed length the curve must be longer than its chord.
    #[error("the requested length {length} is shorter than the chord {chord}")]
    LengthBelowChord {
        /// Requested length.
        length: f64,
        /// Distance between the end points.
        chord: f64,
    },
    /// The end points coincide, so end-point constraints cannot place a segment.
    #[error("the end points coincide (closed curve); end-point constraints need distinct ends")]
    ClosedCurve,
    /// End tangents (C¹ joints) could not be met from the end-point fit.
    #[error("the end tangents could not be kept ({0})")]
    Tangents(String),
    /// No candidate produced a finite fit.
    #[error("no elastica, arc or line could be fitted: {0}")]
    Failed(String),
}
