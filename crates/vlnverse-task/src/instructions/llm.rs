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
//! Requests: `POST {base_url}/chat/completions` with `model`, `messages`, `temperature` (0 by
//! default), `seed` and optionally `max_tokens`; the key, when `api_key_env` names an
//! environment variable, goes in `Authorization: Bearer ...`. Plain `http://` endpoints work out
//! of the box; `https://` needs the crate feature `llm-tls`.

use super::{InstructionGenerator, PathContext};
use crate::episode::{Instruction, Role, Side, Style};
use crate::error::{Result, TaskError};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::time::Duration;
use vlnverse_env::ObjectId;

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
#[serde(default)]
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
}

impl Default for LlmConfig {
    fn default() -> Self {
        LlmConfig {
            base_url: "http://127.0.0.1:8000/v1".into(),
            model: "gpt-4o-mini".into(),
            api_key_env: Some("OPENAI_API_KEY".into()),
            temperature: 0.0,
            max_tokens: Some(400),
            timeout_s: 60.0,
            retries: 2,
            retry_backoff_ms: 500,
            verify: true,
            on_reject: OnReject::Fallback,
        }
    }
}

impl LlmConfig {
    /// Check the values; the error names the field.
    pub fn validate(&self) -> Result<()> {
        if !(self.base_url.starts_with("http://") || self.base_url.starts_with("https://")) {
            return Err(TaskError::invalid(
                "llm.base_url",
                &self.base_url,
                "must start with http:// or https://",
            ));
        }
        if self.base_url.starts_with("https://") && !cfg!(feature = "llm-tls") {
            return Err(TaskError::invalid(
                "llm.base_url",
                &self.base_url,
                "https needs vlnverse-task built with the `llm-tls` feature",
            ));
        }
        if self.model.trim().is_empty() {
            return Err(TaskError::invalid("llm.model", "\"\"", "must not be empty"));
        }
        if !(self.temperature.is_finite() && (0.0..=2.0).contains(&self.temperature)) {
            return Err(TaskError::invalid(
                "llm.temperature",
                self.temperature,
                "must be in [0, 2]",
            ));
        }
        if !(self.timeout_s.is_finite() && self.timeout_s > 0.0) {
            return Err(TaskError::invalid(
                "llm.timeout_s",
                self.timeout_s,
                "must be > 0",
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
    /// The text.
    pub content: String,
}

impl ChatMessage {
    /// A system message.
    pub fn system(content: impl Into<String>) -> Self {
        ChatMessage {
            role: "system".into(),
            content: content.into(),
        }
    }

    /// A user message.
    pub fn user(content: impl Into<String>) -> Self {
        ChatMessage {
            role: "user".into(),
            content: content.into(),
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
}

fn net_error(url: &str, e: impl std::fmt::Display) -> TaskError {
    TaskError::io(PathBuf::from(url), std::io::Error::other(e.to_string()))
}

impl ChatClient {
    /// A client for the configured endpoint (config checked).
    pub fn new(config: LlmConfig) -> Result<Self> {
        config.validate()?;
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .timeout_global(Some(Duration::from_secs_f32(config.timeout_s)))
            .http_status_as_error(false)
            .build()
            .into();
        Ok(ChatClient { config, agent })
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
                Err(_) => Err(TaskError::invalid(
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
            if let Some(k) = &key {
                req = req.header("Authorization", &format!("Bearer {k}"));
            }
            let mut resp = match req.send(&body) {
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
            return parse_reply(&url, &text);
        }
        Err(last_err.unwrap_or_else(|| net_error(&url, "no attempt made")))
    }
}

fn parse_reply(url: &str, text: &str) -> Result<String> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| TaskError::parse(url, "response body", e))?;
    let content = v
        .pointer("/choices/0/message/content")
        .and_then(|c| c.as_str())
        .ok_or_else(|| {
            TaskError::parse(
                url,
                "choices[0].message.content",
                format!("missing or not a string in {}", truncate(text, 200)),
            )
        })?;
    let content = content.trim().trim_matches('"').trim();
    if content.is_empty() {
        return Err(TaskError::parse(
            url,
            "choices[0].message.content",
            "empty reply",
        ));
    }
    Ok(content.to_string())
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

/// An [`InstructionGenerator`] that rewrites the output of `inner` with an LLM (describer /
/// synthesizer) and checks it (verifier); see the module docs.
#[derive(Debug)]
pub struct LlmGenerator<G> {
    inner: G,
    client: ChatClient,
}

impl<G: InstructionGenerator> LlmGenerator<G> {
    /// Wrap `inner` (usually the [`super::TemplateGenerator`]).
    pub fn new(inner: G, config: LlmConfig) -> Result<Self> {
        Ok(LlmGenerator {
            inner,
            client: ChatClient::new(config)?,
        })
    }

    /// The wrapped generator.
    pub fn inner(&self) -> &G {
        &self.inner
    }

    /// The chat client.
    pub fn client(&self) -> &ChatClient {
        &self.client
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
        user: String,
        seed: u64,
    ) -> Result<Instruction> {
        let policy = self.client.config.on_reject;
        let attempt = (|| -> Result<std::result::Result<String, String>> {
            let candidate = self.client.chat(
                &[ChatMessage::system(system), ChatMessage::user(user)],
                seed,
            )?;
            if self.client.config.verify {
                let v = self.verify(&base, &candidate, seed)?;
                if !v.accepted {
                    return Ok(Err(v.reason));
                }
            }
            Ok(Ok(candidate))
        })();
        match (attempt, policy) {
            (Ok(Ok(text)), _) => Ok(Instruction {
                instruction_text: text,
                ..base
            }),
            (Ok(Err(reason)), OnReject::Fallback) => {
                tracing::warn!(%reason, "verifier rejected the LLM instruction; keeping the template");
                Ok(base)
            }
            (Ok(Err(reason)), OnReject::Error) => Err(TaskError::invalid(
                "llm.verifier",
                truncate(&base.instruction_text, 80),
                format!("candidate rejected: {reason}"),
            )),
            (Err(e), OnReject::Fallback) => {
                tracing::warn!(error = %e, "LLM call failed; keeping the template");
                Ok(base)
            }
            (Err(e), OnReject::Error) => Err(e),
        }
    }

    fn describe(&self, base: Instruction, seed: u64) -> Result<Instruction> {
        let user = format!(
            "{}\nRewrite the reference instruction in the requested style.",
            facts(&base)
        );
        self.refine(base, DESCRIBER_PROMPT, user, seed)
    }
}

impl<G: InstructionGenerator> InstructionGenerator for LlmGenerator<G> {
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction> {
        let base = self.inner.fine(ctx, seed)?;
        self.describe(base, seed)
    }

    fn coarse(
        &self,
        ctx: &PathContext<'_>,
        target: ObjectId,
        style: Style,
        seed: u64,
    ) -> Result<Instruction> {
        let base = self.inner.coarse(ctx, target, style, seed)?;
        self.describe(base, seed)
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
        self.refine(base, SYNTHESIZER_PROMPT, user, seed)
    }
}
