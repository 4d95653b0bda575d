//! The agent-server client: one named agent on the server per evaluation, `init` once,
//! `reset` at every episode start, `step` every step.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use serde_json::{json, Map, Value as Json};
use vlnverse_env::Pose;
use vlnverse_eval::agents::wrap_angle;
use vlnverse_eval::{
    ActionSpace, Agent, AgentFactory, EpisodeInputs, Result, StepInput, TaskError,
};
use vlnverse_sensors::{Frame, Observation};
use vlnverse_sim::Action;

use crate::pickle::{self, DType, Value};

/// Longest per-request timeout accepted (an hour; a longer one is a typo, not a plan).
pub const MAX_TIMEOUT: Duration = Duration::from_secs(3600);
/// Most retries accepted.
pub const MAX_RETRIES: u32 = 10;

/// Where the agent server is and how long to wait for it.
#[derive(Debug, Clone)]
pub struct HttpAgentConfig {
    /// Base URL of the server, e.g. `http://127.0.0.1:8087` (routes go under `/agent/`).
    pub url: String,
    /// The agent's name: `model_name` of the `init` request, which picks the agent class on
    /// the server.
    pub agent_name: String,
    /// More fields of the `init` request's `agent_config` (`ckpt_path`, `model_settings`,
    /// ...); `model_name` is always `agent_name`.
    pub agent_config: Map<String, Json>,
    /// Longest wait for one step's reply (the agent thinking included).
    pub step_timeout: Duration,
    /// Longest wait for `init` (the server may load a model then).
    pub init_timeout: Duration,
    /// Extra attempts of a request that certainly did not reach the agent (connection
    /// refused; HTTP 429, 502, 503 or 504). A timeout is never retried.
    pub retries: u32,
    /// Wait before the first retry; doubled for each further one.
    pub retry_backoff: Duration,
}

impl HttpAgentConfig {
    /// Defaults: 60 s per step, 600 s for `init`, 2 retries after 0.5 s and 1 s.
    pub fn new(url: impl Into<String>, agent_name: impl Into<String>) -> Self {
        HttpAgentConfig {
            url: url.into(),
            agent_name: agent_name.into(),
            agent_config: Map::new(),
            step_timeout: Duration::from_secs(60),
            init_timeout: Duration::from_secs(600),
            retries: 2,
            retry_backoff: Duration::from_millis(500),
        }
    }

    /// Check the settings; errors name the field and the value.
    pub fn validate(&self) -> Result<()> {
        let url = self.url.as_str();
        let scheme_ok =
            url.starts_with("http://") || (cfg!(feature = "tls") && url.starts_with("https://"));
        if !scheme_ok {
            let want = if cfg!(feature = "tls") {
                "an http:// or https:// URL"
            } else {
                "an http:// URL (https needs the crate's `tls` feature)"
            };
            return Err(TaskError::invalid("agent_url", &self.url, want));
        }
        let rest = url
            .split_once("://")
            .map_or("", |(_, r)| r.trim_end_matches('/'));
        if rest.is_empty() || rest.contains(char::is_whitespace) {
            return Err(TaskError::invalid(
                "agent_url",
                &self.url,
                "expected http://HOST:PORT",
            ));
        }
        let name = &self.agent_name;
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))
        {
            return Err(TaskError::invalid(
                "agent_name",
                name,
                "expected letters, digits, '-', '_' or '.' (it is part of the route /agent/NAME/step)",
            ));
        }
        for (field, t) in [
            ("step_timeout", self.step_timeout),
            ("init_timeout", self.init_timeout),
        ] {
            if t.is_zero() || t > MAX_TIMEOUT {
                return Err(TaskError::invalid(
                    field,
                    format!("{} s", t.as_secs_f64()),
                    format!(
                        "expected more than 0 and at most {} s",
                        MAX_TIMEOUT.as_secs()
                    ),
                ));
            }
        }
        if self.retries > MAX_RETRIES {
            return Err(TaskError::invalid(
                "retries",
                self.retries,
                format!("expected at most {MAX_RETRIES}"),
            ));
        }
        if self.retry_backoff > Duration::from_secs(60) {
            return Err(TaskError::invalid(
                "retry_backoff",
                format!("{} s", self.retry_backoff.as_secs_f64()),
                "expected at most 60 s",
            ));
        }
        Ok(())
    }

    fn base(&self) -> &str {
        self.url.trim_end_matches('/')
    }

    /// The `init` request's `agent_config`: the original client's fields (`server_host`,
    /// `server_port`, `model_name`, `ckpt_path`, `model_settings`) with the configured ones
    /// over them.
    pub fn init_body(&self) -> Json {
        let rest = self.base().split_once("://").map_or("", |(_, r)| r);
        let authority = rest.split('/').next().unwrap_or("");
        let (host, port) = match authority.rsplit_once(':') {
            Some((h, p)) if p.parse::<u16>().is_ok() => (h, p.parse::<u16>().unwrap_or(80)),
            _ => (authority, 80),
        };
        let mut cfg = Map::new();
        cfg.insert("server_host".into(), json!(host));
        cfg.insert("server_port".into(), json!(port));
        cfg.insert("ckpt_path".into(), json!(""));
        cfg.insert("model_settings".into(), json!({}));
        for (k, v) in &self.agent_config {
            cfg.insert(k.clone(), v.clone());
        }
        cfg.insert("model_name".into(), json!(self.agent_name));
        json!({ "agent_config": cfg })
    }
}

