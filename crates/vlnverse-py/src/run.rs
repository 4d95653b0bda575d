//! Run folders, episodes and scoring from Python: what `vlnverse.evaluate`, `load_episodes`
//! and `score` call. The files are the ones `cargo xtask evaluate` / `score` write.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;

use pyo3::prelude::*;
use vlnverse_task::dataset;
use vlnverse_task::episode::{Episode, Split, Task};
use vlnverse_task::eval::{check_split, finish_run, open_run, run_identity, select_episodes};
use vlnverse_task::eval::{AgentFactory, EvalRequest, LayerIdentity, SceneCache};
use vlnverse_task::eval::{EpisodeRecord, ProgressLog, PROGRESS_FILE};
use vlnverse_task::lock;
use vlnverse_task::metrics::MetricsConfig;
use vlnverse_task::report::write_run;
use vlnverse_task::sample::Sample;
use vlnverse_task::score::{score_with, ScoreOptions};
use vlnverse_task::{trajectory, OutputLock};

use crate::{guarded, parse, py_err};

/// The episodes of a split, as JSON text (the split file's `episodes` array).
#[pyfunction]
pub fn load_episodes(dataset: PathBuf, task: &str, split: &str) -> PyResult<String> {
    let (task, split): (Task, Split) = (parse("task", task)?, parse("split", split)?);
    guarded("load_episodes", || {
        let eps = dataset::read_split(&dataset, task, split).map_err(py_err)?;
        serde_json::to_string(&eps).map_err(py_err)
    })
}

/// Score a trajectory file (JSON lines or VLN-CE format) on a split; writes the run files
/// under `out` and returns `summary.json`'s text.
#[pyfunction]
#[pyo3(signature = (dataset, task, split, trajectories, out, *, success_distance = 3.0,
    fail_on_collision = false, allow_missing = false, method = None, force = false))]
#[allow(clippy::too_many_arguments)]
pub fn score(
    py: Python<'_>,
    dataset: PathBuf,
    task: &str,
    split: &str,
    trajectories: PathBuf,
    out: PathBuf,
    success_distance: f32,
    fail_on_collision: bool,
    allow_missing: bool,
    method: Option<String>,
    force: bool,
) -> PyResult<String> {
    let (task, split): (Task, Split) = (parse("task", task)?, parse("split", split)?);
    py.detach(|| {
        guarded("score", || {
            // The same folder rules as `cargo xtask score`.
            lock::check_score_folder(&out, force).map_err(py_err)?;
            let options = ScoreOptions {
                metrics: MetricsConfig {
                    success_distance,
                    fail_on_collision,
                    ..Default::default()
                },
                allow_missing,
                ..Default::default()
            };
            let trajs = trajectory::read_trajectories(&trajectories).map_err(py_err)?;
            let scored =
                score_with(&dataset, task, split, trajs, &options, &|_| {}).map_err(py_err)?;
            let name = method.unwrap_or_else(|| {
                trajectories
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "trajectories".into())
            });
            let run = scored.run_summary(&name, None);
            let _lock = OutputLock::acquire(&out, "score").map_err(py_err)?;
            lock::check_score_folder(&out, force).map_err(py_err)?;
            lock::write_score_file(&out, &trajectories, &dataset, task, split).map_err(py_err)?;
            write_run(&out, &run, &scored.metrics).map_err(py_err)?;
            serde_json::to_string(&run).map_err(py_err)
        })
    })
}

/// The run identity of an agent that lives in Python: its name and fingerprint.
struct PythonAgent {
    name: String,
    fingerprint: Option<String>,
}

impl AgentFactory for PythonAgent {
    fn name(&self) -> String {
        self.name.clone()
    }
    fn make(&self) -> vlnverse_task::Result<Box<dyn vlnverse_task::Agent>> {
        Err(vlnverse_task::TaskError::invalid(
            "agent",
            &self.name,
            "a Python agent acts from Python (vlnverse.evaluate), not from a Rust runner",
        ))
    }
    fn fingerprint(&self) -> Option<String> {
        self.fingerprint.clone()
    }
}

struct Open {
    req: EvalRequest,
    agent: String,
    episodes: Vec<Episode>,
    done: BTreeMap<u64, EpisodeRecord>,
    log: ProgressLog,
    _lock: OutputLock,
}

/// An evaluation run folder opened for writing by a Python driver: locked, its identity
/// (protocol, dataset, agent name and fingerprint) checked against an earlier run, finished
/// episodes loaded so a run resumes. `record` appends one finished episode, `finish` writes
/// the summary files.
#[pyclass(module = "vlnverse._native")]
pub struct RunFolder {
    open: Mutex<Option<Open>>,
}

