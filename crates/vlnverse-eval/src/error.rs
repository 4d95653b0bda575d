//! Errors of the task layer. Every variant names the file (when there is one), the place in it
//! (line, episode index, field) and the offending value, so a user can fix the input.

use std::path::PathBuf;

/// Result alias of the task layer.
pub type Result<T, E = TaskError> = std::result::Result<T, E>;

/// What went wrong while reading, writing or scoring task data.
#[derive(Debug, thiserror::Error)]
pub enum TaskError {
    /// A file could not be read or written. The message already carries the OS error, so it is
    /// deliberately not also the error's `source()`: chain printers (anyhow's `{:#}`) would
    /// print it twice.
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        error: std::io::Error,
    },
    /// A file exists but its content is not what the format says.
    #[error("{path}: {location}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// Where in the file: `line 12`, `episodes[3]`, `line 4, field \`positions\``.
        location: String,
        /// What is wrong.
        message: String,
    },
    /// A value is out of range or inconsistent.
    #[error("invalid `{field}` = {value}: {reason}")]
    Invalid {
        /// Dotted field name.
        field: String,
        /// The offending value as written.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// An error of the environment layer (scene, map, geodesic).
    #[error(transparent)]
    Env(#[from] vlnverse_env::EnvError),
    /// An error of the simulator layer (physics, embodiment, actions).
    #[error(transparent)]
    Sim(#[from] vlnverse_sim::SimError),
    /// An error of the sensor layer (rig config, renderer).
    #[error(transparent)]
    Sensor(#[from] vlnverse_sensors::SensorError),
}

/// Errors of the scoring crate keep their kind (and so their message).
impl From<vlnverse_score::DataError> for TaskError {
    fn from(e: vlnverse_score::DataError) -> Self {
        use vlnverse_score::DataError as S;
        match e {
            S::Io { path, error } => TaskError::Io { path, error },
            S::Parse {
                path,
                location,
                message,
            } => TaskError::Parse {
                path,
                location,
                message,
            },
            S::Invalid {
                field,
                value,
                reason,
            } => TaskError::Invalid {
                field,
                value,
                reason,
            },
            S::Env(e) => TaskError::Env(e),
        }
    }
}

impl TaskError {
    /// Shorthand for [`TaskError::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        TaskError::Io {
            path: path.into(),
            error: source,
        }
    }

    /// Shorthand for [`TaskError::Parse`].
    pub fn parse(
        path: impl Into<PathBuf>,
        location: impl Into<String>,
        message: impl ToString,
    ) -> Self {
        TaskError::Parse {
            path: path.into(),
            location: location.into(),
            message: message.to_string(),
        }
    }

    /// Shorthand for [`TaskError::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        TaskError::Invalid {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}
