//! The optional LLM stage: an [`InstructionGenerator`] that rewrites another generator's
//! (the templates') instructions through an OpenAI-compatible chat endpoint. Off by default.
//!
//! Three roles, each a system prompt of this module:
//! - **describer** ([`DESCRIBER_PROMPT`]): rewrites a template instruction fluently from its
//!   grounded facts (fine and coarse);
//! - **verifier** ([`VERIFIER_PROMPT`]): checks a candidate against the facts and answers
//!   `YES` or `NO` with a reason;
//! - **synthesizer** ([`SYNTHESIZER_PROMPT`]): combines sub-instructions into one long-horizon
//!   instruction.
//!
//! A candidate the verifier rejects (or a failed call) gives the template output back
//! ([`OnReject::Fallback`], the default) or an error ([`OnReject::Error`]). The grounding
//! metadata is always the template's: the describer is told to keep every fact.
//!
//! The describer also sees pictures when a frame source is attached ([`LlmGenerator::with_frames`];
//! `generate` renders views along the path, or the goal view for coarse episodes), sent as
//! `image_url` parts with PNG data URLs, the format vision models of OpenAI-compatible servers
//! read. A candidate that passes the verifier must still pass [`check_candidate`]: every object
//! class it names is grounded, on the side the facts give, and every word it uses is known
//! (from the facts, this crate's word data or the direction words of `data/rewrite_words.toml`),
//! so a made-up object ("spaceship") is caught; otherwise it falls back too.
//!
//! Requests: `POST {base_url}/chat/completions` with `model`, `messages`, `temperature` (0 by
//! default), `seed` and optionally `max_tokens`; the key, when `api_key_env` names an
//! environment variable, goes in `Authorization: Bearer ...`. Plain `http://` endpoints work out
//! of the box; `https://` needs the crate feature `llm-tls`. At most `max_concurrent` requests
//! are in flight at once. With `cache_dir`, every reply is stored under the SHA-256 of the
//! request (URL and body), so a rerun sends nothing it has sent before: the same bytes come
//! back and an interrupted run resumes without paying twice. [`LlmGenerator::report`] counts
//! calls, cache hits and fallbacks by reason.

use super::{InstructionGenerator, PathContext};
use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;
use vlnverse_env::ObjectId;
use vlnverse_score::episode::{Instruction, Role, Side, Style};
use vlnverse_score::{DataError, Result};

/// System prompt of the describer role.
pub const DESCRIBER_PROMPT: &str = "You are the describer of a navigation benchmark. A robot \
walks through a home following an instruction. You get a draft instruction written from \
templates and the list of facts it is grounded in: the objects it names, what role each plays \
(landmark passed on the way, target to reach, reference that singles out the target) and on \
which side of the robot each one is. Rewrite the draft so that it reads like a person wrote \
it. Keep every object, every colour, every side (left, right, ahead), every turn, every room \
and the end point exactly as given, in the same order. Do not add objects, rooms, colours or \
distances that are not in the draft, and never mention ids or coordinates. Follow the \
requested style. Reply with the instruction text only, no quotes, no preamble.";

/// System prompt of the verifier role.
pub const VERIFIER_PROMPT: &str = "You are the verifier of a navigation benchmark. You get the \
facts an instruction must be grounded in (a reference instruction and the objects it names, \
with their roles and sides) and a candidate instruction. Decide whether a robot following the \
candidate would do the same as with the reference: the same objects, colours, sides, turns, \
rooms and end point, nothing left out that is needed to find the target, and nothing named \
that is not among the facts. Answer with YES or NO as the first word, then one short sentence \
giving the reason.";

/// System prompt of the synthesizer role.
pub const SYNTHESIZER_PROMPT: &str = "You are the synthesizer of a navigation benchmark. You \
get several short navigation sub-instructions that a robot must carry out one after another in \
the same home. Combine them into a single instruction that keeps them in the given order \
(signal the order with words such as first, then, after that, finally) and keeps every object, \
colour, relation and room they mention. Add nothing new. Reply with the combined instruction \
only.";

/// What to do with a candidate the verifier rejects, or a call that fails.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnReject {
    /// Return the template instruction (and log a warning).
    #[default]
    Fallback,
    /// Return an error.
    Error,
}

/// Settings of the LLM stage (`[instructions.llm]` in a generation config).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LlmConfig {
    /// Base URL of the OpenAI-compatible API, e.g. `http://127.0.0.1:8000/v1`.
    pub base_url: String,
    /// Model name sent with every request.
    pub model: String,
    /// Name of the environment variable holding the API key; none sends no key.
    pub api_key_env: Option<String>,
    /// Sampling temperature (0 for repeatable output).
    pub temperature: f32,
    /// Limit on the reply length, if any.
    pub max_tokens: Option<u32>,
    /// Timeout of one request in seconds.
    pub timeout_s: f32,
    /// Extra attempts after a failed request (transport error, HTTP 429 or 5xx).
    pub retries: u32,
    /// Wait before the first retry in milliseconds (doubled on each further retry).
    pub retry_backoff_ms: u64,
    /// Whether the verifier checks each candidate.
    pub verify: bool,
    /// What a rejection or a failed call gives.
    pub on_reject: OnReject,
    /// Requests in flight at once, over all worker threads.
    pub max_concurrent: u32,
    /// Pictures the describer gets: views along a fine path (start to end), the goal view for
    /// coarse instructions; 0 sends text only.
    pub frames: u32,
    /// Folder of the reply cache (`generate` uses `<out>/.llm-cache` when unset); none: no
    /// cache.
    pub cache_dir: Option<PathBuf>,
}

impl Default for LlmConfig {
    fn default() -> Self {
        LlmConfig {
            base_url: "http://127.0.0.1:8000/v1".into(),
            model: "gpt-4o-mini".into(),
            api_key_env: None,
            temperature: 0.0,
            max_tokens: Some(400),
            timeout_s: 60.0,
            retries: 2,
            retry_backoff_ms: 500,
            verify: true,
            on_reject: OnReject::Fallback,
            max_concurrent: 4,
            frames: 3,
            cache_dir: None,
        }
    }
}

