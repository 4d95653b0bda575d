//! A batch of environments stepped together: what the Python package's Gymnasium environments
//! (and any other driver that hands in actions one batch at a time) run on.
//!
//! Every environment drives its episodes through [`EpisodeState`], the same rules as
//! [`crate::run_episode`], so a metric computed here equals the one `xtask evaluate`
//! computes for the same actions. A step of the batch runs the environments on the rayon
//! pool; results do not depend on the number of threads.
//!
//! - Episode order: [`EpisodeOrder::Eval`] hands out the split's episodes in file order (or a
//!   given list) to whichever environment resets next, in environment order, so the first
//!   `len` resets of the whole batch visit every episode exactly once; after that it starts
//!   another pass (`StepInfo::pass`). [`EpisodeOrder::Train`] draws episodes uniformly with a
//!   per-environment seeded generator, staying in one home for [`VecEnvConfig::home_repeat`]
//!   episodes before drawing a home again, one episode ahead: the home of each environment's next
//!   episode is read and prepared for the renderer, and the episode checked (its goals'
//!   distance fields built), on a thread of its own while the batch steps, so a reset rarely
//!   waits for a home or a field (the draws, and so the episodes, are the same).
//! - Autoreset: none inside. An environment whose episode is over refuses further actions
//!   until [`VecEnv::reset_env`] (the Python layer implements Gymnasium's next-step autoreset
//!   on top: the action after the end resets).
//! - The teacher: after every reset and step, the shortest-path follower (the `oracle` agent)
//!   says what it would do next ([`StepInfo::expert_action`]).

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Arc, OnceLock};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use vlnverse_sensors::{Observations, SceneMesh, SensorRig};
use vlnverse_sim::{Action, SimConfig, Simulator};

use crate::agent::Agent;
use crate::agents::OracleAgent;
use crate::episode_loop::{check_episode, ActionKind, Applied, EpisodeSettings, EpisodeState};
use crate::error::{Result, TaskError};
use crate::protocol::EvalConfig;
use crate::resume::EpisodeRecord;
use crate::runner::{sim_config, RendererFactory, SimulatorFactory};
use crate::scene_context::{SceneCache, SceneContext};
use vlnverse_score::dataset;
use vlnverse_score::episode::{Episode, Split, Task};

/// How environments pick their next episode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EpisodeOrder {
    /// Every episode once, in order, shared by all environments.
    #[default]
    Eval,
    /// Uniform draws, seeded per environment, [`VecEnvConfig::home_repeat`] episodes a home.
    Train,
}

/// Optional reward shaping. The default gives 1 at a successful STOP and 0 otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RewardConfig {
    /// Reward per metre of geodesic progress toward the goal (0 = sparse).
    pub progress: f32,
    /// Reward for a successful STOP (within the success distance of the goal).
    pub success: f32,
    /// Penalty (subtracted) per noticeable collision.
    pub collision: f32,
}

impl Default for RewardConfig {
    fn default() -> Self {
        RewardConfig {
            progress: 0.0,
            success: 1.0,
            collision: 0.0,
        }
    }
}

impl RewardConfig {
    /// The documented dense reward: 1 per metre of progress, 2.5 for success, 0.1 per
    /// collision.
    pub fn dense() -> Self {
        RewardConfig {
            progress: 1.0,
            success: 2.5,
            collision: 0.1,
        }
    }
}

/// What a vector environment runs.
#[derive(Debug, Clone)]
pub struct VecEnvConfig {
    /// Dataset folder (`DIR/<task>/<split>/<split>.json.gz`, `DIR/scenes/`).
    pub dataset: PathBuf,
    /// Task.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// The protocol: setting, action space, profile, rig, step limit, success distance, seed.
    pub protocol: EvalConfig,
    /// Environments in the batch (at least 1).
    pub num_envs: usize,
    /// Episode order.
    pub order: EpisodeOrder,
    /// Only these episode ids, in this order (e.g. what a resumed evaluation has left).
    pub episode_ids: Option<Vec<u64>>,
    /// Reward shaping.
    pub reward: RewardConfig,
    /// Train order: episodes an environment draws in one home before it draws a home again
    /// (Habitat's `group_by_scene` with `max_scene_repeat_episodes`), none drawn twice in a
    /// pass over the home's episodes; 1 draws every episode from the whole split. Each draw is
    /// still uniform over the split's episodes.
    pub home_repeat: u32,
}

