//! Errors of the environment layer. Every variant names the file (when there is one), the
//! field and the offending value, so a user can fix the input without reading code.

use std::path::PathBuf;

/// Result alias of the environment layer.
pub type Result<T, E = EnvError> = std::result::Result<T, E>;

/// What went wrong while building, reading or writing a scene.
#[derive(Debug, thiserror::Error)]
pub enum EnvError {
    /// A file could not be read or written. The message holds the path and the OS error; the
    /// OS error is deliberately not also the error's `source()`, so that `{:#}` (anyhow) prints
    /// it once.
    #[error("{}: {error}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        error: std::io::Error,
    },
    /// A file exists but its content is not what the format says.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the field when known.
        message: String,
    },
    /// A configuration value is out of range or inconsistent.
    #[error("{}invalid `{field}` = {value}: {reason}", .path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default())]
    InvalidConfig {
        /// The config file, when the value came from one.
        path: Option<PathBuf>,
        /// Dotted field name, e.g. `rooms.count_min`.
        field: String,
        /// The offending value as written.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// A scene violates an invariant (overlapping objects, unreachable room...).
    #[error("scene {scene}: {message}")]
    InvalidScene {
        /// Scene id.
        scene: String,
        /// What is wrong.
        message: String,
    },
    /// A point lies outside the occupancy map.
    #[error("point ({x:.3}, {z:.3}) is outside the map")]
    OutOfMap {
        /// World x.
        x: f32,
        /// World z.
        z: f32,
    },
}

impl EnvError {
    /// Shorthand for [`EnvError::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        EnvError::Io {
            path: path.into(),
            error: source,
        }
    }

    /// Shorthand for [`EnvError::Parse`].
    pub fn parse(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        EnvError::Parse {
            path: path.into(),
            message: message.into(),
        }
    }

    /// Shorthand for [`EnvError::InvalidConfig`] without a file.
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        EnvError::InvalidConfig {
            path: None,
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Attach a file path to an [`EnvError::InvalidConfig`] that has none.
    pub fn in_file(self, file: impl Into<PathBuf>) -> Self {
        match self {
            EnvError::InvalidConfig {
                path: None,
                field,
                value,
                reason,
            } => EnvError::InvalidConfig {
                path: Some(file.into()),
                field,
                value,
                reason,
            },
            other => other,
        }
    }
}
