//! The evaluation runner: episodes of a split run in parallel (rayon), each through the one
//! episode loop ([`run_episode`]); finished episodes are appended to the run's progress log,
//! so an interrupted run resumes where it stopped. Every random choice is seeded per episode,
//! so results do not depend on the thread count or on the order episodes finish in.
//!
//! [`evaluate`] runs today's defaults (the Rapier simulator, the configured renderer backend);
//! [`evaluate_with`] takes [`Layers`]: factories for the simulator and the renderer (a user's
//! own backend runs under exactly the same rules) and an optional progress callback.
//!
//! ```no_run
//! use vlnverse_eval::{evaluate_with, rapier_simulator, EvalRequest, Layers};
//! use vlnverse_score::{Split, Task};
//!
//! # fn main() -> vlnverse_eval::Result<()> {
//! let req = EvalRequest::new("data/tiny", Task::Fine, Split::Test, "runs/x")
//!     .episodes(10)
//!     .threads(2);
//! let agent = vlnverse_eval::agents::builtin("forward", None, &req.config)?;
//! let layers = Layers::default()
//!     .simulators(rapier_simulator)
//!     .on_episode(&|| eprint!("."));
//! let outcome = evaluate_with(&req, &*agent, layers)?;
//! # Ok(()) }
//! ```

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use rayon::prelude::*;
use vlnverse_sensors::{create_renderer, RasterRenderer, Renderer, RigConfig, SensorRig};
use vlnverse_sim::{PhysicsCache, RapierSimulator, SimConfig, Simulator};

use crate::agent::{Agent, AgentFactory};
use crate::episode_loop::{check_episode, run_episode, ActionKind, EpisodeSettings};
use crate::episode_store::{EpisodeStore, Slot};
use crate::error::{Result, TaskError};
use crate::plots;
use crate::protocol::EvalConfig;
use crate::resume::{self, EpisodeRecord, ProgressLines, ProgressLog, PROGRESS_FILE, RUN_FILE};
use crate::scene_context::SceneCache;
use vlnverse_score::dataset;
use vlnverse_score::episode::{Episode, Split, Task};
use vlnverse_score::metrics::EpisodeMetrics;
use vlnverse_score::report::{write_run, RunSummary};
use vlnverse_score::sample::{sample_episodes, Sample};
use vlnverse_score::trajectory::{to_json_line, Trajectory};
use vlnverse_score::OutputLock;

/// What to evaluate and where the results go: [`EvalRequest::new`] and the chainable
/// setters.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct EvalRequest {
    /// Dataset folder (`<task>/<split>/<split>.json.gz`, `scenes/<scene_id>/`).
    pub dataset: PathBuf,
    /// Task.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// Only the first N episodes of the split file.
    pub episodes: Option<usize>,
    /// A seeded random sample of the split spread over its scenes (the zero-shot protocol);
    /// excludes `episodes`.
    pub sample: Option<Sample>,
    /// Worker threads (None: rayon's default, one per core).
    pub threads: Option<usize>,
    /// Run folder.
    pub out: PathBuf,
    /// Start over: delete an earlier run's files in `out` instead of resuming it.
    pub fresh: bool,
    /// The protocol.
    pub config: EvalConfig,
}

impl EvalRequest {
    /// The whole split of `task` in `dataset`, written to `out`, under the default protocol,
    /// on rayon's default threads, resuming what `out` holds.
    pub fn new(
        dataset: impl Into<PathBuf>,
        task: Task,
        split: Split,
        out: impl Into<PathBuf>,
    ) -> Self {
        EvalRequest {
            dataset: dataset.into(),
            task,
            split,
            episodes: None,
            sample: None,
            threads: None,
            out: out.into(),
            fresh: false,
            config: EvalConfig::default(),
        }
    }

    /// Only the first `n` episodes of the split file (None: all).
    pub fn episodes(mut self, n: impl Into<Option<usize>>) -> Self {
        self.episodes = n.into();
        self
    }

    /// A seeded random sample of the split (None: no sampling).
    pub fn sample(mut self, sample: impl Into<Option<Sample>>) -> Self {
        self.sample = sample.into();
        self
    }

    /// Worker threads (None: one per core).
    pub fn threads(mut self, n: impl Into<Option<usize>>) -> Self {
        self.threads = n.into();
        self
    }

    /// Delete an earlier run's files in `out` instead of resuming it.
    pub fn fresh(mut self, fresh: bool) -> Self {
        self.fresh = fresh;
        self
    }

    /// The protocol.
    pub fn config(mut self, config: EvalConfig) -> Self {
        self.config = config;
        self
    }