#[pymethods]
impl RunFolder {
    #[new]
    #[pyo3(signature = (out, dataset, task, split, *, agent, agent_fingerprint = None,
        setting = "telhop", action_space = "discrete", profile = "vlnverse", sensors = None,
        seed = 0, max_steps = None, success_distance = None, episodes = None, sample = None,
        fresh = false, render = true, backend = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        out: PathBuf,
        dataset: PathBuf,
        task: &str,
        split: &str,
        agent: String,
        agent_fingerprint: Option<String>,
        setting: &str,
        action_space: &str,
        profile: &str,
        sensors: Option<PathBuf>,
        seed: u64,
        max_steps: Option<u32>,
        success_distance: Option<f32>,
        episodes: Option<usize>,
        sample: Option<usize>,
        fresh: bool,
        render: bool,
        backend: Option<&str>,
    ) -> PyResult<Self> {
        let (task, split): (Task, Split) = (parse("task", task)?, parse("split", split)?);
        let config = crate::protocol(
            setting,
            action_space,
            profile,
            sensors,
            seed,
            render,
            backend,
            max_steps,
            success_distance,
        )?;
        if agent.trim().is_empty() {
            return Err(py_err(
                "invalid agent ``: name the agent (it goes into run.json)",
            ));
        }
        guarded("RunFolder", || {
            config.validate().map_err(py_err)?;
            if episodes == Some(0) {
                return Err(py_err(
                    "invalid episodes 0: must be at least 1 (leave it out for the whole split)",
                ));
            }
            let req = EvalRequest::new(dataset.clone(), task, split, out.clone())
                .episodes(episodes)
                .sample(sample.map(|count| Sample { count, seed }))
                .fresh(fresh)
                .config(config);
            let eps = dataset::read_split(&dataset, task, split).map_err(py_err)?;
            if eps.is_empty() {
                return Err(py_err(format!(
                    "{}: the split has no episodes",
                    dataset::split_path(&dataset, task, split).display()
                )));
            }
            let total = eps.len();
            let eps = select_episodes(&req, eps).map_err(py_err)?;
            // Every episode checked in its scene before run.json or a lock is written.
            let split_file = dataset::split_path(&dataset, task, split);
            check_split(&split_file, &eps, &SceneCache::new(&dataset, 4)).map_err(py_err)?;
            let factory = PythonAgent {
                name: agent.clone(),
                fingerprint: agent_fingerprint,
            };
            let layers = LayerIdentity::of_defaults(&req).map_err(py_err)?;
            let identity = run_identity(&req, &factory, &layers).map_err(py_err)?;
            vlnverse_task::eval::check_run_folder(&out).map_err(py_err)?;
            let lock = OutputLock::acquire(&out, "evaluate").map_err(py_err)?;
            let done = open_run(&req, &identity, total).map_err(py_err)?;
            vlnverse_task::eval::check_unchanged(&split_file, &eps, &done).map_err(py_err)?;
            let log = ProgressLog::open(&out.join(PROGRESS_FILE))
                .and_then(|l| l.for_episodes(&eps))
                .map_err(py_err)?;
            Ok(RunFolder {
                open: Mutex::new(Some(Open {
                    req,
                    agent,
                    episodes: eps,
                    done,
                    log,
                    _lock: lock,
                })),
            })
        })
    }

    /// Ids of the episodes still to run, in split order.
    fn todo(&self) -> PyResult<Vec<u64>> {
        self.with(|o| {
            Ok(o.episodes
                .iter()
                .map(|e| e.episode_id)
                .filter(|id| !o.done.contains_key(id))
                .collect())
        })
    }

    /// Episodes already finished (taken from an earlier run or recorded now).
    fn finished(&self) -> PyResult<usize> {
        self.with(|o| Ok(o.done.len()))
    }

    /// Append a finished episode (the JSON of an episode record, `info["record"]`).
    fn record(&self, record: &str) -> PyResult<()> {
        self.with(|o| {
            let mut rec: EpisodeRecord = serde_json::from_str(record)
                .map_err(|e| py_err(format!("record: not an episode record: {e}")))?;
            if !o.episodes.iter().any(|e| e.episode_id == rec.episode_id) {
                return Err(py_err(format!(
                    "record: episode {} is not among this run's episodes",
                    rec.episode_id
                )));
            }
            if o.done.contains_key(&rec.episode_id) {
                return Ok(());
            }
            o.log.append(&mut rec).map_err(py_err)?;
            o.done.insert(rec.episode_id, rec);
            Ok(())
        })
    }

    /// Write summary.json, episodes.csv, report.md, trajectories.jsonl and plots; release
    /// the folder. Returns summary.json's text.
    fn finish(&self, py: Python<'_>) -> PyResult<String> {
        let mut g = self.open.lock().unwrap_or_else(|p| p.into_inner());
        let Some(o) = g.take() else {
            return Err(py_err("the run folder is closed"));
        };
        let missing = o
            .episodes
            .iter()
            .filter(|e| !o.done.contains_key(&e.episode_id))
            .count();
        if missing > 0 {
            let n = o.episodes.len();
            *g = Some(o);
            return Err(py_err(format!(
                "{missing} of {n} episodes have no record yet; run them before finishing"
            )));
        }
        py.detach(|| {
            guarded("finish", || {
                let scenes = SceneCache::new(&o.req.dataset, 2);
                let (summary, _) =
                    finish_run(&o.req, &o.agent, &scenes, &o.episodes, o.done).map_err(py_err)?;
                serde_json::to_string(&summary).map_err(py_err)
            })
        })
    }

    /// Release the folder without writing a summary (what was recorded stays for a resume).
    fn close(&self) {
        *self.open.lock().unwrap_or_else(|p| p.into_inner()) = None;
    }
}

impl RunFolder {
    fn with<T>(&self, f: impl FnOnce(&mut Open) -> PyResult<T>) -> PyResult<T> {
        let mut g = self.open.lock().unwrap_or_else(|p| p.into_inner());
        match g.as_mut() {
            Some(o) => f(o),
            None => Err(py_err("the run folder is closed")),
        }
    }
}