/// Train order's default [`VecEnvConfig::home_repeat`]: about 1,500 steps in a home at a
/// `vlnverse` fine episode's ~47, a pass and a half over a fine train home's 22 episodes, so
/// loading a home is paid once every 32 episodes instead of at almost every reset. VLN-CE's
/// teacher-forcing trainer stays in a scene for all its episodes (~177 in R2R's train split),
/// Habitat's default for 10,000 steps.
pub const DEFAULT_HOME_REPEAT: u32 = 32;

/// A driver's action for one environment.
#[derive(Debug, Clone, PartialEq)]
pub enum EnvAction {
    /// A simulator action (or STOP).
    Act(Action),
    /// Dialogue: ask the oracle. Within the budget it costs no step and the agent does not
    /// move; with the budget spent (or no oracle) it counts as a refused action (one step).
    Ask(String),
}

/// What one environment reports after a reset or a step.
#[derive(Debug, Clone)]
pub struct StepInfo {
    /// Episode id.
    pub episode_id: u64,
    /// Scene id.
    pub scene_id: String,
    /// Pass over the episode list this episode belongs to (0 = first; eval order only).
    pub pass: u32,
    /// Actions taken in the episode so far.
    pub steps: u32,
    /// Geodesic distance (m) to the current goal (NaN off the map).
    pub distance_to_goal: f32,
    /// The last action touched something.
    pub collided: bool,
    /// The last action was a noticeable collision (counted in CR).
    pub noticeable: bool,
    /// Noticeable collisions so far.
    pub collisions: u32,
    /// The simulator refused the last action (why).
    pub refused: Option<String>,
    /// Long-horizon: index of the sub-goal being pursued.
    pub sub_goal: u32,
    /// Dialogue: the oracle's answer to the last question (empty when none was asked).
    pub oracle_answer: String,
    /// Dialogue: questions left.
    pub questions_left: u32,
    /// The teacher's next action.
    pub expert_action: Action,
    /// Reward of the last action.
    pub reward: f32,
    /// The episode ended by STOP or a failure.
    pub terminated: bool,
    /// The episode hit the step limit.
    pub truncated: bool,
    /// When the episode is over: its trajectory and metrics.
    pub record: Option<EpisodeRecord>,
}

/// One environment's observation and report.
#[derive(Debug, Clone)]
pub struct EnvStep {
    /// The rig's readings (empty when rendering is off).
    pub observations: Observations,
    /// The episode now.
    pub episode: Arc<Episode>,
    /// Report.
    pub info: StepInfo,
    /// Base pose.
    pub pose: vlnverse_env::Pose,
    /// Start pose of the episode (GPS and compass are relative to it).
    pub start: vlnverse_env::Pose,
}

struct Running {
    episode: Arc<Episode>,
    scene: Arc<SceneContext>,
    state: EpisodeState,
    pass: u32,
}

struct Slot<S> {
    sim: S,
    rig: Option<SensorRig>,
    teacher: OracleAgent,
    rng: ChaCha8Rng,
    /// Train order: episodes drawn from `rng` but not yet begun, oldest first.
    ahead: VecDeque<(Arc<Episode>, Pinned)>,
    /// Train order: the home of the last draw and how many more draws stay in it.
    visit: Visit,
    run: Option<Running>,
}

/// Train order: where an environment's draws stay for a while.
#[derive(Debug, Clone, Default)]
struct Visit {
    home: usize,
    /// Draws left in this home.
    left: u32,
    /// The home's episodes not yet drawn in this pass over them.
    deck: Vec<usize>,
}

