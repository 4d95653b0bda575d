//! The server's shared state ([`App`]) and what it is started with ([`ServerConfig`]).

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, AtomicUsize};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use vlnverse_sensors::{Backend, SensorRig};
use vlnverse_task::eval::{ActionSpace, EvalConfig, SceneCache, SceneContext, Setting};
use vlnverse_task::{dataset, Episode, OutputLock, Split, Task, Trajectory};

use crate::error::{ApiError, ApiResult};
use crate::review::ReviewFile;

/// What `cargo xtask serve` starts the server with.
#[derive(Debug, Clone)]
pub struct ServerConfig {
    /// Dataset folder (`DIR/<task>/<split>/<split>.json.gz`, `DIR/scenes/`).
    pub dataset: PathBuf,
    /// Evaluation run folders (written by `cargo xtask evaluate` or `score`) shown in Replay.
    pub runs: Vec<PathBuf>,
    /// Where drive logs (`drives/`) and the review file go by default.
    pub out: PathBuf,
    /// The review file (default `OUT/review.json`).
    pub review_file: Option<PathBuf>,
    /// Folder of protocol files `<setting>.toml` (e.g. `configs/eval`); missing files fall back
    /// to the built-in protocol of the setting.
    pub protocol_dir: Option<PathBuf>,
    /// Override of the rig's renderer backend.
    pub backend: Option<Backend>,
    /// Send the teacher's next action with every frame (for tests and demonstrations; a human
    /// study leaves it off).
    pub teacher_hints: bool,
    /// Drivers (one simulator each) at once; more are answered 503.
    pub max_drivers: usize,
    /// JPEG quality of the frames.
    pub jpeg_quality: u8,
    /// Interval of the drive log's rows (ms); the paper logs every 50 ms.
    pub log_interval_ms: u64,
    /// Longest wait for a request's headers; a connection that has not sent them by then is
    /// closed (a client holding half-sent headers must not hold a connection for ever).
    pub header_timeout: Duration,
    /// Connections served at once; a further one is answered at once with a 503 JSON error
    /// and closed.
    pub max_connections: usize,
}

impl ServerConfig {
    /// Defaults for a dataset: drive logs under `runs/web`, 16 drivers, quality 85, 50 ms rows,
    /// 10 s for a request's headers, 256 connections at once.
    pub fn new(dataset: impl Into<PathBuf>) -> Self {
        ServerConfig {
            dataset: dataset.into(),
            runs: Vec::new(),
            out: PathBuf::from("runs/web"),
            review_file: None,
            protocol_dir: None,
            backend: None,
            teacher_hints: false,
            max_drivers: 16,
            jpeg_quality: 85,
            log_interval_ms: 50,
            header_timeout: Duration::from_secs(10),
            max_connections: 256,
        }
    }
}

/// One evaluation run shown in Replay.
#[derive(Debug, Clone)]
pub struct RunDir {
    /// Folder name (shown on the page).
    pub name: String,
    /// The folder, canonical.
    pub dir: PathBuf,
}

/// Shared state of the server.
pub struct App {
    /// The configuration.
    pub cfg: ServerConfig,
    /// The dataset folder, canonical.
    pub dataset: PathBuf,
    /// Runs shown in Replay, in command-line order.
    pub runs: Vec<RunDir>,
    /// The drive logs' folder.
    pub out: PathBuf,
    /// Split files read so far.
    splits: Mutex<HashMap<(Task, Split), Arc<Vec<Episode>>>>,
    /// Scenes (mesh, navigable map) for top-down maps and views.
    pub scenes: SceneCache,
    /// The rig that draws Replay and Review views (one at a time).
    pub viewer: Mutex<Option<SensorRig>>,
    /// Review decisions (kept in the review file).
    pub review: Mutex<ReviewFile>,
    /// Drivers connected now.
    pub drivers: AtomicUsize,
    /// Drives started since the server started (numbers the logs).
    pub drive_seq: AtomicU64,
    /// Serialises rewrites of the merged drive trajectories.
    pub traj_lock: Mutex<()>,
    /// Trajectories of each run, read once.
    run_trajs: Mutex<HashMap<usize, Arc<BTreeMap<u64, Trajectory>>>>,
    /// The output folder's lock (and the review file's folder's, when elsewhere): one server
    /// writes drive logs and review decisions there at a time.
    _locks: Vec<OutputLock>,
}

