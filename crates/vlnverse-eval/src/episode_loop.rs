//! The one episode loop: [`run_episode`] drives any [`Simulator`], any [`SensorRig`] renderer
//! and any [`Agent`] through one episode and scores it. Every rule that shapes the metrics
//! lives here and only here:
//!
//! - STOP never reaches the simulator; in long-horizon episodes a STOP before the last
//!   sub-goal marks that sub-goal reached and the episode goes on;
//! - an action outside the protocol's action space is an error; an action the simulator
//!   refuses changes nothing but still costs a step;
//! - a noticeable collision (`StepOutcome::noticeable`) counts for the collision rate; a Strict
//!   failure ends the episode;
//! - the episode ends at STOP of the last sub-goal, at its step limit (`max_steps` for each of
//!   its goals: a long-horizon episode of three sub-tasks gets three episodes' budget), or when
//!   the simulator says it is over.
//!
//! The evaluation runner ([`crate::evaluate_with`]), the Python environments and remote
//! workers all call it, so they cannot drift apart.

use std::path::PathBuf;
use std::sync::Arc;

use glam::Vec2;
use vlnverse_env::geodesic::{DistanceField, LevelField};
use vlnverse_env::Pose;
use vlnverse_sensors::{AgentState, CollisionInfo, Observations, SensorRig};
use vlnverse_sim::{Action, AgentConfig, Failure, Simulator, StepOutcome};

use crate::agent::{Agent, EpisodeInputs, OracleHandle, Privileged, StepInput, SubGoalProgress};
use crate::error::{Result, TaskError};
use crate::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
use crate::protocol::{EvalConfig, Setting};
use crate::resume::EpisodeRecord;
use crate::scene_context::SceneContext;
use vlnverse_score::episode::{Episode, Split};
use vlnverse_score::metrics::{score_episode, GoalDistance, GoalDistances, MetricsConfig, Nearest};
use vlnverse_score::trajectory::Trajectory;

/// A 64-bit mix (splitmix64), for per-episode seeds.
pub fn episode_seed(seed: u64, episode_id: u64) -> u64 {
    let mut z = seed ^ episode_id.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// What one step of a trajectory was: an [`Action`]'s kind, or a dialogue question. Written
/// into trajectories by [`ActionKind::name`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ActionKind {
    /// [`Action::Stop`].
    Stop,
    /// [`Action::MoveForward`].
    MoveForward,
    /// [`Action::TurnLeft`].
    TurnLeft,
    /// [`Action::TurnRight`].
    TurnRight,
    /// [`Action::LookUp`].
    LookUp,
    /// [`Action::LookDown`].
    LookDown,
    /// [`Action::Velocity`].
    Velocity,
    /// [`Action::Waypoint`].
    Waypoint,
    /// A question to the dialogue oracle (a step when it cannot be asked: no budget left).
    Ask,
}

impl ActionKind {
    /// The name in trajectories (`"move_forward"`, `"ask"`...).
    pub fn name(self) -> &'static str {
        match self {
            ActionKind::Stop => "stop",
            ActionKind::MoveForward => "move_forward",
            ActionKind::TurnLeft => "turn_left",
            ActionKind::TurnRight => "turn_right",
            ActionKind::LookUp => "look_up",
            ActionKind::LookDown => "look_down",
            ActionKind::Velocity => "velocity",
            ActionKind::Waypoint => "waypoint",
            ActionKind::Ask => "ask",
        }
    }
}

impl From<&Action> for ActionKind {
    fn from(a: &Action) -> Self {
        match a {
            Action::Stop => ActionKind::Stop,
            Action::MoveForward(_) => ActionKind::MoveForward,
            Action::TurnLeft(_) => ActionKind::TurnLeft,
            Action::TurnRight(_) => ActionKind::TurnRight,
            Action::LookUp => ActionKind::LookUp,
            Action::LookDown => ActionKind::LookDown,
            Action::Velocity { .. } => ActionKind::Velocity,
            Action::Waypoint { .. } => ActionKind::Waypoint,
        }
    }
}

