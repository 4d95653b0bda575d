//! The one error type of evaluation. Data errors (a file, its place, the offending value) come
//! from `vlnverse-score`; the simulator's and the sensors' errors keep their own kind, so a
//! factory or a layer a user swapped in reports exactly what went wrong.

use std::path::PathBuf;

use vlnverse_score::DataError;

/// Result alias of evaluation.
pub type Result<T, E = TaskError> = std::result::Result<T, E>;

/// What went wrong while evaluating: reading or checking data, the simulator, the sensors.
#[derive(Debug, thiserror::Error)]
pub enum TaskError {
    /// A file could not be read or written, is malformed, or a value is out of range (each
    /// names the file, the place and the value).
    #[error(transparent)]
    Data(#[from] DataError),
    /// An error of the simulator layer (physics, embodiment, actions).
    #[error(transparent)]
    Sim(#[from] vlnverse_sim::SimError),
    /// An error of the sensor layer (rig config, renderer).
    #[error(transparent)]
    Sensor(#[from] vlnverse_sensors::SensorError),
}

/// Errors of the environment layer (scene, map, geodesic) are data errors.
impl From<vlnverse_env::EnvError> for TaskError {
    fn from(e: vlnverse_env::EnvError) -> Self {
        TaskError::Data(DataError::Env(e))
    }
}

impl TaskError {
    /// A file could not be read or written ([`DataError::Io`]).
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        TaskError::Data(DataError::io(path, source))
    }

    /// A file's content is not what its format says ([`DataError::Parse`]).
    pub fn parse(
        path: impl Into<PathBuf>,
        location: impl Into<String>,
        message: impl ToString,
    ) -> Self {
        TaskError::Data(DataError::parse(path, location, message))
    }

    /// A value is out of range or inconsistent ([`DataError::Invalid`]).
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        TaskError::Data(DataError::invalid(field, value, reason))
    }
}
