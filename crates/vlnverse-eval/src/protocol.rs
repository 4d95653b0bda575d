//! The evaluation protocol: `configs/eval/{strict,telhop,lenient}.toml`.
//!
//! ```toml
//! setting = "telhop"          # strict | telhop | lenient
//! max_steps = 200             # per goal: a long-horizon episode of n sub-tasks gets n x 200
//! success_distance = 3.0
//! rig = "../sensors/default.toml"   # relative to this file; empty = the paper's RGB-D rig
//! backend = "raycast"         # optional override of the rig's renderer backend
//! agent_profile = "vlnverse"  # a shipped profile name, or a path to an agent TOML
//! action_space = "discrete"   # discrete | continuous | waypoint
//! render = true               # render the rig every step
//! seed = 0                    # per-episode seeds derive from it
//! plots = 6                   # top-down trajectory PNGs per run
//! external_observations = "files"   # files | base64 (external agents)
//! external_timeout_s = 60.0           # (0, 86400]: longest wait for one reply of an external agent
//! ```

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use vlnverse_sensors::{Backend, RigConfig};
use vlnverse_sim::{Action, AgentConfig, CollisionSetting};

use crate::error::{Result, TaskError};

/// How collisions are handled (the paper's settings, plus VLN-CE's lenient one).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum Setting {
    /// Full physics; a noticeable collision ends the episode as a failure.
    #[default]
    Strict,
    /// Moves teleport; physics only resolves the destination.
    #[serde(alias = "tel_hop")]
    Telhop,
    /// Full physics; collisions are only counted.
    Lenient,
}

impl Setting {
    /// All settings.
    pub const ALL: [Setting; 3] = [Setting::Strict, Setting::Telhop, Setting::Lenient];

    /// Name on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Setting::Strict => "strict",
            Setting::Telhop => "telhop",
            Setting::Lenient => "lenient",
        }
    }

    /// The simulator's collision setting.
    pub fn collision(self) -> CollisionSetting {
        match self {
            Setting::Strict => CollisionSetting::Strict,
            Setting::Telhop => CollisionSetting::TelHop,
            Setting::Lenient => CollisionSetting::Lenient,
        }
    }
}

impl std::fmt::Display for Setting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Setting {
    type Err = TaskError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "strict" => Ok(Setting::Strict),
            "telhop" | "tel_hop" | "tel-hop" => Ok(Setting::Telhop),
            "lenient" => Ok(Setting::Lenient),
            _ => Err(TaskError::invalid(
                "setting",
                s,
                "expected one of strict, telhop, lenient",
            )),
        }
    }
}

/// Which actions an agent may answer with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionSpace {
    /// Stop, move forward, turn left/right, look up/down.
    #[default]
    Discrete,
    /// Velocity commands (plus stop and look up/down).
    Continuous,
    /// Waypoints (plus every discrete action).
    Waypoint,
}

impl ActionSpace {
    /// Name in files.
    pub fn name(self) -> &'static str {
        match self {
            ActionSpace::Discrete => "discrete",
            ActionSpace::Continuous => "continuous",
            ActionSpace::Waypoint => "waypoint",
        }
    }

    /// Whether `action` belongs to this space.
    pub fn allows(self, action: &Action) -> bool {
        let discrete = matches!(
            action,
            Action::Stop
                | Action::MoveForward(_)
                | Action::TurnLeft(_)
                | Action::TurnRight(_)
                | Action::LookUp
                | Action::LookDown
        );
        match self {
            ActionSpace::Discrete => discrete,
            ActionSpace::Continuous => matches!(
                action,
                Action::Stop | Action::LookUp | Action::LookDown | Action::Velocity { .. }
            ),
            ActionSpace::Waypoint => discrete || matches!(action, Action::Waypoint { .. }),
        }
    }
}

impl fmt::Display for ActionSpace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ActionSpace {
    type Err = TaskError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "discrete" => Ok(ActionSpace::Discrete),
            "continuous" => Ok(ActionSpace::Continuous),
            "waypoint" => Ok(ActionSpace::Waypoint),
            _ => Err(TaskError::invalid(
                "action_space",
                s,
                "expected one of discrete, continuous, waypoint",
            )),
        }
    }
}