/// Makes the [`HttpAgent`] of a run. The server keeps one agent per name, so one agent is
/// alive at a time: a second [`AgentFactory::make`] while the first lives is refused (run the
/// evaluation with one worker thread).
pub struct HttpFactory {
    cfg: HttpAgentConfig,
    live: Arc<AtomicBool>,
}

impl HttpFactory {
    /// A factory for `cfg` (checked).
    pub fn new(cfg: HttpAgentConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(HttpFactory {
            cfg,
            live: Arc::new(AtomicBool::new(false)),
        })
    }
}

impl AgentFactory for HttpFactory {
    fn name(&self) -> String {
        "http".into()
    }
    fn make(&self) -> Result<Box<dyn Agent>> {
        if self.live.swap(true, Ordering::SeqCst) {
            return Err(TaskError::invalid(
                "threads",
                "more than 1",
                format!(
                    "the agent server at {} keeps one agent per name (`{}`), so the HTTP agent \
                     runs on one worker thread (--threads 1)",
                    self.cfg.url, self.cfg.agent_name
                ),
            ));
        }
        match HttpAgent::connect(self.cfg.clone()) {
            Ok(mut a) => {
                a.live = Some(self.live.clone());
                Ok(Box::new(a))
            }
            Err(e) => {
                self.live.store(false, Ordering::SeqCst);
                Err(e)
            }
        }
    }
    /// The agent's name on the server: resuming a run with another agent is refused.
    fn fingerprint(&self) -> Option<String> {
        Some(format!("agent server agent `{}`", self.cfg.agent_name))
    }
}

/// What the client needs of an episode (from [`EpisodeInputs`] in an evaluation).
#[derive(Debug, Clone, Default)]
pub struct EpisodeStart {
    /// Episode id (named in errors).
    pub id: u64,
    /// The instruction text (the observation's `instruction`).
    pub instruction: String,
    /// Start pose (origin of `compass` and `gps`).
    pub start: Pose,
    /// Forward step (m) of action 1.
    pub step_size: f32,
    /// Turn (radians) of actions 2 and 3.
    pub turn: f32,
    /// The run's action space (only discrete is served).
    pub action_space: ActionSpace,
}

impl From<&EpisodeInputs> for EpisodeStart {
    fn from(i: &EpisodeInputs) -> Self {
        EpisodeStart {
            id: i.episode_id,
            instruction: i.instruction.clone(),
            start: i.start,
            step_size: i.agent.step_size,
            turn: i.agent.turn_angle(),
            action_space: i.action_space,
        }
    }
}

/// An agent behind an agent server: `act` sends the step's observations (a pickled list of
/// one dict, base64 in JSON, as the original client sends them) and maps the integer action
/// it gets back (0 stop, 1 forward, 2 left, 3 right, 4 look up, 5 look down, -1 stand still).
pub struct HttpAgent {
    cfg: HttpAgentConfig,
    /// The name the server answered `init` with (the routes use it).
    name: String,
    /// One client, so every request reuses one kept-alive connection (a server that serves
    /// one connection at a time would never read a second one).
    http: ureq::Agent,
    episode: EpisodeStart,
    live: Option<Arc<AtomicBool>>,
}

fn http_agent() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .build()
        .into()
}

/// What a failed attempt was.
enum Failure {
    /// The request may be sent again (it did not reach the agent).
    Retry(String),
    /// The run stops.
    Fatal(String),
}