impl LlmConfig {
    /// Check the values; the error names the field.
    pub fn validate(&self) -> Result<()> {
        if !(self.base_url.starts_with("http://") || self.base_url.starts_with("https://")) {
            return Err(DataError::invalid(
                "llm.base_url",
                &self.base_url,
                "must start with http:// or https://",
            ));
        }
        match self.base_url.parse::<ureq::http::Uri>() {
            Ok(uri) if uri.host().is_some_and(|h| !h.is_empty()) => {}
            Ok(_) => {
                return Err(DataError::invalid(
                    "llm.base_url",
                    &self.base_url,
                    "names no host (expected e.g. http://127.0.0.1:8000/v1)",
                ))
            }
            Err(e) => {
                return Err(DataError::invalid(
                    "llm.base_url",
                    &self.base_url,
                    format!("is not a URL ({e})"),
                ))
            }
        }
        if self.base_url.starts_with("https://") && !cfg!(feature = "llm-tls") {
            return Err(DataError::invalid(
                "llm.base_url",
                &self.base_url,
                "https needs the `llm-tls` feature (of vlnverse-instructions, vlnverse-generate or vlnverse-task)",
            ));
        }
        if self.model.trim().is_empty() {
            return Err(DataError::invalid("llm.model", "\"\"", "must not be empty"));
        }
        if !(self.temperature.is_finite() && (0.0..=2.0).contains(&self.temperature)) {
            return Err(DataError::invalid(
                "llm.temperature",
                self.temperature,
                "must be in [0, 2]",
            ));
        }
        if !(self.timeout_s.is_finite() && self.timeout_s > 0.0 && self.timeout_s <= 3600.0) {
            return Err(DataError::invalid(
                "llm.timeout_s",
                self.timeout_s,
                "must be in (0, 3600] seconds",
            ));
        }
        if self.retries > 10 {
            return Err(DataError::invalid(
                "llm.retries",
                self.retries,
                "must be in [0, 10]",
            ));
        }
        if self.retry_backoff_ms > 60_000 {
            return Err(DataError::invalid(
                "llm.retry_backoff_ms",
                self.retry_backoff_ms,
                "must be in [0, 60000] milliseconds",
            ));
        }
        if !(1..=256).contains(&self.max_concurrent) {
            return Err(DataError::invalid(
                "llm.max_concurrent",
                self.max_concurrent,
                "must be in [1, 256]",
            ));
        }
        if self.frames > 8 {
            return Err(DataError::invalid(
                "llm.frames",
                self.frames,
                "must be in [0, 8]",
            ));
        }
        Ok(())
    }

    /// The chat-completions URL.
    pub fn url(&self) -> String {
        format!("{}/chat/completions", self.base_url.trim_end_matches('/'))
    }
}

/// One chat message.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ChatMessage {
    /// `system`, `user` or `assistant`.
    pub role: String,
    /// The text, or text and pictures.
    pub content: Content,
}

/// What a message holds: plain text, or parts (text and images) for vision models.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Content {
    /// Plain text.
    Text(String),
    /// Text and image parts.
    Parts(Vec<Part>),
}

/// One part of a multi-part message (the OpenAI chat format).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Part {
    /// Text.
    Text {
        /// The text.
        text: String,
    },
    /// A picture, as a URL (here a `data:image/png;base64,...` URL).
    ImageUrl {
        /// The picture.
        image_url: ImageUrl,
    },
}

/// The URL of an image part.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImageUrl {
    /// `data:` or `http(s):` URL.
    pub url: String,
}

impl ChatMessage {
    /// A system message.
    pub fn system(content: impl Into<String>) -> Self {
        ChatMessage {
            role: "system".into(),
            content: Content::Text(content.into()),
        }
    }

    /// A user message.
    pub fn user(content: impl Into<String>) -> Self {
        ChatMessage {
            role: "user".into(),
            content: Content::Text(content.into()),
        }
    }

    /// A user message with PNG pictures after the text (plain text when there are none).
    pub fn user_with_images(text: impl Into<String>, pngs: &[Vec<u8>]) -> Self {
        if pngs.is_empty() {
            return Self::user(text);
        }
        let mut parts = vec![Part::Text { text: text.into() }];
        parts.extend(pngs.iter().map(|png| Part::ImageUrl {
            image_url: ImageUrl {
                url: format!("data:image/png;base64,{}", STANDARD.encode(png)),
            },
        }));
        ChatMessage {
            role: "user".into(),
            content: Content::Parts(parts),
        }
    }

    /// The text of the message (the text parts joined).
    pub fn text(&self) -> String {
        match &self.content {
            Content::Text(t) => t.clone(),
            Content::Parts(p) => p
                .iter()
                .filter_map(|p| match p {
                    Part::Text { text } => Some(text.as_str()),
                    Part::ImageUrl { .. } => None,
                })
                .collect::<Vec<_>>()
                .join("\n"),
        }
    }
}

#[derive(Serialize)]
struct ChatRequest<'a> {
    model: &'a str,
    messages: &'a [ChatMessage],
    temperature: f32,
    seed: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_tokens: Option<u32>,
}

/// A blocking client of an OpenAI-compatible chat endpoint.
#[derive(Debug)]
pub struct ChatClient {
    config: LlmConfig,
    agent: ureq::Agent,
    gate: Gate,
    sent: AtomicU64,
    cached: AtomicU64,
}

/// A counting semaphore: at most `max` holders.
#[derive(Debug)]
struct Gate {
    busy: Mutex<u32>,
    free: Condvar,
    max: u32,
}

impl Gate {
    fn enter(&self) -> GateGuard<'_> {
        let mut n = self.busy.lock().unwrap_or_else(|p| p.into_inner());
        while *n >= self.max {
            n = self.free.wait(n).unwrap_or_else(|p| p.into_inner());
        }
        *n += 1;
        GateGuard(self)
    }
}

struct GateGuard<'a>(&'a Gate);

impl Drop for GateGuard<'_> {
    fn drop(&mut self) {
        let mut n = self.0.busy.lock().unwrap_or_else(|p| p.into_inner());
        *n -= 1;
        self.0.free.notify_one();
    }
}

/// A cached reply on disk (with the token counts the endpoint reported, when it did).
#[derive(Serialize, Deserialize)]
struct CacheEntry {
    reply: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    usage: Option<Usage>,
}

/// Token counts of one reply, as the endpoint's `usage` object gives them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Usage {
    /// Tokens of the request.
    pub prompt_tokens: u64,
    /// Tokens of the reply.
    pub completion_tokens: u64,
}

/// A reply with what it cost ([`ChatClient::chat_detailed`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ChatReply {
    /// `choices[0].message.content`, trimmed.
    pub text: String,
    /// Token counts, when the endpoint reported them (kept in the cache with the reply).
    pub usage: Option<Usage>,
    /// Whether the reply came from the cache (nothing was sent).
    pub cached: bool,
    /// HTTP attempts made (0 from the cache; more than 1 when failures were retried).
    pub attempts: u32,
    /// Wall time of the request with its retries (0 from the cache).
    pub latency: Duration,
}

