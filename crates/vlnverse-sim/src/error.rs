//! Errors of the simulator layer. Each variant names the file (when there is one), the field
//! and the offending value.

use std::path::PathBuf;
use vlnverse_env::EnvError;

/// Result alias of the simulator layer.
pub type Result<T, E = SimError> = std::result::Result<T, E>;

/// What went wrong while configuring or driving a simulator.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A config file could not be read or parsed, or a value is out of range: the same
    /// file/field/value error as the environment layer ([`EnvError::Io`], [`EnvError::Parse`],
    /// [`EnvError::InvalidConfig`]).
    #[error(transparent)]
    Env(#[from] EnvError),
    /// An action is NaN, infinite, negative or absurdly large, or points outside the scene.
    #[error("invalid action `{field}` = {value}: {reason}")]
    InvalidAction {
        /// Which action parameter, e.g. `MoveForward.distance`.
        field: String,
        /// The offending value.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The start pose or the scene cannot be simulated.
    #[error("scene {scene}: {message}")]
    InvalidScene {
        /// Scene id.
        scene: String,
        /// What is wrong.
        message: String,
    },
    /// `step` was called before `reset`.
    #[error("the simulator has no episode: call reset(scene, start) first")]
    NotReset,
    /// `step` was called after the episode ended (stop or failure).
    #[error("the episode is over ({0}); call reset to start a new one")]
    EpisodeOver(String),
    /// An unknown embedded agent profile was requested.
    #[error("unknown agent profile `{name}` (known: {known})")]
    UnknownProfile {
        /// The requested name.
        name: String,
        /// The embedded profile names.
        known: String,
    },
}

impl SimError {
    /// Shorthand for [`EnvError::InvalidConfig`] without a file.
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        EnvError::invalid(field, value, reason).into()
    }

    /// Shorthand for [`SimError::InvalidAction`].
    pub fn action(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        SimError::InvalidAction {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Attach a file path to an [`EnvError::InvalidConfig`] that has none.
    pub fn in_file(self, file: impl Into<PathBuf>) -> Self {
        match self {
            SimError::Env(e) => e.in_file(file).into(),
            other => other,
        }
    }
}