impl std::fmt::Display for ActionKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What every episode of an evaluation runs under, derived once from an [`EvalConfig`].
#[derive(Debug, Clone)]
pub struct EpisodeSettings {
    /// The protocol (action space, setting, step limit, success distance, seed).
    pub config: EvalConfig,
    /// The embodiment, as the simulator uses it (told to the agent).
    pub agent: AgentConfig,
    /// How trajectories are scored.
    pub metrics: MetricsConfig,
    /// Whether the agent gets the ground truth ([`Agent::set_truth`]).
    pub privileged: bool,
    /// The split the episodes come from (recorded in the metrics).
    pub split: Option<Split>,
    /// Folder that relative reference-image paths are resolved against (the split's folder).
    pub reference_dir: Option<PathBuf>,
}

impl EpisodeSettings {
    /// Settings for `config` (its agent profile is loaded here); not privileged, no split.
    pub fn new(config: &EvalConfig) -> Result<Self> {
        Ok(EpisodeSettings {
            agent: config.agent_config()?,
            metrics: MetricsConfig {
                success_distance: config.success_distance,
                fail_on_collision: config.setting == Setting::Strict,
                ..Default::default()
            },
            config: config.clone(),
            privileged: false,
            split: None,
            reference_dir: None,
        })
    }
}

/// The dialogue oracle as the agent sees it: free-text questions go to the episode's oracle,
/// the [`ShortestPathOracle`] (true remaining path + scene graph, with the episode's budget),
/// its answers rephrased by an LLM when the protocol has `[oracle_llm]`.
pub struct DialogueHandle<'a> {
    oracle: &'a mut dyn Oracle,
    pose: Pose,
}

/// The dialogue oracle's reply to an empty question (costs no budget).
pub const NOT_UNDERSTOOD: &str = "I did not understand the question; ask \"which way?\", \
                                  \"where is the <object>?\" or \"am I close?\".";

impl OracleHandle for DialogueHandle<'_> {
    fn ask(&mut self, question: &str) -> Option<String> {
        if question
            .trim()
            .trim_matches(['?', '.', '!'])
            .trim()
            .is_empty()
        {
            return Some(NOT_UNDERSTOOD.to_string());
        }
        if self.oracle.remaining() == 0 {
            return None;
        }
        let query = OracleQuery::parse(question);
        match self.oracle.ask(&query, self.pose.position, self.pose.yaw()) {
            Ok(answer) => Some(answer.text),
            Err(e) => Some(format!("I could not answer that: {e}")),
        }
    }
    fn remaining(&self) -> u32 {
        self.oracle.remaining()
    }
}

/// The episode's oracle: the rule-based one, wrapped in the LLM oracle when the protocol has
/// `[oracle_llm]` (seeded with the episode's seed, so answers repeat).
fn dialogue_oracle(
    rule: ShortestPathOracle,
    cfg: &EvalConfig,
    seed: u64,
) -> Result<Box<dyn Oracle>> {
    match &cfg.oracle_llm {
        None => Ok(Box::new(rule)),
        #[cfg(feature = "llm-oracle")]
        Some(llm) => Ok(Box::new(crate::oracle::LlmOracle::new(
            rule,
            llm.clone(),
            seed,
        )?)),
        #[cfg(not(feature = "llm-oracle"))]
        Some(_) => {
            let _ = seed;
            Err(TaskError::invalid(
                "oracle_llm",
                "<section>",
                "this build has no LLM client (feature `llm-oracle` of vlnverse-eval, or `llm` of vlnverse-task)",
            ))
        }
    }
}

/// Why an episode cannot be run in its scene (see [`EpisodeCheckError`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Unrunnable {
    /// A coordinate is NaN or infinite.
    #[error("not finite")]
    NotFinite,
    /// The start is not on the scene's floor.
    #[error("y is {offset:.2} m from the scene's floor ({floor})")]
    OffFloor {
        /// Start height minus the floor height (m).
        offset: f32,
        /// The scene's floor height (m).
        floor: f32,
    },
    /// Outside the scene's navigable map.
    #[error("outside the scene's navigable map")]
    OffMap,
    /// A goal neither on nor near a navigable cell.
    #[error("not on or near a navigable cell")]
    NotNavigable,
    /// A goal the start cannot reach on the navigable map.
    #[error("unreachable from start_position on the navigable map")]
    Unreachable,
    /// The goal's distance field could not be built.
    #[error("{0}")]
    Field(String),
    /// An object id the scene does not have.
    #[error("the scene has no object with this id")]
    NoSuchObject,
}

