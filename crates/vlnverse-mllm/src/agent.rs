//! The agent: builds each decision's request, reads the reply into moves, queues them, and
//! counts what it cost.

use std::collections::{BTreeMap, VecDeque};
use std::sync::{Arc, Mutex};

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use sha2::{Digest, Sha256};
use vlnverse_eval::{
    ActionSpace, Agent, AgentFactory, EpisodeInputs, Result, StepInput, TaskError,
};
use vlnverse_instructions::llm::{ChatClient, ChatMessage, ChatReply, Content, ImageUrl, Part};
use vlnverse_score::episode::Task;
use vlnverse_sensors::config::{CameraSpec, PanoramaSpec};
use vlnverse_sensors::{Frame, Observation, SensorSpec};
use vlnverse_sim::Action;

use crate::accounting::EpisodeStats;
use crate::config::{Fallback, History, MllmConfig, View};
use crate::images::{encode, frame_image, strip, Encoded};
use crate::map::{DepthCamera, ExploredMap};
use crate::parse::{parse_reply, Decision, Steps};
use crate::prompt::{self, Entry, StepText};

/// Sensor names the agent attaches.
pub const RGB_SENSOR: &str = "mllm_rgb";
/// The depth camera behind the map and the text history.
pub const DEPTH_SENSOR: &str = "mllm_depth";
/// The panorama of `view = "panorama4"` / `"panorama12"`.
pub const PANORAMA_SENSOR: &str = "mllm_pano";

const DEPTH_CAMERA: DepthCamera = DepthCamera {
    hfov_deg: 90.0,
    far: 10.0,
    normalized: false,
};

/// Where the agent's requests go: the chat client, or a stand-in (dry run, tests).
pub trait ChatBackend: Send + Sync {
    /// Send `messages`; the reply and what it cost.
    fn chat(&self, messages: &[ChatMessage], seed: u64) -> Result<ChatReply>;
}

impl ChatBackend for ChatClient {
    fn chat(&self, messages: &[ChatMessage], seed: u64) -> Result<ChatReply> {
        self.chat_detailed(messages, seed).map_err(TaskError::from)
    }
}

/// A picture part of a message.
pub fn image_part(img: &Encoded) -> Part {
    Part::ImageUrl {
        image_url: ImageUrl {
            url: format!("data:{};base64,{}", img.mime, STANDARD.encode(&img.bytes)),
        },
    }
}

/// Makes [`MllmAgent`]s sharing one backend (so the concurrency limit holds over all worker
/// threads) and collects their per-episode accounting. Clones share both.
#[derive(Clone)]
pub struct MllmFactory {
    cfg: Arc<MllmConfig>,
    backend: Arc<dyn ChatBackend>,
    stats: Arc<Mutex<BTreeMap<u64, EpisodeStats>>>,
}

impl MllmFactory {
    /// Agents talking to the configured endpoint. The config is checked, and so is the API
    /// key's environment variable (a missing key fails here, not at the first step).
    pub fn new(cfg: MllmConfig) -> Result<Self> {
        cfg.validate()?;
        if let Some(var) = &cfg.api_key_env {
            if std::env::var_os(var).is_none() {
                return Err(TaskError::invalid(
                    "mllm.api_key_env",
                    var,
                    "the environment variable is not set (set it, or leave api_key_env out for a keyless server)",
                ));
            }
        }
        let client = ChatClient::new(cfg.chat_config())?;
        Ok(Self::with_backend(cfg, Arc::new(client)))
    }

    /// Agents talking to `backend` (the config is taken as it is).
    pub fn with_backend(cfg: MllmConfig, backend: Arc<dyn ChatBackend>) -> Self {
        MllmFactory {
            cfg: Arc::new(cfg),
            backend,
            stats: Arc::default(),
        }
    }

    /// The config.
    pub fn config(&self) -> &MllmConfig {
        &self.cfg
    }