/// `line N, field `key`` of a byte offset in a TOML text: the key is what precedes `=` on
/// that line (an error on a value points into the value).
fn toml_location(text: &str, offset: usize) -> String {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line_no = text[..start].matches('\n').count() + 1;
    let line = text[start..].lines().next().unwrap_or("");
    match line.split_once('=') {
        Some((key, _)) if start + key.len() < offset && !key.trim().is_empty() => {
            format!("line {line_no}, field `{}`", key.trim())
        }
        _ => format!("line {line_no}"),
    }
}

/// The `[oracle_llm]` section: an OpenAI-compatible endpoint (the fields of `[instructions.llm]`).
#[cfg(feature = "llm-oracle")]
pub type LlmSection = vlnverse_instructions::llm::LlmConfig;
/// The `[oracle_llm]` section (this build has no LLM client: feature `llm-oracle` is off).
#[cfg(not(feature = "llm-oracle"))]
pub type LlmSection = toml::Table;

/// One evaluation protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EvalConfig {
    /// Collision setting.
    pub setting: Setting,
    /// Actions per episode before it is cut (STOP counts); a long-horizon episode gets this
    /// many for each of its sub-goals.
    pub max_steps: u32,
    /// Success threshold (m).
    pub success_distance: f32,
    /// Sensor rig file (relative paths resolve against the config file's folder); empty for
    /// the paper's RGB-D rig.
    pub rig: String,
    /// Override of the rig's renderer backend.
    pub backend: Option<Backend>,
    /// Agent profile: a shipped name (`vlnverse`, `vlnce`, `rxr`, `locobot`) or a TOML path.
    pub agent_profile: String,
    /// Action space offered to the agent.
    pub action_space: ActionSpace,
    /// Render the rig every step (turn off only to time the protocol without pixels).
    pub render: bool,
    /// Seed of every per-episode random choice (agents, noise).
    pub seed: u64,
    /// Top-down trajectory plots written per run.
    pub plots: u32,
    /// How the `external` agent receives images: `files` or `base64`.
    pub external_observations: crate::agents::ObsEncoding,
    /// Seconds the `external` agent may take to answer one message, in (0, 86400]; past it the
    /// agent is stopped and the run fails naming the command and the step (a hung agent would
    /// otherwise hang the evaluation).
    pub external_timeout_s: f64,
    /// The dialogue oracle's answers rephrased by an LLM (`[oracle_llm]`: an OpenAI-compatible
    /// endpoint, the fields of `[instructions.llm]`); none (the default): the rule-based
    /// shortest-path oracle answers as it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub oracle_llm: Option<LlmSection>,
    /// Folder the relative paths resolve against (set by [`EvalConfig::load`]).
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
}

impl Default for EvalConfig {
    fn default() -> Self {
        EvalConfig {
            setting: Setting::Strict,
            max_steps: 200,
            success_distance: 3.0,
            rig: String::new(),
            backend: None,
            agent_profile: "vlnverse".into(),
            action_space: ActionSpace::Discrete,
            render: true,
            seed: 0,
            plots: 6,
            external_observations: Default::default(),
            external_timeout_s: crate::agents::DEFAULT_EXTERNAL_TIMEOUT_S,
            oracle_llm: None,
            base_dir: None,
        }
    }
}

impl EvalConfig {
    /// The default protocol of a setting, as shipped in `configs/eval/<setting>.toml`: Tel-Hop
    /// agents answer with waypoints (plus every discrete action), the others with discrete
    /// actions.
    pub fn for_setting(setting: Setting) -> Self {
        let action_space = match setting {
            Setting::Telhop => ActionSpace::Waypoint,
            Setting::Strict | Setting::Lenient => ActionSpace::Discrete,
        };
        EvalConfig {
            setting,
            action_space,
            ..Default::default()
        }
    }