/// A batch of environments over one dataset split.
pub struct VecEnv<S: Simulator> {
    cfg: VecEnvConfig,
    settings: EpisodeSettings,
    split_file: PathBuf,
    episodes: Vec<Arc<Episode>>,
    /// Per episode, the index of its home in `by_home`.
    home_of: Vec<usize>,
    /// Per home (in order of first appearance), its episodes' indices.
    by_home: Vec<Vec<usize>>,
    scenes: Arc<SceneCache>,
    slots: Vec<Slot<S>>,
    cursor: usize,
    /// Train order: prepares the homes of drawn episodes in the background.
    prefetch: Option<Prefetch>,
}

/// Episodes drawn ahead per environment in train order (their homes are prepared meanwhile).
const AHEAD: usize = 1;

/// Bytes of stairs' end fields kept for homes the scene cache lets go, in train order: a
/// `vlnverse` home on two floors holds two of ~0.8 MB (~60k cells of ~13 bytes), so this keeps
/// those of ~80 such homes (the whole preset's).
const END_FIELD_BUDGET: usize = 128 << 20;

/// The home of an episode drawn ahead, once the prefetch thread has loaded it: held by the
/// environment until the episode begins, so the scene cache evicting it meanwhile (another
/// environment's homes are newer) does not make the reset load it and build its fields again.
type Pinned = Arc<OnceLock<Arc<SceneContext>>>;

/// A thread that loads the homes of episodes drawn ahead into the scene cache, checks the
/// episodes there ([`check_episode`], which builds and caches their goals' distance fields)
/// and prepares the homes for the renderer ([`SensorRig::scene_preparer`]). What it prepares
/// is only cached: results never depend on it, and its errors show when an environment's reset
/// loads and checks the episode itself (then finding the fields built).
struct Prefetch {
    tx: Option<mpsc::Sender<(Arc<Episode>, Pinned)>>,
    worker: Option<std::thread::JoinHandle<()>>,
}

impl Prefetch {
    fn start(scenes: Arc<SceneCache>, prepare: Option<fn(Arc<SceneMesh>)>) -> Option<Self> {
        let (tx, rx) = mpsc::channel::<(Arc<Episode>, Pinned)>();
        let worker = std::thread::Builder::new()
            .name("vlnverse-prefetch".into())
            .spawn(move || {
                for (ep, pin) in rx {
                    let Ok(ctx) = scenes.get(&ep.scene_id) else {
                        continue;
                    };
                    let _ = pin.set(ctx.clone());
                    // The goals' fields first: a reset that does not find them builds them on
                    // the serial part of a batch, a home not prepared is prepared in parallel.
                    let _ = check_episode(&ep, &ctx);
                    if let (Some(prepare), Ok(mesh)) = (prepare, ctx.mesh()) {
                        prepare(mesh);
                    }
                }
            })
            .ok()?;
        Some(Prefetch {
            tx: Some(tx),
            worker: Some(worker),
        })
    }

    fn request(&self, episode: &Arc<Episode>, pin: &Pinned) {
        if let Some(tx) = &self.tx {
            let _ = tx.send((episode.clone(), pin.clone()));
        }
    }
}

