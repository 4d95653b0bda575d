//! Drive: a person steers the agent through one episode with the keyboard, over a WebSocket.
//!
//! `GET /api/drive?task=fine&split=val_unseen&episode=3&setting=strict&profile=vlnverse`
//! upgrades to a WebSocket. Each connection owns one simulator (a one-environment
//! [`RapierVecEnv`], so the episode runs under exactly the rules of `xtask evaluate`: Strict
//! failures, collisions, the step limit) on its own thread.
//!
//! - The page sends text messages: `{"key": "w"}` (W forward, A/D turn, Q/E look up/down,
//!   Space stop), `{"ask": "which way?"}` (dialogue episodes), `{"view": "depth"}` or
//!   `{"view": "rgb"}`.
//! - The server answers each with a text message `{"type": "state", ...}` (step, pose,
//!   collisions, the current sub-instruction, the oracle's answer, and the metrics once the
//!   episode is over), followed by the first-person view as a binary JPEG message. Errors come
//!   as `{"type": "error", "error": "..."}` and leave the episode as it was.
//! - The drive log, written as the paper logs its human study: a CSV row every 50 ms
//!   (`time_s,step,x,y,z,heading_rad,key`, `key` the keys pressed in that interval) in
//!   `OUT/drives/<task>/<split>/ep<ID>-<unix ms>-<n>.csv`; when the episode ends, its trajectory
//!   joins `OUT/drives/<task>/<split>/trajectories.jsonl` (one line per episode, the latest
//!   drive of an episode wins), the file `cargo xtask score` reads, and its record (trajectory,
//!   metrics, protocol) goes to `ep<ID>-<unix ms>-<n>.json` (`n` numbers the server's drives). A client that drops mid-episode
//!   leaves its CSV (flushed row by row) and no trajectory.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use axum::extract::rejection::QueryRejection;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Query, State};
use axum::response::Response;
use serde::Deserialize;
use serde_json::{json, Value};
use vlnverse_sim::Action;
use vlnverse_task::eval::{
    EnvAction, EnvStep, EpisodeOrder, EvalConfig, RapierVecEnv, RewardConfig, Setting, VecEnvConfig,
};
use vlnverse_task::trajectory::{read_trajectories, write_jsonl};
use vlnverse_task::{Split, Task, Trajectory};

use crate::app::{lock, App};
use crate::error::{ApiError, ApiResult};
use crate::frames::{jpeg, view_pixels, ViewKind};

/// Query of `GET /api/drive` (all strings, checked by the handler so errors are JSON).
#[derive(Debug, Default, Deserialize)]
pub struct DriveQuery {
    /// Task name.
    pub task: Option<String>,
    /// Split name.
    pub split: Option<String>,
    /// Episode id.
    pub episode: Option<String>,
    /// `strict` (default), `telhop` or `lenient`.
    pub setting: Option<String>,
    /// Robot profile (default: the protocol's).
    pub profile: Option<String>,
}

/// What one drive runs.
#[derive(Debug, Clone)]
pub struct DriveSpec {
    /// Task.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// Episode id.
    pub episode_id: u64,
    /// The protocol (discrete actions).
    pub protocol: EvalConfig,
}

/// A message from the page.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Command {
    /// A key: `w`, `a`, `d`, `q`, `e`, or `" "` / `space` (stop).
    Key(String),
    /// A question to the dialogue oracle.
    Ask(String),
    /// Which image the view shows.
    View(ViewKind),
}

/// A message to the page.
enum Out {
    Text(String),
    Binary(Vec<u8>),
}

/// Holds one of the server's driver places; released when dropped.
struct DriverSlot(Arc<App>);

impl Drop for DriverSlot {
    fn drop(&mut self) {
        self.0.drivers.fetch_sub(1, Ordering::SeqCst);
    }
}

fn required<'a>(v: &'a Option<String>, name: &str) -> ApiResult<&'a str> {
    v.as_deref()
        .filter(|s| !s.is_empty())
        .ok_or_else(|| ApiError::bad_request(format!("missing query parameter `{name}`")))
}

/// Check a drive request: the episode exists, the setting and profile are known.
pub fn check_request(app: &App, q: &DriveQuery) -> ApiResult<DriveSpec> {
    let (task, split) = App::task_split(required(&q.task, "task")?, required(&q.split, "split")?)?;
    let episode_id = App::parse_id(required(&q.episode, "episode")?)?;
    app.episode(task, split, episode_id)?;
    let setting: Setting = q
        .setting
        .as_deref()
        .unwrap_or("strict")
        .parse()
        .map_err(|e| ApiError::bad_request(format!("{e}")))?;
    let protocol = app.protocol(setting, q.profile.as_deref())?;
    Ok(DriveSpec {
        task,
        split,
        episode_id,
        protocol,
    })
}