/// An episode that cannot be run in its scene: the episode field, its value and why.
/// Checked before the episode runs ([`check_episode`]), so an impossible episode is refused
/// instead of being scored as a failure.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid `{field}` = {value}: {reason}")]
#[non_exhaustive]
pub struct EpisodeCheckError {
    /// The episode's field (`start_position`, `goals`, `sub_goals[2]`).
    pub field: String,
    /// Its value as written.
    pub value: String,
    /// Why the episode cannot be run.
    pub reason: Unrunnable,
}

impl EpisodeCheckError {
    /// The error as a [`TaskError::invalid`] data error whose field is `location.field` (`location`
    /// names the episode: `FILE: episode 3 (episodes[2])`).
    pub fn at(self, location: &str) -> TaskError {
        TaskError::invalid(
            format!("{location}.{}", self.field),
            self.value,
            self.reason.to_string(),
        )
    }
}

impl From<EpisodeCheckError> for TaskError {
    fn from(e: EpisodeCheckError) -> Self {
        TaskError::invalid(e.field, e.value, e.reason.to_string())
    }
}

/// Check that `ep` can be run in `scene`: a finite start on the floor and on the navigable
/// map, the objects it names in the scene, every goal on the map and reachable from the start.
pub fn check_episode(ep: &Episode, scene: &SceneContext) -> Result<(), EpisodeCheckError> {
    let p = ep.start_position;
    let bad = |field: &str, value: String, reason: Unrunnable| {
        Err(EpisodeCheckError {
            field: field.into(),
            value,
            reason,
        })
    };
    if !p.iter().all(|v| v.is_finite()) || !ep.start_rotation.iter().all(|v| v.is_finite()) {
        return bad("start_position", format!("{p:?}"), Unrunnable::NotFinite);
    }
    // In a home on several floors, the floor of the level the start is on.
    let s = &scene.scene;
    let floor = s
        .level_height(s.level_at_height(p[1]))
        .unwrap_or(s.floor_height);
    if (p[1] - floor).abs() > 0.5 {
        let offset = p[1] - floor;
        return bad(
            "start_position",
            format!("{p:?}"),
            Unrunnable::OffFloor { offset, floor },
        );
    }
    let map = scene.navigable_at(p);
    if map.world_to_cell(Vec2::new(p[0], p[2])).is_none() {
        return bad("start_position", format!("{p:?}"), Unrunnable::OffMap);
    }
    let objects =
        ep.target_object_id
            .map(|id| ("target_object_id".to_string(), id))
            .into_iter()
            .chain(
                ep.goals.iter().enumerate().filter_map(|(i, g)| {
                    g.object_id.map(|id| (format!("goals[{i}].object_id"), id))
                }),
            )
            .chain(ep.sub_goals.iter().enumerate().filter_map(|(i, g)| {
                g.object_id
                    .map(|id| (format!("sub_goals[{i}].object_id"), id))
            }));
    for (field, id) in objects {
        if scene.scene.object(id).is_none() {
            return bad(&field, id.to_string(), Unrunnable::NoSuchObject);
        }
    }
    for (i, g) in ep.goal_sequence().iter().enumerate() {
        let field_name = if ep.sub_goals.is_empty() {
            "goals".to_string()
        } else {
            format!("sub_goals[{i}]")
        };
        let value = format!("{:?}", g.position);
        if !g.position.iter().all(|v| v.is_finite()) {
            return bad(&field_name, value, Unrunnable::NotFinite);
        }
        if scene
            .navigable_at(g.position)
            .world_to_cell(Vec2::new(g.position[0], g.position[2]))
            .is_none()
        {
            return bad(&field_name, value, Unrunnable::OffMap);
        }
        let field = match scene.field(g.position) {
            Ok(f) => f,
            Err(e) => return bad(&field_name, value, Unrunnable::Field(e.to_string())),
        };
        if field.goal().is_none() {
            return bad(&field_name, value, Unrunnable::NotNavigable);
        }
        let reachable = match scene.level_field(g.position) {
            Ok(Some(lf)) => GoalDistance::distance(&*lf, p).is_some(),
            Ok(None) => GoalDistance::distance(&*field, p).is_some(),
            Err(e) => return bad(&field_name, value, Unrunnable::Field(e.to_string())),
        };
        if !reachable {
            return bad(&field_name, value, Unrunnable::Unreachable);
        }
    }
    Ok(())
}

