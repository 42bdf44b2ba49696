use elastica::blade::BladeError;
use elastica::fit::FitError;

/// Why a run failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HotBladeError {
    /// A parameter out of range (see [`crate::Params::problems`]).
    #[error("invalid {field}: {message}")]
    Invalid {
        /// The field of [`crate::Params`].
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The geometry failed (cutting direction, sectioning, surface normals).
    #[error("{context}: {source}")]
    Geom {
        /// What was being done.
        context: &'static str,
        /// The geometry error.
        source: geom::GeomError,
    },
    /// No elastica could be fitted to a section part.
    #[error("column {column} (range {:.6}..{:.6}), plane {plane}: {source}", range.0, range.1)]
    Fit {
        /// Column of the grid.
        column: usize,
        /// The part's range across the cut.
        range: (f64, f64),
        /// Plane index.
        plane: usize,
        /// The fit's error.
        source: FitError,
    },
    /// A fit could not be extended to the blade.
    #[error("plane {plane}: {source}")]
    Blade {
        /// Plane index.
        plane: usize,
        /// The blade's error.
        source: BladeError,
    },
}