impl HttpAgent {
    /// `init` the agent on the server (`POST /agent/init`).
    pub fn connect(cfg: HttpAgentConfig) -> Result<Self> {
        cfg.validate()?;
        let mut agent = HttpAgent {
            name: cfg.agent_name.clone(),
            http: http_agent(),
            cfg,
            episode: EpisodeStart::default(),
            live: None,
        };
        let reply = agent.post("/agent/init", &agent.cfg.init_body().to_string(), true)?;
        if let Some(name) = reply.get("agent_name").and_then(Json::as_str) {
            if name != agent.name {
                tracing::info!(asked = %agent.name, answered = %name, "agent server renamed the agent");
                agent.name = name.to_string();
            }
        }
        Ok(agent)
    }

    fn error(&self, route: &str, msg: impl std::fmt::Display) -> TaskError {
        let at = if route.ends_with("/init") {
            String::new()
        } else {
            format!(" (episode {})", self.episode.id)
        };
        TaskError::invalid(
            "agent_url",
            &self.cfg.url,
            format!("POST {route}{at}: {msg}"),
        )
    }

    /// POST `body` to `route` with bounded retries; the reply's JSON object.
    fn post(&self, route: &str, body: &str, init: bool) -> Result<Json> {
        let url = format!("{}{route}", self.cfg.base());
        let timeout = if init {
            self.cfg.init_timeout
        } else {
            self.cfg.step_timeout
        };
        let http = &self.http;
        let mut wait = self.cfg.retry_backoff;
        let mut attempt = 0;
        loop {
            match Self::attempt(http, &url, body, timeout) {
                Ok(v) => return Ok(v),
                Err(Failure::Retry(msg)) if attempt < self.cfg.retries => {
                    attempt += 1;
                    tracing::warn!(%url, attempt, error = %msg, "agent server request failed; retrying");
                    std::thread::sleep(wait);
                    wait = wait.saturating_mul(2);
                }
                Err(Failure::Retry(msg)) => {
                    let tries = attempt + 1;
                    return Err(self.error(
                        route,
                        format!("{msg} (gave up after {tries} attempt{})", plural(tries)),
                    ));
                }
                Err(Failure::Fatal(msg)) => return Err(self.error(route, msg)),
            }
        }
    }

    fn attempt(
        http: &ureq::Agent,
        url: &str,
        body: &str,
        timeout: Duration,
    ) -> std::result::Result<Json, Failure> {
        let sent = http
            .post(url)
            .header("Content-Type", "application/json")
            .config()
            .timeout_global(Some(timeout))
            .build()
            .send(body);
        let mut resp = match sent {
            Ok(r) => r,
            Err(ureq::Error::Timeout(_)) => {
                return Err(Failure::Fatal(format!(
                    "no reply within {} s (the per-request timeout)",
                    timeout.as_secs_f64()
                )))
            }
            Err(e @ ureq::Error::ConnectionFailed) => {
                return Err(Failure::Retry(format!(
                    "cannot connect ({e}); is the agent server running?"
                )))
            }
            Err(ureq::Error::Io(e)) if e.kind() == std::io::ErrorKind::ConnectionRefused => {
                return Err(Failure::Retry(format!(
                    "cannot connect ({e}); is the agent server running?"
                )))
            }
            Err(e) => return Err(Failure::Fatal(e.to_string())),
        };
        let status = resp.status().as_u16();
        let text = match resp.body_mut().read_to_string() {
            Ok(t) => t,
            Err(ureq::Error::Timeout(_)) => {
                return Err(Failure::Fatal(format!(
                    "no complete reply within {} s (the per-request timeout)",
                    timeout.as_secs_f64()
                )))
            }
            Err(e) => return Err(Failure::Fatal(format!("reading the reply: {e}"))),
        };
        if matches!(status, 429 | 502 | 503 | 504) {
            return Err(Failure::Retry(format!("HTTP {status}: {}", clip(&text))));
        }
        if !(200..300).contains(&status) {
            return Err(Failure::Fatal(format!("HTTP {status}: {}", clip(&text))));
        }
        let v: Json = serde_json::from_str(&text)
            .map_err(|e| Failure::Fatal(format!("reply is not JSON ({e}): {}", clip(&text))))?;
        if !v.is_object() {
            return Err(Failure::Fatal(format!(
                "reply is not a JSON object: {}",
                clip(&text)
            )));
        }
        Ok(v)
    }

