//! The error type of the output layer (summaries, tables, figures).

use std::path::PathBuf;
use thiserror::Error;

/// What can go wrong when writing or reading results.
#[derive(Debug, Error)]
pub enum ReportError {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A file could not be parsed.
    #[error("{path}: malformed: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What the parser said.
        message: String,
    },
    /// Data passed in (or read back) violates its invariants: lengths, ranges, finiteness.
    #[error("invalid data: {0}")]
    Invalid(String),
    /// The plotting library failed.
    #[error("plotting failed: {0}")]
    Plot(String),
}

impl ReportError {
    /// Shorthand for an [`ReportError::Io`] at `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        ReportError::Io {
            path: path.into(),
            source,
        }
    }

    /// Shorthand for [`ReportError::Invalid`].
    pub fn invalid(message: impl Into<String>) -> Self {
        ReportError::Invalid(message.into())
    }
}
