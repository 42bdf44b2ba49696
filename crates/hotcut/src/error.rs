//! Errors of the hotcut library. Every message names the job file and, where there is one,
//! the line and column or the JSON pointer of the offending field.

use std::path::PathBuf;

/// One problem with one job file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum JobError {
    /// The file could not be read (the message names it).
    #[error("{message}")]
    Read {
        /// Job file.
        path: PathBuf,
        /// What is wrong, naming the file.
        message: String,
    },
    /// RON syntax error.
    #[error("{path}:{line}:{col}: syntax error: {message}")]
    Syntax {
        /// Job file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// What the parser expected.
        message: String,
    },
    /// Well-formed RON that does not fit the job structure (unknown field, wrong type,
    /// missing field).
    #[error("{path}:{line}:{col}: {pointer}: {message}")]
    Structure {
        /// Job file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// JSON pointer of the field (e.g. `/blade/lenght`).
        pointer: String,
        /// What is wrong.
        message: String,
    },
    /// A value outside what the JSON Schema allows (e.g. a negative length, NaN).
    #[error("{path}: {pointer}: {message}")]
    Schema {
        /// Job file.
        path: PathBuf,
        /// JSON pointer of the field.
        pointer: String,
        /// What is wrong.
        message: String,
    },
    /// A value that is well-typed but cannot work (missing mesh file, bad expression,
    /// unsupported combination).
    #[error("{path}: {pointer}: {message}")]
    Semantic {
        /// Job file.
        path: PathBuf,
        /// JSON pointer of the field.
        pointer: String,
        /// What is wrong.
        message: String,
    },
}

/// Everything that can fail in hotcut.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HotcutError {
    /// One or more job files are invalid.
    #[error("{}", .0.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<JobError>),
    /// The geometry failed on valid input.
    #[error("{path}: {context}: {source}")]
    Geom {
        /// Job file.
        path: PathBuf,
        /// What was being done.
        context: String,
        /// The geometry error.
        source: geom::GeomError,
    },
    /// A task could not produce its result from valid input (e.g. a section no elastica
    /// fits).
    #[error("{path}: {message}")]
    Task {
        /// Job file.
        path: PathBuf,
        /// What failed, and where.
        message: String,
    },
    /// Writing an output failed.
    #[error("{path}: {source}")]
    Export {
        /// Output file.
        path: PathBuf,
        /// The writer's error.
        source: export::ExportError,
    },
    /// The run was stopped at the caller's request ([`crate::Progress::cancelled`]); no
    /// output was placed.
    #[error("the run was stopped before it finished; the earlier output, if any, is unchanged")]
    Cancelled,
    /// File-system failure.
    #[error("{path}: {source}")]
    Io {
        /// File or folder.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
}

impl JobError {
    /// A semantic error of job file `path` at JSON pointer `pointer`.
    pub fn semantic(path: &std::path::Path, pointer: &str, message: impl Into<String>) -> Self {
        Self::Semantic {
            path: path.to_path_buf(),
            pointer: pointer.into(),
            message: message.into(),
        }
    }
}

impl From<JobError> for HotcutError {
    fn from(e: JobError) -> Self {
        Self::Invalid(vec![e])
    }
}

/// Result alias of this crate.
pub type Result<T, E = HotcutError> = std::result::Result<T, E>;