/// One episode in progress, driven step by step from outside: [`run_episode`] drives it with
/// an [`Agent`]; the Python environments drive it with actions that arrive one batch at a
/// time. It holds no simulator or rig (they are passed to each call), so many of them can
/// live in a vector environment. The rules of this module's docs are applied in
/// [`EpisodeState::apply`].
pub struct EpisodeState {
    /// What the agent is told at the start.
    pub inputs: EpisodeInputs,
    goal_fields: Vec<Arc<DistanceField>>,
    /// In a home on several floors, the fields toward the goals across floors (in order);
    /// empty in a single-storey scene.
    level_fields: Vec<Arc<LevelField>>,
    pose: Pose,
    progress: SubGoalProgress,
    dialogue: Option<Box<dyn Oracle>>,
    positions: Vec<[f32; 3]>,
    headings: Vec<f32>,
    actions: Vec<ActionKind>,
    stops: Vec<u32>,
    steps: u32,
    /// Steps the episode may take: `max_steps` for each of its goals.
    limit: u32,
    collisions: u32,
    stopped: bool,
    over: bool,
    last: Option<StepOutcome>,
    failure: Option<Failure>,
}

/// What [`EpisodeState::apply`] did with one action.
#[derive(Debug, Clone, PartialEq)]
pub enum Applied {
    /// STOP: the episode ended (or, long-horizon, a sub-goal was declared reached).
    Stop {
        /// A long-horizon sub-goal was declared reached and the episode goes on.
        sub_goal: bool,
    },
    /// The simulator stepped ([`EpisodeState::last`] holds its outcome).
    Stepped,
    /// The simulator refused the action (nothing changed; the step still counts).
    Refused(String),
}

impl EpisodeState {
    /// Reset `sim` (and `rig`, when rendering) at the episode's start in `scene`.
    ///
    /// The rig is given the scene only when it shows another one ([`SensorRig::scene_id`]).
    pub fn begin<S: Simulator>(
        sim: &mut S,
        rig: Option<&mut SensorRig>,
        ep: &Episode,
        scene: &SceneContext,
        settings: &EpisodeSettings,
    ) -> Result<Self> {
        let cfg = &settings.config;
        let goal_fields: Vec<Arc<DistanceField>> = ep
            .goal_sequence()
            .iter()
            .map(|g| scene.field(g.position))
            .collect::<Result<_>>()?;
        let level_fields: Vec<Arc<LevelField>> = ep
            .goal_sequence()
            .iter()
            .filter_map(|g| scene.level_field(g.position).transpose())
            .collect::<Result<_>>()?;
        if goal_fields.is_empty() {
            return Err(TaskError::invalid(
                format!("episode {}: goals", ep.episode_id),
                "[]",
                "an episode needs a goal",
            ));
        }
        let start = Pose {
            position: ep.start_position,
            rotation: ep.start_rotation,
        };
        let pose = sim.reset(&scene.scene, start)?;
        if let Some(rig) = rig {
            if rig.scene_id() != Some(ep.scene_id.as_str()) {
                rig.set_mesh(scene.mesh()?)?;
            }
            rig.reset(pose);
        }
        // A long-horizon episode chains sub-tasks; each gets the budget of one episode.
        let limit = cfg.max_steps.saturating_mul(goal_fields.len() as u32);
        let inputs = EpisodeInputs {
            episode_id: ep.episode_id,
            scene_id: ep.scene_id.clone(),
            task: ep.task,
            instruction: ep.instruction.instruction_text.clone(),
            sub_instructions: ep.instruction.sub_instructions.clone(),
            reference_image: ep
                .reference_image
                .as_ref()
                .map(|r| match &settings.reference_dir {
                    Some(d) => d.join(r),
                    None => PathBuf::from(r),
                }),
            start: pose,
            agent: settings.agent.clone(),
            action_space: cfg.action_space,
            setting: cfg.setting,
            success_distance: cfg.success_distance,
            max_steps: limit,
            oracle_budget: ep.oracle_budget,
            seed: episode_seed(cfg.seed, ep.episode_id),
        };
        let total = goal_fields.len() as u32;
        let dialogue = match ep.oracle_budget {
            Some(_) => Some(dialogue_oracle(
                with_levels(
                    ShortestPathOracle::for_episode(
                        scene.scene.clone(),
                        scene.graph(),
                        match scene.levels() {
                            Some(_) => Arc::new(scene.navigable_at(last_goal(ep)).clone()),
                            None => scene.navigable.clone(),
                        },
                        ep,
                        OracleConfig::default(),
                    )?,
                    level_fields.last(),
                ),
                cfg,
                inputs.seed,
            )?),
            None => None,
        };
        Ok(EpisodeState {
            inputs,
            goal_fields,
            level_fields,
            pose,
            progress: SubGoalProgress { current: 0, total },
            dialogue,
            positions: vec![pose.position],
            headings: vec![pose.yaw()],
            actions: Vec::new(),
            stops: Vec::new(),
            steps: 0,
            limit,
            collisions: 0,
            stopped: false,
            over: limit == 0,
            last: None,
            failure: None,
        })
    }