    /// Accounting of the episodes finished so far, in episode order.
    pub fn stats(&self) -> Vec<EpisodeStats> {
        self.stats
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .values()
            .cloned()
            .collect()
    }
}

impl AgentFactory for MllmFactory {
    fn name(&self) -> String {
        let cot = if self.cfg.chain_of_thought {
            "+cot"
        } else {
            ""
        };
        let mode = match self.cfg.history {
            History::Text => "text",
            History::Map => "map",
        };
        format!("mllm:{}:{mode}{cot}", self.cfg.model)
    }

    fn make(&self) -> Result<Box<dyn Agent>> {
        Ok(Box::new(MllmAgent::new(
            self.cfg.clone(),
            self.backend.clone(),
            self.stats.clone(),
        )))
    }

    /// The model and every setting that changes what is sent, plus the prompt files; not the
    /// endpoint, timeouts, retries, concurrency or cache (they do not change the replies).
    fn fingerprint(&self) -> Option<String> {
        let mut c = (*self.cfg).clone();
        c.endpoint.clear();
        c.api_key_env = None;
        c.timeout_s = 1.0;
        c.retries = 0;
        c.retry_backoff_ms = 0;
        c.max_concurrent_requests = 1;
        c.cache = true;
        c.cache_dir = None;
        let mut h = Sha256::new();
        h.update(toml::to_string(&c).unwrap_or_default().as_bytes());
        for p in prompt::ALL {
            h.update(p.as_bytes());
        }
        let hex: String = h.finalize()[..8]
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        Some(format!(
            "mllm model {} of vlnverse-mllm {}; settings and prompts {hex}",
            self.cfg.model,
            env!("CARGO_PKG_VERSION")
        ))
    }
}

/// Per-episode state.
struct Episode {
    inputs: EpisodeInputs,
    system: String,
    steps: Steps,
    reference: Option<Encoded>,
    map: ExploredMap,
    queue: VecDeque<Action>,
    history: Vec<Entry>,
    answers: Vec<(String, String)>,
    stats: EpisodeStats,
    sub_goal: u32,
}

/// A zero-shot agent driven by a chat model (see the crate docs).
pub struct MllmAgent {
    cfg: Arc<MllmConfig>,
    backend: Arc<dyn ChatBackend>,
    sink: Arc<Mutex<BTreeMap<u64, EpisodeStats>>>,
    ep: Option<Episode>,
}

impl MllmAgent {
    /// An agent sending to `backend`, reporting each finished episode into `sink`.
    pub fn new(
        cfg: Arc<MllmConfig>,
        backend: Arc<dyn ChatBackend>,
        sink: Arc<Mutex<BTreeMap<u64, EpisodeStats>>>,
    ) -> Self {
        MllmAgent {
            cfg,
            backend,
            sink,
            ep: None,
        }
    }
}

/// "open floor ahead 1.2 m, left 0.4 m, right more than 9.8 m" from the depth camera's middle
/// row (thirds of the image).
pub fn clearance(depth: &Frame, cam: DepthCamera) -> Option<String> {
    if depth.depth.len() != depth.pixels() || depth.width < 3 {
        return None;
    }
    let row = depth.height / 2;
    let w = depth.width;
    let third = |a: u32, b: u32| {
        (a..b)
            .map(|u| {
                let d = depth.depth[depth.index(u, row)];
                if cam.normalized {
                    d * cam.far
                } else {
                    d
                }
            })
            .filter(|d| d.is_finite() && *d > 0.0)
            .fold(f32::INFINITY, f32::min)
    };
    let say = |d: f32| {
        if d >= cam.far * 0.98 {
            format!("more than {:.0} m", cam.far * 0.98)
        } else if d.is_finite() {
            format!("{d:.1} m")
        } else {
            "unknown".to_string()
        }
    };
    Some(format!(
        "open floor ahead {}, left {}, right {}",
        say(third(w / 3, 2 * w / 3)),
        say(third(0, w / 3)),
        say(third(2 * w / 3, w))
    ))
}

