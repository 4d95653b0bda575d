//! Generation configs: `configs/generate/<preset>.toml`, embedded in the crate, validated with
//! errors that name the file, the field and the value.

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use vlnverse_score::episode::{Split, Task};
use vlnverse_score::{DataError, Result};

/// The shipped generation presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GeneratePreset {
    /// A few small homes and a few hundred episodes, generated in seconds.
    Tiny,
    /// The benchmark: 263 homes and exactly the paper's Table 2 episode counts.
    Vlnverse,
}

impl GeneratePreset {
    /// Every preset.
    pub const ALL: [GeneratePreset; 2] = [GeneratePreset::Tiny, GeneratePreset::Vlnverse];

    /// Name on the command line and file stem.
    pub fn name(self) -> &'static str {
        match self {
            GeneratePreset::Tiny => "tiny",
            GeneratePreset::Vlnverse => "vlnverse",
        }
    }

    /// The embedded TOML text.
    pub fn toml(self) -> &'static str {
        match self {
            GeneratePreset::Tiny => include_str!("../configs/generate/tiny.toml"),
            GeneratePreset::Vlnverse => include_str!("../configs/generate/vlnverse.toml"),
        }
    }

    /// Parse and validate the preset.
    pub fn config(self) -> Result<GenerateConfig> {
        let path = format!("configs/generate/{}.toml", self.name());
        GenerateConfig::from_toml_str(self.toml(), Path::new(&path))
    }
}

impl fmt::Display for GeneratePreset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for GeneratePreset {
    type Err = DataError;
    fn from_str(s: &str) -> Result<Self> {
        GeneratePreset::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| DataError::invalid("preset", s, "expected `tiny` or `vlnverse`"))
    }
}

/// A count per split.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SplitCounts {
    /// Train.
    pub train: usize,
    /// Validation in train scenes.
    pub val_seen: usize,
    /// Validation in unseen scenes.
    pub val_unseen: usize,
    /// Test.
    pub test: usize,
}

impl SplitCounts {
    /// The count of `split`.
    pub fn get(&self, split: Split) -> usize {
        match split {
            Split::Train => self.train,
            Split::ValSeen => self.val_seen,
            Split::ValUnseen => self.val_unseen,
            Split::Test => self.test,
        }
    }

    /// Set the count of `split`.
    pub fn set(&mut self, split: Split, n: usize) {
        match split {
            Split::Train => self.train = n,
            Split::ValSeen => self.val_seen = n,
            Split::ValUnseen => self.val_unseen = n,
            Split::Test => self.test = n,
        }
    }

    /// Sum over the splits.
    pub fn total(&self) -> usize {
        self.train + self.val_seen + self.val_unseen + self.test
    }
}

/// How many scenes each scene-disjoint split gets (val_seen reuses train scenes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSplits {
    /// Train scenes.
    pub train: usize,
    /// Val-unseen scenes.
    pub val_unseen: usize,
    /// Test scenes.
    pub test: usize,
}

impl SceneSplits {
    /// All scenes.
    pub fn total(&self) -> usize {
        self.train + self.val_unseen + self.test
    }

    /// Scenes a split may draw from (val_seen: the train scenes).
    pub fn pool(&self, split: Split) -> usize {
        match split {
            Split::Train | Split::ValSeen => self.train,
            Split::ValUnseen => self.val_unseen,
            Split::Test => self.test,
        }
    }
}

/// Path sampling settings shared by the tasks.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingConfig {
    /// Samples tried per trajectory before giving up on a scene.
    pub max_attempts: u32,
    /// Farthest a goal point may be from its target object's footprint (m).
    pub goal_max_distance: f32,
    /// Closest a goal point may be to its target object's footprint (m), so that the agent
    /// does not stand inside the object's margin.
    pub goal_min_distance: f32,
    /// Most target objects per scene (a seeded choice among the usable ones; 0 = all). Each
    /// target costs one distance field (about ten A* queries), so this bounds sampling time.
    #[serde(default)]
    pub max_targets: usize,
    /// In a home on several floors, the share of each task's samples whose start and goal are
    /// drawn on different levels (the path takes the stairs). Single-storey homes ignore it.
    /// Left out of written configs at its default, so manifests of earlier runs still match.
    #[serde(
        default = "default_cross_floor_share",
        skip_serializing_if = "is_default_cross_floor_share"
    )]
    pub cross_floor_share: f32,
}