/// Make `dir` and write (then remove) a probe file in it.
fn check_writable(dir: &std::path::Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let probe = dir.join(format!(".probe{}", std::process::id()));
    std::fs::write(&probe, b"")?;
    std::fs::remove_file(&probe)
}

fn net_error(url: &str, e: impl std::fmt::Display) -> DataError {
    DataError::io(PathBuf::from(url), std::io::Error::other(e.to_string()))
}

impl ChatClient {
    /// A client for the configured endpoint. Everything that can be checked without a request
    /// is checked here, before any work: the values, that a named key variable is set, and
    /// that the cache folder can be written (replies would otherwise be paid for and lost).
    pub fn new(config: LlmConfig) -> Result<Self> {
        config.validate()?;
        if let Some(var) = &config.api_key_env {
            if std::env::var_os(var).is_none() {
                return Err(DataError::invalid(
                    "llm.api_key_env",
                    var,
                    "the environment variable is not set (set it, or leave api_key_env out \
                     for an endpoint without a key)",
                ));
            }
        }
        if let Some(dir) = &config.cache_dir {
            check_writable(dir).map_err(|e| {
                DataError::invalid(
                    "llm.cache_dir",
                    dir.display(),
                    format!("cannot be written: {e}"),
                )
            })?;
        }
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .timeout_global(Some(Duration::from_secs_f32(config.timeout_s)))
            .http_status_as_error(false)
            .build()
            .into();
        let gate = Gate {
            busy: Mutex::new(0),
            free: Condvar::new(),
            max: config.max_concurrent.max(1),
        };
        Ok(ChatClient {
            config,
            agent,
            gate,
            sent: AtomicU64::new(0),
            cached: AtomicU64::new(0),
        })
    }

    /// Requests sent to the endpoint (retries not counted) and replies taken from the cache.
    pub fn counts(&self) -> (u64, u64) {
        (
            self.sent.load(Ordering::Relaxed),
            self.cached.load(Ordering::Relaxed),
        )
    }

    /// The cache file of a request body, when caching.
    fn cache_file(&self, url: &str, body: &str) -> Option<PathBuf> {
        let dir = self.config.cache_dir.as_ref()?;
        let mut h = Sha256::new();
        h.update(url.as_bytes());
        h.update(b"\n");
        h.update(body.as_bytes());
        let hex: String = h.finalize().iter().map(|b| format!("{b:02x}")).collect();
        Some(dir.join(&hex[..2]).join(format!("{hex}.json")))
    }

    /// The settings.
    pub fn config(&self) -> &LlmConfig {
        &self.config
    }

    fn api_key(&self) -> Result<Option<String>> {
        match &self.config.api_key_env {
            None => Ok(None),
            Some(var) => match std::env::var(var) {
                Ok(k) => Ok(Some(k)),
                Err(_) => Err(DataError::invalid(
                    "llm.api_key_env",
                    var,
                    "the environment variable is not set (set it, or leave api_key_env out \
                     for an endpoint without a key)",
                )),
            },
        }
    }

    /// Send `messages` and return the reply text (`choices[0].message.content`), retrying
    /// transport errors, HTTP 429 and 5xx.
    pub fn chat(&self, messages: &[ChatMessage], seed: u64) -> Result<String> {
        self.chat_detailed(messages, seed).map(|r| r.text)
    }

    /// [`ChatClient::chat`] with the reply's token counts, attempts, latency and whether it
    /// came from the cache.
    pub fn chat_detailed(&self, messages: &[ChatMessage], seed: u64) -> Result<ChatReply> {
        let url = self.config.url();
        let key = self.api_key()?;
        let body = serde_json::to_string(&ChatRequest {
            model: &self.config.model,
            messages,
            temperature: self.config.temperature,
            seed,
            max_tokens: self.config.max_tokens,
        })
        .map_err(|e| net_error(&url, e))?;
        let cache = self.cache_file(&url, &body);
        if let Some(file) = &cache {
            if let Ok(bytes) = std::fs::read(file) {
                match serde_json::from_slice::<CacheEntry>(&bytes) {
                    Ok(e) => {
                        self.cached.fetch_add(1, Ordering::Relaxed);
                        return Ok(ChatReply {
                            text: e.reply,
                            usage: e.usage,
                            cached: true,
                            attempts: 0,
                            latency: Duration::ZERO,
                        });
                    }
                    // A damaged entry is asked again and rewritten.
                    Err(e) => tracing::warn!(file = %file.display(), error = %e, "bad cache entry"),
                }
            }
        }
        let reply = self.send(&url, &body, key.as_deref())?;
        if let Some(file) = &cache {
            let entry = serde_json::to_vec(&CacheEntry {
                reply: reply.text.clone(),
                usage: reply.usage,
            })
            .map_err(|e| net_error(&url, e))?;
            if let Some(dir) = file.parent() {
                std::fs::create_dir_all(dir).map_err(|e| DataError::io(dir, e))?;
            }
            vlnverse_score::dataset::write_atomic(file, &entry)?;
        }
        Ok(reply)
    }

    /// One request with retries, within the concurrency limit.
    fn send(&self, url: &str, body: &str, key: Option<&str>) -> Result<ChatReply> {
        let _slot = self.gate.enter();
        self.sent.fetch_add(1, Ordering::Relaxed);
        let started = std::time::Instant::now();
        let url = url.to_string();
        let mut last_err = None;
        for attempt in 0..=self.config.retries {
            if attempt > 0 {
                let wait = self.config.retry_backoff_ms << (attempt - 1).min(10);
                std::thread::sleep(Duration::from_millis(wait));
            }
            let mut req = self
                .agent
                .post(&url)
                .header("Content-Type", "application/json");
            if let Some(k) = key {
                req = req.header("Authorization", &format!("Bearer {k}"));
            }
            let mut resp = match req.send(body) {
                Ok(r) => r,
                Err(e) => {
                    tracing::warn!(%url, attempt, error = %e, "LLM request failed");
                    last_err = Some(net_error(&url, e));
                    continue;
                }
            };
            let status = resp.status().as_u16();
            let text = match resp.body_mut().read_to_string() {
                Ok(t) => t,
                Err(e) => {
                    last_err = Some(net_error(&url, e));
                    continue;
                }
            };
            if status == 429 || status >= 500 {
                tracing::warn!(%url, attempt, status, "LLM endpoint busy or failing");
                last_err = Some(net_error(&url, format!("HTTP {status}: {text}")));
                continue;
            }
            if status != 200 {
                return Err(net_error(&url, format!("HTTP {status}: {text}")));
            }
            let (text, usage) = parse_reply(&url, &text)?;
            return Ok(ChatReply {
                text,
                usage,
                cached: false,
                attempts: attempt + 1,
                latency: started.elapsed(),
            });
        }
        Err(last_err.unwrap_or_else(|| net_error(&url, "no attempt made")))
    }
}