fn describe(actions: &[Action], steps: &Steps) -> String {
    let n = actions.len() as f32;
    match actions.first() {
        Some(Action::MoveForward(_)) => format!("move forward {:.0} cm", n * steps.step_m * 100.0),
        Some(Action::TurnLeft(_)) => format!("turn left {:.0} degrees", n * steps.turn_deg),
        Some(Action::TurnRight(_)) => format!("turn right {:.0} degrees", n * steps.turn_deg),
        Some(Action::Stop) => "stop".into(),
        _ => "other".into(),
    }
}

impl MllmAgent {
    fn ep(&mut self) -> Result<&mut Episode> {
        self.ep
            .as_mut()
            .ok_or_else(|| TaskError::invalid("mllm", "act", "act before reset"))
    }

    /// The pictures of this decision (reference, view, map) and their descriptions.
    fn pictures(&self, step: &StepInput) -> Result<(Vec<Encoded>, Vec<String>)> {
        let cfg = &self.cfg;
        let ep = self.ep.as_ref().expect("reset before act");
        let (mut imgs, mut words) = (Vec::new(), Vec::new());
        if let Some(r) = &ep.reference {
            imgs.push(r.clone());
            words.push("first, the reference picture taken at the goal".to_string());
        }
        match cfg.view {
            View::Current => {
                if let Some(Observation::Rgb(f)) = step.observations.get(RGB_SENSOR) {
                    if let Some(img) = frame_image(f) {
                        imgs.push(encode(&img, cfg.image_format, cfg.jpeg_quality)?);
                        words.push("the robot's camera, facing forward".to_string());
                    }
                }
            }
            View::Panorama4 | View::Panorama12 => {
                if let Some(Observation::Panorama(views)) = step.observations.get(PANORAMA_SENSOR) {
                    // Views come counter-clockwise from the heading; shown right to left so
                    // the strip reads like turning on the spot, with the heading in the middle.
                    let n = views.len();
                    let order: Vec<&Frame> = (0..n).map(|k| &views[(n / 2 + n - k) % n]).collect();
                    if let Some(img) = strip(&order) {
                        imgs.push(encode(&img, cfg.image_format, cfg.jpeg_quality)?);
                        words.push(format!(
                            "a strip of {n} views all around the robot, {} degrees apart, the middle one facing forward, left of it the views to the robot's left",
                            360 / n.max(1)
                        ));
                    }
                }
            }
            View::None => {}
        }
        if cfg.history == History::Map {
            let img = ep.map.render(cfg.map_size);
            imgs.push(encode(&img, cfg.image_format, cfg.jpeg_quality)?);
            words.push(format!(
                "last, the map of the explored area ({:.3} m per pixel)",
                ep.map.metres_per_pixel(cfg.map_size)
            ));
        }
        Ok((imgs, words))
    }

    fn user_message(
        &self,
        step: &StepInput,
        pictures: &(Vec<Encoded>, Vec<String>),
    ) -> ChatMessage {
        let ep = self.ep.as_ref().expect("reset before act");
        let depth = match step.observations.get(DEPTH_SENSOR) {
            Some(Observation::Depth(f)) => clearance(f, DEPTH_CAMERA),
            _ => None,
        };
        let goals = (ep.inputs.task == Task::LongHorizon && !ep.inputs.sub_instructions.is_empty())
            .then_some((ep.inputs.sub_instructions.as_slice(), step.sub_goal.current));
        let dialogue = ep.inputs.oracle_budget.map(|_| {
            let left = step.oracle.as_ref().map_or(0, |o| o.remaining());
            (left, ep.answers.as_slice())
        });
        let text = StepText {
            instruction: &ep.inputs.instruction,
            goals,
            dialogue,
            step: step.step,
            max_steps: ep.inputs.max_steps,
            history: &ep.history,
            history_steps: self.cfg.history_steps as usize,
            seen_now: depth.as_deref(),
            blocked_now: step.last.is_some_and(|l| l.collided),
            pictures: &pictures.1,
        }
        .render(self.cfg.history);
        let mut parts = vec![Part::Text { text }];
        parts.extend(pictures.0.iter().map(image_part));
        ChatMessage {
            role: "user".into(),
            content: Content::Parts(parts),
        }
    }

