//! The episode format: VLN-CE-compatible serde types.
//!
//! A split file holds `{"episodes": [...]}`. Every key VLN-CE's R2R loader reads is here with its
//! VLN-CE name and meaning (`episode_id`, `trajectory_id`, `scene_id`, `start_position`,
//! `start_rotation`, `goals` [{position, radius}], `instruction` {instruction_text,
//! instruction_tokens}, `reference_path`, `info` {geodesic_distance}). Everything task specific is
//! an addition with `#[serde(default)]`, left out of the file when empty, so an existing VLN-CE
//! loader reads our files and we read theirs.
//!
//! Long-horizon episodes keep `goals = [final goal]` (VLN-CE measures distance to the nearest entry
//! of `goals`, so listing every sub-goal there would let a loader count an intermediate one as
//! success) and list all goals in order in `sub_goals`, the last one equal to `goals[0]`.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize};

use crate::error::DataError;

/// The five tasks of the benchmark.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum Task {
    /// Fine-grained, step-by-step instructions (R2R-style). The default for VLN-CE files.
    #[default]
    Fine,
    /// Coarse-grained goal descriptions, three styles per trajectory.
    Coarse,
    /// Coarse-grained plus a reference image rendered at the goal.
    VisualReference,
    /// 2-3 coarse sub-tasks chained in one scene.
    LongHorizon,
    /// Coarse-grained plus an oracle the agent may query.
    Dialogue,
}

impl Task {
    /// All tasks, in the order of the paper's tables.
    pub const ALL: [Task; 5] = [
        Task::Fine,
        Task::Coarse,
        Task::VisualReference,
        Task::LongHorizon,
        Task::Dialogue,
    ];

    /// The name used in folder names, files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Task::Fine => "fine",
            Task::Coarse => "coarse",
            Task::VisualReference => "visual_reference",
            Task::LongHorizon => "long_horizon",
            Task::Dialogue => "dialogue",
        }
    }
}

/// Dataset splits. Train, val_unseen and test are scene-disjoint; val_seen uses train scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Split {
    /// Training episodes.
    Train,
    /// Validation episodes in training scenes.
    ValSeen,
    /// Validation episodes in scenes not used for training.
    ValUnseen,
    /// Test episodes.
    Test,
}

impl Split {
    /// All splits.
    pub const ALL: [Split; 4] = [Split::Train, Split::ValSeen, Split::ValUnseen, Split::Test];

    /// The name used in folder names, files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Split::Train => "train",
            Split::ValSeen => "val_seen",
            Split::ValUnseen => "val_unseen",
            Split::Test => "test",
        }
    }
}

/// Style of a coarse-grained instruction (three per trajectory).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// Complete sentences, precise wording.
    Formal,
    /// Everyday wording.
    Natural,
    /// Short and informal.
    Casual,
}

impl Style {
    /// All styles.
    pub const ALL: [Style; 3] = [Style::Formal, Style::Natural, Style::Casual];

    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            Style::Formal => "formal",
            Style::Natural => "natural",
            Style::Casual => "casual",
        }
    }
}

macro_rules! name_impls {
    ($ty:ident, $what:literal) => {
        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl FromStr for $ty {
            type Err = DataError;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                $ty::ALL
                    .iter()
                    .copied()
                    .find(|v| v.name() == s)
                    .ok_or_else(|| {
                        let names: Vec<&str> = $ty::ALL.iter().map(|v| v.name()).collect();
                        DataError::invalid(
                            $what,
                            s,
                            format!("expected one of {}", names.join(", ")),
                        )
                    })
            }
        }
    };
}
name_impls!(Task, "task");
name_impls!(Split, "split");
name_impls!(Style, "style");

/// Role of an object mentioned by an instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Passed on the way.
    Landmark,
    /// The object to reach.
    Target,
    /// Used to single out the target ("the lamp next to the sofa").
    Reference,
}

/// Side of a mentioned object as seen from the path at the point where it is mentioned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// To the left of the walking direction.
    Left,
    /// To the right.
    Right,
    /// In front.
    Ahead,
    /// Behind.
    Behind,
}

/// An object an instruction mentions, so the instruction can be checked mechanically.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GroundedObject {
    /// Object id in the scene (`scene.json`).
    pub object_id: u32,
    /// Semantic class name, e.g. `sofa`.
    pub class: String,
    /// Why it is mentioned.
    pub role: Role,
    /// Its side as seen from the path; absent when the side is not stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<Side>,
    /// Index into `reference_path` of the point it is mentioned at.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path_index: Option<u32>,
}