    /// The ground truth of a privileged agent (the teacher).
    pub fn privileged<'a>(&'a self, ep: &'a Episode) -> Privileged<'a> {
        Privileged {
            episode: ep,
            fields: &self.goal_fields,
            levels: &self.level_fields,
        }
    }

    /// The agent's base pose now.
    pub fn pose(&self) -> Pose {
        self.pose
    }

    /// Actions taken so far (STOPs and refused actions included).
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Noticeable collisions so far.
    pub fn collisions(&self) -> u32 {
        self.collisions
    }

    /// Long-horizon progress (sub-goals declared reached).
    pub fn sub_goal(&self) -> SubGoalProgress {
        self.progress
    }

    /// What an agent without the dialogue oracle gets at this step (the teacher's input).
    pub fn step_input<'a>(&'a self, observations: &'a Observations) -> StepInput<'a> {
        StepInput {
            step: self.steps,
            observations,
            pose: self.pose,
            last: self.last.as_ref(),
            sub_goal: self.progress,
            oracle: None,
        }
    }

    /// The outcome of the last simulator step (`None` at the start and after a refused action).
    pub fn last(&self) -> Option<&StepOutcome> {
        self.last.as_ref()
    }

    /// Whether the episode is over: STOP of the last sub-goal, a failure, or the step limit.
    pub fn is_over(&self) -> bool {
        self.over
    }

    /// Whether the agent called STOP for the last sub-goal.
    pub fn stopped(&self) -> bool {
        self.stopped
    }

    /// Geodesic distance (m) from the agent to the current sub-goal (the goal for the other
    /// tasks); `None` when the agent stands off the navigable map.
    pub fn distance_to_goal(&self) -> Option<f32> {
        let k = (self.progress.current as usize).min(self.goal_fields.len() - 1);
        if let Some(lf) = self.level_fields.get(k) {
            return GoalDistance::distance(&**lf, self.pose.position);
        }
        GoalDistance::distance(&*self.goal_fields[k], self.pose.position)
    }

    /// What the rig is told about the agent at this step.
    pub fn agent_state(&self) -> AgentState {
        let last = self.last.as_ref();
        AgentState {
            base: self.pose,
            step: self.steps as u64,
            time_s: 0.0,
            collision: CollisionInfo {
                collided: last.is_some_and(|o| o.collided),
                displacement: last.map_or(0.0, |o| {
                    (Vec2::from_array(o.commanded) - Vec2::from_array(o.achieved)).length()
                }),
                count: self.collisions,
            },
        }
    }

    /// The rig's readings at this step.
    pub fn observe(&self, rig: &mut SensorRig) -> Result<Observations> {
        Ok(rig.observe(&self.agent_state())?)
    }

    /// Dialogue episodes: ask the oracle (within the episode's budget; see [`OracleHandle`]).
    /// `None` when the episode has no oracle or its budget is spent.
    pub fn ask(&mut self, question: &str) -> Option<String> {
        let pose = self.pose;
        let oracle = self.dialogue.as_deref_mut()?;
        DialogueHandle { oracle, pose }.ask(question)
    }