fn parse_reply(url: &str, text: &str) -> Result<(String, Option<Usage>)> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| DataError::parse(url, "response body", e))?;
    let content = v
        .pointer("/choices/0/message/content")
        .and_then(|c| c.as_str())
        .ok_or_else(|| {
            DataError::parse(
                url,
                "choices[0].message.content",
                format!("missing or not a string in {}", truncate(text, 200)),
            )
        })?;
    let content = content.trim().trim_matches('"').trim();
    if content.is_empty() {
        return Err(DataError::parse(
            url,
            "choices[0].message.content",
            "empty reply",
        ));
    }
    let usage = v
        .get("usage")
        .and_then(|u| serde_json::from_value::<Usage>(u.clone()).ok());
    Ok((content.to_string(), usage))
}

fn truncate(s: &str, n: usize) -> String {
    s.chars().take(n).collect()
}

/// The verifier's decision.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Verdict {
    /// Whether the candidate was accepted.
    pub accepted: bool,
    /// The reason given.
    pub reason: String,
}

/// Read a verifier reply: `YES` / `NO` as the first word (any case, punctuation ignored), the
/// rest is the reason. Anything else counts as a rejection.
pub fn parse_verdict(reply: &str) -> Verdict {
    let t = reply.trim();
    let first: String = t
        .chars()
        .take_while(|c| c.is_alphabetic())
        .collect::<String>()
        .to_uppercase();
    let rest = t[first.len().min(t.len())..]
        .trim_start_matches([',', '.', ':', ';', '-', ' '])
        .trim()
        .to_string();
    match first.as_str() {
        "YES" => Verdict {
            accepted: true,
            reason: rest,
        },
        "NO" => Verdict {
            accepted: false,
            reason: rest,
        },
        _ => Verdict {
            accepted: false,
            reason: format!("unreadable verdict: {}", truncate(t, 120)),
        },
    }
}

fn role_words(r: Role) -> &'static str {
    match r {
        Role::Landmark => "landmark passed on the way",
        Role::Target => "target to reach",
        Role::Reference => "reference that singles out the target",
    }
}

fn side_words(s: Option<Side>) -> &'static str {
    match s {
        Some(Side::Left) => "on the left",
        Some(Side::Right) => "on the right",
        Some(Side::Ahead) => "ahead",
        Some(Side::Behind) => "behind",
        None => "side not stated",
    }
}

fn style_words(s: Option<Style>) -> &'static str {
    match s {
        Some(Style::Formal) => "formal: complete sentences, precise and polite wording",
        Some(Style::Natural) => "natural: the everyday wording of a person giving directions",
        Some(Style::Casual) => "casual: short, informal, lower case, like a quick text message",
        None => "plain, clear step-by-step directions",
    }
}

/// The facts block given to the describer and the verifier: the template text, the style and
/// every grounded object (class words, role, side, path point).
pub fn facts(ins: &Instruction) -> String {
    let mut s = format!(
        "Reference instruction: {}\nStyle: {}\nObjects named:\n",
        ins.instruction_text,
        style_words(ins.style)
    );
    if ins.grounding.is_empty() {
        s.push_str("- none\n");
    }
    for g in &ins.grounding {
        s.push_str(&format!(
            "- {} ({}, {}{})\n",
            g.class.replace('_', " "),
            role_words(g.role),
            side_words(g.side),
            g.path_index
                .map(|i| format!(", at path point {i}"))
                .unwrap_or_default()
        ));
    }
    if !ins.sub_instructions.is_empty() {
        s.push_str("Sub-instructions in order:\n");
        for (i, t) in ins.sub_instructions.iter().enumerate() {
            s.push_str(&format!("{}. {t}\n", i + 1));
        }
    }
    s
}

/// Pictures for the describer: views along `ctx`'s path, or of the coarse `target`.
pub type FrameSource =
    dyn Fn(&PathContext<'_>, Option<ObjectId>, u32) -> Result<Vec<Vec<u8>>> + Send + Sync;

/// Why a candidate was not used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Fallback {
    /// The verifier answered NO (or something unreadable).
    Rejected,
    /// The candidate names a class that is not grounded, or puts one on the wrong side.
    Ungrounded,
    /// The request failed (after retries) or the reply was unreadable.
    CallFailed,
}

impl Fallback {
    fn name(self) -> &'static str {
        match self {
            Fallback::Rejected => "verifier_rejected",
            Fallback::Ungrounded => "grounding_check_failed",
            Fallback::CallFailed => "call_failed",
        }
    }
}

/// What the LLM stage did in one run ([`LlmGenerator::report`]).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct LlmReport {
    /// Instructions the stage was asked to rewrite.
    pub instructions: u64,
    /// Rewritten instructions kept.
    pub accepted: u64,
    /// Instructions that kept the template text, by reason (`verifier_rejected`,
    /// `grounding_check_failed`, `call_failed`).
    pub fallbacks: BTreeMap<String, u64>,
    /// Requests sent to the endpoint.
    pub requests: u64,
    /// Replies read from the cache instead.
    pub cache_hits: u64,
}