impl Drop for Prefetch {
    fn drop(&mut self) {
        // Closing the channel ends the thread after the home it is preparing.
        self.tx = None;
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}

/// The default vector environment: Rapier physics and the rig's configured renderer.
pub type RapierVecEnv = VecEnv<vlnverse_sim::RapierSimulator>;

impl RapierVecEnv {
    /// Environments with the default layers.
    pub fn new(cfg: VecEnvConfig) -> Result<Self> {
        VecEnv::with_layers(cfg, &crate::rapier_simulator, &crate::configured_renderer)
    }
}

/// Per episode the index of its home, and per home (in order of first appearance) its
/// episodes' indices.
fn group_by_home(episodes: &[Arc<Episode>]) -> (Vec<usize>, Vec<Vec<usize>>) {
    let mut index = std::collections::HashMap::new();
    let mut by_home: Vec<Vec<usize>> = Vec::new();
    let home_of = episodes
        .iter()
        .enumerate()
        .map(|(k, ep)| {
            let h = *index.entry(ep.scene_id.as_str()).or_insert_with(|| {
                by_home.push(Vec::new());
                by_home.len() - 1
            });
            by_home[h].push(k);
            h
        })
        .collect();
    (home_of, by_home)
}

/// Train order's next episode (an index into the split): a draw over the whole split when the
/// visit is over, else a draw among the visited home's episodes not yet drawn in this pass over
/// them (a new pass once all were). A home is drawn in proportion to its episodes and a visit
/// lasts `repeat` draws whatever the home, so every draw is uniform over the split's episodes.
fn draw(
    rng: &mut ChaCha8Rng,
    visit: &mut Visit,
    home_of: &[usize],
    by_home: &[Vec<usize>],
    repeat: u32,
) -> usize {
    if visit.left == 0 {
        let k = rng.random_range(0..home_of.len());
        visit.home = home_of[k];
        visit.left = repeat - 1;
        visit.deck.clear();
        if repeat > 1 {
            visit
                .deck
                .extend(by_home[visit.home].iter().filter(|&&e| e != k));
        }
        return k;
    }
    visit.left -= 1;
    if visit.deck.is_empty() {
        visit.deck.extend(&by_home[visit.home]);
    }
    let j = rng.random_range(0..visit.deck.len());
    visit.deck.swap_remove(j)
}

/// Most environments one [`VecEnv`] holds: each has a simulator and a renderer (1024 rendering
/// ones took 3.5 GB), so a mistyped count is refused.
pub const MAX_ENVS: usize = 256;

fn invalid(field: &str, value: impl ToString, why: impl Into<String>) -> TaskError {
    TaskError::invalid(field, value, why.into())
}

impl<S: Simulator> VecEnv<S> {
    /// Environments whose simulators and renderers come from the given factories.
    pub fn with_layers<SF, RF>(cfg: VecEnvConfig, sims: &SF, renderers: &RF) -> Result<Self>
    where
        SF: SimulatorFactory<Sim = S>,
        RF: RendererFactory,
    {
        cfg.protocol.validate()?;
        if cfg.num_envs == 0 || cfg.num_envs > MAX_ENVS {
            return Err(invalid(
                "num_envs",
                cfg.num_envs,
                format!("must be in [1, {MAX_ENVS}]"),
            ));
        }
        let split_file = dataset::split_path(&cfg.dataset, cfg.task, cfg.split);
        let all = dataset::read_split(&cfg.dataset, cfg.task, cfg.split)?;
        let episodes: Vec<Arc<Episode>> = match &cfg.episode_ids {
            None => all.into_iter().map(Arc::new).collect(),
            Some(ids) => {
                let by_id: std::collections::BTreeMap<u64, Episode> =
                    all.into_iter().map(|e| (e.episode_id, e)).collect();
                ids.iter()
                    .map(|id| {
                        by_id.get(id).cloned().map(Arc::new).ok_or_else(|| {
                            invalid(
                                "episode_ids",
                                id,
                                format!("no such episode in {}", split_file.display()),
                            )
                        })
                    })
                    .collect::<Result<_>>()?
            }
        };
        if episodes.is_empty() {
            return Err(invalid(
                "episodes",
                split_file.display(),
                "the split has no episodes",
            ));
        }
        let sim_cfg: SimConfig = sim_config(&cfg.protocol)?;
        let rig_cfg = cfg.protocol.rig_config()?;
        let mut settings = EpisodeSettings::new(&cfg.protocol)?;
        settings.split = Some(cfg.split);
        settings.reference_dir = split_file.parent().map(Path::to_path_buf);
        let mut slots = Vec::with_capacity(cfg.num_envs);
        for i in 0..cfg.num_envs {
            let sim = sims.make(&sim_cfg)?;
            let rig = if cfg.protocol.render {
                Some(SensorRig::with_renderer(
                    rig_cfg.clone(),
                    renderers.make(&rig_cfg)?,
                ))
            } else {
                None
            };
            slots.push(Slot {
                sim,
                rig,
                teacher: OracleAgent::default(),
                rng: ChaCha8Rng::seed_from_u64(crate::episode_loop::episode_seed(
                    cfg.protocol.seed,
                    i as u64,
                )),
                ahead: VecDeque::new(),
                visit: Visit::default(),
                run: None,
            });
        }
        let train = cfg.order == EpisodeOrder::Train;
        if cfg.home_repeat == 0 {
            return Err(invalid(
                "home_repeat",
                cfg.home_repeat,
                "must be at least 1 (1 draws every episode from the whole split)",
            ));
        }
        let (home_of, by_home) = group_by_home(&episodes);
        // Room for the homes shown and, in train order, those prepared ahead.
        let capacity = cfg.num_envs * if train { 1 + AHEAD } else { 1 } + 2;
        // Train order comes back to homes the cache has let go: their stairs' end fields are
        // kept for the next visit (in the process's store, which later environments share).
        let scenes = SceneCache::new(&cfg.dataset, capacity);
        let scenes = Arc::new(if train {
            scenes.sharing_end_fields(END_FIELD_BUDGET)
        } else {
            scenes
        });
        let prepare = slots
            .first()
            .and_then(|s| s.rig.as_ref())
            .and_then(SensorRig::scene_preparer);
        let prefetch = if train {
            Prefetch::start(scenes.clone(), prepare)
        } else {
            None
        };
        Ok(VecEnv {
            scenes,
            settings,
            split_file,
            episodes,
            home_of,
            by_home,
            slots,
            cursor: 0,
            prefetch,
            cfg,
        })
    }