    /// Questions left to ask the oracle (0 without one).
    pub fn questions_left(&self) -> u32 {
        self.dialogue.as_ref().map_or(0, |o| o.remaining())
    }

    /// Apply one action under the loop's rules. An action outside the protocol's action space
    /// is an error (and changes nothing); so is any action once the episode is over.
    pub fn apply<S: Simulator>(
        &mut self,
        sim: &mut S,
        action: Action,
        cfg: &EvalConfig,
    ) -> Result<Applied> {
        self.check_live(&format!("{action:?}"))?;
        if !cfg.action_space.allows(&action) {
            return Err(TaskError::invalid(
                "action",
                format!("{action:?}"),
                format!(
                    "episode {}: not in the {} action space",
                    self.inputs.episode_id,
                    cfg.action_space.name()
                ),
            ));
        }
        self.steps += 1;
        self.actions.push(ActionKind::from(&action));
        let applied = if action == Action::Stop {
            if self.progress.current + 1 < self.progress.total {
                // A long-horizon sub-goal declared reached; the episode goes on.
                self.stops.push(self.positions.len() as u32 - 1);
                self.progress.current += 1;
                Applied::Stop { sub_goal: true }
            } else {
                self.stopped = true;
                self.over = true;
                Applied::Stop { sub_goal: false }
            }
        } else {
            match sim.step(action) {
                Ok(out) => {
                    self.pose = out.pose;
                    self.positions.push(self.pose.position);
                    self.headings.push(self.pose.yaw());
                    if out.noticeable {
                        self.collisions += 1;
                    }
                    if let Some(f) = &out.failure {
                        self.failure = Some(f.clone());
                    }
                    self.over |= out.done;
                    self.last = Some(out);
                    Applied::Stepped
                }
                Err(e) => {
                    // An invalid action changes nothing; it still costs a step.
                    tracing::warn!(episode = self.inputs.episode_id, "action refused: {e}");
                    self.stand_still();
                    Applied::Refused(e.to_string())
                }
            }
        };
        self.end_if_limit();
        Ok(applied)
    }

    /// An action that cannot be carried out (`kind` in the trajectory, e.g. a question with
    /// no budget left: [`ActionKind::Ask`]): nothing moves, the step counts.
    pub fn refuse(&mut self, kind: ActionKind, why: &str) -> Result<Applied> {
        self.check_live(kind.name())?;
        self.steps += 1;
        self.actions.push(kind);
        self.stand_still();
        self.end_if_limit();
        Ok(Applied::Refused(why.to_string()))
    }

    /// Acting on a finished episode is an error naming the action.
    fn check_live(&self, action: &str) -> Result<()> {
        if self.over {
            return Err(TaskError::invalid(
                "action",
                action,
                format!(
                    "episode {} is over; reset before stepping again",
                    self.inputs.episode_id
                ),
            ));
        }
        Ok(())
    }

    /// A counted step in which the agent did not move.
    fn stand_still(&mut self) {
        self.last = None;
        self.positions.push(self.pose.position);
        self.headings.push(self.pose.yaw());
    }

    /// The step limit ends the episode.
    fn end_if_limit(&mut self) {
        if self.steps >= self.limit {
            self.over = true;
        }
    }

    /// The trajectory so far.
    pub fn trajectory(&self) -> Trajectory {
        Trajectory {
            episode_id: self.inputs.episode_id,
            positions: self.positions.clone(),
            headings: Some(self.headings.clone()),
            stopped: self.stopped,
            collisions: self.collisions,
            steps: self.steps,
            stops: self.stops.clone(),
            actions: Some(self.actions.iter().map(|a| a.name().into()).collect()),
        }
    }

    /// Score the episode as it stands (normally once it is over).
    pub fn finish(
        &self,
        ep: &Episode,
        scene: &SceneContext,
        settings: &EpisodeSettings,
    ) -> Result<EpisodeRecord> {
        let traj = self.trajectory();
        let distances = if self.level_fields.is_empty() {
            goal_distances(scene, ep, &self.goal_fields)?
        } else {
            level_goal_distances(scene, ep, &self.level_fields)?
        };
        let mut metrics = score_episode(ep, &traj, &distances, &settings.metrics);
        metrics.split = settings.split;
        Ok(EpisodeRecord::new(
            ep.episode_id,
            traj,
            metrics,
            self.failure.clone(),
        ))
    }
}