/// Check a candidate against the facts of `base`: every object class the candidate names
/// (by its class words, e.g. "tv stand") must be grounded in `base` or named by its text,
/// and a grounded landmark named in a sentence that gives one side (left or right) must
/// stand on that side. Walls, floors, doors and other structure are room features, not
/// objects, and are not checked. Then every word must be known (`check_vocabulary`): a word
/// in neither the facts nor the word data names something the facts do not hold. `Err` gives
/// the first problem.
pub fn check_candidate(base: &Instruction, candidate: &str) -> std::result::Result<(), String> {
    use vlnverse_env::SemanticClass;
    check_text(&base.instruction_text, candidate)?;
    let lower = candidate.to_lowercase();
    let base_text = base.instruction_text.to_lowercase();
    let grounded: Vec<String> = base
        .grounding
        .iter()
        .map(|g| g.class.replace('_', " "))
        .collect();
    // Longest names first, so "tv stand" is not also read as "tv".
    let mut names: Vec<(String, SemanticClass)> = SemanticClass::ALL
        .iter()
        // Doorways are on nearly every route and a rewrite may mention their doors freely.
        .filter(|c| !c.is_structure() && **c != SemanticClass::Door)
        .map(|c| (c.words(), *c))
        .collect();
    names.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then_with(|| a.0.cmp(&b.0)));
    for sentence in lower.split(['.', ';', '!', '?']) {
        let mut rest = format!(" {} ", sentence.replace(',', " "));
        let sides: Vec<Side> = [("left", Side::Left), ("right", Side::Right)]
            .into_iter()
            .filter(|(w, _)| has_word(&rest, w))
            .map(|(_, s)| s)
            .collect();
        for (words, _) in &names {
            let pattern = format!(" {words} ");
            let plural = format!(" {words}s ");
            if !(rest.contains(&pattern) || rest.contains(&plural)) {
                continue;
            }
            rest = rest.replace(&pattern, " ").replace(&plural, " ");
            let known = grounded.iter().any(|g| g == words) || has_word(&base_text, words);
            if !known {
                return Err(format!("names a {words}, which the facts do not"));
            }
            if let [side] = sides.as_slice() {
                let wrong = base.grounding.iter().any(|g| {
                    g.class.replace('_', " ") == *words
                        && matches!(g.side, Some(Side::Left | Side::Right))
                        && g.side != Some(*side)
                        && !base
                            .grounding
                            .iter()
                            .any(|h| h.class.replace('_', " ") == *words && h.side == Some(*side))
                });
                if wrong {
                    return Err(format!("puts the {words} on the wrong side"));
                }
            }
        }
    }
    check_vocabulary(base, candidate)
}

/// The direction words file, as errors name it.
const REWRITE_WORDS_FILE: &str = "data/rewrite_words.toml";

/// Words any rewrite may use: the direction words of `data/rewrite_words.toml` and every word
/// of this crate's class, colour and phrase data and room names.
static KNOWN_WORDS: std::sync::LazyLock<BTreeSet<String>> = std::sync::LazyLock::new(|| {
    let mut set = BTreeSet::new();
    let files = [
        (
            REWRITE_WORDS_FILE,
            include_str!("../data/rewrite_words.toml"),
        ),
        ("data/classes.toml", include_str!("../data/classes.toml")),
        ("data/colours.toml", include_str!("../data/colours.toml")),
        ("data/phrases.toml", include_str!("../data/phrases.toml")),
    ];
    for (file, text) in files {
        let value: toml::Value = crate::data::expect_embedded(crate::data::parse_toml(file, text));
        let mut strings = Vec::new();
        collect_strings(&value, &mut strings);
        for s in strings {
            set.extend(words(&strip_placeholders(s)));
        }
    }
    for kind in vlnverse_env::RoomType::ALL {
        for name in crate::lexicon::room_names(*kind) {
            set.extend(words(name));
        }
    }
    for class in vlnverse_env::SemanticClass::ALL {
        set.extend(words(&class.name().replace('_', " ")));
    }
    set
});

fn collect_strings<'a>(v: &'a toml::Value, out: &mut Vec<&'a str>) {
    match v {
        toml::Value::String(s) => out.push(s),
        toml::Value::Array(a) => a.iter().for_each(|x| collect_strings(x, out)),
        toml::Value::Table(t) => t.values().for_each(|x| collect_strings(x, out)),
        _ => {}
    }
}

/// `s` without its `{placeholder}`s, which the code fills.
fn strip_placeholders(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut depth = 0usize;
    for c in s.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// The lower-case words of `text`: runs of letters, split at apostrophes too ("you'll" is
/// "you" and "ll") and at hyphens ("off-white"); digits and punctuation separate words.
fn words(text: &str) -> Vec<String> {
    text.to_lowercase()
        .split(|c: char| !c.is_alphabetic())
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect()
}

/// Whether `word` or a plain form of it (without a plural, past, -ing or -ly ending) is in
/// `set`.
fn knows(set: &BTreeSet<String>, word: &str) -> bool {
    if set.contains(word) {
        return true;
    }
    let mut forms: Vec<String> = Vec::new();
    let cut = |suffix: &str| word.strip_suffix(suffix).filter(|b| b.len() >= 2);
    if let Some(b) = cut("ies").or_else(|| cut("ied")).or_else(|| cut("ily")) {
        forms.push(format!("{b}y"));
    }
    for suffix in ["s", "es", "ly"] {
        forms.extend(cut(suffix).map(str::to_string));
    }
    for suffix in ["ing", "ed"] {
        if let Some(b) = cut(suffix) {
            forms.push(b.to_string());
            forms.push(format!("{b}e"));
            // "stopped", "stepping": one of a doubled last consonant.
            let mut cs = b.chars().rev();
            if let (Some(x), Some(y)) = (cs.next(), cs.next()) {
                if x == y {
                    forms.push(b[..b.len() - x.len_utf8()].to_string());
                }
            }
        }
    }
    forms.iter().any(|f| set.contains(f))
}

/// Every word of `candidate` must be known: in the text `base` rewrites (or its
/// sub-instructions), a word of its grounded classes, or one of [`KNOWN_WORDS`]. A word found
/// nowhere most likely names something the facts do not hold ("spaceship"). Single letters
/// ("u-turn", "L-shaped") pass.
fn check_vocabulary(base: &Instruction, candidate: &str) -> std::result::Result<(), String> {
    let mut facts: BTreeSet<String> = words(&base.instruction_text).into_iter().collect();
    for t in &base.sub_instructions {
        facts.extend(words(t));
    }
    for g in &base.grounding {
        facts.extend(words(&g.class.replace('_', " ")));
    }
    match words(candidate)
        .into_iter()
        .find(|w| w.chars().count() > 1 && !knows(&facts, w) && !knows(&KNOWN_WORDS, w))
    {
        Some(w) => Err(format!(
            "uses the word {w:?}, which is neither in the facts nor an ordinary direction word \
             ({REWRITE_WORDS_FILE})"
        )),
        None => Ok(()),
    }
}

/// Longest rewrite accepted, relative to the template text it rewrites: fluent wording may
/// grow a text, but not by an order of magnitude.
pub const MAX_GROWTH: usize = 3;
/// Characters a rewrite may always have beyond [`MAX_GROWTH`] times the original (short
/// originals).
pub const LENGTH_SLACK: usize = 200;

/// A rewrite is plain text of a sensible length: not empty, no control characters (NUL, escape
/// sequences) or bidirectional overrides (U+202A..U+202E, U+2066..U+2069, which reorder what
/// a reader sees), at most [`MAX_GROWTH`] times the original plus [`LENGTH_SLACK`] characters.
pub fn check_text(original: &str, candidate: &str) -> std::result::Result<(), String> {
    if candidate.trim().is_empty() {
        return Err("is empty".into());
    }
    if let Some(c) = candidate.chars().find(|&c| {
        (c.is_control() && c != '\n')
            || ('\u{202a}'..='\u{202e}').contains(&c)
            || ('\u{2066}'..='\u{2069}').contains(&c)
            || c == '\u{200e}'
            || c == '\u{200f}'
    }) {
        return Err(format!("holds the control character U+{:04X}", c as u32));
    }
    let (n, max) = (
        candidate.chars().count(),
        original.chars().count() * MAX_GROWTH + LENGTH_SLACK,
    );
    if n > max {
        return Err(format!(
            "is {n} characters long, more than {max} ({MAX_GROWTH} times the original's plus \
             {LENGTH_SLACK})"
        ));
    }
    Ok(())
}

fn has_word(text: &str, word: &str) -> bool {
    text.split(|c: char| !c.is_alphanumeric() && c != '\'')
        .collect::<Vec<_>>()
        .windows(word.split(' ').count())
        .any(|w| w.join(" ") == word)
}

/// Field of the error that stops a run under `on_reject = "error"` ([`stops_the_run`]).
const STOP_FIELD: &str = "llm.on_reject";

fn stopped_error(why: String) -> DataError {
    DataError::invalid(
        STOP_FIELD,
        "\"error\"",
        format!(
            "{why}; generation stops (on_reject = \"fallback\" keeps the template text instead)"
        ),
    )
}

/// Whether `e` is the LLM stage's stop under `on_reject = "error"`: a generator must end the
/// run with it rather than treat it as one more unusable sample and try again.
pub fn stops_the_run(e: &DataError) -> bool {
    matches!(e, DataError::Invalid { field, .. } if field == STOP_FIELD)
}

/// An [`InstructionGenerator`] that rewrites the output of `inner` with an LLM (describer /
/// synthesizer) and checks it (verifier, then [`check_candidate`]); see the module docs.
pub struct LlmGenerator<G> {
    inner: G,
    client: ChatClient,
    frames: Option<Box<FrameSource>>,
    asked: AtomicU64,
    accepted: AtomicU64,
    fallbacks: Mutex<BTreeMap<Fallback, u64>>,
    /// Set by the first error under [`OnReject::Error`]: later calls send nothing.
    stopped: std::sync::atomic::AtomicBool,
}

impl<G> std::fmt::Debug for LlmGenerator<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LlmGenerator")
            .field("client", &self.client)
            .field("frames", &self.frames.is_some())
            .finish()
    }
}

