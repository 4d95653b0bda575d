//! Errors of the sensor layer.

use std::path::PathBuf;

/// Result alias of the sensor layer.
pub type Result<T, E = SensorError> = std::result::Result<T, E>;

/// What went wrong while configuring sensors or rendering.
#[derive(Debug, thiserror::Error)]
pub enum SensorError {
    /// A config file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A config file is not valid TOML for the rig config.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What is wrong (from the TOML parser, naming the field).
        message: String,
    },
    /// A configuration value is out of range.
    #[error("{}invalid `{field}` = {value}: {reason}", .path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default())]
    InvalidConfig {
        /// The config file, when the value came from one.
        path: Option<PathBuf>,
        /// Dotted field name, e.g. `sensors[1].width`.
        field: String,
        /// The offending value.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// No GPU / software rasteriser is available for the wgpu backend.
    #[error("wgpu backend unavailable: {0}")]
    NoAdapter(String),
    /// The GPU device reported an error while rendering or reading back.
    #[error("wgpu rendering failed: {0}")]
    Gpu(String),
    /// The scene has nothing to render or cast rays against, or is inconsistent.
    #[error("scene {scene}: {message}")]
    Scene {
        /// Scene id.
        scene: String,
        /// What is wrong.
        message: String,
    },
    /// `render` was called before `set_scene`.
    #[error("no scene loaded: call `set_scene` first")]
    NoScene,
}

impl SensorError {
    /// Shorthand for [`SensorError::InvalidConfig`] without a file.
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        SensorError::InvalidConfig {
            path: None,
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Attach a file path to an [`SensorError::InvalidConfig`] that has none.
    pub fn in_file(self, file: impl Into<PathBuf>) -> Self {
        match self {
            SensorError::InvalidConfig {
                path: None,
                field,
                value,
                reason,
            } => SensorError::InvalidConfig {
                path: Some(file.into()),
                field,
                value,
                reason,
            },
            other => other,
        }
    }
}
