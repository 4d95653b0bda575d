//! Errors of an export; each names the file, field or episode at fault.

use std::path::{Path, PathBuf};

/// What went wrong in an export.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A file or folder could not be read or written (the message carries the OS error).
    #[error("{path}: {error}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The OS error.
        error: std::io::Error,
    },
    /// A request value is out of range or inconsistent.
    #[error("invalid `{field}` = {value}: {reason}")]
    Invalid {
        /// The option or field.
        field: String,
        /// The offending value.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The dataset, the simulator or the renderer refused (the message names the episode).
    #[error(transparent)]
    Task(#[from] vlnverse_task::TaskError),
    /// A dataset file could not be read (the message names the file and field).
    #[error(transparent)]
    Dataset(#[from] vlnverse_score::DataError),
    /// A Parquet file could not be written.
    #[error("{path}: writing Parquet: {message}")]
    Parquet {
        /// The file.
        path: PathBuf,
        /// What the writer said.
        message: String,
    },
    /// The output folder holds something this export cannot continue.
    #[error("{path}: {reason}")]
    Output {
        /// The folder or file.
        path: PathBuf,
        /// Why, and what to do.
        reason: String,
    },
}

impl ExportError {
    /// An I/O error on `path`.
    pub fn io(path: &Path, error: std::io::Error) -> Self {
        ExportError::Io {
            path: path.to_path_buf(),
            error,
        }
    }

    /// An invalid value.
    pub fn invalid(field: &str, value: impl ToString, reason: impl Into<String>) -> Self {
        ExportError::Invalid {
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// Result of an export step.
pub type Result<T, E = ExportError> = std::result::Result<T, E>;