impl<G: InstructionGenerator> LlmGenerator<G> {
    /// Wrap `inner` (usually the [`super::TemplateGenerator`]).
    pub fn new(inner: G, config: LlmConfig) -> Result<Self> {
        Ok(LlmGenerator {
            inner,
            client: ChatClient::new(config)?,
            frames: None,
            asked: AtomicU64::new(0),
            accepted: AtomicU64::new(0),
            fallbacks: Mutex::new(BTreeMap::new()),
            stopped: std::sync::atomic::AtomicBool::new(false),
        })
    }

    /// Give the describer pictures from `frames` (called with the configured `frames`
    /// count; nothing is rendered when it is 0).
    pub fn with_frames(mut self, frames: Box<FrameSource>) -> Self {
        self.frames = Some(frames);
        self
    }

    /// The wrapped generator.
    pub fn inner(&self) -> &G {
        &self.inner
    }

    /// The chat client.
    pub fn client(&self) -> &ChatClient {
        &self.client
    }

    /// What the stage did so far.
    pub fn report(&self) -> LlmReport {
        let (requests, cache_hits) = self.client.counts();
        LlmReport {
            instructions: self.asked.load(Ordering::Relaxed),
            accepted: self.accepted.load(Ordering::Relaxed),
            fallbacks: self
                .fallbacks
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .iter()
                .map(|(k, v)| (k.name().to_string(), *v))
                .collect(),
            requests,
            cache_hits,
        }
    }

    /// Ask the verifier about `candidate` for the facts of `base`.
    pub fn verify(&self, base: &Instruction, candidate: &str, seed: u64) -> Result<Verdict> {
        let reply = self.client.chat(
            &[
                ChatMessage::system(VERIFIER_PROMPT),
                ChatMessage::user(format!(
                    "{}\nCandidate instruction: {candidate}\nIs the candidate faithful?",
                    facts(base)
                )),
            ],
            seed,
        )?;
        Ok(parse_verdict(&reply))
    }

    fn refine(
        &self,
        base: Instruction,
        system: &str,
        user: ChatMessage,
        seed: u64,
    ) -> Result<Instruction> {
        let policy = self.client.config.on_reject;
        if self.stopped.load(Ordering::Relaxed) {
            return Err(stopped_error(
                "an earlier instruction was not used (on_reject = \"error\")".into(),
            ));
        }
        self.asked.fetch_add(1, Ordering::Relaxed);
        let attempt = (|| -> Result<std::result::Result<String, (Fallback, String)>> {
            let candidate = self
                .client
                .chat(&[ChatMessage::system(system), user], seed)?;
            if self.client.config.verify {
                let v = self.verify(&base, &candidate, seed)?;
                if !v.accepted {
                    return Ok(Err((Fallback::Rejected, v.reason)));
                }
            }
            if let Err(why) = check_candidate(&base, &candidate) {
                return Ok(Err((Fallback::Ungrounded, why)));
            }
            Ok(Ok(candidate))
        })();
        let fell_back = |why: Fallback| {
            *self
                .fallbacks
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .entry(why)
                .or_default() += 1;
        };
        match (attempt, policy) {
            (Ok(Ok(text)), _) => {
                self.accepted.fetch_add(1, Ordering::Relaxed);
                Ok(Instruction {
                    instruction_text: text,
                    ..base
                })
            }
            (Ok(Err((why, reason))), OnReject::Fallback) => {
                fell_back(why);
                tracing::warn!(%reason, why = why.name(), "LLM instruction not used; keeping the template");
                Ok(base)
            }
            (Ok(Err((why, reason))), OnReject::Error) => {
                self.stopped.store(true, Ordering::Relaxed);
                Err(stopped_error(format!(
                    "the rewrite of {:?} was not used ({}): {reason}",
                    truncate(&base.instruction_text, 80),
                    why.name()
                )))
            }
            (Err(e), OnReject::Fallback) => {
                fell_back(Fallback::CallFailed);
                tracing::warn!(error = %e, "LLM call failed; keeping the template");
                Ok(base)
            }
            (Err(e), OnReject::Error) => {
                self.stopped.store(true, Ordering::Relaxed);
                Err(stopped_error(format!("the LLM call failed: {e}")))
            }
        }
    }

