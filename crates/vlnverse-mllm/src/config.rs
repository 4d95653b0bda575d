//! The agent config (`--agent-config FILE`, TOML): endpoint, what each step sends, sampling,
//! timeouts and the reply cache. Every field has a range; [`MllmConfig::validate`] names the
//! field and the value it refuses.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use vlnverse_eval::{Result, TaskError};
use vlnverse_instructions::llm::LlmConfig;

/// How past steps reach the model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum History {
    /// A list of the last actions and what the depth camera showed after each.
    #[default]
    Text,
    /// A top-down map of the explored area with the trajectory and heading.
    Map,
}

/// Which camera picture goes with each step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum View {
    /// The forward RGB view.
    #[default]
    Current,
    /// A strip of 4 views, 90 degrees apart.
    Panorama4,
    /// A strip of 12 views, 30 degrees apart.
    Panorama12,
    /// No camera picture (text or map only).
    None,
}

impl View {
    /// Views in the picture (0 for none).
    pub fn count(self) -> u32 {
        match self {
            View::Current => 1,
            View::Panorama4 => 4,
            View::Panorama12 => 12,
            View::None => 0,
        }
    }
}

/// How pictures are encoded in the request.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ImageFormat {
    /// Lossless PNG.
    #[default]
    Png,
    /// JPEG at `jpeg_quality` (smaller requests).
    Jpeg,
}

/// How the model is asked to write its action.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionFormat {
    /// A short phrase: `move forward 75 cm`, `turn left 30 degrees`, `stop`, `ask: ...`.
    #[default]
    Text,
    /// A JSON object: `{"action": "move_forward", "distance_cm": 75}`.
    Json,
}

/// What an unusable reply turns into (after the corrective retry).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fallback {
    /// One turn left: keeps looking around without walking into anything.
    #[default]
    TurnLeft,
    /// One turn right.
    TurnRight,
    /// One forward step.
    MoveForward,
    /// End the episode.
    Stop,
}

/// Settings of the MLLM agent.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MllmConfig {
    /// Base URL of the OpenAI-compatible API (`--mllm-endpoint` overrides it), e.g.
    /// `http://127.0.0.1:8000/v1`.
    pub endpoint: String,
    /// Model name sent with each request (`--mllm-model` overrides it).
    pub model: String,
    /// Environment variable holding the API key; leave it out for a keyless local server.
    pub api_key_env: Option<String>,
    /// `text` or `map`.
    pub history: History,
    /// Ask for reasoning before the action (the action then comes on a last `Action:` line).
    pub chain_of_thought: bool,
    /// Camera picture per step: `current`, `panorama4`, `panorama12` or `none`.
    pub view: View,
    /// Side of each camera view in pixels (rendered at this size).
    pub image_size: u32,
    /// Side of the map picture in pixels (map history).
    pub map_size: u32,
    /// Metres per map cell.
    pub map_resolution_m: f32,
    /// `png` or `jpeg`.
    pub image_format: ImageFormat,
    /// JPEG quality, 1 to 100.
    pub jpeg_quality: u8,
    /// Past steps listed in the text history.
    pub history_steps: u32,
    /// Sampling temperature (0: repeatable).
    pub temperature: f32,
    /// Limit on the reply length in tokens.
    pub max_tokens: u32,
    /// Timeout of one request (seconds).
    pub timeout_s: f32,
    /// Extra attempts after a transport error, HTTP 429 or 5xx.
    pub retries: u32,
    /// Wait before the first retry (ms), doubled on each further retry.
    pub retry_backoff_ms: u64,
    /// Requests in flight at once over all worker threads.
    pub max_concurrent_requests: u32,
    /// `text` or `json`.
    pub action_format: ActionFormat,
    /// Most primitive actions one reply may ask for ("move forward 10 m" is cut there).
    pub max_actions_per_reply: u32,
    /// Questions to the oracle within one step (dialogue episodes).
    pub asks_per_step: u32,
    /// What an unusable reply becomes: `turn_left`, `turn_right`, `move_forward`, `stop`.
    pub fallback: Fallback,
    /// Keep replies in a cache keyed on the SHA-256 of the request.
    pub cache: bool,
    /// Folder of the cache; unset: `<run folder>/.mllm-cache`.
    pub cache_dir: Option<PathBuf>,
}

