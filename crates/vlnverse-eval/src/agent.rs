//! The swap point of evaluation: an [`Agent`] answers each step's observations with an action.
//!
//! ```
//! use vlnverse_eval::{Agent, EpisodeInputs, StepInput};
//! use vlnverse_sim::Action;
//!
//! /// Walks forward 20 steps, then stops.
//! struct Walker { left: u32, step: f32 }
//!
//! impl Agent for Walker {
//!     fn reset(&mut self, inputs: &EpisodeInputs) -> vlnverse_eval::Result<()> {
//!         self.left = 20;
//!         self.step = inputs.agent.step_size;
//!         Ok(())
//!     }
//!     fn act(&mut self, _step: &mut StepInput) -> vlnverse_eval::Result<Action> {
//!         if self.left == 0 { return Ok(Action::Stop); }
//!         self.left -= 1;
//!         Ok(Action::MoveForward(self.step))
//!     }
//! }
//! ```

use std::path::PathBuf;

use vlnverse_env::Pose;
use vlnverse_sensors::{Observations, SensorSpec};
use vlnverse_sim::{Action, AgentConfig, StepOutcome};

use crate::error::Result;
use crate::protocol::{ActionSpace, Setting};
use vlnverse_score::episode::Task;

/// What an agent is told once per episode (never the goal position or target id). More may
/// be told in later versions, hence `#[non_exhaustive]`.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct EpisodeInputs {
    /// Episode id.
    pub episode_id: u64,
    /// Scene id.
    pub scene_id: String,
    /// Task.
    pub task: Task,
    /// The instruction text.
    pub instruction: String,
    /// Long-horizon: one instruction per sub-goal.
    pub sub_instructions: Vec<String>,
    /// Visual reference: absolute path of the reference image.
    pub reference_image: Option<PathBuf>,
    /// Start pose (the agent's odometry origin).
    pub start: Pose,
    /// The embodiment (step size, turn angle, ...).
    pub agent: AgentConfig,
    /// Actions the agent may answer with.
    pub action_space: ActionSpace,
    /// Collision setting.
    pub setting: Setting,
    /// Success distance (m).
    pub success_distance: f32,
    /// Step limit.
    pub max_steps: u32,
    /// Dialogue: questions the agent may ask.
    pub oracle_budget: Option<u32>,
    /// Seed for the agent's own random choices (depends on the config seed and the episode only).
    pub seed: u64,
}

/// Long-horizon progress: how many sub-goals the agent has declared reached (with STOP).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SubGoalProgress {
    /// Index of the sub-goal being pursued (= STOPs issued so far).
    pub current: u32,
    /// Sub-goals in the episode (1 for the other tasks).
    pub total: u32,
}

/// The dialogue oracle as an agent sees it: ask a question, get an answer (within a budget).
pub trait OracleHandle {
    /// Answer `question`; `None` when the budget is spent. An empty question (blank or only
    /// punctuation) gets a short "I did not understand; ask ..." text and costs no budget; any
    /// other text the oracle cannot classify is taken as "which way?".
    fn ask(&mut self, question: &str) -> Option<String>;
    /// Questions left.
    fn remaining(&self) -> u32;
}

/// One step's input.
pub struct StepInput<'a> {
    /// Step index (0 before the first action).
    pub step: u32,
    /// Readings of the configured rig (empty when rendering is off).
    pub observations: &'a Observations,
    /// Current base pose (odometry: GPS + compass).
    pub pose: Pose,
    /// Outcome of the previous action.
    pub last: Option<&'a StepOutcome>,
    /// Long-horizon sub-goal progress.
    pub sub_goal: SubGoalProgress,
    /// Dialogue episodes: the oracle.
    pub oracle: Option<&'a mut dyn OracleHandle>,
}

/// A navigation policy under evaluation. One instance runs one episode at a time; instances
/// are made per worker thread by an [`AgentFactory`].
pub trait Agent: Send {
    /// Sensors the agent needs beyond the configured rig (attached when missing).
    fn required_sensors(&self) -> Vec<SensorSpec> {
        Vec::new()
    }
    /// Start an episode.
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()>;
    /// Choose the next action.
    fn act(&mut self, step: &mut StepInput) -> Result<Action>;
    /// The episode ended (stop, step limit or failure).
    fn end_episode(&mut self) -> Result<()> {
        Ok(())
    }
    /// Privileged agents (the oracle) get the ground truth before [`Agent::reset`]; called only
    /// when the factory says [`AgentFactory::privileged`].
    fn set_truth(&mut self, _truth: &Privileged) {}
}

/// Ground truth a privileged agent (the oracle) may use; given to factories, never to
/// [`EpisodeInputs`].
pub struct Privileged<'a> {
    /// The episode.
    pub episode: &'a vlnverse_score::episode::Episode,
    /// Distance fields to the goals in order (`Episode::goal_sequence`).
    pub fields: &'a [std::sync::Arc<vlnverse_env::geodesic::DistanceField>],
    /// In a home on several floors, the fields toward the goals across floors (in order;
    /// `fields` then lie on each goal's level); empty in a single-storey scene.
    pub levels: &'a [std::sync::Arc<vlnverse_env::geodesic::LevelField>],
}

/// Makes agents (one per worker) and hands each episode's privileged view to agents that may
/// use it.
pub trait AgentFactory: Sync {
    /// Name in reports.
    fn name(&self) -> String;
    /// A fresh agent.
    fn make(&self) -> Result<Box<dyn Agent>>;
    /// Whether its agents may see the ground truth ([`Agent::set_truth`]); false by default.
    fn privileged(&self) -> bool {
        false
    }
    /// The command behind the agent, when it is another program (the `external` agent's shell
    /// command); part of the run's identity in `run.json`, so a resume with another command is
    /// refused.
    fn command(&self) -> Option<String> {
        None
    }
    /// What the agent is, beyond its name: a version, a checkpoint hash, a hash of its
    /// program's files. Recorded in `run.json`; resuming a run with another fingerprint is
    /// refused, so results of two different agents are never mixed. `None` (the default for
    /// agents that cannot tell) records nothing to compare beyond the name.
    fn fingerprint(&self) -> Option<String> {
        None
    }
}