/// Remove the temporary files a killed server left beside `file` (`.NAME.tmpPID`, written by
/// the atomic rewrite of `NAME`); the caller holds the folder's lock, so no live writer owns
/// them. Nothing else is touched.
pub fn remove_stale_temp_files(file: &Path) {
    let (Some(dir), Some(name)) = (file.parent(), file.file_name()) else {
        return;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!(".{}.tmp", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let n = e.file_name();
        let n = n.to_string_lossy();
        let ours = n
            .strip_prefix(&prefix)
            .is_some_and(|pid| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()));
        if ours && e.file_type().is_ok_and(|t| t.is_file()) {
            match std::fs::remove_file(e.path()) {
                Ok(()) => {
                    tracing::info!(file = %e.path().display(), "removed a stale temporary file")
                }
                Err(err) => {
                    tracing::warn!(file = %e.path().display(), error = %err, "cannot remove a stale temporary file")
                }
            }
        }
    }
}

/// Lock a mutex; a poisoned one (a panicking holder) is still usable: every value behind these
/// locks is rebuilt from files.
pub fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

fn canonical_dir(path: &Path, what: &str) -> Result<PathBuf, String> {
    let c = path
        .canonicalize()
        .map_err(|e| format!("{what} `{}`: {e}", path.display()))?;
    if !c.is_dir() {
        return Err(format!("{what} `{}` is not a folder", path.display()));
    }
    Ok(c)
}