    /// Environments in the batch.
    pub fn num_envs(&self) -> usize {
        self.slots.len()
    }

    /// The episodes this batch draws from (in eval order).
    pub fn episodes(&self) -> &[Arc<Episode>] {
        &self.episodes
    }

    /// The configuration.
    pub fn config(&self) -> &VecEnvConfig {
        &self.cfg
    }

    /// The settings every episode runs under.
    pub fn settings(&self) -> &EpisodeSettings {
        &self.settings
    }

    /// The sensor rig of environment 0 (all are alike), when rendering.
    pub fn rig(&self) -> Option<&SensorRig> {
        self.slots.first().and_then(|s| s.rig.as_ref())
    }

    /// Reseed the per-environment episode draws (train order) and restart the eval order.
    pub fn seed(&mut self, seed: u64) {
        for (i, s) in self.slots.iter_mut().enumerate() {
            s.rng = ChaCha8Rng::seed_from_u64(crate::episode_loop::episode_seed(seed, i as u64));
            s.ahead.clear();
            s.visit = Visit::default();
        }
        self.cursor = 0;
    }

    /// The next episode for environment `i`, its pass, and its home when the prefetch thread
    /// has loaded it.
    fn next_episode(&mut self, i: usize) -> (Arc<Episode>, u32, Option<Arc<SceneContext>>) {
        let n = self.episodes.len();
        match self.cfg.order {
            EpisodeOrder::Eval => {
                let k = self.cursor;
                self.cursor += 1;
                (self.episodes[k % n].clone(), (k / n) as u32, None)
            }
            EpisodeOrder::Train => {
                let slot = &mut self.slots[i];
                while slot.ahead.len() <= AHEAD {
                    let k = draw(
                        &mut slot.rng,
                        &mut slot.visit,
                        &self.home_of,
                        &self.by_home,
                        self.cfg.home_repeat,
                    );
                    let ep = self.episodes[k].clone();
                    let pin = Pinned::default();
                    // The first draw is begun now; later ones are prepared meanwhile.
                    if let (Some(p), false) = (&self.prefetch, slot.ahead.is_empty()) {
                        p.request(&ep, &pin);
                    }
                    slot.ahead.push_back((ep, pin));
                }
                let (ep, pin) = slot.ahead.pop_front().expect("drawn above");
                (ep, 0, pin.get().cloned())
            }
        }
    }

