//! Errors of the simulator layer. Each variant names the file (when there is one), the field
//! and the offending value.

use std::path::PathBuf;

/// Result alias of the simulator layer.
pub type Result<T, E = SimError> = std::result::Result<T, E>;

/// What went wrong while configuring or driving a simulator.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A config file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A config file is not valid TOML or has unknown/missing fields.
    #[error("{path}: {message}")]
    Parse {
        /// The file (or `profile:<name>` for an embedded profile).
        path: PathBuf,
        /// What is wrong, naming the field when known.
        message: String,
    },
    /// A configuration value is out of range.
    #[error("{}invalid `{field}` = {value}: {reason}", .path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default())]
    InvalidConfig {
        /// The config file, when the value came from one.
        path: Option<PathBuf>,
        /// Dotted field name, e.g. `shape.radius`.
        field: String,
        /// The offending value.
        value: String,
        /// What is allowed.
        reason: String,
    },
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
    /// Shorthand for [`SimError::InvalidConfig`] without a file.
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        SimError::InvalidConfig {
            path: None,
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
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

    /// Attach a file path to an [`SimError::InvalidConfig`] that has none.
    pub fn in_file(self, file: impl Into<PathBuf>) -> Self {
        match self {
            SimError::InvalidConfig {
                path: None,
                field,
                value,
                reason,
            } => SimError::InvalidConfig {
                path: Some(file.into()),
                field,
                value,
                reason,
            },
            other => other,
        }
    }
}
