//! The evaluation loop: per episode, reset the simulator at the start pose, then
//! `observations -> Agent::act -> Simulator::step` until STOP, the step limit or a Strict
//! failure; score the trajectory on the scene's navigable map; append it to the run's progress
//! log. Episodes run in parallel (rayon); every random choice is seeded per episode, so results
//! do not depend on the thread count or on the order episodes finish in.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use glam::Vec2;
use rayon::prelude::*;
use vlnverse_env::geodesic::DistanceField;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{AgentState, CollisionInfo, Observations, RigConfig, SensorRig};
use vlnverse_sim::{Action, PhysicsScene, RapierSimulator, SimConfig, Simulator, StepOutcome};

use crate::dataset;
use crate::episode::{Episode, Split, Task};
use crate::error::{Result, TaskError};
use crate::eval::agent::{
    Agent, AgentFactory, EpisodeInputs, OracleHandle, Privileged, StepInput, SubGoalProgress,
};
use crate::eval::plots;
use crate::eval::protocol::{EvalConfig, Setting};
use crate::eval::resume::{self, EpisodeRecord, ProgressLog, PROGRESS_FILE};
use crate::metrics::{score_episode, GoalDistance, GoalDistances, MetricsConfig, Nearest};
use crate::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
use crate::report::{write_run, RunSummary};
use crate::score::navigable_map_path;
use crate::trajectory::{write_jsonl, Trajectory};

/// What to evaluate and where the results go.
#[derive(Debug, Clone)]
pub struct EvalRequest {
    /// Dataset folder (`<task>/<split>/<split>.json.gz`, `scenes/<scene_id>/`).
    pub dataset: PathBuf,
    /// Task.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// Only the first N episodes of the split file.
    pub episodes: Option<usize>,
    /// Worker threads (None: rayon's default, one per core).
    pub threads: Option<usize>,
    /// Run folder.
    pub out: PathBuf,
    /// The protocol.
    pub config: EvalConfig,
}

/// The result of [`evaluate`].
#[derive(Debug, Clone)]
pub struct EvalOutcome {
    /// `summary.json` content.
    pub summary: RunSummary,
    /// Per-episode records, in split-file order.
    pub records: Vec<EpisodeRecord>,
    /// Episodes taken from an earlier, interrupted run.
    pub resumed: usize,
    /// Agent actions run in this call (resumed episodes excluded).
    pub steps_run: u64,
}

fn sim_err(what: &str, value: impl ToString, e: impl ToString) -> TaskError {
    TaskError::invalid(what, value, e.to_string())
}