    /// Start an episode: `POST /agent/NAME/reset` with `{"reset_index": [0]}`.
    pub fn begin(&mut self, episode: EpisodeStart) -> Result<()> {
        let space = episode.action_space;
        self.episode = episode;
        if space != ActionSpace::Discrete {
            return Err(TaskError::invalid(
                "action_space",
                space.name(),
                "the agent server answers discrete actions; run with --action-space discrete",
            ));
        }
        let route = format!("/agent/{}/reset", self.name);
        self.post(&route, &json!({"reset_index": [0]}).to_string(), false)?;
        Ok(())
    }

    /// One step: `POST /agent/NAME/step` with the step's observations; the action answered.
    pub fn step(&mut self, step: &StepInput) -> Result<Action> {
        let route = format!("/agent/{}/step", self.name);
        let body = self.step_body(step);
        let reply = self.post(&route, &body, false)?;
        self.action(&route, &reply, step.step)
    }

    /// The step's observation dict (see the crate docs for the keys).
    pub fn observation(&self, step: &StepInput) -> Value {
        let mut d: Vec<(String, Value)> = Vec::new();
        let has = |d: &[(String, Value)], k: &str| d.iter().any(|(n, _)| n == k);
        for (name, obs) in step.observations {
            // The first camera of a kind gets the common key, further ones their own name.
            let key = |d: &[(String, Value)], common: &str| {
                if name == common || !has(d, common) {
                    common.to_string()
                } else {
                    name.clone()
                }
            };
            match obs {
                Observation::Rgb(f) if !f.rgb.is_empty() => {
                    let k = key(&d, "rgb");
                    d.push((k, rgb(f)));
                }
                Observation::Depth(f) if !f.depth.is_empty() => {
                    let k = key(&d, "depth");
                    d.push((k, depth(f)));
                }
                Observation::Semantic(f) if !f.semantic.is_empty() => {
                    let k = key(&d, "semantic");
                    let data = f.semantic.iter().flat_map(|v| v.to_le_bytes()).collect();
                    d.push((k, image(f, 1, DType::U16, data)));
                }
                Observation::Instance(f) if !f.instance.is_empty() => {
                    let k = key(&d, "instance");
                    let data = f.instance.iter().flat_map(|v| v.to_le_bytes()).collect();
                    d.push((k, image(f, 1, DType::U32, data)));
                }
                Observation::Panorama(views) if !views.is_empty() => {
                    let (h, w) = (views[0].height as usize, views[0].width as usize);
                    if views.iter().all(|v| !v.rgb.is_empty()) {
                        let data = views.iter().flat_map(|v| v.rgb.iter().copied()).collect();
                        d.push((
                            format!("{name}_rgb"),
                            Value::Array {
                                dtype: DType::U8,
                                shape: vec![views.len(), h, w, 3],
                                data,
                            },
                        ));
                    }
                    if views.iter().all(|v| !v.depth.is_empty()) {
                        let vals: Vec<f32> =
                            views.iter().flat_map(|v| v.depth.iter().copied()).collect();
                        d.push((
                            format!("{name}_depth"),
                            Value::f32_array(vec![views.len(), h, w, 1], &vals),
                        ));
                    }
                }
                Observation::Lidar(scan) => {
                    let shape = vec![scan.channels as usize, scan.beams as usize];
                    d.push((key(&d, "lidar"), Value::f32_array(shape, &scan.ranges)));
                }
                // Pose, compass and GPS are sent below whatever the rig holds.
                _ => {}
            }
        }
        let ep = &self.episode;
        let pos = step.pose.position;
        let yaw = step.pose.yaw();
        // The original's frame: Z up, (x, y, z) here is (x, -z, y) there; its heading is
        // measured from +X, ours from -Z, both counter-clockwise seen from above.
        let heading = yaw + std::f32::consts::FRAC_PI_2;
        let (s, c) = (heading * 0.5).sin_cos();
        d.push((
            "globalgps".into(),
            Value::f32_array(vec![3], &[pos[0], -pos[2], pos[1]]),
        ));
        d.push((
            "globalrotation".into(),
            Value::f32_array(vec![4], &[c, 0.0, 0.0, s]),
        ));
        d.push(("instruction".into(), Value::Str(ep.instruction.clone())));
        // The keys of the `vlnverse` Python observations.
        d.push((
            "pose".into(),
            Value::f32_array(vec![4], &[pos[0], pos[1], pos[2], yaw]),
        ));
        d.push((
            "compass".into(),
            Value::f32_array(vec![1], &[wrap_angle(yaw - ep.start.yaw())]),
        ));
        let rel = ep.start.quat().inverse()
            * (glam::Vec3::from_array(pos) - glam::Vec3::from_array(ep.start.position));
        d.push(("gps".into(), Value::f32_array(vec![2], &[-rel.z, rel.x])));
        d.push((
            "sub_instruction_index".into(),
            Value::Array {
                dtype: DType::I64,
                shape: vec![1],
                data: i64::from(step.sub_goal.current).to_le_bytes().to_vec(),
            },
        ));
        Value::Dict(d)
    }