/// Default of [`SamplingConfig::cross_floor_share`].
pub const DEFAULT_CROSS_FLOOR_SHARE: f32 = 0.3;

fn default_cross_floor_share() -> f32 {
    DEFAULT_CROSS_FLOOR_SHARE
}

fn is_default_cross_floor_share(v: &f32) -> bool {
    *v == DEFAULT_CROSS_FLOOR_SHARE
}

/// Settings of one task.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskConfig {
    /// Whether the task is generated at all.
    #[serde(default = "yes")]
    pub enabled: bool,
    /// Shortest geodesic path (m), per leg for long-horizon episodes.
    pub min_length: f32,
    /// Longest geodesic path (m), per leg for long-horizon episodes.
    pub max_length: f32,
    /// Episodes per split.
    pub episodes: SplitCounts,
    /// Scenes the episodes of each split are spread over.
    pub scenes: SplitCounts,
    /// Long-horizon: fewest sub-tasks per episode.
    #[serde(default)]
    pub sub_tasks_min: usize,
    /// Long-horizon: most sub-tasks per episode.
    #[serde(default)]
    pub sub_tasks_max: usize,
    /// Dialogue: questions the agent may ask.
    #[serde(default)]
    pub oracle_budget: u32,
    /// This task's share of trajectories across floors in homes on several floors, instead of
    /// `sampling.cross_floor_share` (absent: that one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cross_floor_share: Option<f32>,
}

fn yes() -> bool {
    true
}

/// The five tasks' settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TasksConfig {
    /// Fine-grained.
    pub fine: TaskConfig,
    /// Coarse-grained.
    pub coarse: TaskConfig,
    /// Visual reference.
    pub visual_reference: TaskConfig,
    /// Long-horizon.
    pub long_horizon: TaskConfig,
    /// Dialogue.
    pub dialogue: TaskConfig,
}

impl TasksConfig {
    /// Settings of `task`.
    pub fn get(&self, task: Task) -> &TaskConfig {
        match task {
            Task::Fine => &self.fine,
            Task::Coarse => &self.coarse,
            Task::VisualReference => &self.visual_reference,
            Task::LongHorizon => &self.long_horizon,
            Task::Dialogue => &self.dialogue,
        }
    }

    /// The task whose trajectories and instructions `task` is drawn as. Visual-reference and
    /// dialogue episodes reuse the coarse task's (the paper: "identical trajectories and
    /// instructions as the coarse-grained dataset", so the three tasks compare episode by
    /// episode) when their lengths and counts equal the coarse task's; otherwise, and for
    /// every other task, `task` itself.
    pub fn sampled_as(&self, task: Task) -> Task {
        let (t, c) = (self.get(task), &self.coarse);
        let same = (t.min_length, t.max_length, t.episodes, t.scenes)
            == (c.min_length, c.max_length, c.episodes, c.scenes)
            && t.cross_floor_share == c.cross_floor_share;
        match task {
            Task::VisualReference | Task::Dialogue if same => Task::Coarse,
            _ => task,
        }
    }

    /// The share of `task`'s trajectories across floors in a home on several floors: its own
    /// `cross_floor_share`, else `sampling`'s.
    pub fn cross_floor_share(&self, task: Task, sampling: &SamplingConfig) -> f32 {
        self.get(task)
            .cross_floor_share
            .unwrap_or(sampling.cross_floor_share)
    }

    /// Mutable settings of `task`.
    pub fn get_mut(&mut self, task: Task) -> &mut TaskConfig {
        match task {
            Task::Fine => &mut self.fine,
            Task::Coarse => &mut self.coarse,
            Task::VisualReference => &mut self.visual_reference,
            Task::LongHorizon => &mut self.long_horizon,
            Task::Dialogue => &mut self.dialogue,
        }
    }
}

/// Reference images of the visual-reference task.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageConfig {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Horizontal field of view (degrees).
    pub hfov_deg: f32,
    /// Camera height above the floor (m).
    pub camera_height: f32,
}