    /// Parse TOML; `origin` names the source in errors and anchors relative paths.
    pub fn from_toml_str(text: &str, origin: &Path) -> Result<Self> {
        let mut cfg: EvalConfig = toml::from_str(text).map_err(|e| {
            let loc = e
                .span()
                .map(|s| toml_location(text, s.start))
                .unwrap_or_else(|| "top level".into());
            TaskError::parse(origin, loc, e.message())
        })?;
        cfg.base_dir = origin.parent().map(Path::to_path_buf);
        cfg.validate()
            .map_err(|e| TaskError::parse(origin, "value", e))?;
        Ok(cfg)
    }

    /// Read and validate a config file.
    pub fn load(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| TaskError::io(path, e))?;
        Self::from_toml_str(&text, path)
    }

    /// Check ranges; errors name the field and value.
    pub fn validate(&self) -> Result<()> {
        if let Some(llm) = &self.oracle_llm {
            #[cfg(feature = "llm-oracle")]
            llm.validate()
                .map_err(|e| TaskError::invalid("oracle_llm", "<section>", e.to_string()))?;
            #[cfg(not(feature = "llm-oracle"))]
            {
                let _ = llm;
                return Err(TaskError::invalid(
                    "oracle_llm",
                    "<section>",
                    "this build has no LLM client (feature `llm-oracle` of vlnverse-eval)",
                ));
            }
        }
        if self.max_steps == 0 || self.max_steps > 100_000 {
            return Err(TaskError::invalid(
                "max_steps",
                self.max_steps,
                "must be in [1, 100000]",
            ));
        }
        if !(self.success_distance.is_finite() && self.success_distance > 0.0) {
            return Err(TaskError::invalid(
                "success_distance",
                self.success_distance,
                "must be a positive number of metres",
            ));
        }
        if self.agent_profile.trim().is_empty() {
            return Err(TaskError::invalid(
                "agent_profile",
                "\"\"",
                "name a profile or an agent TOML file",
            ));
        }
        if !(self.external_timeout_s > 0.0 && self.external_timeout_s <= 86_400.0) {
            return Err(TaskError::invalid(
                "external_timeout_s",
                self.external_timeout_s,
                "must be in (0, 86400] seconds",
            ));
        }
        if self.plots > 10_000 {
            return Err(TaskError::invalid("plots", self.plots, "at most 10000"));
        }
        Ok(())
    }

    /// A path of the config resolved against its folder.
    pub fn resolve(&self, p: &str) -> PathBuf {
        let path = PathBuf::from(p);
        match &self.base_dir {
            Some(b) if path.is_relative() => b.join(path),
            _ => path,
        }
    }

    /// The sensor rig (with the backend override applied).
    pub fn rig_config(&self) -> Result<RigConfig> {
        let mut rig = if self.rig.trim().is_empty() {
            RigConfig::default()
        } else {
            let path = self.resolve(&self.rig);
            RigConfig::load(&path)
                .map_err(|e| TaskError::invalid("rig", path.display(), e.to_string()))?
        };
        if let Some(b) = self.backend {
            rig.backend = b;
        }
        Ok(rig)
    }

    /// The agent embodiment.
    pub fn agent_config(&self) -> Result<AgentConfig> {
        let p = &self.agent_profile;
        let res = if p.ends_with(".toml") {
            AgentConfig::from_toml_file(self.resolve(p))
        } else {
            AgentConfig::profile(p)
        };
        res.map_err(|e| TaskError::invalid("agent_profile", p, e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_defaults_equal_the_shipped_protocol_files() {
        // Run outside the repository, `evaluate` falls back to `for_setting`: it must not
        // change the protocol silently.
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/eval");
        for setting in [Setting::Strict, Setting::Telhop, Setting::Lenient] {
            let file = EvalConfig::load(dir.join(format!("{setting}.toml"))).unwrap();
            let built = EvalConfig::for_setting(setting);
            let key = |c: &EvalConfig| {
                (
                    c.setting,
                    c.max_steps,
                    c.success_distance,
                    c.agent_profile.clone(),
                    c.action_space,
                    c.render,
                    c.seed,
                    c.plots,
                )
            };
            assert_eq!(key(&file), key(&built), "{setting}");
        }
    }
}