    /// The step request body: `{"observation": base64(pickle([obs]))}`.
    pub fn step_body(&self, step: &StepInput) -> String {
        let obs = Value::List(vec![self.observation(step)]);
        let b64 = STANDARD.encode(pickle::dumps(&obs));
        let mut body = String::with_capacity(b64.len() + 20);
        body.push_str("{\"observation\":\"");
        body.push_str(&b64);
        body.push_str("\"}");
        body
    }

    /// The action of a step reply.
    fn action(&self, route: &str, reply: &Json, step: u32) -> Result<Action> {
        let code =
            action_code(reply).map_err(|m| self.error(route, format!("step {step}: {m}")))?;
        let ep = &self.episode;
        Ok(match code {
            0 => Action::Stop,
            1 => Action::MoveForward(ep.step_size),
            2 => Action::TurnLeft(ep.turn),
            3 => Action::TurnRight(ep.turn),
            4 => Action::LookUp,
            5 => Action::LookDown,
            // Stand still: the step passes, the agent stays.
            -1 => Action::TurnLeft(0.0),
            other => {
                return Err(self.error(
                    route,
                    format!(
                        "step {step}: action {other} is none of -1 (stand still), 0 (stop), \
                         1 (forward), 2 (left), 3 (right), 4 (look up), 5 (look down)"
                    ),
                ))
            }
        })
    }
}

/// The first environment's action code of a step reply: `{"action": [[a]]}` (one list per
/// environment), `{"action": [a]}`, `{"action": [{"action": [a], ...}]}` or `{"action": a}`.
pub fn action_code(reply: &Json) -> std::result::Result<i64, String> {
    let top = reply
        .get("action")
        .ok_or_else(|| format!("reply has no `action`: {}", clip(&reply.to_string())))?;
    let mut v = top;
    for _ in 0..4 {
        v = match v {
            Json::Array(a) => a
                .first()
                .ok_or_else(|| format!("`action` is an empty list: {top}"))?,
            // `ideal_flag: false` marks a velocity command, which is no discrete action.
            Json::Object(o) if o.get("ideal_flag") == Some(&Json::Bool(false)) => {
                return Err(format!(
                    "the agent answered a velocity command (`ideal_flag: false`), which this \
                     client does not run: {}",
                    clip(&top.to_string())
                ))
            }
            Json::Object(o) => o
                .get("action")
                .ok_or_else(|| format!("`action` entry has no `action`: {top}"))?,
            _ => break,
        };
    }
    let f = v
        .as_f64()
        .ok_or_else(|| format!("`action` holds no integer: {}", clip(&top.to_string())))?;
    if f.fract() != 0.0 || !f.is_finite() {
        return Err(format!("action {f} is not an integer"));
    }
    Ok(f as i64)
}

fn rgb(f: &Frame) -> Value {
    image(f, 3, DType::U8, f.rgb.clone())
}

fn depth(f: &Frame) -> Value {
    Value::f32_array(vec![f.height as usize, f.width as usize, 1], &f.depth)
}

fn image(f: &Frame, channels: usize, dtype: DType, data: Vec<u8>) -> Value {
    Value::Array {
        dtype,
        shape: vec![f.height as usize, f.width as usize, channels],
        data,
    }
}

fn plural(n: u32) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

fn clip(s: &str) -> String {
    const MAX: usize = 300;
    let t = s.trim();
    if t.chars().count() <= MAX {
        t.to_string()
    } else {
        format!("{}...", t.chars().take(MAX).collect::<String>())
    }
}

impl Agent for HttpAgent {
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.begin(EpisodeStart::from(inputs))
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        self.step(step)
    }
}

impl Drop for HttpAgent {
    fn drop(&mut self) {
        if let Some(live) = &self.live {
            live.store(false, Ordering::SeqCst);
        }
    }
}