/// `GET /api/drive`: check the request, then upgrade to the drive WebSocket.
pub async fn drive_ws(
    State(app): State<Arc<App>>,
    query: Result<Query<DriveQuery>, QueryRejection>,
    ws: Result<WebSocketUpgrade, axum::extract::ws::rejection::WebSocketUpgradeRejection>,
) -> ApiResult<Response> {
    let Query(q) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let spec = check_request(&app, &q)?;
    let ws = ws.map_err(|e| {
        ApiError::bad_request(format!(
            "/api/drive is a WebSocket endpoint; connect with a WebSocket client ({})",
            e.body_text()
        ))
    })?;
    let n = app.drivers.fetch_add(1, Ordering::SeqCst);
    let slot = DriverSlot(app.clone());
    if n >= app.cfg.max_drivers {
        return Err(ApiError::busy(format!(
            "{n} drivers are connected, the most this server takes (--max-drivers)"
        )));
    }
    Ok(ws.on_upgrade(move |socket| session(app, socket, spec, slot)))
}

async fn session(app: Arc<App>, mut socket: WebSocket, spec: DriveSpec, slot: DriverSlot) {
    let (cmd_tx, cmd_rx) = std::sync::mpsc::channel::<Command>();
    let (out_tx, mut out_rx) = tokio::sync::mpsc::channel::<Out>(8);
    let worker_app = app.clone();
    let worker = std::thread::Builder::new()
        .name(format!("drive-ep{}", spec.episode_id))
        .spawn(move || {
            if let Err(e) = drive(&worker_app, &spec, &cmd_rx, &out_tx) {
                let msg = json!({"type": "error", "fatal": true, "error": e.message});
                let _ = out_tx.blocking_send(Out::Text(msg.to_string()));
            }
        });
    let worker = match worker {
        Ok(w) => w,
        Err(e) => {
            let msg = json!({"type": "error", "fatal": true, "error": format!("cannot start a driver thread: {e}")});
            let _ = socket.send(Message::Text(msg.to_string().into())).await;
            return;
        }
    };
    loop {
        tokio::select! {
            msg = socket.recv() => match msg {
                Some(Ok(Message::Text(t))) => match serde_json::from_str::<Command>(&t) {
                    Ok(cmd) => {
                        if cmd_tx.send(cmd).is_err() {
                            break;
                        }
                    }
                    Err(e) => {
                        let msg = json!({"type": "error", "error": format!(
                            "cannot read message `{}`: {e}; expected {{\"key\": \"w\"}}, {{\"ask\": \"...\"}} or {{\"view\": \"depth\"}}",
                            t.as_str().chars().take(80).collect::<String>())});
                        if socket.send(Message::Text(msg.to_string().into())).await.is_err() {
                            break;
                        }
                    }
                },
                Some(Ok(Message::Binary(b))) => {
                    let msg = json!({"type": "error", "error": format!(
                        "binary messages are not read ({} bytes received); send JSON text such as {{\"key\": \"w\"}}, {{\"ask\": \"...\"}} or {{\"view\": \"depth\"}}",
                        b.len())});
                    if socket.send(Message::Text(msg.to_string().into())).await.is_err() {
                        break;
                    }
                }
                Some(Ok(Message::Close(_))) | None | Some(Err(_)) => break,
                Some(Ok(_)) => {}
            },
            out = out_rx.recv() => {
                let sent = match out {
                    Some(Out::Text(s)) => socket.send(Message::Text(s.into())).await,
                    Some(Out::Binary(b)) => socket.send(Message::Binary(b.into())).await,
                    None => break,
                };
                if sent.is_err() {
                    break;
                }
            }
        }
    }
    // The worker sees the closed channels, finishes its log and drops its simulator.
    drop(cmd_tx);
    drop(out_rx);
    let _ = tokio::task::spawn_blocking(move || worker.join()).await;
    drop(slot);
}

/// The action of a key.
pub fn key_action(key: &str, agent: &vlnverse_sim::AgentConfig) -> Option<(Action, &'static str)> {
    match key.to_ascii_lowercase().as_str() {
        "w" => Some((Action::forward(agent), "w")),
        "a" => Some((Action::left(agent), "a")),
        "d" => Some((Action::right(agent), "d")),
        "q" => Some((Action::LookUp, "q")),
        "e" => Some((Action::LookDown, "e")),
        " " | "space" => Some((Action::Stop, "space")),
        _ => None,
    }
}

/// The key that gives an action (the teacher's hint).
pub fn action_key(a: &Action) -> Option<&'static str> {
    match a {
        Action::MoveForward(_) => Some("w"),
        Action::TurnLeft(_) => Some("a"),
        Action::TurnRight(_) => Some("d"),
        Action::LookUp => Some("q"),
        Action::LookDown => Some("e"),
        Action::Stop => Some("space"),
        _ => None,
    }
}

