//! `external`: a policy in another process (Python, PyTorch, ...) speaking JSON lines on its
//! stdin/stdout; the protocol is in `docs/agents.md`. One process per worker thread, reused
//! across episodes. Observations go as files in a private temporary folder (PNG for RGB, `.npy`
//! for depth, semantic and instance images, written by `vlnverse_sensors::output`; overwritten
//! every step) or inline as standard base64 of the raw little-endian array.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use serde::{Deserialize, Serialize};
use serde_json::{json, Map, Value};
use vlnverse_sensors::output::{self, NpyElement};
use vlnverse_sensors::{Frame, Observation, Result as SensorResult};
use vlnverse_sim::{Action, WaypointMode};

use crate::agent::{Agent, AgentFactory, EpisodeInputs, StepInput};
use crate::error::{Result, TaskError};

/// How image observations travel to the external agent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObsEncoding {
    /// Files in a temporary folder (`path` in the message).
    #[default]
    Files,
    /// Inline base64 of the raw little-endian array (`data` in the message).
    Base64,
}

/// Seconds an external agent may take to answer one message unless the protocol says
/// otherwise (`external_timeout_s`).
pub const DEFAULT_EXTERNAL_TIMEOUT_S: f64 = 60.0;

/// Makes one [`ExternalAgent`] process per worker.
pub struct ExternalFactory {
    cmd: String,
    encoding: ObsEncoding,
    timeout: Duration,
}

impl ExternalFactory {
    /// Agents running `cmd` through `sh -c`, observations as files, replies awaited
    /// [`DEFAULT_EXTERNAL_TIMEOUT_S`].
    pub fn new(cmd: &str) -> Self {
        ExternalFactory {
            cmd: cmd.into(),
            encoding: ObsEncoding::Files,
            timeout: Duration::from_secs_f64(DEFAULT_EXTERNAL_TIMEOUT_S),
        }
    }

    /// Choose how observations are sent.
    pub fn with_encoding(mut self, encoding: ObsEncoding) -> Self {
        self.encoding = encoding;
        self
    }

    /// How long to wait for one reply before the agent is stopped and the run fails.
    pub fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }
}

impl AgentFactory for ExternalFactory {
    fn name(&self) -> String {
        "external".into()
    }
    fn make(&self) -> Result<Box<dyn Agent>> {
        let mut agent = ExternalAgent::spawn(&self.cmd, self.encoding)?;
        agent.timeout = self.timeout;
        Ok(Box::new(agent))
    }
    fn command(&self) -> Option<String> {
        Some(self.cmd.clone())
    }
    /// A hash of the files the command names (its script, its checkpoint), so an edited
    /// program is a different agent; `None` when the command names no existing file.
    fn fingerprint(&self) -> Option<String> {
        command_files_hash(&self.cmd)
    }
}

/// FNV-1a 64 over the names and contents of the existing files among the command's words
/// (stable across platforms and Rust versions, unlike `DefaultHasher`).
pub fn command_files_hash(cmd: &str) -> Option<String> {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    let mut files = 0;
    for word in cmd.split_whitespace() {
        let word = word.trim_matches(['"', '\'']);
        let path = std::path::Path::new(word);
        if !path.is_file() {
            continue;
        }
        let Ok(bytes) = std::fs::read(path) else {
            continue;
        };
        eat(word.as_bytes());
        eat(&(bytes.len() as u64).to_le_bytes());
        eat(&bytes);
        files += 1;
    }
    (files > 0).then(|| format!("files {h:016x}"))
}

/// A thread that sends each line of `out` (without its newline) until it ends.
fn read_lines(mut out: BufReader<ChildStdout>) -> Receiver<std::io::Result<String>> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || loop {
        let mut line = String::new();
        match out.read_line(&mut line) {
            Ok(0) => break,
            Ok(_) => {
                if tx.send(Ok(line)).is_err() {
                    break;
                }
            }
            Err(e) => {
                let _ = tx.send(Err(e));
                break;
            }
        }
    });
    rx
}