/// A whole generation config (`configs/generate/*.toml`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GenerateConfig {
    /// Name written into the generation report.
    pub name: String,
    /// Global seed of every random choice.
    pub seed: u64,
    /// The procedural scene preset (`configs/scenes/<name>.toml`) used unless scenes come from
    /// a folder.
    pub scene_preset: String,
    /// Scenes per scene-disjoint split.
    pub splits: SceneSplits,
    /// Path sampling.
    pub sampling: SamplingConfig,
    /// Reference images.
    pub image: ImageConfig,
    /// Per task settings.
    pub tasks: TasksConfig,
    /// The instruction stage: templates, plus the LLM stage when `[instructions.llm]` is set.
    #[serde(default, skip_serializing_if = "InstructionsConfig::is_templates")]
    pub instructions: InstructionsConfig,
}

/// Most scenes a generation config may ask for, all splits together (the `vlnverse` preset has
/// 263): a bound that keeps a mistyped count an error instead of an allocation that fails.
pub const MAX_SCENES: usize = 100_000;

/// Most episodes one task's split may ask for (the `vlnverse` preset's largest has 11,895).
pub const MAX_EPISODES_PER_SPLIT: usize = 1_000_000;

/// Most sampling attempts per trajectory (`sampling.max_attempts`).
pub const MAX_ATTEMPTS: u32 = 1_000_000;
/// Most target objects considered per scene (`sampling.max_targets`).
pub const MAX_TARGETS: usize = 100_000;
/// Longest distance a config may give (path lengths, goal distances), in metres: far beyond
/// any home, short of the values that only a typo gives.
pub const MAX_METRES: f32 = 1000.0;
/// Most sub-tasks of a long-horizon episode.
pub const MAX_SUB_TASKS: usize = 10;
/// Most oracle questions per dialogue episode.
pub const MAX_ORACLE_BUDGET: u32 = 1000;

/// The `[instructions.llm]` section: an OpenAI-compatible endpoint and how to use it.
#[cfg(feature = "llm")]
pub type LlmSection = vlnverse_instructions::llm::LlmConfig;
/// The `[instructions.llm]` section (this build has no LLM stage: feature `llm` is off).
#[cfg(not(feature = "llm"))]
pub type LlmSection = toml::Table;

/// How instructions are written.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InstructionsConfig {
    /// The paper's describe-verify-synthesize stage over the template instructions; none
    /// (the default) keeps the templates.
    #[serde(default)]
    pub llm: Option<LlmSection>,
}

impl InstructionsConfig {
    /// Templates only (nothing to write into a manifest).
    pub fn is_templates(&self) -> bool {
        self.llm.is_none()
    }
}

/// Episodes sharing one sampled trajectory: three instruction styles for the coarse-based tasks.
pub fn episodes_per_trajectory(task: Task) -> usize {
    match task {
        Task::Coarse | Task::VisualReference | Task::Dialogue => 3,
        Task::Fine | Task::LongHorizon => 1,
    }
}

impl GenerateConfig {
    /// Parse and validate TOML text; `path` names the source in errors.
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Self> {
        let cfg: GenerateConfig = toml::from_str(text).map_err(|e| {
            let loc = match e.span() {
                Some(span) => {
                    let start = span.start.min(text.len());
                    let line = text[..start].matches('\n').count() + 1;
                    let src = text.lines().nth(line - 1).unwrap_or("").trim();
                    format!("line {line} `{src}`")
                }
                None => "top level".to_string(),
            };
            DataError::parse(path, loc, e.message())
        })?;
        cfg.validate_in(path)?;
        Ok(cfg)
    }