/// The drive log: a CSV row every interval.
struct DriveLog {
    file: std::io::BufWriter<std::fs::File>,
    path: PathBuf,
}

impl DriveLog {
    fn create(path: PathBuf) -> ApiResult<Self> {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)
                .map_err(|e| ApiError::internal(format!("{}: {e}", dir.display())))?;
        }
        let f = std::fs::File::create_new(&path)
            .map_err(|e| ApiError::internal(format!("{}: {e}", path.display())))?;
        let mut log = DriveLog {
            file: std::io::BufWriter::new(f),
            path,
        };
        log.line("time_s,step,x,y,z,heading_rad,key")?;
        Ok(log)
    }

    fn line(&mut self, s: &str) -> ApiResult<()> {
        writeln!(self.file, "{s}")
            .and_then(|_| self.file.flush())
            .map_err(|e| ApiError::internal(format!("{}: {e}", self.path.display())))
    }

    fn row(&mut self, t: f64, step: &EnvStep, keys: &str) -> ApiResult<()> {
        let p = step.pose.position;
        self.line(&format!(
            "{t:.3},{},{:.4},{:.4},{:.4},{:.5},{keys}",
            step.info.steps,
            p[0],
            p[1],
            p[2],
            step.pose.yaw()
        ))
    }
}

fn unix_ms() -> u128 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_millis())
}

/// The folder of a split's drive logs.
pub fn drive_dir(out: &Path, task: Task, split: Split) -> PathBuf {
    out.join("drives").join(task.name()).join(split.name())
}

/// Add (or replace) an episode's trajectory in a merged `trajectories.jsonl`, atomically.
pub fn merge_trajectory(path: &Path, traj: &Trajectory) -> ApiResult<()> {
    let mut all: Vec<Trajectory> = if path.is_file() {
        read_trajectories(path).map_err(|e| ApiError::internal(e.to_string()))?
    } else {
        Vec::new()
    };
    all.retain(|t| t.episode_id != traj.episode_id);
    all.push(traj.clone());
    all.sort_by_key(|t| t.episode_id);
    write_jsonl(path, &all).map_err(|e| ApiError::internal(e.to_string()))
}

fn env_err(e: impl std::fmt::Display) -> ApiError {
    ApiError::internal(e.to_string())
}

/// The state message of a step.
fn state_json(app: &App, spec: &DriveSpec, step: &EnvStep, view: ViewKind, log: &Path) -> Value {
    let info = &step.info;
    let ep = &step.episode;
    let sub = ep
        .instruction
        .sub_instructions
        .get(info.sub_goal as usize)
        .cloned();
    let mut v = json!({
        "type": "state",
        "episode_id": info.episode_id,
        "scene_id": info.scene_id,
        "task": spec.task.name(),
        "split": spec.split.name(),
        "setting": spec.protocol.setting.name(),
        "profile": spec.protocol.agent_profile,
        "step": info.steps,
        "max_steps": spec.protocol.max_steps,
        "position": step.pose.position,
        "heading": step.pose.yaw(),
        "collided": info.collided,
        "noticeable": info.noticeable,
        "collisions": info.collisions,
        "refused": info.refused,
        "sub_goal": info.sub_goal,
        "sub_goals": ep.instruction.sub_instructions.len(),
        "sub_instruction": sub,
        "answer": info.oracle_answer,
        "questions_left": info.questions_left,
        "done": info.terminated || info.truncated,
        "terminated": info.terminated,
        "truncated": info.truncated,
        "view": view,
        "log": log.display().to_string(),
    });
    if let Some(rec) = &info.record {
        v["metrics"] = serde_json::to_value(&rec.metrics).unwrap_or(Value::Null);
        v["failure"] = json!(rec.failure.as_ref().map(ToString::to_string));
    }
    if app.cfg.teacher_hints {
        v["expert_key"] = json!(action_key(&info.expert_action));
        v["distance_to_goal"] = json!(info.distance_to_goal);
    }
    v
}