impl App {
    /// Check the folders and read the review file; errors name the folder or file.
    pub fn new(cfg: ServerConfig) -> Result<Self, String> {
        let dataset = canonical_dir(&cfg.dataset, "--dataset")?;
        if !dataset.join("scenes").is_dir() {
            return Err(format!(
                "--dataset `{}` has no `scenes/` folder; is it a dataset made by `cargo xtask generate`?",
                cfg.dataset.display()
            ));
        }
        let mut runs = Vec::new();
        for r in &cfg.runs {
            let dir = canonical_dir(r, "--runs")?;
            if !dir.join("trajectories.jsonl").is_file() {
                return Err(format!(
                    "--runs `{}` has no trajectories.jsonl; is it a run folder of `cargo xtask evaluate`?",
                    r.display()
                ));
            }
            let name = dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| r.display().to_string());
            runs.push(RunDir { name, dir });
        }
        std::fs::create_dir_all(&cfg.out)
            .map_err(|e| format!("--out `{}`: {e}", cfg.out.display()))?;
        let out = canonical_dir(&cfg.out, "--out")?;
        let review_path = cfg
            .review_file
            .clone()
            .unwrap_or_else(|| out.join("review.json"));
        // One server per output: a second one on the same folder would overwrite the first's
        // review decisions with its own copy of the file.
        let mut locks =
            vec![OutputLock::acquire(&out, "serve").map_err(|e| format!("--out: {e}"))?];
        let review_dir = review_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        let same = review_dir.canonicalize().is_ok_and(|d| d == out);
        if !same {
            locks.push(
                OutputLock::acquire(&review_dir, "serve")
                    .map_err(|e| format!("--review-file: {e}"))?,
            );
        }
        remove_stale_temp_files(&review_path);
        let review = ReviewFile::open(&review_path, &dataset).map_err(|e| e.to_string())?;
        Ok(App {
            scenes: SceneCache::new(&dataset, 4),
            dataset,
            runs,
            out,
            splits: Mutex::new(HashMap::new()),
            viewer: Mutex::new(None),
            review: Mutex::new(review),
            drivers: AtomicUsize::new(0),
            drive_seq: AtomicU64::new(0),
            traj_lock: Mutex::new(()),
            run_trajs: Mutex::new(HashMap::new()),
            _locks: locks,
            cfg,
        })
    }

    /// Task and split from request strings (400 naming the value).
    pub fn task_split(task: &str, split: &str) -> ApiResult<(Task, Split)> {
        let t: Task = task
            .parse()
            .map_err(|e| ApiError::bad_request(format!("{e}")))?;
        let s: Split = split
            .parse()
            .map_err(|e| ApiError::bad_request(format!("{e}")))?;
        Ok((t, s))
    }

    /// The episodes of a split (read once; 404 when the dataset has no such split).
    pub fn episodes(&self, task: Task, split: Split) -> ApiResult<Arc<Vec<Episode>>> {
        if let Some(e) = lock(&self.splits).get(&(task, split)) {
            return Ok(e.clone());
        }
        let path = dataset::split_path(&self.dataset, task, split);
        if !path.is_file() {
            return Err(ApiError::not_found(format!(
                "the dataset has no {task}/{split} split ({} is missing)",
                path.display()
            )));
        }
        let eps = Arc::new(
            dataset::read_split(&self.dataset, task, split)
                .map_err(|e| ApiError::internal(e.to_string()))?,
        );
        lock(&self.splits).insert((task, split), eps.clone());
        Ok(eps)
    }

    /// One episode (404 naming the id and the split).
    pub fn episode(
        &self,
        task: Task,
        split: Split,
        id: u64,
    ) -> ApiResult<(Arc<Vec<Episode>>, usize)> {
        let eps = self.episodes(task, split)?;
        let i = eps.iter().position(|e| e.episode_id == id).ok_or_else(|| {
            ApiError::not_found(format!(
                "no episode with episode_id {id} in {task}/{split} ({} episodes)",
                eps.len()
            ))
        })?;
        Ok((eps, i))
    }

    /// An episode id from a request string (400 naming the value).
    pub fn parse_id(s: &str) -> ApiResult<u64> {
        s.trim().parse().map_err(|_| {
            ApiError::bad_request(format!(
                "invalid episode id `{s}`: expected a non-negative integer"
            ))
        })
    }

    /// The scene of an episode.
    pub fn scene(&self, id: &str) -> ApiResult<Arc<SceneContext>> {
        self.scenes
            .get(id)
            .map_err(|e| ApiError::internal(format!("scene `{id}`: {e}")))
    }

    /// The protocol a drive runs under: `<protocol_dir>/<setting>.toml` when present, else the
    /// setting's built-in protocol; always the discrete action space (the keys), the given
    /// robot profile, and the backend override.
    pub fn protocol(&self, setting: Setting, profile: Option<&str>) -> ApiResult<EvalConfig> {
        let file = self
            .cfg
            .protocol_dir
            .as_ref()
            .map(|d| d.join(format!("{setting}.toml")))
            .filter(|f| f.is_file());
        let mut cfg = match file {
            Some(f) => EvalConfig::load(&f).map_err(|e| ApiError::internal(e.to_string()))?,
            None => EvalConfig::for_setting(setting),
        };
        cfg.action_space = ActionSpace::Discrete;
        if let Some(p) = profile.filter(|p| !p.is_empty()) {
            let known = profiles();
            if !known.contains(&p) {
                return Err(ApiError::bad_request(format!(
                    "invalid profile `{p}`: expected one of {}",
                    known.join(", ")
                )));
            }
            cfg.agent_profile = p.to_string();
        }
        if self.cfg.backend.is_some() {
            cfg.backend = self.cfg.backend;
        }
        cfg.validate()
            .map_err(|e| ApiError::bad_request(e.to_string()))?;
        Ok(cfg)
    }

    /// Index of a run (404 naming it).
    pub fn run(&self, i: usize) -> ApiResult<&RunDir> {
        self.runs.get(i).ok_or_else(|| {
            ApiError::not_found(format!(
                "no run {i}: the server was started with {} run(s)",
                self.runs.len()
            ))
        })
    }

    /// The trajectories of run `i`, by episode id (read once).
    pub fn run_trajectories(&self, i: usize) -> ApiResult<Arc<BTreeMap<u64, Trajectory>>> {
        if let Some(t) = lock(&self.run_trajs).get(&i) {
            return Ok(t.clone());
        }
        let run = self.run(i)?;
        let path = run.dir.join("trajectories.jsonl");
        let list = vlnverse_task::trajectory::read_trajectories(&path)
            .map_err(|e| ApiError::internal(e.to_string()))?;
        let map = Arc::new(list.into_iter().map(|t| (t.episode_id, t)).collect());
        lock(&self.run_trajs).insert(i, Arc::clone(&map));
        Ok(map)
    }

    /// Run `f` with the viewer rig (made on first use with the strict protocol's rig).
    pub fn with_viewer<T>(&self, f: impl FnOnce(&mut SensorRig) -> ApiResult<T>) -> ApiResult<T> {
        let mut guard = lock(&self.viewer);
        if guard.is_none() {
            let rig_cfg = self
                .protocol(Setting::Strict, None)?
                .rig_config()
                .map_err(|e| ApiError::internal(e.to_string()))?;
            let rig = SensorRig::new(rig_cfg).map_err(|e| ApiError::internal(e.to_string()))?;
            *guard = Some(rig);
        }
        f(guard.as_mut().expect("made above"))
    }
}

/// Robot profiles shipped with the simulator (`vlnverse-sim` `AgentConfig::profile`).
pub fn profiles() -> Vec<&'static str> {
    vlnverse_sim::config::PROFILES
        .iter()
        .map(|(n, _)| *n)
        .collect()
}
