//! Errors of the sensor layer.

use std::path::PathBuf;

use vlnverse_env::EnvError;

/// Result alias of the sensor layer.
pub type Result<T, E = SensorError> = std::result::Result<T, E>;

/// What went wrong while configuring sensors or rendering.
#[derive(Debug, thiserror::Error)]
pub enum SensorError {
    /// A config file could not be read or parsed, or a value is out of range (names the file,
    /// the dotted field such as `sensors[1].width`, and the value).
    #[error(transparent)]
    Env(#[from] EnvError),
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
    /// An observation could not be encoded or written to a file ([`crate::output`]).
    #[error("writing {}: {message}", path.display())]
    Write {
        /// The file (or what was being encoded).
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

impl SensorError {
    /// An out-of-range config value, without a file ([`EnvError::InvalidConfig`]).
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        EnvError::invalid(field, value, reason).into()
    }

    /// Attach a file path to a config error that has none.
    pub fn in_file(self, file: impl Into<PathBuf>) -> Self {
        match self {
            SensorError::Env(e) => e.in_file(file).into(),
            other => other,
        }
    }
}