    fn describe(
        &self,
        base: Instruction,
        ctx: &PathContext<'_>,
        target: Option<ObjectId>,
        seed: u64,
    ) -> Result<Instruction> {
        let n = self.client.config.frames;
        let pictures = match &self.frames {
            Some(f) if n > 0 => f(ctx, target, n)?,
            _ => Vec::new(),
        };
        let mut text = facts(&base);
        if !pictures.is_empty() {
            text.push_str(&format!(
                "Pictures: {} view(s) {}.\n",
                pictures.len(),
                if target.is_some() {
                    "from the end point, facing the target"
                } else {
                    "along the path, from the start to the end, facing the way the robot walks"
                }
            ));
        }
        text.push_str("Rewrite the reference instruction in the requested style.");
        let user = ChatMessage::user_with_images(text, &pictures);
        self.refine(base, DESCRIBER_PROMPT, user, seed)
    }
}

impl<G: InstructionGenerator> InstructionGenerator for LlmGenerator<G> {
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction> {
        let base = self.inner.fine(ctx, seed)?;
        self.describe(base, ctx, None, seed)
    }

    fn coarse(
        &self,
        ctx: &PathContext<'_>,
        target: ObjectId,
        style: Style,
        seed: u64,
    ) -> Result<Instruction> {
        let base = self.inner.coarse(ctx, target, style, seed)?;
        self.describe(base, ctx, Some(target), seed)
    }

    fn chain(&self, parts: &[Instruction], seed: u64) -> Result<Instruction> {
        let base = self.inner.chain(parts, seed)?;
        if parts.len() < 2 {
            return Ok(base);
        }
        let mut user = String::from("Sub-instructions in order:\n");
        for (i, p) in parts.iter().enumerate() {
            user.push_str(&format!("{}. {}\n", i + 1, p.instruction_text));
        }
        user.push_str("Combine them into one instruction.");
        self.refine(base, SYNTHESIZER_PROMPT, ChatMessage::user(user), seed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_score::episode::GroundedObject;

    #[test]
    fn no_api_key_env_sends_no_key_and_a_missing_key_variable_is_refused_up_front() {
        let (url, seen) = vlnverse_testkit::llm_stub::stub(vec![(200, "Go.".into())]);
        let client = ChatClient::new(LlmConfig {
            base_url: url.clone(),
            ..LlmConfig::default()
        })
        .unwrap();
        assert_eq!(client.chat(&[ChatMessage::user("hi")], 0).unwrap(), "Go.");
        assert_eq!(seen.lock().unwrap()[0].authorization, None);
        let err = ChatClient::new(LlmConfig {
            base_url: url,
            api_key_env: Some("VLNVERSE_TEST_SURELY_UNSET_KEY".into()),
            ..LlmConfig::default()
        })
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("llm.api_key_env") && err.contains("VLNVERSE_TEST_SURELY_UNSET_KEY"),
            "{err}"
        );
    }

    #[test]
    fn a_malformed_base_url_and_an_unwritable_cache_are_refused_by_name() {
        for bad in ["http://[::1", "http://", "http:// spaced/v1"] {
            let err = LlmConfig {
                base_url: bad.into(),
                ..LlmConfig::default()
            }
            .validate()
            .unwrap_err()
            .to_string();
            assert!(err.contains("llm.base_url") && err.contains(bad), "{err}");
        }
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a_file");
        std::fs::write(&file, "").unwrap();
        let err = ChatClient::new(LlmConfig {
            cache_dir: Some(file.join("cache")),
            ..LlmConfig::default()
        })
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("llm.cache_dir") && err.contains("a_file"),
            "{err}"
        );
        // A writable one is made and left empty.
        let cache = dir.path().join("cache");
        ChatClient::new(LlmConfig {
            cache_dir: Some(cache.clone()),
            ..LlmConfig::default()
        })
        .unwrap();
        assert_eq!(std::fs::read_dir(&cache).unwrap().count(), 0);
    }

    #[test]
    fn rewrites_with_control_characters_or_far_too_long_are_refused() {
        let base = with(&[("sofa", Some(Side::Left))]);
        let ok = "Pass the sofa on your left and stop by the door.";
        assert_eq!(check_candidate(&base, ok), Ok(()));
        for (bad, why) in [
            ("Pass the sofa\u{0} on your left.", "U+0000"),
            ("Pass the \u{202e}tfel ruoy no afos.", "U+202E"),
            ("Pass the sofa.\u{1b}[2J", "U+001B"),
            ("   ", "empty"),
        ] {
            let err = check_candidate(&base, bad).unwrap_err();
            assert!(err.contains(why), "{bad:?}: {err}");
        }
        let long = "Walk on. ".repeat(65_536 / 9);
        let err = check_candidate(&base, &long).unwrap_err();
        assert!(err.contains("characters long"), "{err}");
    }

    #[test]
    fn unbounded_timeouts_and_retries_are_refused_by_name() {
        let ok = LlmConfig::default();
        assert!(ok.validate().is_ok(), "{:?}", ok.validate());
        let cases = [
            (
                LlmConfig {
                    timeout_s: 1e20,
                    ..ok.clone()
                },
                "llm.timeout_s",
            ),
            (
                LlmConfig {
                    timeout_s: 0.0,
                    ..ok.clone()
                },
                "llm.timeout_s",
            ),
            (
                LlmConfig {
                    retries: 1_000_000_000,
                    ..ok.clone()
                },
                "llm.retries",
            ),
            (
                LlmConfig {
                    retry_backoff_ms: 1_000_000_000_000_000,
                    ..ok.clone()
                },
                "llm.retry_backoff_ms",
            ),
        ];
        for (cfg, field) in cases {
            let e = cfg.validate().expect_err(field).to_string();
            assert!(e.contains(field), "{e}");
        }
    }