    /// Another run folder.
    pub fn out(mut self, out: impl Into<PathBuf>) -> Self {
        self.out = out.into();
        self
    }
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

/// Most worker threads a run may ask for: each holds a simulator, a renderer and an agent, so a
/// mistyped count is refused instead of spawning threads without end.
pub const MAX_THREADS: usize = 1024;

/// Scenes the cache holds beyond one per worker thread (it holds `threads + this`) while the
/// split is checked and while a batch of small homes runs; a run lets its homes go after each
/// batch ([`home_batches`]). When the split is checked in scene order, one spare home loaded no
/// home more often than two did (coarse test and train of the `vlnverse` preset: 113 and 362
/// loads with either, 137 and 459 with none).
const SCENE_CACHE_SLACK: usize = 1;

/// Episodes per worker a batch of homes holds at least before it ends at a home boundary
/// ([`home_batches`]).
const BATCH_PER_WORKER: usize = 8;

/// `todo` (in scene order) cut at home boundaries into batches: a home with at least `min`
/// episodes alone, the homes between such homes together, `min` episodes or more a batch
/// (the last may hold fewer).
fn home_batches(todo: &[Slot], min: usize) -> Vec<&[Slot]> {
    let mut batches = Vec::new();
    let (mut start, mut home) = (0, 0);
    for i in 1..=todo.len() {
        if i < todo.len() && todo[i].scene() == todo[i - 1].scene() {
            continue;
        }
        // `todo[home..i]` is one home's episodes; `todo[start..home]` the small homes before it.
        if i - home >= min && home > start {
            batches.push(&todo[start..home]);
            start = home;
        }
        if i - start >= min || i == todo.len() {
            batches.push(&todo[start..i]);
            start = i;
        }
        home = i;
    }
    batches
}

/// Files of a run folder that [`evaluate`] writes (`plots/` besides).
pub const RUN_FILES: [&str; 6] = [
    RUN_FILE,
    PROGRESS_FILE,
    "summary.json",
    "episodes.csv",
    "report.md",
    "trajectories.jsonl",
];

/// One worker's simulator, rig and agent.
struct Worker<S> {
    sim: S,
    rig: Option<SensorRig>,
    agent: Box<dyn Agent>,
}

/// Makes a simulator for an evaluation's settings. Closures `Fn(&SimConfig) ->
/// Result<S>` are factories.
pub trait SimulatorFactory: Sync {
    /// The simulator type.
    type Sim: Simulator;
    /// A fresh simulator with these settings.
    fn make(&self, cfg: &SimConfig) -> Result<Self::Sim>;
    /// What the simulators are beyond their [`Simulator::name`] (a version, a hash of the
    /// engine's files): recorded in `run.json`, and a resume with another is refused. `None`
    /// (the default) records nothing beyond the name.
    fn fingerprint(&self) -> Option<String> {
        None
    }
}

impl<S: Simulator, F: Fn(&SimConfig) -> Result<S> + Sync> SimulatorFactory for F {
    type Sim = S;
    fn make(&self, cfg: &SimConfig) -> Result<S> {
        self(cfg)
    }
}

/// Makes a renderer for an evaluation's rig. Closures `Fn(&RigConfig) ->
/// Result<Box<dyn Renderer>>` are factories.
pub trait RendererFactory: Sync {
    /// A fresh renderer for this rig.
    fn make(&self, rig: &RigConfig) -> Result<Box<dyn Renderer>>;
    /// What the renderers are beyond their [`Renderer::name`]; see
    /// [`SimulatorFactory::fingerprint`].
    fn fingerprint(&self) -> Option<String> {
        None
    }
}

impl<F: Fn(&RigConfig) -> Result<Box<dyn Renderer>> + Sync> RendererFactory for F {
    fn make(&self, rig: &RigConfig) -> Result<Box<dyn Renderer>> {
        self(rig)
    }
}

/// The default simulator: [`RapierSimulator`].
pub fn rapier_simulator(cfg: &SimConfig) -> Result<RapierSimulator> {
    Ok(RapierSimulator::new(cfg.clone())?)
}

/// Megabytes of physics worlds kept for the simulators of [`evaluation_simulator`] (unless
/// [`vlnverse_sim::physics_cache::PHYSICS_CACHE_MB_VAR`] says otherwise) besides the newest
/// world, which is always kept. An evaluation runs a split home by home, so a home's world is
/// asked for again only while the workers are in that home: the newest is all it uses (16 MB,
/// the budget before runs went home by home, added 10 MB to a coarse test run's peak and took
/// no less time). (The process-wide cache of [`RapierSimulator::new`] keeps 512 MB for
/// training, which comes back to homes; an evaluation on it kept every home it had visited,
/// growing with the split.)
pub const EVAL_PHYSICS_CACHE_MB: usize = 0;

/// The physics worlds of [`evaluation_simulator`]s, process-wide (budget read once).
fn evaluation_physics() -> Arc<PhysicsCache> {
    static CACHE: OnceLock<Arc<PhysicsCache>> = OnceLock::new();
    CACHE
        .get_or_init(|| {
            Arc::new(PhysicsCache::new(vlnverse_env::cache::budget_from_env(
                vlnverse_sim::physics_cache::PHYSICS_CACHE_MB_VAR,
                EVAL_PHYSICS_CACHE_MB,
            )))
        })
        .clone()
}

/// The default simulator of an evaluation ([`Layers::default`]): a [`RapierSimulator`] whose
/// physics worlds come from a cache of [`EVAL_PHYSICS_CACHE_MB`], so that an evaluation's
/// memory stays flat in the number of homes of its split (same worlds, same results as
/// [`rapier_simulator`]).
pub fn evaluation_simulator(cfg: &SimConfig) -> Result<RapierSimulator> {
    Ok(RapierSimulator::with_cache(
        cfg.clone(),
        evaluation_physics(),
    )?)
}

/// The default renderer: the backend the rig (or the protocol's override) names.
pub fn configured_renderer(rig: &RigConfig) -> Result<Box<dyn Renderer>> {
    Ok(create_renderer(rig.backend)?)
}

/// Type of [`evaluation_simulator`], the default simulator factory of [`Layers`].
pub type DefaultSimulators = fn(&SimConfig) -> Result<RapierSimulator>;
/// The default renderer of an evaluation ([`Layers::default`]): [`configured_renderer`], except
/// that the CPU rasteriser keeps its prepared scenes in the small cache of
/// [`RasterRenderer::visiting_once`] (an evaluation runs a split in scene order and does not come
/// back to a home it left), so that its memory stays flat in the number of homes. The same
/// backend and images.
pub fn evaluation_renderer(rig: &RigConfig) -> Result<Box<dyn Renderer>> {
    let r = configured_renderer(rig)?;
    if r.name() == RasterRenderer::new().name() {
        return Ok(Box::new(RasterRenderer::visiting_once()));
    }
    Ok(r)
}

/// Type of [`evaluation_renderer`], the default renderer factory of [`Layers`].
pub type DefaultRenderers = fn(&RigConfig) -> Result<Box<dyn Renderer>>;

/// The layers an evaluation runs on besides the agent, for [`evaluate_with`]: a simulator
/// factory, a renderer factory (one of each per worker thread) and an optional callback called
/// once per finished episode (progress bars). [`Layers::default`] is what [`evaluate`] uses;
/// replace a part with the chainable setters.
pub struct Layers<'a, SF = DefaultSimulators, RF = DefaultRenderers> {
    /// Makes the simulators.
    pub simulators: SF,
    /// Makes the renderers (when the protocol renders).
    pub renderers: RF,
    /// Called once per finished episode.
    pub on_episode: Option<&'a (dyn Fn() + Sync)>,
}