    /// Reset every environment to its next episode.
    pub fn reset_all(&mut self) -> Result<Vec<EnvStep>> {
        let n = self.slots.len();
        self.reset_all_into(vec![(); n], |_, ()| Ok(()))
    }

    /// [`reset_all`](Self::reset_all), handing environment `i`'s result and `outs[i]` to
    /// `sink` inside the parallel step (see [`step_into`](Self::step_into)).
    pub fn reset_all_into<T: Send>(
        &mut self,
        outs: Vec<T>,
        sink: impl Fn(&EnvStep, T) -> Result<()> + Sync,
    ) -> Result<Vec<EnvStep>> {
        let work = (0..self.slots.len()).map(|i| (i, None)).collect();
        self.run_batch(work, outs, sink)
    }

    /// Reset one environment to its next episode.
    pub fn reset_env(&mut self, i: usize) -> Result<EnvStep> {
        self.check_index(i)?;
        let outs = vec![(); self.slots.len()];
        Ok(self
            .run_batch(vec![(i, None)], outs, |_, ()| Ok(()))?
            .remove(0))
    }

    /// Step every environment: `actions[i]` for environment `i`; `None` resets that
    /// environment instead (the next-step autoreset of a finished one).
    pub fn step(&mut self, actions: Vec<Option<EnvAction>>) -> Result<Vec<EnvStep>> {
        let n = self.slots.len();
        self.step_into(actions, vec![(); n], |_, ()| Ok(()))
    }

    /// [`step`](Self::step), handing environment `i`'s result and `outs[i]` to `sink` on the
    /// thread that stepped it, so per-environment work after the step (copying observations
    /// into a caller's batched buffers) runs in parallel too. `outs` has one entry per
    /// environment.
    pub fn step_into<T: Send>(
        &mut self,
        actions: Vec<Option<EnvAction>>,
        outs: Vec<T>,
        sink: impl Fn(&EnvStep, T) -> Result<()> + Sync,
    ) -> Result<Vec<EnvStep>> {
        if actions.len() != self.slots.len() {
            return Err(invalid(
                "actions",
                actions.len(),
                format!("expected one action per environment ({})", self.slots.len()),
            ));
        }
        self.run_batch(actions.into_iter().enumerate().collect(), outs, sink)
    }

    fn check_index(&self, i: usize) -> Result<()> {
        if i >= self.slots.len() {
            return Err(invalid(
                "env",
                i,
                format!("there are {} environments", self.slots.len()),
            ));
        }
        Ok(())
    }

    /// Assign episodes (serially, in environment order, so the order is deterministic) and
    /// load and check their scenes (errors name the episode), then run the resets and steps in
    /// parallel.
    fn run_batch<T: Send>(
        &mut self,
        work: Vec<(usize, Option<EnvAction>)>,
        outs: Vec<T>,
        sink: impl Fn(&EnvStep, T) -> Result<()> + Sync,
    ) -> Result<Vec<EnvStep>> {
        if outs.len() != self.slots.len() {
            return Err(invalid(
                "outs",
                outs.len(),
                format!("expected one per environment ({})", self.slots.len()),
            ));
        }
        let mut jobs: Vec<Option<Job>> = (0..self.slots.len()).map(|_| None).collect();
        for (i, a) in work {
            jobs[i] = Some(match a {
                Some(a) => Job::Step(a),
                None => {
                    let (ep, pass, loaded) = self.next_episode(i);
                    let scene = self.load_checked(&ep, loaded)?;
                    Job::Reset(ep, scene, pass)
                }
            });
        }
        let ctx = Ctx {
            settings: &self.settings,
            reward: self.cfg.reward,
        };
        let results: Vec<Option<Result<EnvStep>>> = self
            .slots
            .par_iter_mut()
            .zip(jobs.into_par_iter().zip(outs.into_par_iter()))
            .with_max_len(1)
            .map(|(slot, (job, out))| {
                job.map(|j| {
                    let step = ctx.run(slot, j)?;
                    sink(&step, out)?;
                    Ok(step)
                })
            })
            .collect();
        results.into_iter().flatten().collect()
    }