    #[test]
    fn images_are_standard_base64_data_urls() {
        let m = ChatMessage::user_with_images("look", &[vec![0xfb, 0xff], b"Man".to_vec()]);
        let Content::Parts(parts) = &m.content else {
            panic!("{m:?}")
        };
        let urls: Vec<&str> = parts
            .iter()
            .filter_map(|p| match p {
                Part::ImageUrl { image_url } => Some(image_url.url.as_str()),
                Part::Text { .. } => None,
            })
            .collect();
        assert_eq!(
            urls,
            ["data:image/png;base64,+/8=", "data:image/png;base64,TWFu"]
        );
    }

    fn with(objects: &[(&str, Option<Side>)]) -> Instruction {
        Instruction {
            instruction_text: "Walk past the sofa and stop by the bed.".into(),
            grounding: objects
                .iter()
                .enumerate()
                .map(|(i, (class, side))| GroundedObject {
                    object_id: i as u32,
                    class: class.to_string(),
                    role: Role::Landmark,
                    side: *side,
                    path_index: None,
                })
                .collect(),
            ..Default::default()
        }
    }

    #[test]
    fn candidates_name_only_grounded_objects_on_their_side() {
        let base = with(&[("sofa", Some(Side::Left)), ("tv_stand", Some(Side::Right))]);
        let ok = "Keep the sofa on your left. The tv stand is on the right; stop at the wall.";
        assert_eq!(check_candidate(&base, ok), Ok(()));
        // "tv stand" is read as one name, not as a tv.
        assert!(check_candidate(&base, "Go to the tv stand.").is_ok());
        let err = check_candidate(&base, "Pass the piano, then the sofa.").unwrap_err();
        assert!(err.contains("piano"), "{err}");
        let err = check_candidate(&base, "Keep the sofa on your right.").unwrap_err();
        assert!(err.contains("wrong side"), "{err}");
        // Named by the reference text though not grounded (the bed): allowed.
        assert!(check_candidate(&base, "Stop by the bed.").is_ok());
    }

    /// A template-like instruction and the objects it grounds, for paraphrase checks.
    fn route() -> Instruction {
        Instruction {
            instruction_text: "Walk out of the bedroom and turn left into the hallway. Go past \
                the bookshelf on your right and stop next to the red sofa in the living room."
                .into(),
            ..with(&[("bookshelf", Some(Side::Right)), ("sofa", None)])
        }
    }

    #[test]
    fn realistic_paraphrases_pass_the_vocabulary_check() {
        let base = route();
        for ok in [
            "Leave the bedroom and take a left into the hallway. Walk past the bookshelf on \
             your right, then stop beside the red sofa in the living room.",
            "Exit the bedroom, turn left down the corridor, pass the bookcase on your right and \
             come to a halt next to the red couch in the lounge.",
            "Head out of the bedroom and go left into the hall. Keep the bookshelf on your right \
             as you pass it, and stop when you reach the red sofa in the living room.",
            "From the bedroom, turn left into the hallway. Continue past the bookshelf to your \
             right and wait by the red sofa.",
            "Please exit the bedroom and turn to your left, entering the hallway. Proceed past \
             the bookshelf, which will be on your right-hand side, and stop next to the red \
             sofa in the living room.",
            "get out of the bedroom, hang a left into the hallway, walk by the bookshelf on the \
             right and stop at the red sofa in the living room",
            "Walk out of the bedroom, then turn left. Go along the hallway past the bookshelf on \
             your right. You'll find the red sofa in the living room; stop right next to it.",
            "Step out of the bedroom and make a left turn into the hallway. After passing the \
             bookshelf on your right, stop near the red sofa in the living room.",
            "Once you leave the bedroom, turn left and follow the hallway. The bookshelf should \
             be on your right as you walk by. Your destination is the red sofa in the living \
             room.",
            "Turn left after leaving the bedroom and walk down the hallway, passing the \
             bookshelf on your right. Stop once you're next to the red sofa in the living room.",
            "Go out of the bedroom and turn left into the hallway. Walk straight past the \
             bookshelf on your right and stop by the red sofa, which is in the living room.",
            "Leave the bedroom by turning left into the hallway; go past the bookshelf on the \
             right, and you will see the red sofa in the living room. Stop beside it.",
            "out of the bedroom, left into the hall, past the bookshelf on ur right, stop at the \
             red sofa in the living room",
            "Leave the bedroom, take the 1st left into the hallway, pass the bookshelf on \
             your right and stop 2 m from the red sofa in the living room.",
            "First, exit the bedroom and turn left into the hallway. Next, walk past the \
             bookshelf, keeping it on your right. Finally, stop when you are next to the red \
             sofa in the living room.",
        ] {
            assert_eq!(check_candidate(&base, ok), Ok(()), "{ok}");
        }
    }

    #[test]
    fn made_up_objects_are_refused_by_name() {
        let base = route();
        for (bad, word) in [
            (
                "Leave the bedroom, turn left and walk past the spaceship to the red sofa.",
                "spaceship",
            ),
            (
                "Turn left into the hallway, pass the dragon on your right and stop by the sofa.",
                "dragon",
            ),
            (
                "Walk out of the bedroom and stop next to the blue submarine in the hallway.",
                "submarine",
            ),
            // Plural and possessive forms of an unknown word are no better.
            ("Pass the dragons' bookshelf on your right.", "dragons"),
        ] {
            let err = check_candidate(&base, bad).unwrap_err();
            assert!(err.contains(&format!("{word:?}")), "{bad}: {err}");
        }
        // A word is known through the text it rewrites, even one no list has.
        let base = Instruction {
            instruction_text: "Stop by the spaceship.".into(),
            ..with(&[])
        };
        assert_eq!(
            check_candidate(&base, "Go to the spaceship and stop."),
            Ok(())
        );
    }

    #[test]
    fn direction_words_are_single_lower_case_words() {
        let v: toml::Value = toml::from_str(include_str!("../data/rewrite_words.toml")).unwrap();
        let mut strings = Vec::new();
        collect_strings(&v, &mut strings);
        assert!(strings.len() > 500, "{}", strings.len());
        for w in strings {
            assert!(
                !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase()),
                "{REWRITE_WORDS_FILE}: {w:?} is not one lower-case word"
            );
        }
        // No object noun slipped into the lists (these would make rewrites naming them pass).
        for noun in [
            "spaceship",
            "dragon",
            "submarine",
            "volcano",
            "rocket",
            "giraffe",
            "robe",
        ] {
            assert!(!knows(&KNOWN_WORDS, noun), "{noun}");
        }
    }
}