    fn call(&mut self, messages: &[ChatMessage]) -> Option<String> {
        let seed = self.ep.as_ref().map_or(0, |e| e.inputs.seed);
        let result = self.backend.chat(messages, seed);
        let s = &mut self.ep.as_mut().expect("reset before act").stats;
        match result {
            Ok(r) => {
                s.calls += 1;
                if r.cached {
                    s.cache_hits += 1;
                } else {
                    s.requests += 1;
                    s.transport_retries += u64::from(r.attempts.saturating_sub(1));
                    s.latency_ms += r.latency.as_secs_f64() * 1e3;
                }
                match r.usage {
                    Some(u) => {
                        s.prompt_tokens += u.prompt_tokens;
                        s.completion_tokens += u.completion_tokens;
                    }
                    None => s.calls_without_usage += 1,
                }
                Some(r.text)
            }
            Err(e) => {
                s.failed_calls += 1;
                tracing::warn!(error = %e, "MLLM call failed; taking the fallback move");
                None
            }
        }
    }

    /// Ask the model for the next moves: at most `asks_per_step` questions to the oracle and
    /// one corrective retry, then the fallback. Never loops further.
    fn decide(&mut self, step: &mut StepInput) -> Result<Vec<Action>> {
        let pictures = self.pictures(step)?;
        let system = ChatMessage::system(self.ep()?.system.clone());
        let mut messages = vec![system.clone(), self.user_message(step, &pictures)];
        let steps = self.ep()?.steps;
        let mut asked = 0;
        let mut corrected = false;
        while let Some(reply) = self.call(&messages) {
            let correction = match parse_reply(&reply, &steps) {
                Some(Decision::Act(a)) => return Ok(a),
                Some(Decision::Ask(q)) => {
                    let can = asked < self.cfg.asks_per_step
                        && step.oracle.as_ref().is_some_and(|o| o.remaining() > 0);
                    let answer = if can {
                        self.ep()?.stats.asks += 1;
                        step.oracle.as_mut().and_then(|o| o.ask(&q))
                    } else {
                        None
                    };
                    match answer {
                        Some(a) => {
                            asked += 1;
                            self.ep()?.answers.push((q, a));
                            messages = vec![system.clone(), self.user_message(step, &pictures)];
                            continue;
                        }
                        None => prompt::NO_QUESTIONS,
                    }
                }
                None => prompt::CORRECTIVE,
            };
            if corrected {
                break;
            }
            corrected = true;
            self.ep()?.stats.parse_retries += 1;
            messages.push(ChatMessage {
                role: "assistant".into(),
                content: Content::Text(reply),
            });
            messages.push(ChatMessage::user(correction.trim()));
        }
        let ep = self.ep()?;
        ep.stats.fallbacks += 1;
        let s = ep.steps;
        Ok(vec![match self.cfg.fallback {
            Fallback::TurnLeft => Action::TurnLeft(s.turn_deg.to_radians()),
            Fallback::TurnRight => Action::TurnRight(s.turn_deg.to_radians()),
            Fallback::MoveForward => Action::MoveForward(s.step_m),
            Fallback::Stop => Action::Stop,
        }])
    }
}