/// Run one episode: reset `sim` (and `rig`, when rendering) at the episode's start in
/// `scene`, then `observe -> agent.act -> sim.step` under the rules in this module's docs, and
/// score the trajectory on the scene's navigable map. Deterministic for a deterministic
/// simulator, renderer and agent.
///
/// The rig is given the scene only when it shows another one ([`SensorRig::scene_id`]).
pub fn run_episode<S: Simulator>(
    sim: &mut S,
    mut rig: Option<&mut SensorRig>,
    agent: &mut dyn Agent,
    ep: &Episode,
    scene: &SceneContext,
    settings: &EpisodeSettings,
) -> Result<EpisodeRecord> {
    let mut st = EpisodeState::begin(sim, rig.as_deref_mut(), ep, scene, settings)?;
    if settings.privileged {
        agent.set_truth(&st.privileged(ep));
    }
    agent.reset(&st.inputs)?;
    let empty = Observations::new();
    while !st.over {
        let obs = match rig.as_deref_mut() {
            Some(rig) => st.observe(rig)?,
            None => empty.clone(),
        };
        let pose = st.pose;
        let mut handle = st
            .dialogue
            .as_deref_mut()
            .map(|oracle| DialogueHandle { oracle, pose });
        let action = agent.act(&mut StepInput {
            step: st.steps,
            observations: &obs,
            pose,
            last: st.last.as_ref(),
            sub_goal: st.progress,
            oracle: handle.as_mut().map(|h| h as &mut dyn OracleHandle),
        })?;
        st.apply(sim, action, &settings.config)?;
    }
    agent.end_episode()?;
    st.finish(ep, scene, settings)
}

/// The position of an episode's final goal (the start when it has none).
fn last_goal(ep: &Episode) -> [f32; 3] {
    ep.goal_sequence()
        .last()
        .map_or(ep.start_position, |g| g.position)
}

/// The dialogue oracle with the final goal's field across floors, in a home on several floors.
fn with_levels(o: ShortestPathOracle, field: Option<&Arc<LevelField>>) -> ShortestPathOracle {
    match field {
        Some(f) => o.with_levels(f.clone()),
        None => o,
    }
}

/// [`goal_distances`] across the floors of a home on several floors.
fn level_goal_distances(
    scene: &SceneContext,
    ep: &Episode,
    seq: &[Arc<LevelField>],
) -> Result<GoalDistances> {
    let goals: Vec<Arc<dyn GoalDistance>> = ep
        .goals
        .iter()
        .filter_map(|g| scene.level_field(g.position).transpose())
        .map(|f| f.map(|f| f as Arc<dyn GoalDistance>))
        .collect::<Result<_>>()?;
    let seq = seq.iter().map(|f| f.clone() as Arc<dyn GoalDistance>);
    Ok(distances_of(ep, goals, seq.collect()))
}

/// The goal's distance (the nearest of several goals; the last of `seq` when the episode
/// names none) and, for long-horizon episodes, each sub-goal's in order.
fn distances_of(
    ep: &Episode,
    goals: Vec<Arc<dyn GoalDistance>>,
    seq: Vec<Arc<dyn GoalDistance>>,
) -> GoalDistances {
    let goal: Arc<dyn GoalDistance> = match goals.len() {
        0 => seq[seq.len() - 1].clone(),
        1 => goals[0].clone(),
        _ => Arc::new(Nearest(goals)),
    };
    let sub_goals = if ep.sub_goals.is_empty() {
        Vec::new()
    } else {
        seq
    };
    GoalDistances { goal, sub_goals }
}

/// Distances to the goal (the nearest of several goals) and, for long-horizon episodes, to
/// each sub-goal in order.
fn goal_distances(
    scene: &SceneContext,
    ep: &Episode,
    seq: &[Arc<DistanceField>],
) -> Result<GoalDistances> {
    let goals: Vec<Arc<dyn GoalDistance>> = ep
        .goals
        .iter()
        .map(|g| scene.field(g.position).map(|f| f as Arc<dyn GoalDistance>))
        .collect::<Result<_>>()?;
    let seq = seq.iter().map(|f| f.clone() as Arc<dyn GoalDistance>);
    Ok(distances_of(ep, goals, seq.collect()))
}