    /// The episode's home (`loaded`: as the prefetch thread loaded it, put back in the scene
    /// cache if it was evicted meanwhile), and the episode checked in it.
    fn load_checked(
        &self,
        ep: &Episode,
        loaded: Option<Arc<SceneContext>>,
    ) -> Result<Arc<SceneContext>> {
        let locate = || format!("{}: episode {}", self.split_file.display(), ep.episode_id);
        let got = match loaded {
            Some(ctx) => Ok(self.scenes.keep(&ep.scene_id, ctx)),
            None => self.scenes.get(&ep.scene_id),
        };
        let ctx = got.map_err(|e| {
            invalid(
                &format!("{}.scene_id", locate()),
                &ep.scene_id,
                e.to_string(),
            )
        })?;
        check_episode(ep, &ctx).map_err(|e| e.at(&locate()))?;
        Ok(ctx)
    }
}

enum Job {
    Reset(Arc<Episode>, Arc<SceneContext>, u32),
    Step(EnvAction),
}

struct Ctx<'a> {
    settings: &'a EpisodeSettings,
    reward: RewardConfig,
}

impl Ctx<'_> {
    fn run<S: Simulator>(&self, slot: &mut Slot<S>, job: Job) -> Result<EnvStep> {
        let mut info_extra = Extra::default();
        match job {
            Job::Reset(ep, scene, pass) => {
                let state = EpisodeState::begin(
                    &mut slot.sim,
                    slot.rig.as_mut(),
                    &ep,
                    &scene,
                    self.settings,
                )?;
                slot.teacher.set_truth(&state.privileged(&ep));
                slot.teacher.reset(&state.inputs)?;
                slot.run = Some(Running {
                    episode: ep,
                    scene,
                    state,
                    pass,
                });
            }
            Job::Step(action) => {
                let Some(run) = slot.run.as_mut() else {
                    return Err(invalid("env", "<not reset>", "reset before stepping"));
                };
                let before = run.state.distance_to_goal();
                match action {
                    EnvAction::Ask(q) if run.state.questions_left() > 0 => {
                        info_extra.answer = run.state.ask(&q).unwrap_or_default();
                    }
                    EnvAction::Ask(_) => {
                        // Nothing to ask: a refused action, one step.
                        run.state.refuse(ActionKind::Ask, "no questions left")?;
                        info_extra.refused = Some("no questions left".into());
                    }
                    EnvAction::Act(a) => {
                        match run.state.apply(&mut slot.sim, a, &self.settings.config)? {
                            Applied::Refused(why) => info_extra.refused = Some(why),
                            Applied::Stepped => {
                                let out = run.state.last();
                                info_extra.collided = out.is_some_and(|o| o.collided);
                                info_extra.noticeable = out.is_some_and(|o| o.noticeable);
                            }
                            Applied::Stop { .. } => {}
                        }
                    }
                }
                let after = run.state.distance_to_goal();
                if let (Some(b), Some(a)) = (before, after) {
                    info_extra.progress = b - a;
                }
            }
        }
        let run = slot.run.as_mut().expect("reset above");
        let observations = match slot.rig.as_mut() {
            Some(rig) => run.state.observe(rig)?,
            None => Observations::new(),
        };
        let state = &run.state;
        let over = state.is_over();
        let record = if over {
            Some(state.finish(&run.episode, &run.scene, self.settings)?)
        } else {
            None
        };
        let expert_action = if over {
            Action::Stop
        } else {
            slot.teacher.act(&mut state.step_input(&observations))?
        };
        let success = record.as_ref().is_some_and(|r| r.metrics.success);
        let r = &self.reward;
        let reward = r.progress * info_extra.progress
            + if success && state.stopped() {
                r.success
            } else {
                0.0
            }
            - if info_extra.noticeable {
                r.collision
            } else {
                0.0
            };
        let terminated =
            over && (state.stopped() || record.as_ref().is_some_and(|r| r.failure.is_some()));
        Ok(EnvStep {
            observations,
            info: StepInfo {
                episode_id: run.episode.episode_id,
                scene_id: run.episode.scene_id.clone(),
                pass: run.pass,
                steps: state.steps(),
                distance_to_goal: state.distance_to_goal().unwrap_or(f32::NAN),
                collided: info_extra.collided,
                noticeable: info_extra.noticeable,
                collisions: state.collisions(),
                refused: info_extra.refused,
                sub_goal: state.sub_goal().current,
                oracle_answer: info_extra.answer,
                questions_left: state.questions_left(),
                expert_action,
                reward: if reward.is_finite() { reward } else { 0.0 },
                terminated,
                truncated: over && !terminated,
                record,
            },
            pose: state.pose(),
            start: state.inputs.start,
            episode: run.episode.clone(),
        })
    }
}