/// A thread that writes each message it gets to `stdin` and answers each with the write's
/// result, so a write to an agent that never reads its input (once the pipe buffer is full)
/// can be given up after a timeout instead of blocking the run. It ends, closing `stdin`, when
/// the sender is dropped or a write fails.
fn write_lines(mut stdin: ChildStdin) -> (Sender<Vec<u8>>, Receiver<std::io::Result<()>>) {
    let (tx, rx) = std::sync::mpsc::channel::<Vec<u8>>();
    let (done_tx, done_rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for buf in rx {
            let r = stdin.write_all(&buf).and_then(|_| stdin.flush());
            let failed = r.is_err();
            if done_tx.send(r).is_err() || failed {
                break;
            }
        }
    });
    (tx, done_rx)
}

/// A running external agent.
pub struct ExternalAgent {
    cmd: String,
    child: Child,
    /// Messages for the agent's stdin, written by a thread ([`write_lines`]).
    stdin: Option<Sender<Vec<u8>>>,
    /// The result of each write, in order.
    written: Receiver<std::io::Result<()>>,
    /// Lines of the agent's stdout, read by a thread so a reply can be awaited with a timeout.
    replies: Receiver<std::io::Result<String>>,
    timeout: Duration,
    /// Step of the message last sent (for errors).
    step: Option<u32>,
    /// Folder for observations sent as files; made at the first one, removed on drop.
    tmp: PathBuf,
    encoding: ObsEncoding,
    stderr_tail: Arc<Mutex<VecDeque<String>>>,
    stderr_thread: Option<JoinHandle<()>>,
    episode_id: u64,
    step_size: f32,
    turn_deg: f32,
}

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Lines of the agent's stderr kept for error messages.
pub const STDERR_TAIL_LINES: usize = 10;