impl Default for MllmConfig {
    fn default() -> Self {
        MllmConfig {
            endpoint: String::new(),
            model: String::new(),
            api_key_env: None,
            history: History::Text,
            chain_of_thought: false,
            view: View::Current,
            image_size: 224,
            map_size: 256,
            map_resolution_m: 0.1,
            image_format: ImageFormat::Png,
            jpeg_quality: 85,
            history_steps: 20,
            temperature: 0.0,
            max_tokens: 300,
            timeout_s: 120.0,
            retries: 2,
            retry_backoff_ms: 1000,
            max_concurrent_requests: 4,
            action_format: ActionFormat::Text,
            max_actions_per_reply: 12,
            asks_per_step: 1,
            fallback: Fallback::TurnLeft,
            cache: true,
            cache_dir: None,
        }
    }
}

fn bad(field: &str, value: impl ToString, why: &str) -> TaskError {
    TaskError::invalid(format!("mllm.{field}"), value, why)
}

impl MllmConfig {
    /// Read a TOML file (unknown keys refused) and check it; errors name the file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| TaskError::io(path, e))?;
        let cfg: MllmConfig =
            toml::from_str(&text).map_err(|e| TaskError::parse(path, "agent config", e))?;
        cfg.validate_fields().map_err(|e| {
            TaskError::parse(path, "agent config", e.to_string().replace('\n', " "))
        })?;
        Ok(cfg)
    }

    /// Check every range but the endpoint and model (which the command line may still set).
    pub fn validate_fields(&self) -> Result<()> {
        if let Some(var) = &self.api_key_env {
            if var.trim().is_empty() || var.contains('=') || var.contains('\0') {
                return Err(bad(
                    "api_key_env",
                    format!("{var:?}"),
                    "must name an environment variable (leave it out for no key)",
                ));
            }
        }
        let between = |field: &str, v: u64, lo: u64, hi: u64, unit: &str| {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(bad(field, v, &format!("must be in [{lo}, {hi}]{unit}")))
            }
        };
        between("image_size", self.image_size.into(), 32, 1024, " pixels")?;
        between("map_size", self.map_size.into(), 64, 1024, " pixels")?;
        between("jpeg_quality", self.jpeg_quality.into(), 1, 100, "")?;
        between("history_steps", self.history_steps.into(), 0, 500, " steps")?;
        between("max_tokens", self.max_tokens.into(), 1, 32768, " tokens")?;
        between("retries", self.retries.into(), 0, 10, "")?;
        between("retry_backoff_ms", self.retry_backoff_ms, 0, 60_000, " ms")?;
        between(
            "max_concurrent_requests",
            self.max_concurrent_requests.into(),
            1,
            256,
            "",
        )?;
        between(
            "max_actions_per_reply",
            self.max_actions_per_reply.into(),
            1,
            50,
            "",
        )?;
        between("asks_per_step", self.asks_per_step.into(), 0, 5, "")?;
        if !(self.map_resolution_m.is_finite() && (0.02..=0.5).contains(&self.map_resolution_m)) {
            return Err(bad(
                "map_resolution_m",
                self.map_resolution_m,
                "must be in [0.02, 0.5] metres",
            ));
        }
        if !(self.temperature.is_finite() && (0.0..=2.0).contains(&self.temperature)) {
            return Err(bad("temperature", self.temperature, "must be in [0, 2]"));
        }
        if !(self.timeout_s.is_finite() && self.timeout_s > 0.0 && self.timeout_s <= 3600.0) {
            return Err(bad(
                "timeout_s",
                self.timeout_s,
                "must be in (0, 3600] seconds",
            ));
        }
        if self.view == View::None && self.history == History::Text {
            return Err(bad(
                "view",
                "none",
                "with history = \"text\" the model would see no picture at all; choose a view or history = \"map\"",
            ));
        }
        Ok(())
    }

    /// Check everything, the endpoint and model included.
    pub fn validate(&self) -> Result<()> {
        self.validate_fields()?;
        if !(self.endpoint.starts_with("http://") || self.endpoint.starts_with("https://")) {
            return Err(bad(
                "endpoint",
                format!("{:?}", self.endpoint),
                "must start with http:// or https:// (--mllm-endpoint)",
            ));
        }
        if self.model.trim().is_empty() {
            return Err(bad("model", "\"\"", "must not be empty (--mllm-model)"));
        }
        self.chat_config().validate().map_err(TaskError::from)
    }

    /// The chat client's settings.
    pub fn chat_config(&self) -> LlmConfig {
        LlmConfig {
            base_url: self.endpoint.clone(),
            model: self.model.clone(),
            api_key_env: self.api_key_env.clone(),
            temperature: self.temperature,
            max_tokens: Some(self.max_tokens),
            timeout_s: self.timeout_s,
            retries: self.retries,
            retry_backoff_ms: self.retry_backoff_ms,
            verify: false,
            max_concurrent: self.max_concurrent_requests,
            frames: 0,
            cache_dir: if self.cache {
                self.cache_dir.clone()
            } else {
                None
            },
            ..LlmConfig::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_fields_are_named_with_their_value() {
        let ok = MllmConfig {
            endpoint: "http://127.0.0.1:1/v1".into(),
            model: "m".into(),
            ..Default::default()
        };
        ok.validate().unwrap();
        let cases: Vec<(MllmConfig, &str, &str)> = vec![
            (
                MllmConfig {
                    image_size: 8,
                    ..ok.clone()
                },
                "mllm.image_size",
                "8",
            ),
            (
                MllmConfig {
                    temperature: 3.0,
                    ..ok.clone()
                },
                "mllm.temperature",
                "3",
            ),
            (
                MllmConfig {
                    timeout_s: 0.0,
                    ..ok.clone()
                },
                "mllm.timeout_s",
                "0",
            ),
            (
                MllmConfig {
                    retries: 99,
                    ..ok.clone()
                },
                "mllm.retries",
                "99",
            ),
            (
                MllmConfig {
                    max_concurrent_requests: 0,
                    ..ok.clone()
                },
                "mllm.max_concurrent_requests",
                "0",
            ),
            (
                MllmConfig {
                    jpeg_quality: 0,
                    ..ok.clone()
                },
                "mllm.jpeg_quality",
                "0",
            ),
            (
                MllmConfig {
                    api_key_env: Some(" ".into()),
                    ..ok.clone()
                },
                "mllm.api_key_env",
                "\" \"",
            ),
            (
                MllmConfig {
                    endpoint: "ftp://x".into(),
                    ..ok.clone()
                },
                "mllm.endpoint",
                "ftp://x",
            ),
            (
                MllmConfig {
                    model: " ".into(),
                    ..ok.clone()
                },
                "mllm.model",
                "\"\"",
            ),
            (
                MllmConfig {
                    view: View::None,
                    ..ok.clone()
                },
                "mllm.view",
                "none",
            ),
        ];
        for (cfg, field, value) in cases {
            let e = cfg.validate().expect_err(field).to_string();
            assert!(e.contains(field) && e.contains(value), "{field}: {e}");
        }
    }

    #[test]
    fn a_file_with_an_unknown_key_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("agent.toml");
        std::fs::write(&f, "history = \"map\"\nchain_of_thougth = true\n").unwrap();
        let e = MllmConfig::load(&f).unwrap_err().to_string();
        assert!(
            e.contains("agent.toml") && e.contains("chain_of_thougth"),
            "{e}"
        );
        std::fs::write(&f, "history = \"map\"\nmap_size = 5000\n").unwrap();
        let e = MllmConfig::load(&f).unwrap_err().to_string();
        assert!(
            e.contains("agent.toml") && e.contains("map_size") && e.contains("5000"),
            "{e}"
        );
        std::fs::write(&f, "history = \"map\"\nview = \"panorama12\"\n").unwrap();
        let c = MllmConfig::load(&f).unwrap();
        assert_eq!((c.history, c.view.count()), (History::Map, 12));
    }
}