/// The instruction of an episode (VLN-CE `instruction`, with additions).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Instruction {
    /// The text given to the agent (VLN-CE key).
    pub instruction_text: String,
    /// Token ids of a vocabulary (VLN-CE key); we leave it out, VLN-CE files have it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub instruction_tokens: Option<Vec<u32>>,
    /// Style of a coarse-grained instruction.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub style: Option<Style>,
    /// Objects the text mentions.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub grounding: Vec<GroundedObject>,
    /// Long-horizon: one instruction per sub-goal, in order (`instruction_text` combines them).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sub_instructions: Vec<String>,
}

/// A goal (VLN-CE `NavigationGoal`, plus the target object when there is one).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Goal {
    /// Goal position on the floor, world frame.
    pub position: [f32; 3],
    /// Success radius in metres (VLN-CE writes 3.0; `null` reads as 3.0).
    #[serde(default = "default_radius", deserialize_with = "radius_or_default")]
    pub radius: f32,
    /// The object the goal is in front of, when the task names one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object_id: Option<u32>,
}

/// The success radius of the paper (3 m).
pub const DEFAULT_GOAL_RADIUS: f32 = 3.0;

fn default_radius() -> f32 {
    DEFAULT_GOAL_RADIUS
}

fn radius_or_default<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    Ok(Option::<f32>::deserialize(d)?.unwrap_or(DEFAULT_GOAL_RADIUS))
}

/// `info` of an episode.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct EpisodeInfo {
    /// Geodesic distance from the start to the goal in metres (VLN-CE key). For long-horizon
    /// episodes, the length of the whole chain start -> sub-goal 1 -> ... -> final goal.
    pub geodesic_distance: f32,
    /// Other keys, kept as they are (sorted, so output stays deterministic).
    #[serde(flatten)]
    pub extra: BTreeMap<String, serde_json::Value>,
}

/// One episode of a split file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Episode {
    /// Unique id within the split file (VLN-CE key).
    pub episode_id: u64,
    /// Id of the sampled path; the three coarse styles of one path share it (VLN-CE key).
    #[serde(default)]
    pub trajectory_id: u64,
    /// Scene folder name under `DIR/scenes/` (VLN-CE key).
    pub scene_id: String,
    /// Start position on the floor (VLN-CE key).
    pub start_position: [f32; 3],
    /// Start orientation as a quaternion `[x, y, z, w]` (VLN-CE key).
    pub start_rotation: [f32; 4],
    /// Goals (VLN-CE key); one for every task, the final goal for long-horizon.
    pub goals: Vec<Goal>,
    /// The instruction (VLN-CE key).
    pub instruction: Instruction,
    /// Reference path from the start to the goal, start and goal included (VLN-CE key).
    #[serde(default)]
    pub reference_path: Vec<[f32; 3]>,
    /// Episode information (VLN-CE key).
    #[serde(default)]
    pub info: EpisodeInfo,
    /// Which task the episode belongs to (addition; VLN-CE files read as `fine`).
    #[serde(default)]
    pub task: Task,
    /// Coarse / visual reference / dialogue: the object to reach.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_object_id: Option<u32>,
    /// Visual reference: the reference image, relative to the split file's folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_image: Option<String>,
    /// Long-horizon: all goals in order, the last one equal to `goals[0]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sub_goals: Vec<Goal>,
    /// Dialogue: how many questions the agent may ask the oracle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oracle_budget: Option<u32>,
}

impl Default for Episode {
    /// An empty fine-grained episode facing -Z (identity rotation): a base for struct-update
    /// syntax in converters, tests and benches.
    fn default() -> Self {
        Episode {
            episode_id: 0,
            trajectory_id: 0,
            scene_id: String::new(),
            start_position: [0.0; 3],
            start_rotation: [0.0, 0.0, 0.0, 1.0],
            goals: Vec::new(),
            instruction: Instruction::default(),
            reference_path: Vec::new(),
            info: EpisodeInfo::default(),
            task: Task::default(),
            target_object_id: None,
            reference_image: None,
            sub_goals: Vec::new(),
            oracle_budget: None,
        }
    }
}

impl Episode {
    /// The goals the agent must reach in order: `sub_goals` for long-horizon episodes, else the
    /// first of `goals` (empty only for a malformed episode).
    pub fn goal_sequence(&self) -> &[Goal] {
        if !self.sub_goals.is_empty() {
            &self.sub_goals
        } else if self.goals.is_empty() {
            &[]
        } else {
            &self.goals[..1]
        }
    }

    /// Style of the instruction, if any.
    pub fn style(&self) -> Option<Style> {
        self.instruction.style
    }
}

/// A split file: `{"episodes": [...]}`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Dataset {
    /// The episodes, in file order.
    pub episodes: Vec<Episode>,
}