/// A 64-bit mix (splitmix64), for per-episode seeds.
pub fn episode_seed(seed: u64, episode_id: u64) -> u64 {
    let mut z = seed ^ episode_id.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A scene and what is derived from it, shared by the workers.
pub struct SceneContext {
    /// The scene.
    pub scene: Arc<Scene>,
    /// Its navigable (agent-dilated) map.
    pub navigable: Arc<GridMap>,
    physics: Arc<PhysicsScene>,
    graph: OnceLock<Arc<SceneGraph>>,
    fields: Mutex<BTreeMap<(u32, u32), Arc<DistanceField>>>,
}

/// Distance fields kept per scene (coarse styles share goals); the cache is cleared beyond it.
const FIELD_CACHE: usize = 48;

impl SceneContext {
    /// The scene graph, built on first use (only dialogue episodes need it).
    pub fn graph(&self) -> Arc<SceneGraph> {
        self.graph
            .get_or_init(|| Arc::new(SceneGraph::build(&self.scene)))
            .clone()
    }

    /// Load `dataset/scenes/<id>/` (scene and navigable map) and build its physics world.
    pub fn load(dataset: &Path, scene_id: &str, cfg: &SimConfig) -> Result<Self> {
        let dir = dataset.join("scenes").join(scene_id);
        let scene = vlnverse_env::io::load_scene(&dir)?;
        let navigable = GridMap::load_ros(navigable_map_path(dataset, scene_id))?;
        let physics = PhysicsScene::build(&scene, &cfg.agent)
            .map_err(|e| sim_err("scene", dir.display(), e))?;
        Ok(SceneContext {
            scene: Arc::new(scene),
            navigable: Arc::new(navigable),
            physics: Arc::new(physics),
            graph: OnceLock::new(),
            fields: Mutex::new(BTreeMap::new()),
        })
    }

    /// The distance field to a goal point (cached).
    pub fn field(&self, goal: [f32; 3]) -> Result<Arc<DistanceField>> {
        let key = (goal[0].to_bits(), goal[2].to_bits());
        if let Some(f) = self.lock().get(&key) {
            return Ok(f.clone());
        }
        let f = Arc::new(DistanceField::new(
            &self.navigable,
            Vec2::new(goal[0], goal[2]),
        )?);
        let mut c = self.lock();
        if c.len() >= FIELD_CACHE {
            c.clear();
        }
        c.insert(key, f.clone());
        Ok(f)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, BTreeMap<(u32, u32), Arc<DistanceField>>> {
        self.fields
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// One worker's simulator, rig and agent.
struct Worker {
    sim: RapierSimulator,
    rig: Option<SensorRig>,
    rig_scene: Option<String>,
    agent: Box<dyn Agent>,
}

/// The dialogue oracle as the agent sees it: free-text questions go to the episode's
/// [`ShortestPathOracle`] (true remaining path + scene graph, with the episode's budget).
pub struct DialogueHandle<'a> {
    oracle: &'a mut ShortestPathOracle,
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

/// Everything an episode run needs that does not change between episodes.
struct Shared<'a> {
    req: &'a EvalRequest,
    factory: &'a dyn AgentFactory,
    sim_cfg: SimConfig,
    rig_cfg: RigConfig,
    metrics_cfg: MetricsConfig,
    scenes: Mutex<BTreeMap<String, Arc<SceneContext>>>,
    pool: Mutex<Vec<Worker>>,
    log: ProgressLog,
}

impl Shared<'_> {
    fn scene(&self, id: &str) -> Result<Arc<SceneContext>> {
        if let Some(s) = self.scenes_lock().get(id) {
            return Ok(s.clone());
        }
        let ctx = Arc::new(SceneContext::load(&self.req.dataset, id, &self.sim_cfg)?);
        Ok(self
            .scenes_lock()
            .entry(id.to_string())
            .or_insert(ctx)
            .clone())
    }

    fn scenes_lock(&self) -> std::sync::MutexGuard<'_, BTreeMap<String, Arc<SceneContext>>> {
        self.scenes
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn take_worker(&self, scene: &str) -> Result<Worker> {
        {
            let mut pool = self
                .pool
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            if let Some(i) = pool
                .iter()
                .position(|w| w.rig_scene.as_deref() == Some(scene))
            {
                return Ok(pool.swap_remove(i));
            }
            if let Some(w) = pool.pop() {
                return Ok(w);
            }
        }
        self.new_worker(self.factory.make()?)
    }

    /// A worker around `agent`: its simulator and, when rendering, its rig with the agent's
    /// required sensors attached.
    fn new_worker(&self, agent: Box<dyn Agent>) -> Result<Worker> {
        let sim = RapierSimulator::new(self.sim_cfg.clone())
            .map_err(|e| sim_err("agent_profile", &self.req.config.agent_profile, e))?;
        let rig = if self.req.config.render {
            let mut rig = SensorRig::new(self.rig_cfg.clone())
                .map_err(|e| sim_err("rig", &self.req.config.rig, e))?;
            for spec in agent.required_sensors() {
                if !rig.config().sensors.iter().any(|s| s.name() == spec.name()) {
                    rig.attach(spec)
                        .map_err(|e| sim_err("rig", &self.req.config.rig, e))?;
                }
            }
            Some(rig)
        } else {
            None
        };
        Ok(Worker {
            sim,
            rig,
            rig_scene: None,
            agent,
        })
    }

    fn give_back(&self, w: Worker) {
        self.pool
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(w);
    }

    fn run_episode(&self, ep: &Episode) -> Result<(EpisodeRecord, u64)> {
        let ctx = self.scene(&ep.scene_id)?;
        let mut w = self.take_worker(&ep.scene_id)?;
        let res = self.run_with(&mut w, &ctx, ep);
        self.give_back(w);
        res
    }

    fn run_with(
        &self,
        w: &mut Worker,
        ctx: &SceneContext,
        ep: &Episode,
    ) -> Result<(EpisodeRecord, u64)> {
        let cfg = &self.req.config;
        let goal_fields: Vec<Arc<DistanceField>> = ep
            .goal_sequence()
            .iter()
            .map(|g| ctx.field(g.position))
            .collect::<Result<_>>()?;
        if goal_fields.is_empty() {
            return Err(TaskError::invalid(
                format!("episodes[{}].goals", ep.episode_id),
                "[]",
                "an episode needs a goal",
            ));
        }
        let start = Pose {
            position: ep.start_position,
            rotation: ep.start_rotation,
        };
        let mut pose = w
            .sim
            .reset_in(ctx.physics.clone(), start)
            .map_err(|e| sim_err("start_position", format!("{:?}", ep.start_position), e))?;
        if let Some(rig) = w.rig.as_mut() {
            if w.rig_scene.as_deref() != Some(ep.scene_id.as_str()) {
                rig.set_scene(&ctx.scene)
                    .map_err(|e| sim_err("scene", &ep.scene_id, e))?;
                w.rig_scene = Some(ep.scene_id.clone());
            }
            rig.reset(pose);
        }
        let inputs = EpisodeInputs {
            episode_id: ep.episode_id,
            scene_id: ep.scene_id.clone(),
            task: ep.task,
            instruction: ep.instruction.instruction_text.clone(),
            sub_instructions: ep.instruction.sub_instructions.clone(),
            reference_image: ep.reference_image.as_ref().map(|r| {
                dataset::split_path(&self.req.dataset, self.req.task, self.req.split)
                    .parent()
                    .map(|d| d.join(r))
                    .unwrap_or_else(|| PathBuf::from(r))
            }),
            start: pose,
            agent: self.sim_cfg.agent.clone(),
            action_space: cfg.action_space,
            setting: cfg.setting,
            success_distance: cfg.success_distance,
            max_steps: cfg.max_steps,
            oracle_budget: ep.oracle_budget,
            seed: episode_seed(cfg.seed, ep.episode_id),
        };
        if self.factory.privileged() {
            w.agent.set_truth(&Privileged {
                episode: ep,
                fields: &goal_fields,
            });
        }
        w.agent.reset(&inputs)?;
        let total = goal_fields.len() as u32;
        let mut progress = SubGoalProgress { current: 0, total };
        let mut dialogue = match ep.oracle_budget {
            Some(_) => Some(ShortestPathOracle::for_episode(
                ctx.scene.clone(),
                ctx.graph(),
                ctx.navigable.clone(),
                ep,
                OracleConfig::default(),
            )?),
            None => None,
        };
        let mut positions = vec![pose.position];
        let mut headings = vec![pose.yaw()];
        let mut actions: Vec<String> = Vec::new();
        let mut stops: Vec<u32> = Vec::new();
        let (mut steps, mut collisions, mut stopped) = (0u32, 0u32, false);
        let mut last: Option<StepOutcome> = None;
        let mut failure = None;
        let empty = Observations::new();
        while steps < cfg.max_steps {
            let obs = match w.rig.as_mut() {
                Some(rig) => rig
                    .observe(&AgentState {
                        base: pose,
                        step: steps as u64,
                        time_s: 0.0,
                        collision: CollisionInfo {
                            collided: last.as_ref().is_some_and(|o| o.collided),
                            displacement: last.as_ref().map_or(0.0, |o| {
                                (Vec2::from_array(o.commanded) - Vec2::from_array(o.achieved))
                                    .length()
                            }),
                            count: collisions,
                        },
                    })
                    .map_err(|e| sim_err("rig", &ep.scene_id, e))?,
                None => empty.clone(),
            };
            let mut handle = dialogue
                .as_mut()
                .map(|oracle| DialogueHandle { oracle, pose });
            let action = w.agent.act(&mut StepInput {
                step: steps,
                observations: &obs,
                pose,
                last: last.as_ref(),
                sub_goal: progress,
                oracle: handle.as_mut().map(|h| h as &mut dyn OracleHandle),
            })?;
            if !cfg.action_space.allows(&action) {
                return Err(TaskError::invalid(
                    "action",
                    format!("{action:?}"),
                    format!(
                        "episode {}: not in the {} action space",
                        ep.episode_id,
                        cfg.action_space.name()
                    ),
                ));
            }
            steps += 1;
            actions.push(action_name(&action).to_string());
            if action == Action::Stop {
                if progress.current + 1 < total {
                    // A long-horizon sub-goal declared reached; the episode goes on.
                    stops.push(positions.len() as u32 - 1);
                    progress.current += 1;
                    continue;
                }
                stopped = true;
                break;
            }
            let out = match w.sim.step(action) {
                Ok(o) => o,
                Err(e) => {
                    // An invalid action changes nothing; it still costs a step.
                    tracing::warn!(episode = ep.episode_id, "action refused: {e}");
                    last = None;
                    positions.push(pose.position);
                    headings.push(pose.yaw());
                    continue;
                }
            };
            pose = out.pose;
            positions.push(pose.position);
            headings.push(pose.yaw());
            if out.noticeable {
                collisions += 1;
            }
            let done = out.done;
            if let Some(f) = &out.failure {
                failure = Some(serde_json::to_string(f).unwrap_or_else(|_| format!("{f:?}")));
            }
            last = Some(out);
            if done {
                break;
            }
        }
        w.agent.end_episode()?;
        let traj = Trajectory {
            episode_id: ep.episode_id,
            positions,
            headings: Some(headings),
            stopped,
            collisions,
            steps,
            stops,
            actions: Some(actions),
        };
        let distances = self.distances(ctx, ep, &goal_fields)?;
        let mut metrics = score_episode(ep, &traj, &distances, &self.metrics_cfg);
        metrics.split = Some(self.req.split);
        let rec = EpisodeRecord {
            episode_id: ep.episode_id,
            trajectory: traj,
            metrics,
            failure,
        };
        self.log.append(&rec)?;
        Ok((rec, steps as u64))
    }

    fn distances(
        &self,
        ctx: &SceneContext,
        ep: &Episode,
        seq: &[Arc<DistanceField>],
    ) -> Result<GoalDistances> {
        let goals: Vec<Arc<dyn GoalDistance>> = ep
            .goals
            .iter()
            .map(|g| ctx.field(g.position).map(|f| f as Arc<dyn GoalDistance>))
            .collect::<Result<_>>()?;
        let goal: Arc<dyn GoalDistance> = match goals.len() {
            0 => seq[seq.len() - 1].clone(),
            1 => goals[0].clone(),
            _ => Arc::new(Nearest(goals)),
        };
        let sub_goals = if ep.sub_goals.is_empty() {
            Vec::new()
        } else {
            seq.iter()
                .map(|f| f.clone() as Arc<dyn GoalDistance>)
                .collect()
        };
        Ok(GoalDistances { goal, sub_goals })
    }
}

/// Short action name for trajectories.
pub fn action_name(a: &Action) -> &'static str {
    match a {
        Action::Stop => "stop",
        Action::MoveForward(_) => "move_forward",
        Action::TurnLeft(_) => "turn_left",
        Action::TurnRight(_) => "turn_right",
        Action::LookUp => "look_up",
        Action::LookDown => "look_down",
        Action::Velocity { .. } => "velocity",
        Action::Waypoint { .. } => "waypoint",
    }
}

/// The simulator settings of a protocol.
pub fn sim_config(cfg: &EvalConfig) -> Result<SimConfig> {
    Ok(SimConfig {
        agent: cfg.agent_config()?,
        setting: cfg.setting.collision(),
        seed: cfg.seed,
        ..Default::default()
    })
}

/// Evaluate the agents of `factory` on a split; writes `summary.json`, `episodes.csv`,
/// `report.md`, `trajectories.jsonl`, `progress.jsonl`, `run.json` and `plots/*.png` under
/// `req.out`. Episodes already in `progress.jsonl` are kept, not re-run. `on_episode` is
/// called once per finished episode (progress bars).
pub fn evaluate(
    req: &EvalRequest,
    factory: &dyn AgentFactory,
    on_episode: &(dyn Fn() + Sync),
) -> Result<EvalOutcome> {
    req.config.validate()?;
    if req.episodes == Some(0) {
        return Err(TaskError::invalid(
            "episodes",
            0,
            "must be at least 1 (leave it out to run the whole split)",
        ));
    }
    let mut episodes = dataset::read_split(&req.dataset, req.task, req.split)?;
    if let Some(n) = req.episodes {
        episodes.truncate(n);
    }
    // An agent that looks would run blind: refuse before anything is written, so the same
    // folder can be used again once rendering is on.
    let probe = if req.config.render {
        None
    } else {
        let agent = factory.make()?;
        let needs: Vec<String> = agent
            .required_sensors()
            .iter()
            .map(|s| s.name().to_string())
            .collect();
        if !needs.is_empty() {
            return Err(TaskError::invalid(
                "render",
                false,
                format!(
                    "agent `{}` looks at its sensors ({}) and would run blind without \
                     rendering; drop --no-render / set `render = true`",
                    factory.name(),
                    needs.join(", ")
                ),
            ));
        }
        Some(agent)
    };
    std::fs::create_dir_all(&req.out).map_err(|e| TaskError::io(&req.out, e))?;
    let identity = run_identity(req, factory)?;
    resume::check_or_write_identity(&req.out, &identity)?;
    let progress_path = req.out.join(PROGRESS_FILE);
    let mut done: BTreeMap<u64, EpisodeRecord> = resume::load_progress(&progress_path)?
        .into_iter()
        .map(|r| (r.episode_id, r))
        .collect();
    let todo: Vec<&Episode> = {
        let mut v: Vec<&Episode> = episodes
            .iter()
            .filter(|e| !done.contains_key(&e.episode_id))
            .collect();
        // Scene order keeps each worker in one scene for long stretches.
        v.sort_by(|a, b| a.scene_id.cmp(&b.scene_id));
        v
    };
    let resumed = episodes.len() - todo.len();
    let shared = Shared {
        req,
        factory,
        sim_cfg: sim_config(&req.config)?,
        rig_cfg: req.config.rig_config()?,
        metrics_cfg: MetricsConfig {
            success_distance: req.config.success_distance,
            fail_on_collision: req.config.setting == Setting::Strict,
            ..Default::default()
        },
        scenes: Mutex::new(BTreeMap::new()),
        pool: Mutex::new(Vec::new()),
        log: ProgressLog::open(&progress_path)?,
    };
    if let Some(agent) = probe.filter(|_| !todo.is_empty()) {
        // The probe agent becomes the first worker, so nothing is made twice.
        let w = shared.new_worker(agent)?;
        shared.give_back(w);
    }
    let run = || -> Vec<Result<(EpisodeRecord, u64)>> {
        todo.par_iter()
            .with_max_len(4)
            .map(|ep| {
                let r = shared.run_episode(ep);
                on_episode();
                r
            })
            .collect()
    };
    let results = match req.threads {
        Some(k) => rayon::ThreadPoolBuilder::new()
            .num_threads(k.max(1))
            .build()
            .map_err(|e| TaskError::invalid("threads", k, e.to_string()))?
            .install(run),
        None => run(),
    };
    let mut steps_run = 0;
    for r in results {
        let (rec, steps) = r?;
        steps_run += steps;
        done.insert(rec.episode_id, rec);
    }
    let records: Vec<EpisodeRecord> = episodes
        .iter()
        .filter_map(|e| done.remove(&e.episode_id))
        .collect();
    let metrics: Vec<_> = records.iter().map(|r| r.metrics.clone()).collect();
    let summary = RunSummary::new(
        &factory.name(),
        Some(req.config.setting.name()),
        req.task,
        req.split,
        &metrics,
    );
    write_run(&req.out, &summary, &metrics)?;
    let trajs: Vec<Trajectory> = records.iter().map(|r| r.trajectory.clone()).collect();
    write_jsonl(&req.out.join("trajectories.jsonl"), &trajs)?;
    write_plots(req, &shared, &episodes, &records)?;
    Ok(EvalOutcome {
        summary,
        records,
        resumed,
        steps_run,
    })
}

/// What makes a run's results what they are, in the order a mismatch is reported (the first
/// differing key is named): `run.json` of the run folder. Besides the protocol's names and
/// paths it records their contents (`agent_config`, `rig_config`), so an edited file is noticed. Thread count and episode count are
/// left out (a resume may use other values).
pub fn run_identity(
    req: &EvalRequest,
    factory: &dyn AgentFactory,
) -> Result<Vec<(&'static str, serde_json::Value)>> {
    use serde_json::{json, to_value};
    let cfg = &req.config;
    let value = |what: &str, v: std::result::Result<serde_json::Value, serde_json::Error>| {
        v.map_err(|e| TaskError::invalid(what, "<config>", e.to_string()))
    };
    let rig_path = if cfg.rig.trim().is_empty() {
        String::new()
    } else {
        cfg.resolve(&cfg.rig).display().to_string()
    };
    Ok(vec![
        ("setting", json!(cfg.setting.name())),
        ("task", json!(req.task.name())),
        ("split", json!(req.split.name())),
        ("dataset", json!(req.dataset.display().to_string())),
        ("agent", json!(factory.name())),
        ("agent_cmd", json!(factory.command())),
        ("action_space", json!(cfg.action_space.name())),
        ("max_steps", json!(cfg.max_steps)),
        ("success_distance", json!(cfg.success_distance)),
        ("agent_profile", json!(cfg.agent_profile)),
        ("rig", json!(rig_path)),
        ("backend", value("backend", to_value(cfg.backend))?),
        ("render", json!(cfg.render)),
        (
            "external_observations",
            value("external_observations", to_value(cfg.external_observations))?,
        ),
        ("seed", json!(cfg.seed)),
        // What the names and paths above resolve to, last: a profile or rig file edited
        // between the runs.
        (
            "agent_config",
            value("agent_profile", to_value(cfg.agent_config()?))?,
        ),
        ("rig_config", value("rig", to_value(cfg.rig_config()?))?),
    ])
}

fn write_plots(
    req: &EvalRequest,
    shared: &Shared,
    episodes: &[Episode],
    records: &[EpisodeRecord],
) -> Result<()> {
    let dir = req.out.join("plots");
    for i in plots::sample_indices(records.len(), req.config.plots as usize) {
        let rec = &records[i];
        let Some(ep) = episodes.iter().find(|e| e.episode_id == rec.episode_id) else {
            continue;
        };
        let ctx = shared.scene(&ep.scene_id)?;
        let img = plots::plot_episode(
            &ctx.scene,
            Some(&ctx.navigable),
            ep,
            &rec.trajectory,
            &rec.metrics,
        );
        plots::save_png(&dir.join(format!("episode_{}.png", ep.episode_id)), &img)?;
    }
    Ok(())
}