    /// Read, parse and validate a TOML file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| DataError::io(path, e))?;
        Self::from_toml_str(&text, path)
    }

    /// The config as TOML (written next to a dataset so `merge` can check its parts agree).
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// Check every field; errors name `<config>` as the file.
    pub fn validate(&self) -> Result<()> {
        self.validate_in(Path::new("<config>"))
    }

    /// Check every field; errors name `path`.
    pub fn validate_in(&self, path: &Path) -> Result<()> {
        let bad = |field: String, value: String, reason: &str| -> DataError {
            DataError::parse(
                PathBuf::from(path),
                field,
                format!("value {value}: {reason}"),
            )
        };
        if let Some(llm) = &self.instructions.llm {
            #[cfg(feature = "llm")]
            llm.validate().map_err(|e| {
                DataError::parse(PathBuf::from(path), "instructions.llm", e.to_string())
            })?;
            #[cfg(not(feature = "llm"))]
            {
                let _ = llm;
                return Err(bad(
                    "instructions.llm".into(),
                    "a table".into(),
                    "this build has no LLM stage (feature `llm` of vlnverse-generate)",
                ));
            }
        }
        let sp = &self.splits;
        for (name, n) in [
            ("train", sp.train),
            ("val_unseen", sp.val_unseen),
            ("test", sp.test),
        ] {
            if n > MAX_SCENES {
                return Err(bad(
                    format!("splits.{name}"),
                    n.to_string(),
                    &format!("at most {MAX_SCENES} scenes"),
                ));
            }
        }
        if self.splits.total() > MAX_SCENES {
            return Err(bad(
                "splits".into(),
                format!("{} scenes", self.splits.total()),
                &format!("at most {MAX_SCENES} scenes in all"),
            ));
        }
        if self.splits.total() == 0 {
            return Err(bad(
                "splits".into(),
                "0 scenes".into(),
                "at least one scene is needed",
            ));
        }
        let s = &self.sampling;
        if !(1..=MAX_ATTEMPTS).contains(&s.max_attempts) {
            return Err(bad(
                "sampling.max_attempts".into(),
                s.max_attempts.to_string(),
                &format!("must be in [1, {MAX_ATTEMPTS}]"),
            ));
        }
        if s.max_targets > MAX_TARGETS {
            return Err(bad(
                "sampling.max_targets".into(),
                s.max_targets.to_string(),
                &format!("must be in [0, {MAX_TARGETS}] (0: all)"),
            ));
        }
        if !(s.goal_max_distance.is_finite()
            && s.goal_max_distance > 0.0
            && s.goal_max_distance <= MAX_METRES)
        {
            return Err(bad(
                "sampling.goal_max_distance".into(),
                s.goal_max_distance.to_string(),
                &format!("must be a distance in (0, {MAX_METRES}] metres"),
            ));
        }
        if !(s.goal_min_distance.is_finite()
            && s.goal_min_distance >= 0.0
            && s.goal_min_distance < s.goal_max_distance)
        {
            return Err(bad(
                "sampling.goal_min_distance".into(),
                s.goal_min_distance.to_string(),
                "must be >= 0 and below sampling.goal_max_distance",
            ));
        }
        if !(s.cross_floor_share.is_finite() && (0.0..=1.0).contains(&s.cross_floor_share)) {
            return Err(bad(
                "sampling.cross_floor_share".into(),
                s.cross_floor_share.to_string(),
                "must be a share in [0, 1]",
            ));
        }
        let im = &self.image;
        if !(1..=4096).contains(&im.width) || !(1..=4096).contains(&im.height) {
            return Err(bad(
                "image.width/height".into(),
                format!("{}x{}", im.width, im.height),
                "must be 1..=4096 pixels",
            ));
        }
        if !(im.hfov_deg > 1.0 && im.hfov_deg < 179.0) {
            return Err(bad(
                "image.hfov_deg".into(),
                im.hfov_deg.to_string(),
                "must be between 1 and 179 degrees",
            ));
        }
        if !(im.camera_height.is_finite() && im.camera_height > 0.0 && im.camera_height <= 10.0) {
            return Err(bad(
                "image.camera_height".into(),
                im.camera_height.to_string(),
                "must be in (0, 10] metres",
            ));
        }
        for task in Task::ALL {
            let t = self.tasks.get(task);
            let f = |name: &str| format!("tasks.{}.{name}", task.name());
            if let Some(v) = t.cross_floor_share {
                if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                    return Err(bad(
                        f("cross_floor_share"),
                        v.to_string(),
                        "must be a share in [0, 1]",
                    ));
                }
            }
            if !(t.min_length.is_finite() && t.min_length >= 0.0) {
                return Err(bad(
                    f("min_length"),
                    t.min_length.to_string(),
                    "must be a non-negative length in metres",
                ));
            }
            if !(t.max_length.is_finite() && t.max_length > t.min_length)
                || t.max_length > MAX_METRES
            {
                return Err(bad(
                    f("max_length"),
                    t.max_length.to_string(),
                    &format!("must be greater than min_length and at most {MAX_METRES} metres"),
                ));
            }
            if task == Task::LongHorizon
                && !(t.sub_tasks_min >= 2
                    && t.sub_tasks_min <= t.sub_tasks_max
                    && t.sub_tasks_max <= MAX_SUB_TASKS)
            {
                return Err(bad(
                    f("sub_tasks_min"),
                    format!("{}..{}", t.sub_tasks_min, t.sub_tasks_max),
                    &format!("need 2 <= sub_tasks_min <= sub_tasks_max <= {MAX_SUB_TASKS}"),
                ));
            }
            if t.oracle_budget > MAX_ORACLE_BUDGET {
                return Err(bad(
                    f("oracle_budget"),
                    t.oracle_budget.to_string(),
                    &format!("must be in [0, {MAX_ORACLE_BUDGET}] questions"),
                ));
            }
            let per = episodes_per_trajectory(task);
            for split in Split::ALL {
                let e = t.episodes.get(split);
                let n = t.scenes.get(split);
                let field = |what: &str| format!("tasks.{}.{what}.{}", task.name(), split.name());
                if e > MAX_EPISODES_PER_SPLIT {
                    return Err(bad(
                        field("episodes"),
                        e.to_string(),
                        &format!("at most {MAX_EPISODES_PER_SPLIT} episodes per task and split"),
                    ));
                }
                if !e.is_multiple_of(per) {
                    return Err(bad(
                        field("episodes"),
                        e.to_string(),
                        &format!("must be a multiple of {per} (episodes per trajectory)"),
                    ));
                }
                let pool = self.splits.pool(split);
                if n > pool {
                    return Err(bad(
                        field("scenes"),
                        n.to_string(),
                        &format!("only {pool} scenes are in that split (see [splits])"),
                    ));
                }
                if (e > 0) != (n > 0) || e / per < n {
                    return Err(bad(
                        field("scenes"),
                        n.to_string(),
                        &format!(
                            "every listed scene needs at least one of the {} trajectories",
                            e / per
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The same config for a world of `scenes` scenes (scenes from a folder): scene splits and
    /// per-cell scene counts scaled proportionally, trajectories per scene kept. With fewer
    /// than 3 scenes every scene is a train scene.
    pub fn rescaled(&self, scenes: usize) -> GenerateConfig {
        let mut cfg = self.clone();
        let old = self.splits.total();
        if scenes == old {
            return cfg;
        }
        cfg.splits = if scenes < 3 {
            SceneSplits {
                train: scenes,
                val_unseen: 0,
                test: 0,
            }
        } else {
            let share = |n: usize| ((n * scenes) as f64 / old as f64).round().max(1.0) as usize;
            let val_unseen = share(self.splits.val_unseen);
            let test = share(self.splits.test).min(scenes - 1 - val_unseen);
            SceneSplits {
                train: scenes - val_unseen - test,
                val_unseen,
                test,
            }
        };
        for task in Task::ALL {
            let per = episodes_per_trajectory(task);
            let t = cfg.tasks.get_mut(task);
            let before = *t;
            for split in Split::ALL {
                let old_pool = self.splits.pool(split).max(1);
                let pool = cfg.splits.pool(split);
                let n_old = before.scenes.get(split);
                let n = if n_old == 0 || pool == 0 {
                    0
                } else {
                    ((n_old * pool) as f64 / old_pool as f64)
                        .round()
                        .clamp(1.0, pool as f64) as usize
                };
                let traj_old = before.episodes.get(split) / per;
                let traj = if n == 0 {
                    0
                } else {
                    ((traj_old as f64 / n_old as f64) * n as f64)
                        .round()
                        .max(n as f64) as usize
                };
                t.scenes.set(split, n);
                t.episodes.set(split, traj * per);
            }
        }
        cfg
    }
}
