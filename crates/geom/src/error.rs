//! The error type of the geometry kernel.

use std::path::PathBuf;

/// Everything that can go wrong in `geom`. Each variant says what was wrong with the input.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum GeomError {
    /// A B-spline was given inconsistent degree, knots or control points.
    #[error("invalid B-spline: {0}")]
    InvalidSpline(String),
    /// A fit was asked for with too few or unusable points.
    #[error("cannot fit: {0}")]
    InvalidFit(String),
    /// A value that must be finite was NaN or infinite.
    #[error("{what} is not finite")]
    NonFinite {
        /// What was not finite.
        what: String,
    },
    /// A mesh file could not be read.
    #[error("cannot read mesh {path}: {message}")]
    MeshRead {
        /// The file.
        path: PathBuf,
        /// The reader's message.
        message: String,
    },
    /// The mesh has no triangles (or no vertices).
    #[error("mesh is empty: {0}")]
    EmptyMesh(String),
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {vertex}, but the mesh has {count} vertices")]
    BadIndex {
        /// Face index.
        face: usize,
        /// Offending vertex index.
        vertex: usize,
        /// Number of vertices.
        count: usize,
    },
    /// The mesh was required to be closed but has boundary edges.
    #[error("mesh is open: {boundary_edges} boundary edge(s) in {boundary_loops} loop(s), but a closed mesh is required")]
    OpenMesh {
        /// Edges used by exactly one face.
        boundary_edges: usize,
        /// Number of boundary loops.
        boundary_loops: usize,
    },
    /// The mesh has edges shared by more than two faces.
    #[error("mesh is non-manifold: {0} edge(s) are shared by more than two faces")]
    NonManifold(usize),
    /// A height-field expression could not be parsed or evaluated.
    #[error("expression error at column {column}: {message}")]
    Expression {
        /// 1-based column in the expression text.
        column: usize,
        /// What went wrong.
        message: String,
    },
    /// A domain (interval, rectangle, box) was empty or inverted.
    #[error("invalid domain: {0}")]
    InvalidDomain(String),
    /// A direction vector had zero length.
    #[error("direction must be a non-zero vector")]
    ZeroDirection,
    /// The operation is not supported for this input.
    #[error("unsupported: {0}")]
    Unsupported(String),
}

/// Result alias for `geom`.
pub type Result<T, E = GeomError> = std::result::Result<T, E>;

/// A parameter out of range, as the algorithm crates' `Params::problems` list them: the
/// field, the index of the offending element for a list field, and what is wrong. The
/// caller maps the field to its own name for it (a job file's pointer, a CLI flag).
///
/// ```
/// use geom::ParamProblem;
/// let p = ParamProblem { field: "directions", index: Some(2), message: "must be finite".into() };
/// assert_eq!(p.to_string(), "directions 2 must be finite");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParamProblem {
    /// The field of the parameters.
    pub field: &'static str,
    /// The element of a list field.
    pub index: Option<usize>,
    /// What is wrong, e.g. `must be 1–256, got 0`.
    pub message: String,
}

impl std::fmt::Display for ParamProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.index {
            Some(i) => write!(f, "{} {i} {}", self.field, self.message),
            None => write!(f, "{} {}", self.field, self.message),
        }
    }
}