/// Run one drive until the page goes away.
fn drive(
    app: &App,
    spec: &DriveSpec,
    cmds: &Receiver<Command>,
    out: &tokio::sync::mpsc::Sender<Out>,
) -> ApiResult<()> {
    let mut env = RapierVecEnv::new(VecEnvConfig {
        dataset: app.dataset.clone(),
        task: spec.task,
        split: spec.split,
        protocol: spec.protocol.clone(),
        num_envs: 1,
        order: EpisodeOrder::Eval,
        episode_ids: Some(vec![spec.episode_id]),
        reward: RewardConfig::default(),
        home_repeat: 1,
    })
    .map_err(env_err)?;
    let agent = env.settings().agent.clone();
    let mut step = env.reset_all().map_err(env_err)?.remove(0);
    let dir = drive_dir(&app.out, spec.task, spec.split);
    let seq = app.drive_seq.fetch_add(1, Ordering::SeqCst);
    let stem = format!("ep{}-{}-{seq}", spec.episode_id, unix_ms());
    let mut log = DriveLog::create(dir.join(format!("{stem}.csv")))?;
    let log_path = log.path.clone();
    let started = Instant::now();
    let interval = Duration::from_millis(app.cfg.log_interval_ms.max(1));
    let mut next_row = started;
    let mut keys = String::new();
    let mut view = ViewKind::Rgb;
    let mut frames = 0u64;
    let send = |msg: Out| out.blocking_send(msg).is_ok();
    let send_frame = |step: &EnvStep, view: ViewKind, frames: &mut u64| -> ApiResult<bool> {
        let state = state_json(app, spec, step, view, &log_path);
        if !send(Out::Text(state.to_string())) {
            return Ok(false);
        }
        if let Some((w, h, px)) = view_pixels(&step.observations, view) {
            *frames += 1;
            return Ok(send(Out::Binary(jpeg(w, h, &px, app.cfg.jpeg_quality)?)));
        }
        Ok(true)
    };
    if !send_frame(&step, view, &mut frames)? {
        return Ok(());
    }
    let mut live = true;
    loop {
        // One row per 50 ms tick, stamped with the tick's time (ticks that passed while the
        // simulator stepped are written now, with the pose after the step).
        let now = Instant::now();
        while live && next_row <= now {
            log.row((next_row - started).as_secs_f64(), &step, &keys)?;
            keys.clear();
            next_row += interval;
        }
        let wait = if live {
            next_row.saturating_duration_since(Instant::now())
        } else {
            Duration::from_secs(3600)
        };
        let cmd = match cmds.recv_timeout(wait) {
            Ok(c) => c,
            Err(RecvTimeoutError::Timeout) => continue,
            Err(RecvTimeoutError::Disconnected) => break,
        };
        let action = match &cmd {
            Command::View(v) => {
                view = *v;
                if !send_frame(&step, view, &mut frames)? {
                    break;
                }
                continue;
            }
            _ if !live => {
                let e = json!({"type": "error", "error": format!(
                    "episode {} is over; open it again to drive it anew", spec.episode_id)});
                if !send(Out::Text(e.to_string())) {
                    break;
                }
                continue;
            }
            Command::Ask(q) => {
                if !keys.is_empty() {
                    keys.push('+');
                }
                keys.push_str("ask");
                EnvAction::Ask(q.clone())
            }
            Command::Key(k) => match key_action(k, &agent) {
                Some((a, name)) => {
                    if !keys.is_empty() {
                        keys.push('+');
                    }
                    keys.push_str(name);
                    EnvAction::Act(a)
                }
                None => {
                    let e = json!({"type": "error", "error": format!(
                        "unknown key `{k}`: W forward, A/D turn, Q/E look up/down, Space stop")});
                    if !send(Out::Text(e.to_string())) {
                        break;
                    }
                    continue;
                }
            },
        };
        step = match env.step(vec![Some(action)]) {
            Ok(mut v) => v.remove(0),
            Err(e) => {
                let e = json!({"type": "error", "error": e.to_string()});
                if !send(Out::Text(e.to_string())) {
                    break;
                }
                continue;
            }
        };
        if let Some(rec) = &step.info.record {
            live = false;
            // The ticks that passed while the last action ran, then the end itself.
            let now = Instant::now();
            while next_row <= now {
                log.row((next_row - started).as_secs_f64(), &step, &keys)?;
                keys.clear();
                next_row += interval;
            }
            log.row(started.elapsed().as_secs_f64(), &step, &keys)?;
            keys.clear();
            let _guard = lock(&app.traj_lock);
            merge_trajectory(&dir.join("trajectories.jsonl"), &rec.trajectory)?;
            let record = json!({
                "episode_id": rec.episode_id,
                "task": spec.task.name(),
                "split": spec.split.name(),
                "setting": spec.protocol.setting.name(),
                "profile": spec.protocol.agent_profile,
                "duration_s": started.elapsed().as_secs_f64(),
                "metrics": rec.metrics,
                "failure": rec.failure.as_ref().map(ToString::to_string),
                "trajectory": rec.trajectory,
            });
            let text = serde_json::to_string_pretty(&record).map_err(env_err)?;
            vlnverse_task::dataset::write_atomic(
                &dir.join(format!("{stem}.json")),
                text.as_bytes(),
            )
            .map_err(env_err)?;
        }
        if !send_frame(&step, view, &mut frames)? {
            break;
        }
    }
    let secs = started.elapsed().as_secs_f64();
    tracing::info!(
        episode = spec.episode_id,
        frames,
        seconds = secs,
        finished = !live,
        "drive ended ({})",
        log_path.display()
    );
    Ok(())
}