impl Default for Layers<'_> {
    fn default() -> Self {
        Layers {
            simulators: evaluation_simulator,
            renderers: evaluation_renderer,
            on_episode: None,
        }
    }
}

impl<SF, RF> std::fmt::Debug for Layers<'_, SF, RF> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Layers")
            .field("on_episode", &self.on_episode.is_some())
            .finish_non_exhaustive()
    }
}

impl<'a, SF, RF> Layers<'a, SF, RF> {
    /// Simulators from `simulators` instead.
    pub fn simulators<S2: SimulatorFactory>(self, simulators: S2) -> Layers<'a, S2, RF> {
        Layers {
            simulators,
            renderers: self.renderers,
            on_episode: self.on_episode,
        }
    }

    /// Renderers from `renderers` instead.
    pub fn renderers<R2: RendererFactory>(self, renderers: R2) -> Layers<'a, SF, R2> {
        Layers {
            simulators: self.simulators,
            renderers,
            on_episode: self.on_episode,
        }
    }

    /// Call `f` once per finished episode.
    pub fn on_episode(mut self, f: &'a (dyn Fn() + Sync)) -> Self {
        self.on_episode = Some(f);
        self
    }
}

/// What ran a run besides the agent, as `run.json` records it: the simulator, the renderer
/// (none when the protocol does not render) and the sensor rig, each by name and fingerprint.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct LayerIdentity {
    /// [`Simulator::name`].
    pub simulator: String,
    /// [`SimulatorFactory::fingerprint`].
    pub simulator_fingerprint: Option<String>,
    /// [`Renderer::name`] (None without rendering).
    pub renderer: Option<String>,
    /// [`RendererFactory::fingerprint`].
    pub renderer_fingerprint: Option<String>,
    /// A hash of the rig as it runs (the agent's sensors attached), None without rendering.
    pub rig_fingerprint: Option<String>,
}

impl LayerIdentity {
    /// The identity of a simulator and a rig made by these factories.
    pub fn of<S: Simulator>(
        sim: &S,
        sims: &impl SimulatorFactory,
        rig: Option<&SensorRig>,
        renderers: &impl RendererFactory,
    ) -> Result<Self> {
        Ok(LayerIdentity {
            simulator: sim.name(),
            simulator_fingerprint: sims.fingerprint(),
            renderer: rig.map(SensorRig::backend_name),
            renderer_fingerprint: rig.and_then(|_| renderers.fingerprint()),
            rig_fingerprint: rig.map(|r| rig_fingerprint(r.config())).transpose()?,
        })
    }

    /// The identity of the default layers ([`Layers::default`]) for `req`'s protocol: makes
    /// one simulator and, when rendering, one renderer to ask their names (for runs whose
    /// episodes are driven from outside, as Python's run folders).
    pub fn of_defaults(req: &EvalRequest) -> Result<Self> {
        let layers = Layers::default();
        let sim = layers.simulators.make(&sim_config(&req.config)?)?;
        let rig = if req.config.render {
            let rig_cfg = req.config.rig_config()?;
            Some(SensorRig::with_renderer(
                rig_cfg.clone(),
                layers.renderers.make(&rig_cfg)?,
            ))
        } else {
            None
        };
        LayerIdentity::of(&sim, &layers.simulators, rig.as_ref(), &layers.renderers)
    }
}

/// A stable hash (hex) of a rig's settings.
fn rig_fingerprint(rig: &RigConfig) -> Result<String> {
    let json = serde_json::to_vec(rig)
        .map_err(|e| TaskError::invalid("rig", "<config>", e.to_string()))?;
    let mut key = vlnverse_env::cache::ContentKey::new();
    key.bytes(&json);
    Ok(format!("{:016x}", key.finish()))
}

/// Everything an episode run needs that does not change between episodes.
struct Shared<'a, SF: SimulatorFactory, RF> {
    req: &'a EvalRequest,
    factory: &'a dyn AgentFactory,
    sims: &'a SF,
    renderers: &'a RF,
    sim_cfg: SimConfig,
    rig_cfg: RigConfig,
    settings: EpisodeSettings,
    split_file: PathBuf,
    /// Split-file index of each episode id (errors name both).
    index: BTreeMap<u64, usize>,
    scenes: SceneCache,
    pool: Mutex<Vec<Worker<SF::Sim>>>,
}