impl Agent for MllmAgent {
    fn required_sensors(&self) -> Vec<SensorSpec> {
        let size = self.cfg.image_size;
        let cam = |name: &str| CameraSpec {
            name: name.into(),
            width: size,
            height: size,
            ..CameraSpec::default()
        };
        let mut out = vec![SensorSpec::Depth(CameraSpec {
            name: DEPTH_SENSOR.into(),
            width: 128,
            height: 32,
            hfov_deg: DEPTH_CAMERA.hfov_deg,
            far: DEPTH_CAMERA.far,
            normalize: false,
            ..CameraSpec::default()
        })];
        match self.cfg.view {
            View::Current => out.push(SensorSpec::Rgb(cam(RGB_SENSOR))),
            View::Panorama4 | View::Panorama12 => {
                let views = self.cfg.view.count();
                out.push(SensorSpec::Panorama(PanoramaSpec {
                    camera: cam(PANORAMA_SENSOR),
                    views,
                    step_deg: 360.0 / views as f32,
                    rgb: true,
                    depth: false,
                    semantic: false,
                }))
            }
            View::None => {}
        }
        out
    }

    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        if inputs.action_space != ActionSpace::Discrete {
            return Err(TaskError::invalid(
                "action_space",
                format!("{:?}", inputs.action_space).to_lowercase(),
                "the MLLM agent answers with discrete moves; run it with --action-space discrete",
            ));
        }
        let steps = Steps {
            step_m: inputs.agent.step_size,
            turn_deg: inputs.agent.turn_angle_deg,
            max_repeat: self.cfg.max_actions_per_reply,
        };
        let reference = match (&inputs.reference_image, inputs.task) {
            (Some(path), Task::VisualReference) => {
                let bytes = std::fs::read(path).map_err(|e| TaskError::io(path, e))?;
                let img = image::load_from_memory(&bytes)
                    .map_err(|e| TaskError::parse(path, "reference image", e))?;
                let img = img.to_rgb8();
                Some(encode(&img, self.cfg.image_format, self.cfg.jpeg_quality)?)
            }
            _ => None,
        };
        self.ep = Some(Episode {
            system: prompt::system(&self.cfg, inputs.task, steps.step_m, steps.turn_deg),
            steps,
            reference,
            map: ExploredMap::new(&inputs.start, self.cfg.map_resolution_m),
            queue: VecDeque::new(),
            history: Vec::new(),
            answers: Vec::new(),
            stats: EpisodeStats {
                episode_id: inputs.episode_id,
                ..Default::default()
            },
            sub_goal: 0,
            inputs: inputs.clone(),
        });
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        let depth = match step.observations.get(DEPTH_SENSOR) {
            Some(Observation::Depth(f)) => Some(f),
            _ => None,
        };
        let seen = depth.and_then(|f| clearance(f, DEPTH_CAMERA));
        let blocked = step.last.is_some_and(|l| l.collided);
        let ep = self.ep()?;
        ep.map.observe(&step.pose, depth.map(|f| (f, DEPTH_CAMERA)));
        if blocked {
            if let Some(e) = ep.history.last_mut() {
                e.blocked = true;
            }
            // The rest of a blocked walk would push into the same obstacle.
            if matches!(ep.queue.front(), Some(Action::MoveForward(_))) {
                ep.queue.clear();
            }
        }
        if step.sub_goal.current != ep.sub_goal {
            ep.sub_goal = step.sub_goal.current;
            ep.queue.clear();
        }
        if let Some(a) = ep.queue.pop_front() {
            return Ok(a);
        }
        if let Some(e) = ep.history.last_mut() {
            e.seen = seen;
        }
        let actions = self.decide(step)?;
        let ep = self.ep()?;
        ep.stats.decisions += 1;
        ep.history.push(Entry {
            step: step.step,
            action: describe(&actions, &ep.steps),
            blocked: false,
            seen: None,
        });
        ep.queue.extend(actions);
        Ok(ep.queue.pop_front().unwrap_or(Action::Stop))
    }

    fn end_episode(&mut self) -> Result<()> {
        if let Some(ep) = self.ep.take() {
            self.sink
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .insert(ep.stats.episode_id, ep.stats);
        }
        Ok(())
    }
}