#[derive(Default)]
struct Extra {
    answer: String,
    refused: Option<String>,
    collided: bool,
    noticeable: bool,
    progress: f32,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An episode requested ahead is loaded and checked on the prefetch thread: its home is in
    /// the cache (loaded once) and pinned for the environment, and its goals' fields are
    /// built, so its reset finds them; a pinned home evicted meanwhile is put back, not loaded.
    #[test]
    fn the_prefetch_thread_builds_the_goal_fields_of_an_episode_drawn_ahead() {
        let dir = tempfile::tempdir().unwrap();
        let episodes = vlnverse_testkit::datasets::make_dataset(dir.path(), Task::Fine, 2, 2, 3);
        let scenes = Arc::new(SceneCache::new(dir.path(), 4));
        let ep = Arc::new(episodes[1].clone());
        let prefetch = Prefetch::start(scenes.clone(), None).unwrap();
        let pin = Pinned::default();
        prefetch.request(&ep, &pin);
        // Dropping it waits for the requests sent.
        drop(prefetch);
        assert_eq!(scenes.loads(), 1);
        let ctx = scenes.get(&ep.scene_id).unwrap();
        assert_eq!(scenes.loads(), 1, "the reset finds the home loaded");
        // The environment holds the home it was loaded as, whatever the cache evicts.
        assert!(Arc::ptr_eq(pin.get().unwrap(), &ctx));
        let other_home = episodes.iter().find(|e| e.scene_id != ep.scene_id).unwrap();
        let small = SceneCache::new(dir.path(), 1);
        small.get(&other_home.scene_id).unwrap();
        let kept = small.keep(&ep.scene_id, ctx.clone());
        assert!(Arc::ptr_eq(&kept, &ctx), "put back, not loaded again");
        assert_eq!((small.loads(), small.len()), (1, 1));
        assert!(Arc::ptr_eq(&small.get(&ep.scene_id).unwrap(), &ctx));
        let goals = ep.goal_sequence();
        assert!(!goals.is_empty());
        for g in goals {
            assert!(ctx.has_field(g.position), "{:?}", g.position);
        }
        // An episode not requested: no field for its goal yet.
        let other = episodes
            .iter()
            .find(|e| e.scene_id == ep.scene_id && e.goals[0].position != ep.goals[0].position)
            .unwrap();
        assert!(!ctx.has_field(other.goals[0].position));
    }
}
