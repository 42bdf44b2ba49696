/// Why a segmentation could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SegError {
    /// A constraint or parameter out of range.
    #[error("invalid {what}: {message}")]
    Invalid {
        /// The offending field.
        what: String,
        /// What is wrong with it.
        message: String,
    },
    /// The facade has no usable section.
    #[error("the facade has no section to segment")]
    NoSections,
    /// A section curve could not be analysed.
    #[error("section {index}: {message}")]
    Section {
        /// Plane index.
        index: usize,
        /// The geometry error.
        message: String,
    },
    /// The algorithm would need more pieces than its cap (constraints that segmentation
    /// cannot meet, e.g. a design curvature above the blade's).
    #[error("more than {cap} bands or moves needed: {why}")]
    TooManyPieces {
        /// The cap.
        cap: usize,
        /// What kept the bands narrow.
        why: String,
    },
    /// A piece's section part could not be fitted or extended to the blade.
    #[error("piece {piece}: section {plane}: {message}")]
    Rationalize {
        /// Piece id.
        piece: usize,
        /// Plane index of the section.
        plane: usize,
        /// The fit's or blade's error.
        message: String,
    },
}