impl<SF: SimulatorFactory, RF: RendererFactory> Shared<'_, SF, RF> {
    fn take_worker(&self, scene: &str) -> Result<Worker<SF::Sim>> {
        {
            let mut pool = self
                .pool
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            if let Some(i) = pool
                .iter()
                .position(|w| w.rig.as_ref().and_then(|r| r.scene_id()) == Some(scene))
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
    fn new_worker(&self, agent: Box<dyn Agent>) -> Result<Worker<SF::Sim>> {
        let sim = self.sims.make(&self.sim_cfg)?;
        let rig = if self.req.config.render {
            let renderer = self.renderers.make(&self.rig_cfg)?;
            let mut rig = SensorRig::with_renderer(self.rig_cfg.clone(), renderer);
            for spec in agent.required_sensors() {
                if !rig.config().sensors.iter().any(|s| s.name() == spec.name()) {
                    rig.attach(spec)?;
                }
            }
            Some(rig)
        } else {
            None
        };
        Ok(Worker { sim, rig, agent })
    }

    /// The first worker, made before anything is written: an agent that looks at its
    /// sensors is refused when rendering is off (it would run blind).
    fn probe_worker(&self) -> Result<Worker<SF::Sim>> {
        let agent = self.factory.make()?;
        if !self.req.config.render {
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
                        self.factory.name(),
                        needs.join(", ")
                    ),
                ));
            }
        }
        self.new_worker(agent)
    }

    fn give_back(&self, w: Worker<SF::Sim>) {
        self.pool
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(w);
    }

    /// Where an episode is, for errors: `FILE: episode ID (episodes[I])`.
    fn locate(&self, ep: &Episode) -> String {
        format!(
            "{}: episode {} (episodes[{}])",
            self.split_file.display(),
            ep.episode_id,
            self.index.get(&ep.episode_id).copied().unwrap_or(0)
        )
    }

    fn run(&self, ep: &Episode, log: &ProgressLog) -> Result<EpisodeRecord> {
        let ctx = self.scenes.get(&ep.scene_id).map_err(|e| {
            TaskError::invalid(
                format!("{}.scene_id", self.locate(ep)),
                &ep.scene_id,
                e.to_string(),
            )
        })?;
        check_episode(ep, &ctx).map_err(|e| e.at(&self.locate(ep)))?;
        let mut w = self.take_worker(&ep.scene_id)?;
        let res = run_episode(
            &mut w.sim,
            w.rig.as_mut(),
            w.agent.as_mut(),
            ep,
            &ctx,
            &self.settings,
        );
        self.give_back(w);
        let mut rec = res?;
        log.append(&mut rec)?;
        Ok(rec)
    }
}

/// Check every episode of `episodes` in its scene ([`check_episode`]) before anything is
/// written, so an impossible episode late in a split fails the run at its start instead of
/// leaving a half-made run folder. Scenes come from `scenes` (one at a time per thread, in
/// scene order); the first bad episode in split order is reported, naming `split_file`.
pub fn check_split(split_file: &Path, episodes: &[Episode], scenes: &SceneCache) -> Result<()> {
    let mut order: Vec<usize> = (0..episodes.len()).collect();
    order.sort_by(|&a, &b| episodes[a].scene_id.cmp(&episodes[b].scene_id));
    let errors: Vec<(usize, TaskError)> = order
        .par_iter()
        .with_max_len(8)
        .filter_map(|&i| {
            let ep = &episodes[i];
            let at = format!(
                "{}: episode {} (episodes[{i}])",
                split_file.display(),
                ep.episode_id
            );
            let checked = scenes
                .get(&ep.scene_id)
                .map_err(|e| {
                    TaskError::invalid(format!("{at}.scene_id"), &ep.scene_id, e.to_string())
                })
                .and_then(|ctx| check_episode(ep, &ctx).map_err(|e| e.at(&at)));
            checked.err().map(|e| (i, e))
        })
        .collect();
    match errors.into_iter().min_by_key(|(i, _)| *i) {
        Some((_, e)) => Err(e),
        None => Ok(()),
    }
}

/// A run folder is a folder (made if missing) and not a dataset's folder, whose files the
/// run's would mix with.
pub fn check_run_folder(out: &Path) -> Result<()> {
    vlnverse_score::lock::check_is_folder(out)?;
    Ok(vlnverse_score::lock::refuse_dataset_folder(out)?)
}