impl ExternalAgent {
    /// Start `sh -c cmd` with piped stdin/stdout; its stderr is passed through to ours, and
    /// the last `STDERR_TAIL_LINES` lines are kept for the error when the agent dies.
    pub fn spawn(cmd: &str, encoding: ObsEncoding) -> Result<Self> {
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(cmd)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| TaskError::invalid("agent_cmd", cmd, e.to_string()))?;
        let stderr_tail = Arc::new(Mutex::new(VecDeque::new()));
        let stderr_thread = child.stderr.take().map(|err| {
            let tail = stderr_tail.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(err)
                    .lines()
                    .map_while(std::result::Result::ok)
                {
                    eprintln!("{line}");
                    let mut t = tail
                        .lock()
                        .unwrap_or_else(std::sync::PoisonError::into_inner);
                    if t.len() == STDERR_TAIL_LINES {
                        t.pop_front();
                    }
                    t.push_back(line);
                }
            })
        });
        let (stdin, written) = match child.stdin.take() {
            Some(pipe) => {
                let (tx, rx) = write_lines(pipe);
                (Some(tx), rx)
            }
            None => (None, std::sync::mpsc::channel().1),
        };
        let stdout = child
            .stdout
            .take()
            .map(BufReader::new)
            .ok_or_else(|| TaskError::invalid("agent_cmd", cmd, "no stdout pipe"))?;
        let replies = read_lines(stdout);
        let tmp = std::env::temp_dir().join(format!(
            "vlnverse-agent-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        Ok(ExternalAgent {
            cmd: cmd.into(),
            child,
            stdin,
            written,
            replies,
            timeout: Duration::from_secs_f64(DEFAULT_EXTERNAL_TIMEOUT_S),
            step: None,
            tmp,
            encoding,
            stderr_tail,
            stderr_thread,
            episode_id: 0,
            step_size: 0.25,
            turn_deg: 15.0,
        })
    }

    fn err(&self, msg: impl Into<String>) -> TaskError {
        let step = self.step.map(|s| format!(", step {s}")).unwrap_or_default();
        TaskError::invalid(
            "agent_cmd",
            &self.cmd,
            format!("episode {}{step}: {}", self.episode_id, msg.into()),
        )
    }

    /// The error of an agent that stopped talking: its exit status (waiting up to a second for
    /// it) and the last lines of its stderr.
    fn dead(&mut self, what: String) -> TaskError {
        let mut status = None;
        for _ in 0..50 {
            if let Ok(Some(s)) = self.child.try_wait() {
                status = Some(s);
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        // Once the process is gone its stderr ends; let the reader catch the last lines.
        if let Some(t) = self.stderr_thread.take() {
            for _ in 0..50 {
                if t.is_finished() {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            if t.is_finished() {
                let _ = t.join();
            } else {
                self.stderr_thread = Some(t);
            }
        }
        let status = status.map_or_else(
            || "it is still running".to_string(),
            |s| format!("it exited with {s}"),
        );
        let tail: Vec<String> = self
            .stderr_tail
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .iter()
            .cloned()
            .collect();
        let stderr = if tail.is_empty() {
            "; its stderr was empty".to_string()
        } else {
            format!("; last lines of its stderr:\n    {}", tail.join("\n    "))
        };
        self.err(format!("{what}: {status}{stderr}"))
    }

    /// Write one message, waiting at most the reply timeout for the agent to take it.
    fn send(&mut self, v: &Value) -> Result<()> {
        let mut line = v.to_string();
        line.push('\n');
        let bytes = line.len();
        let queued = match &self.stdin {
            Some(tx) => tx.send(line.into_bytes()).is_ok(),
            None => false,
        };
        if !queued {
            return Err(self.dead("cannot write to the agent (its input is closed)".into()));
        }
        match self.written.recv_timeout(self.timeout) {
            Ok(Ok(())) => Ok(()),
            Ok(Err(e)) => Err(self.dead(format!("cannot write to the agent ({e})"))),
            Err(RecvTimeoutError::Disconnected) => {
                Err(self.dead("cannot write to the agent (its input is closed)".into()))
            }
            Err(RecvTimeoutError::Timeout) => {
                // The agent does not read its input: stopping it also ends the blocked write.
                let _ = self.child.kill();
                self.stdin = None;
                Err(self.err(format!(
                    "the agent did not read a {bytes}-byte message within {:.1} s \
                     (external_timeout_s); the agent was stopped",
                    self.timeout.as_secs_f64()
                )))
            }
        }
    }

    fn receive(&mut self) -> Result<Value> {
        let line = loop {
            match self.replies.recv_timeout(self.timeout) {
                Ok(Ok(line)) if line.trim().is_empty() => continue,
                Ok(Ok(line)) => break line,
                Ok(Err(e)) => {
                    return Err(self.dead(format!("cannot read from the agent ({e})")));
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(self.dead("the agent closed its output".into()));
                }
                Err(RecvTimeoutError::Timeout) => {
                    // A hung agent is stopped, so the run ends instead of waiting forever.
                    let _ = self.child.kill();
                    return Err(self.err(format!(
                        "no reply within {:.1} s (external_timeout_s); the agent was stopped",
                        self.timeout.as_secs_f64()
                    )));
                }
            }
        };
        serde_json::from_str(line.trim())
            .map_err(|e| self.err(format!("reply is not JSON ({e}): {}", line.trim())))
    }

    fn frame_entry(&self, name: &str, kind: &str, f: &Frame) -> Result<Value> {
        let (w, h) = (f.width as usize, f.height as usize);
        // A frame channel as `.npy` bytes (files) or its raw little-endian array (base64).
        fn array<T: NpyElement>(data: &[T], shape: &[usize], npy: bool) -> SensorResult<Vec<u8>> {
            if npy {
                return output::npy(shape, data);
            }
            let mut raw = Vec::with_capacity(std::mem::size_of_val(data));
            data.iter().for_each(|v| v.put_le(&mut raw));
            Ok(raw)
        }
        let files = self.encoding == ObsEncoding::Files;
        let hw = [h, w];
        let (ext, dtype, shape, bytes) = match kind {
            "rgb" => {
                let shape = vec![h, w, 3];
                let bytes = if files {
                    output::rgb_png(f)
                } else {
                    array(&f.rgb, &shape, false)
                };
                ("png", u8::DESCR, shape, bytes)
            }
            "depth" => ("npy", f32::DESCR, hw.to_vec(), array(&f.depth, &hw, files)),
            "semantic" => (
                "npy",
                u16::DESCR,
                hw.to_vec(),
                array(&f.semantic, &hw, files),
            ),
            _ => (
                "npy",
                u32::DESCR,
                hw.to_vec(),
                array(&f.instance, &hw, files),
            ),
        };
        let bytes = bytes.map_err(|e| self.err(format!("observation `{name}` ({kind}): {e}")))?;
        let mut v = json!({"kind": kind, "width": w, "height": h, "dtype": dtype, "shape": shape});
        if files {
            // Made at the first file, so an agent reading inline data leaves no folder behind
            // even when its process is killed.
            std::fs::create_dir_all(&self.tmp).map_err(|e| TaskError::io(&self.tmp, e))?;
            let path = self.tmp.join(format!("{name}.{ext}"));
            std::fs::write(&path, bytes).map_err(|e| TaskError::io(&path, e))?;
            v["encoding"] = json!("file");
            v["path"] = json!(path.display().to_string());
        } else {
            v["encoding"] = json!("base64");
            v["data"] = json!(STANDARD.encode(&bytes));
        }
        Ok(v)
    }

    fn observations(&self, step: &StepInput) -> Result<Value> {
        let mut out = Map::new();
        for (name, obs) in step.observations {
            let v = match obs {
                Observation::Rgb(f) => self.frame_entry(name, "rgb", f)?,
                Observation::Depth(f) => self.frame_entry(name, "depth", f)?,
                Observation::Semantic(f) => self.frame_entry(name, "semantic", f)?,
                Observation::Instance(f) => self.frame_entry(name, "instance", f)?,
                Observation::Panorama(frames) => {
                    let mut views = Vec::new();
                    for (i, f) in frames.iter().enumerate() {
                        let mut view = Map::new();
                        for kind in ["rgb", "depth", "semantic"] {
                            let has = match kind {
                                "rgb" => !f.rgb.is_empty(),
                                "depth" => !f.depth.is_empty(),
                                _ => !f.semantic.is_empty(),
                            };
                            if has {
                                view.insert(
                                    kind.into(),
                                    self.frame_entry(&format!("{name}_{i}_{kind}"), kind, f)?,
                                );
                            }
                        }
                        views.push(Value::Object(view));
                    }
                    json!({"kind": "panorama", "views": views})
                }
                Observation::Lidar(scan) => {
                    let ranges: Vec<Value> = scan
                        .ranges
                        .iter()
                        .map(|r| if r.is_finite() { json!(r) } else { Value::Null })
                        .collect();
                    json!({"kind": "lidar", "beams": scan.beams, "channels": scan.channels, "ranges": ranges})
                }
                Observation::Pose(p) => {
                    json!({"kind": "pose", "position": p.position, "rotation": p.rotation})
                }
                Observation::Compass(h) => json!({"kind": "compass", "value": h}),
                Observation::Gps(g) => json!({"kind": "gps", "value": g}),
                Observation::Collision(c) => json!({"kind": "collision", "collided": c.collided,
                    "displacement": c.displacement, "count": c.count}),
            };
            out.insert(name.clone(), v);
        }
        Ok(Value::Object(out))
    }

    fn parse_action(&self, v: &Value) -> Result<Action> {
        let name = v.get("action").and_then(Value::as_str).unwrap_or("");
        let num = |k: &str| v.get(k).and_then(Value::as_f64).map(|x| x as f32);
        let need = |k: &str| {
            num(k).ok_or_else(|| self.err(format!("action `{name}` needs a number `{k}`: {v}")))
        };
        Ok(match name {
            "stop" => Action::Stop,
            "move_forward" => Action::MoveForward(num("distance").unwrap_or(self.step_size)),
            "turn_left" => Action::TurnLeft(num("degrees").unwrap_or(self.turn_deg).to_radians()),
            "turn_right" => Action::TurnRight(num("degrees").unwrap_or(self.turn_deg).to_radians()),
            "look_up" => Action::LookUp,
            "look_down" => Action::LookDown,
            "velocity" => Action::Velocity {
                v: need("v")?,
                omega: need("omega")?,
                duration: need("duration")?,
            },
            "waypoint" => Action::Waypoint {
                x: need("x")?,
                z: need("z")?,
                mode: match v.get("mode").and_then(Value::as_str) {
                    Some("telhop") | Some("tel_hop") => WaypointMode::TelHop,
                    _ => WaypointMode::Drive,
                },
            },
            _ => return Err(self.err(format!("unknown action in reply: {v}"))),
        })
    }
}

impl Agent for ExternalAgent {
    fn reset(&mut self, i: &EpisodeInputs) -> Result<()> {
        self.episode_id = i.episode_id;
        self.step = None;
        self.step_size = i.agent.step_size;
        self.turn_deg = i.agent.turn_angle_deg;
        let msg = json!({
            "type": "episode",
            "episode_id": i.episode_id,
            "scene_id": i.scene_id,
            "task": i.task.name(),
            "instruction": i.instruction,
            "sub_instructions": i.sub_instructions,
            "reference_image": i.reference_image.as_ref().map(|p| p.display().to_string()),
            "action_space": i.action_space.name(),
            "setting": i.setting.name(),
            "step_size": i.agent.step_size,
            "turn_angle_deg": i.agent.turn_angle_deg,
            "success_distance": i.success_distance,
            "max_steps": i.max_steps,
            "oracle_budget": i.oracle_budget,
            "seed": i.seed,
        });
        self.send(&msg)
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        self.step = Some(step.step);
        let msg = json!({
            "type": "step",
            "step": step.step,
            "pose": {"position": step.pose.position, "yaw": step.pose.yaw()},
            "collided": step.last.is_some_and(|o| o.collided),
            "sub_goal": {"current": step.sub_goal.current, "total": step.sub_goal.total},
            "oracle_left": step.oracle.as_ref().map(|o| o.remaining()),
            "observations": self.observations(step)?,
        });
        self.send(&msg)?;
        loop {
            let reply = self.receive()?;
            if reply.get("action").and_then(Value::as_str) == Some("ask") {
                let q = reply.get("question").and_then(Value::as_str).unwrap_or("");
                let answer = step.oracle.as_mut().and_then(|o| o.ask(q));
                self.send(&json!({"type": "answer", "text": answer}))?;
                continue;
            }
            return self.parse_action(&reply);
        }
    }

    fn end_episode(&mut self) -> Result<()> {
        let msg = json!({"type": "episode_end", "episode_id": self.episode_id});
        self.send(&msg)
    }
}

impl Drop for ExternalAgent {
    fn drop(&mut self) {
        drop(self.stdin.take());
        // Give the process a moment to exit on EOF, then make sure it is gone.
        for _ in 0..50 {
            if matches!(self.child.try_wait(), Ok(Some(_))) {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        if matches!(self.child.try_wait(), Ok(None)) {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
        if let Some(t) = self.stderr_thread.take() {
            if t.is_finished() {
                let _ = t.join();
            }
        }
        let _ = std::fs::remove_dir_all(&self.tmp);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_sensors::Frame;

    fn frame() -> Frame {
        Frame {
            width: 3,
            height: 2,
            rgb: (0..18).collect(),
            depth: vec![0.5; 6],
            semantic: vec![7; 6],
            instance: vec![0x0102_0304; 6],
        }
    }

    fn agent(encoding: ObsEncoding) -> ExternalAgent {
        ExternalAgent::spawn("cat > /dev/null", encoding).unwrap()
    }

    #[test]
    fn a_message_the_agent_never_reads_fails_after_the_timeout_naming_command_episode_and_step() {
        // Sleeps without reading: a message larger than the pipe buffer cannot be written.
        let cmd = "exec sleep 30";
        let mut a = ExternalAgent::spawn(cmd, ObsEncoding::Files).unwrap();
        a.timeout = Duration::from_millis(300);
        a.episode_id = 7;
        a.step = Some(3);
        let big = json!({"type": "step", "pad": "x".repeat(1 << 20)});
        let err = a.send(&big).unwrap_err().to_string();
        assert!(
            err.contains(cmd)
                && err.contains("episode 7, step 3")
                && err.contains("did not read")
                && err.contains("external_timeout_s"),
            "{err}"
        );
        // The agent was stopped, and later messages fail at once instead of blocking.
        assert!(a.send(&json!({"type": "step"})).is_err());
        assert!(a.child.try_wait().unwrap().is_some());
    }

    /// Files: RGB as PNG, the other channels as `.npy` with their dtype and `[h, w]` shape.
    #[test]
    fn file_observations_are_png_and_npy() {
        let a = agent(ObsEncoding::Files);
        let v = a.frame_entry("depth", "depth", &frame()).unwrap();
        assert_eq!(
            (v["dtype"].as_str(), v["encoding"].as_str()),
            (Some("<f4"), Some("file"))
        );
        let b = std::fs::read(v["path"].as_str().unwrap()).unwrap();
        assert_eq!(&b[..6], b"\x93NUMPY");
        let hlen = u16::from_le_bytes([b[8], b[9]]) as usize;
        assert_eq!((10 + hlen) % 64, 0);
        let header = String::from_utf8_lossy(&b[10..10 + hlen]);
        assert!(
            header.contains("'descr': '<f4'") && header.contains("'shape': (2, 3,)"),
            "{header}"
        );
        assert_eq!(b.len(), 10 + hlen + 24);
        let v = a.frame_entry("sem", "semantic", &frame()).unwrap();
        let b = std::fs::read(v["path"].as_str().unwrap()).unwrap();
        assert!(String::from_utf8_lossy(&b).contains("'<u2'"));
        let v = a.frame_entry("rgb", "rgb", &frame()).unwrap();
        let png = std::fs::read(v["path"].as_str().unwrap()).unwrap();
        let img = image::load_from_memory(&png).unwrap().to_rgb8();
        assert_eq!(img.as_raw(), &frame().rgb);
        let folder = a.tmp.clone();
        assert!(folder.is_dir());
        drop(a);
        assert!(!folder.exists(), "the files' folder goes with the agent");
    }

    /// Base64: the standard alphabet with padding over the raw little-endian array.
    #[test]
    fn base64_observations_are_the_raw_little_endian_array() {
        let a = agent(ObsEncoding::Base64);
        let v = a.frame_entry("instance", "instance", &frame()).unwrap();
        assert_eq!(v["encoding"], "base64");
        // No folder for inline data (none is left behind if the process is killed).
        assert!(!a.tmp.exists());
        assert_eq!(v["shape"], json!([2, 3]));
        let raw = STANDARD.decode(v["data"].as_str().unwrap()).unwrap();
        assert_eq!(raw, [4u8, 3, 2, 1].repeat(6));
        let v = a.frame_entry("rgb", "rgb", &frame()).unwrap();
        assert_eq!(v["dtype"], "|u1");
        // 18 bytes: six groups of four characters, no padding.
        assert_eq!(v["data"].as_str().unwrap().len(), 24);
        assert_eq!(
            STANDARD.decode(v["data"].as_str().unwrap()).unwrap(),
            frame().rgb
        );
    }
}