/// Run `f` on a pool of `threads` threads (rayon's global pool when None).
fn in_pool<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> Result<T> {
    match threads {
        Some(k) => Ok(rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .map_err(|e| TaskError::invalid("threads", k, e.to_string()))?
            .install(f)),
        None => Ok(f()),
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

/// Evaluate the agents of `factory` on a split with the default layers (the Rapier simulator,
/// the configured renderer, no progress callback); see [`evaluate_with`].
pub fn evaluate(req: &EvalRequest, factory: &dyn AgentFactory) -> Result<EvalOutcome> {
    evaluate_with(req, factory, Layers::default())
}

/// Evaluate the agents of `factory` on a split, with simulators and renderers from `layers`
/// (one of each per worker thread); writes `summary.json`, `episodes.csv`, `report.md`,
/// `trajectories.jsonl`, `progress.jsonl`, `run.json` and `plots/*.png` under `req.out`.
/// Episodes already in `progress.jsonl` are kept, not re-run; a folder of a run made with
/// another agent, simulator, renderer or rig is refused (`run.json`).
///
/// The folder is locked for the run (a second job on it is refused). Nothing is written
/// before the inputs are checked, and a run that fails before its first episode finishes
/// leaves the folder as it found it.
pub fn evaluate_with<SF: SimulatorFactory, RF: RendererFactory>(
    req: &EvalRequest,
    factory: &dyn AgentFactory,
    layers: Layers<'_, SF, RF>,
) -> Result<EvalOutcome> {
    req.config.validate()?;
    if req.episodes == Some(0) {
        return Err(TaskError::invalid(
            "episodes",
            0,
            "must be at least 1 (leave it out to run the whole split)",
        ));
    }
    if let Some(n) = req.threads.filter(|n| !(1..=MAX_THREADS).contains(n)) {
        return Err(TaskError::invalid(
            "threads",
            n,
            format!("must be in [1, {MAX_THREADS}] (leave it out for one per core)"),
        ));
    }
    check_run_folder(&req.out)?;
    let split_file = dataset::split_path(&req.dataset, req.task, req.split);
    let mut episodes = dataset::read_split(&req.dataset, req.task, req.split)?;
    if episodes.is_empty() {
        return Err(TaskError::invalid(
            "episodes",
            split_file.display(),
            "the split has no episodes",
        ));
    }
    let total_in_split = episodes.len();
    episodes = select_episodes(req, episodes)?;
    let mut settings = EpisodeSettings::new(&req.config)?;
    settings.privileged = factory.privileged();
    settings.split = Some(req.split);
    settings.reference_dir = split_file.parent().map(Path::to_path_buf);
    let shared = Shared {
        req,
        factory,
        sims: &layers.simulators,
        renderers: &layers.renderers,
        sim_cfg: sim_config(&req.config)?,
        rig_cfg: req.config.rig_config()?,
        settings,
        index: episodes
            .iter()
            .enumerate()
            .map(|(i, e)| (e.episode_id, i))
            .collect(),
        split_file,
        scenes: SceneCache::new(&req.dataset, workers(req) + SCENE_CACHE_SLACK),
        pool: Mutex::new(Vec::new()),
    };
    // Make one agent, simulator and renderer before anything is written: a bad profile, rig
    // or agent command fails here and leaves no folder behind; they become the first worker.
    let probe = shared.probe_worker()?;
    let layer_identity = LayerIdentity::of(
        &probe.sim,
        shared.sims,
        probe.rig.as_ref(),
        shared.renderers,
    )?;
    shared.give_back(probe);
    in_pool(req.threads, || {
        check_split(&shared.split_file, &episodes, &shared.scenes)
    })??;
    let identity = run_identity(req, factory, &layer_identity)?;
    let created = !req.out.exists();
    let lock = OutputLock::acquire(&req.out, "evaluate")?;
    let result = evaluate_locked(
        &shared,
        &identity,
        episodes,
        total_in_split,
        layers.on_episode,
    );
    // The workers and the scenes go before the records are read back from the log: the
    // records take room the run no longer needs instead of adding to its peak.
    drop(shared);
    let result = result.and_then(Finished::outcome);
    if result.is_err() {
        clean_failed_start(&req.out, created);
    }
    drop(lock);
    if result.is_err() && created {
        let _ = std::fs::remove_file(req.out.join(vlnverse_score::lock::LOCK_FILE));
        let _ = std::fs::remove_dir(&req.out);
    }
    result
}

/// Worker threads of a run of `req`.
fn workers(req: &EvalRequest) -> usize {
    req.threads.unwrap_or_else(rayon::current_num_threads)
}

/// The episodes `req` asks for: the first `episodes`, a `sample`, or all.
pub fn select_episodes(req: &EvalRequest, mut episodes: Vec<Episode>) -> Result<Vec<Episode>> {
    match (req.episodes, req.sample) {
        (Some(_), Some(_)) => Err(TaskError::invalid(
            "sample",
            "with episodes",
            "choose one: the first N episodes (--episodes) or a seeded sample (--sample)",
        )),
        (_, Some(s)) if s.count == 0 => Err(TaskError::invalid(
            "sample",
            0,
            "must be at least 1 (leave it out to run the whole split)",
        )),
        (Some(n), None) => {
            episodes.truncate(n);
            Ok(episodes)
        }
        (None, Some(s)) => Ok(sample_episodes(episodes, s)),
        (None, None) => Ok(episodes),
    }
}

/// After a failure: if no episode was recorded, remove what this call wrote (run.json and an
/// empty progress log), so the folder is as it was.
fn clean_failed_start(out: &Path, created: bool) {
    let progress = out.join(PROGRESS_FILE);
    let empty = std::fs::metadata(&progress).map_or(true, |m| m.len() == 0);
    if !empty {
        return;
    }
    let _ = std::fs::remove_file(&progress);
    if created {
        let _ = std::fs::remove_file(out.join(RUN_FILE));
    }
}

fn evaluate_locked<SF: SimulatorFactory, RF: RendererFactory>(
    shared: &Shared<'_, SF, RF>,
    identity: &[(&'static str, serde_json::Value)],
    episodes: Vec<Episode>,
    total_in_split: usize,
    on_episode: Option<&(dyn Fn() + Sync)>,
) -> Result<Finished> {
    let req = shared.req;
    let done = open_run(req, identity, total_in_split)?;
    resume::check_unchanged(&shared.split_file, &episodes, &done)?;
    let progress = req.out.join(PROGRESS_FILE);
    let log = ProgressLog::open(&progress)?.for_episodes(&episodes)?;
    // From here on the episodes are held packed by scene, a scene's unpacked while workers
    // are in it: the split's size does not add to the run's memory.
    let store = EpisodeStore::pack(episodes, workers(req) + SCENE_CACHE_SLACK)?;
    // Scene order keeps each worker in one scene for long stretches, and the scene cache
    // small.
    let todo: Vec<Slot> = store
        .in_scene_order()
        .into_iter()
        .filter(|(id, _)| !done.contains_key(id))
        .map(|(_, slot)| slot)
        .collect();
    let resumed = store.len() - todo.len();
    // The first failure stops the run (no further episodes start): a broken agent or
    // simulator would otherwise fail, or wait out its timeout, once per remaining episode.
    // A finished episode's record is in the log; only its metrics are kept here (the
    // trajectories are read back from the log when the files are written).
    let run_one = |slot: Slot| {
        let r = store
            .get(slot)
            .and_then(|ep| shared.run(&ep, &log))
            .map(|rec| (rec.episode_id, rec.trajectory.steps, rec.metrics));
        if let Some(f) = on_episode {
            f();
        }
        r
    };
    // Home by home: the workers share a home's episodes, handed out in order, and the next
    // home starts once they are done, so one home is held at a time, whatever the split's
    // size. Homes with few episodes go in batches, to keep every worker busy.
    let run = || -> Result<Vec<(u64, u32, EpisodeMetrics)>> {
        let mut results = Vec::with_capacity(todo.len());
        for batch in home_batches(&todo, BATCH_PER_WORKER * workers(req)) {
            let done: Vec<_> = batch
                .iter()
                .par_bridge()
                .map(|&slot| run_one(slot))
                .collect::<Result<_>>()?;
            results.extend(done);
            shared.scenes.clear();
        }
        Ok(results)
    };
    let results = in_pool(req.threads, run)??;
    drop(log);
    let mut steps_run = 0;
    let mut metrics: BTreeMap<u64, EpisodeMetrics> =
        done.into_iter().map(|(id, r)| (id, r.metrics)).collect();
    for (id, steps, m) in results {
        steps_run += steps as u64;
        metrics.insert(id, m);
    }
    let lines = ProgressLines::index(&progress)?;
    let (ids, metrics): (Vec<u64>, Vec<EpisodeMetrics>) = store
        .in_split_order()
        .filter_map(|(id, _)| metrics.remove(&id).map(|m| (id, m)))
        .unzip();
    let agent = shared.factory.name();
    let find = |id| Ok(store.find(id)?.map(|e| Cow::Owned(e.clone())));
    let summary = write_results(req, &agent, &metrics, &shared.scenes, find, |i| {
        Ok(Cow::Owned(read_record(&lines, ids[i], &mut Vec::new())?))
    })
    .and_then(|summary| {
        write_logged_trajectories(&req.out.join("trajectories.jsonl"), &lines, &ids)?;
        Ok(summary)
    })?;
    Ok(Finished {
        summary,
        ids,
        lines,
        resumed,
        steps_run,
    })
}

/// Write `trajectories.jsonl` at `path` for the episodes `ids` (split order), each read back
/// from its line in the run's log: the same file whichever order the episodes finished (and
/// were logged) in.
fn write_logged_trajectories(path: &Path, lines: &ProgressLines, ids: &[u64]) -> Result<()> {
    let mut buf = Vec::new();
    write_trajectories(
        path,
        ids.iter().map(|&id| {
            let t: Option<TrajectoryOf> = lines.read(id, &mut buf)?;
            let t = t.ok_or_else(|| missing_line(lines.path(), id))?;
            Ok(Cow::Owned(t.trajectory))
        }),
    )
}

/// The trajectory of a `progress.jsonl` line, the rest skipped.
#[derive(serde::Deserialize)]
struct TrajectoryOf {
    trajectory: Trajectory,
}

/// An episode the run recorded whose line the log lost (it was edited during the run).
fn missing_line(progress: &Path, id: u64) -> TaskError {
    TaskError::invalid(
        format!("{}: episode {id}", progress.display()),
        id,
        "the run recorded this episode but the log has no line of it (was the file changed \
         during the run?); rerun the folder to write its results",
    )
}

/// Episode `id`'s whole record from the log.
fn read_record(lines: &ProgressLines, id: u64, buf: &mut Vec<u8>) -> Result<EpisodeRecord> {
    lines
        .read(id, buf)?
        .ok_or_else(|| missing_line(lines.path(), id))
}

/// The action names of a trajectory read from a file that are the episode loop's own
/// ([`ActionKind::name`]) borrowed again, as the loop records them: an owned `String` a step
/// would make the records read back at the end of a run about twice the size they had.
fn borrow_action_names(t: &mut Trajectory) {
    const KINDS: [ActionKind; 9] = [
        ActionKind::Stop,
        ActionKind::MoveForward,
        ActionKind::TurnLeft,
        ActionKind::TurnRight,
        ActionKind::LookUp,
        ActionKind::LookDown,
        ActionKind::Velocity,
        ActionKind::Waypoint,
        ActionKind::Ask,
    ];
    for name in t.actions.iter_mut().flatten() {
        if let Cow::Owned(s) = name {
            if let Some(k) = KINDS.iter().find(|k| k.name() == s.as_str()) {
                *name = Cow::Borrowed(k.name());
            }
        }
    }
}

/// A run whose results are written; its records stay in the log until [`Finished::outcome`]
/// reads them back, in split order.
struct Finished {
    summary: RunSummary,
    /// The recorded episodes, in split order.
    ids: Vec<u64>,
    lines: ProgressLines,
    resumed: usize,
    steps_run: u64,
}

impl Finished {
    fn outcome(self) -> Result<EvalOutcome> {
        let mut buf = Vec::new();
        let records = self
            .ids
            .iter()
            .map(|&id| {
                let mut r = read_record(&self.lines, id, &mut buf)?;
                borrow_action_names(&mut r.trajectory);
                Ok(r)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(EvalOutcome {
            summary: self.summary,
            records,
            resumed: self.resumed,
            steps_run: self.steps_run,
        })
    }
}

/// Make `req.out` ready for a run whose lock the caller holds: `--fresh` removes an earlier
/// run's files, the run identity is checked against (or written to) `run.json`, and the
/// episodes already finished there are returned (by id). A smaller `--episodes` than a
/// finished run holds is refused rather than shrinking its summary.
pub fn open_run(
    req: &EvalRequest,
    identity: &[(&str, serde_json::Value)],
    total_in_split: usize,
) -> Result<BTreeMap<u64, EpisodeRecord>> {
    if req.fresh {
        remove_run_files(&req.out)?;
    }
    resume::check_or_write_identity(&req.out, identity)?;
    let progress_path = req.out.join(PROGRESS_FILE);
    let done: BTreeMap<u64, EpisodeRecord> = resume::load_progress(&progress_path)?
        .into_iter()
        .map(|r| (r.episode_id, r))
        .collect();
    // A finished run's summary covers more episodes than asked for now: keep it.
    if let Some(n) = req.episodes {
        if n < total_in_split && done.len() > n && req.out.join("summary.json").exists() {
            return Err(TaskError::invalid(
                "episodes",
                n,
                format!(
                    "{} already holds {} finished episodes; rewriting its summary with {n} \
                     would lose them: leave --episodes out to rebuild the full summary, use \
                     --fresh to start over, or choose another --out",
                    req.out.display(),
                    done.len()
                ),
            ));
        }
    }
    Ok(done)
}

/// Write a run's results for `episodes` (in split order) from the finished records `done`:
/// `summary.json`, `episodes.csv`, `report.md`, `trajectories.jsonl` and the plots.
pub fn finish_run(
    req: &EvalRequest,
    agent_name: &str,
    scenes: &SceneCache,
    episodes: &[Episode],
    mut done: BTreeMap<u64, EpisodeRecord>,
) -> Result<(RunSummary, Vec<EpisodeRecord>)> {
    let records: Vec<EpisodeRecord> = episodes
        .iter()
        .filter_map(|e| done.remove(&e.episode_id))
        .collect();
    let metrics: Vec<_> = records.iter().map(|r| r.metrics.clone()).collect();
    let find = |id| {
        Ok(episodes
            .iter()
            .find(|e| e.episode_id == id)
            .map(Cow::Borrowed))
    };
    let summary = write_results(req, agent_name, &metrics, scenes, find, |i| {
        Ok(Cow::Borrowed(&records[i]))
    })?;
    write_trajectories(
        &req.out.join("trajectories.jsonl"),
        records.iter().map(|r| Ok(Cow::Borrowed(&r.trajectory))),
    )?;
    Ok((summary, records))
}

/// Write `summary.json`, `episodes.csv`, `report.md` from the recorded episodes' `metrics`
/// (split order) and the plots, for which `record(i)` gives the `i`th record and `find` an
/// episode by id.
fn write_results<'r, 'e>(
    req: &EvalRequest,
    agent_name: &str,
    metrics: &[EpisodeMetrics],
    scenes: &SceneCache,
    find: impl Fn(u64) -> Result<Option<Cow<'e, Episode>>>,
    record: impl FnMut(usize) -> Result<Cow<'r, EpisodeRecord>>,
) -> Result<RunSummary> {
    let summary = RunSummary::new(
        agent_name,
        Some(req.config.setting.name()),
        req.task,
        req.split,
        metrics,
    );
    write_run(&req.out, &summary, metrics)?;
    write_plots(req, scenes, find, metrics.len(), record)?;
    Ok(summary)
}

/// Write trajectories as JSON lines (the bytes of
/// [`vlnverse_score::trajectory::write_jsonl`]), atomically: line by line into a temporary
/// file beside `path`, then renamed. They come one at a time (from the records, or read back
/// from the run's log): neither the whole set nor the whole file's text is held (a train
/// split's file runs to tens of megabytes).
fn write_trajectories<'t>(
    path: &Path,
    trajectories: impl IntoIterator<Item = Result<Cow<'t, Trajectory>>>,
) -> Result<()> {
    use std::io::Write;
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| TaskError::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    let written = (|| -> Result<()> {
        let f = std::fs::File::create(&tmp).map_err(|e| TaskError::io(&tmp, e))?;
        let mut w = std::io::BufWriter::new(f);
        for t in trajectories {
            let line = to_json_line(&*t?);
            w.write_all(line.as_bytes())
                .and_then(|_| w.write_all(b"\n"))
                .map_err(|e| TaskError::io(&tmp, e))?;
        }
        w.flush().map_err(|e| TaskError::io(&tmp, e))
    })();
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        TaskError::io(path, e)
    })
}

/// `--fresh`: delete an earlier run's files (and only those) from `out`.
fn remove_run_files(out: &Path) -> Result<()> {
    for f in RUN_FILES {
        let p = out.join(f);
        match std::fs::remove_file(&p) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(TaskError::io(&p, e)),
        }
    }
    let plots = out.join("plots");
    if plots.is_dir() {
        std::fs::remove_dir_all(&plots).map_err(|e| TaskError::io(&plots, e))?;
    }
    Ok(())
}

/// What makes a run's results what they are, in the order a mismatch is reported (the first
/// differing key is named): `run.json` of the run folder. Besides the protocol's names and
/// paths it records their contents (`agent_config`, `rig_config`), so an edited file is
/// noticed, and the layers that ran it (`simulator`, `renderer`, `rig_fingerprint`: see
/// [`LayerIdentity`]). The split file's content is not part of it: each finished episode is
/// checked on resume instead ([`resume::check_unchanged`]), so an edit to an episode the run
/// has not reached is no reason to refuse. Thread count and episode count are left out (a
/// resume may use other values).
pub fn run_identity(
    req: &EvalRequest,
    factory: &dyn AgentFactory,
    layers: &LayerIdentity,
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
    let mut identity = vec![
        // First: a run of another benchmark version is another benchmark.
        (
            "benchmark_version",
            json!(vlnverse_score::BENCHMARK_VERSION),
        ),
        ("setting", json!(cfg.setting.name())),
        ("task", json!(req.task.name())),
        ("split", json!(req.split.name())),
        ("dataset", json!(req.dataset.display().to_string())),
        ("agent", json!(factory.name())),
        ("agent_cmd", json!(factory.command())),
        ("agent_fingerprint", json!(factory.fingerprint())),
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
        // The layers that ran it, after the protocol that chose them (a protocol change is
        // named by the protocol's key).
        ("simulator", json!(layers.simulator)),
        ("simulator_fingerprint", json!(layers.simulator_fingerprint)),
        ("renderer", json!(layers.renderer)),
        ("renderer_fingerprint", json!(layers.renderer_fingerprint)),
        ("rig_fingerprint", json!(layers.rig_fingerprint)),
    ];
    // Only when set, so runs made before these options existed still resume.
    if let Some(sample) = req.sample {
        identity.push(("sample", json!(sample)));
    }
    if let Some(llm) = &cfg.oracle_llm {
        identity.push(("oracle_llm", value("oracle_llm", to_value(llm))?));
    }
    Ok(identity)
}

/// The plots of `count` recorded episodes (split order), `record(i)` the `i`th.
fn write_plots<'r, 'e>(
    req: &EvalRequest,
    scenes: &SceneCache,
    find: impl Fn(u64) -> Result<Option<Cow<'e, Episode>>>,
    count: usize,
    mut record: impl FnMut(usize) -> Result<Cow<'r, EpisodeRecord>>,
) -> Result<()> {
    let dir = req.out.join("plots");
    for i in plots::sample_indices(count, req.config.plots as usize) {
        let rec = record(i)?;
        let Some(ep) = find(rec.episode_id)? else {
            continue;
        };
        let ctx = scenes.get(&ep.scene_id)?;
        let img = plots::plot_episode(
            &ctx.scene,
            Some(&ctx.navigable),
            ctx.levels().map(|l| &**l),
            &ep,
            &rec.trajectory,
            &rec.metrics,
        );
        plots::save_png(&dir.join(format!("episode_{}.png", ep.episode_id)), &img)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_score::trajectory::{write_jsonl, Trajectory};

    use crate::plots::tests::metrics;

    /// Batches end at home boundaries once they hold `min` episodes: a large home alone, small
    /// homes together, the rest last; every episode once, in order.
    #[test]
    fn home_batches_hold_a_home_alone_or_small_homes_together() {
        let episodes: Vec<Episode> = [("a", 5), ("b", 1), ("c", 2), ("d", 6), ("e", 1)]
            .iter()
            .flat_map(|&(scene, n)| (0..n).map(move |_| scene))
            .enumerate()
            .map(|(i, scene)| Episode {
                episode_id: i as u64,
                scene_id: scene.into(),
                ..Episode::default()
            })
            .collect();
        let store = EpisodeStore::pack(episodes, 1).unwrap();
        let todo: Vec<Slot> = store.in_scene_order().into_iter().map(|(_, s)| s).collect();
        let sizes =
            |min| -> Vec<usize> { home_batches(&todo, min).iter().map(|b| b.len()).collect() };
        assert_eq!(sizes(4), [5, 3, 6, 1]);
        assert_eq!(sizes(1), [5, 1, 2, 6, 1]);
        assert_eq!(sizes(100), [15]);
        let flat: Vec<Slot> = home_batches(&todo, 3).concat();
        assert_eq!(flat, todo);
        assert!(home_batches(&[], 3).is_empty());
    }

    /// The trajectories file written from the records, line by line, is the file
    /// `write_jsonl` writes from the trajectories, byte for byte; no temporary file is left.
    #[test]
    fn trajectories_are_written_as_write_jsonl_writes_them() {
        let dir = std::env::temp_dir().join(format!("vlnverse-eval-traj-{}", std::process::id()));
        let trajs: Vec<Trajectory> = (0..5u64)
            .map(|i| {
                let mut t = Trajectory::from_positions(
                    i,
                    (0..=i).map(|k| [k as f32 * 0.25, 0.0, -0.5]).collect(),
                    i % 2 == 0,
                );
                t.actions = Some(vec!["MOVE_FORWARD".into(); i as usize]);
                t
            })
            .collect();
        let records: Vec<EpisodeRecord> = trajs
            .iter()
            .map(|t| EpisodeRecord::new(t.episode_id, t.clone(), metrics(), None))
            .collect();
        let (ours, theirs) = (dir.join("a.jsonl"), dir.join("b.jsonl"));
        write_trajectories(
            &ours,
            records.iter().map(|r| Ok(Cow::Borrowed(&r.trajectory))),
        )
        .unwrap();
        write_jsonl(&theirs, &trajs).unwrap();
        assert_eq!(
            std::fs::read(&ours).unwrap(),
            std::fs::read(&theirs).unwrap()
        );
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(left.len(), 2, "only the two files");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Trajectories read back from the run's log, whichever order the episodes finished and
    /// were logged in, are written in split order as `write_jsonl` writes them, byte for byte;
    /// the records read back equal the ones logged. An episode logged twice is read from its
    /// last line, as a resume keeps it.
    #[test]
    fn trajectories_from_the_log_are_the_same_whichever_order_episodes_finish_in() {
        let dir = tempfile::tempdir().unwrap();
        let records: Vec<EpisodeRecord> = (0..7u64)
            .map(|i| {
                let id = 100 + (i * 37) % 11;
                let mut t = Trajectory::from_positions(
                    id,
                    (0..=i)
                        .map(|k| [k as f32 * 0.1 + 1.0 / 3.0, 0.07 * i as f32, -0.5e-3])
                        .collect(),
                    i % 2 == 0,
                );
                t.headings = Some((0..=i).map(|k| k as f32 * 0.7 - 3.1).collect());
                t.actions = Some(vec!["move_forward".into(); i as usize]);
                t.collisions = i as u32 % 3;
                let mut m = metrics();
                m.episode_id = id;
                EpisodeRecord::new(id, t, m, None)
            })
            .collect();
        let split: Vec<u64> = records.iter().map(|r| r.episode_id).collect();
        let trajs: Vec<Trajectory> = records.iter().map(|r| r.trajectory.clone()).collect();
        let expected = dir.path().join("expected.jsonl");
        write_jsonl(&expected, &trajs).unwrap();
        let orders: [Vec<usize>; 3] = [
            (0..records.len()).collect(),
            (0..records.len()).rev().collect(),
            vec![3, 0, 6, 2, 5, 1, 4],
        ];
        for (n, order) in orders.iter().enumerate() {
            let log_path = dir.path().join(format!("progress{n}.jsonl"));
            let log = ProgressLog::open(&log_path).unwrap();
            if n == 2 {
                // An earlier, different line of episode 3 (a rerun): the last line counts.
                let mut stale = records[3].clone();
                stale.trajectory.steps += 1;
                log.append(&mut stale).unwrap();
            }
            for &i in order {
                log.append(&mut records[i].clone()).unwrap();
            }
            drop(log);
            let lines = ProgressLines::index(&log_path).unwrap();
            let out = dir.path().join(format!("t{n}.jsonl"));
            write_logged_trajectories(&out, &lines, &split).unwrap();
            assert_eq!(
                std::fs::read(&out).unwrap(),
                std::fs::read(&expected).unwrap(),
                "finish order {order:?}"
            );
            let mut buf = Vec::new();
            for r in &records {
                let mut back = read_record(&lines, r.episode_id, &mut buf).unwrap();
                assert_eq!(&back, r);
                // The loop's own names are borrowed again, as the loop records them.
                borrow_action_names(&mut back.trajectory);
                assert_eq!(&back, r);
                let names = back.trajectory.actions.iter().flatten();
                assert!(names
                    .into_iter()
                    .all(|n| matches!(n, Cow::Borrowed("move_forward"))));
            }
            // An episode the log does not hold is an error naming it.
            let err = write_logged_trajectories(&out, &lines, &[100, 999])
                .unwrap_err()
                .to_string();
            assert!(err.contains("999"), "{err}");
        }
    }
}
