//! A scripted OpenAI-compatible chat endpoint on loopback, for tests and for trying the agent
//! without a model (`cargo run -p vlnverse-mllm --example scripted_server`).
//!
//! The reply to a request is chosen from a script: the first rule whose `contains` occurs in
//! the text of the request's last message, else the last rule without `contains`. A rule picks
//! among its replies by the request's SHA-256 (`pick = "hash"`, the default: the same request
//! always gets the same reply, whatever the thread count) or in arrival order (`pick =
//! "turn"`). Every reply carries a `usage` object: the prompt tokens estimated as in the dry
//! run, the completion tokens as the reply's words.
//!
//! ```toml
//! delay_ms = 0      # wait before answering (to see the concurrency limit at work)
//! fail_first = 0    # answer HTTP 500 to the first N requests (to see retries)
//!
//! [[rule]]
//! contains = "could not read a move"
//! replies = ["turn left 30 degrees"]
//!
//! [[rule]]
//! replies = ["move forward 75 cm", "turn right 45 degrees", "stop"]
//! ```

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use serde::Deserialize;
use sha2::{Digest, Sha256};
use vlnverse_instructions::llm::{ChatMessage, Usage};

use crate::dry::request_tokens;

/// How a rule picks among its replies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pick {
    /// By the request's hash.
    #[default]
    Hash,
    /// In arrival order (per rule).
    Turn,
}

/// One rule of a script.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rule {
    /// Text the last message must contain; none: the default rule.
    pub contains: Option<String>,
    /// Replies (assistant content).
    pub replies: Vec<String>,
    /// How to pick.
    #[serde(default)]
    pub pick: Pick,
}

/// A script.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Script {
    /// Wait before each answer (ms).
    #[serde(default)]
    pub delay_ms: u64,
    /// HTTP 500 for the first N requests.
    #[serde(default)]
    pub fail_first: u64,
    /// The rules, first match wins.
    #[serde(rename = "rule")]
    pub rules: Vec<Rule>,
}

impl Script {
    /// Parse a TOML script; the error names the problem.
    pub fn parse(text: &str) -> Result<Self, String> {
        let s: Script = toml::from_str(text).map_err(|e| e.message().to_string())?;
        if let Some(i) = s.rules.iter().position(|r| r.replies.is_empty()) {
            return Err(format!("rule[{i}].replies is empty"));
        }
        if !s.rules.iter().any(|r| r.contains.is_none()) {
            return Err("no default rule (a [[rule]] without `contains`)".into());
        }
        Ok(s)
    }

    /// Every rule, in arrival order, the same replies: a fixed sequence.
    pub fn sequence(replies: &[&str]) -> Self {
        Script {
            rules: vec![Rule {
                contains: None,
                replies: replies.iter().map(|r| r.to_string()).collect(),
                pick: Pick::Turn,
            }],
            ..Default::default()
        }
    }
}

/// What the server saw.
#[derive(Debug, Default)]
pub struct Seen {
    /// Requests answered (any status).
    pub requests: AtomicU64,
    /// Requests being answered right now.
    pub in_flight: AtomicU64,
    /// Most requests answered at once.
    pub peak_in_flight: AtomicU64,
    /// Bodies of the answered requests with the usage returned (HTTP 200 only), in order.
    pub log: Mutex<Vec<(serde_json::Value, Usage)>>,
}

/// A running scripted server.
pub struct ScriptedServer {
    /// Base URL (`http://127.0.0.1:PORT/v1`).
    pub url: String,
    /// What it saw.
    pub seen: Arc<Seen>,
}

impl ScriptedServer {
    /// Serve `script` on `127.0.0.1:port` (0: any free port) from background threads.
    pub fn start(script: Script, port: u16) -> std::io::Result<Self> {
        let listener = TcpListener::bind(("127.0.0.1", port))?;
        let url = format!("http://{}/v1", listener.local_addr()?);
        let seen = Arc::new(Seen::default());
        let state = Arc::new((script, Mutex::new(vec![0usize; 64])));
        let log = seen.clone();
        std::thread::spawn(move || {
            for stream in listener.incoming() {
                let Ok(stream) = stream else { continue };
                let (state, log) = (state.clone(), log.clone());
                std::thread::spawn(move || {
                    let _ = serve(stream, &state.0, &state.1, &log);
                });
            }
        });
        Ok(ScriptedServer { url, seen })
    }
}

fn last_text(body: &serde_json::Value) -> String {
    let Some(m) = body
        .get("messages")
        .and_then(|m| m.as_array())
        .and_then(|m| m.last())
    else {
        return String::new();
    };
    match m.get("content") {
        Some(serde_json::Value::String(s)) => s.clone(),
        Some(serde_json::Value::Array(parts)) => parts
            .iter()
            .filter_map(|p| p.get("text").and_then(|t| t.as_str()))
            .collect::<Vec<_>>()
            .join("\n"),
        _ => String::new(),
    }
}

fn serve(
    stream: TcpStream,
    script: &Script,
    turns: &Mutex<Vec<usize>>,
    seen: &Seen,
) -> std::io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(30)))?;
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut line = String::new();
    reader.read_line(&mut line)?;
    let mut len = 0usize;
    loop {
        let mut h = String::new();
        if reader.read_line(&mut h)? == 0 {
            break;
        }
        let h = h.trim_end();
        if h.is_empty() {
            break;
        }
        if let Some(v) = h.to_ascii_lowercase().strip_prefix("content-length:") {
            len = v.trim().parse().unwrap_or(0);
        }
    }
    let mut body = vec![0u8; len];
    reader.read_exact(&mut body)?;
    let now = seen.in_flight.fetch_add(1, Ordering::SeqCst) + 1;
    seen.peak_in_flight.fetch_max(now, Ordering::SeqCst);
    let k = seen.requests.fetch_add(1, Ordering::SeqCst);
    if script.delay_ms > 0 {
        std::thread::sleep(Duration::from_millis(script.delay_ms));
    }
    let (status, payload) = match serde_json::from_slice::<serde_json::Value>(&body) {
        _ if k < script.fail_first => (500, "{\"error\": \"scripted failure\"}".to_string()),
        Err(e) => (
            400,
            serde_json::json!({ "error": e.to_string() }).to_string(),
        ),
        Ok(v) => {
            let text = last_text(&v);
            let i = script
                .rules
                .iter()
                .position(|r| {
                    r.contains
                        .as_ref()
                        .is_some_and(|c| text.contains(c.as_str()))
                })
                .or_else(|| script.rules.iter().rposition(|r| r.contains.is_none()))
                .unwrap_or(0);
            let rule = &script.rules[i];
            let n = match rule.pick {
                Pick::Hash => {
                    let h = Sha256::digest(&body);
                    u64::from_le_bytes(h[..8].try_into().unwrap_or_default()) as usize
                }
                Pick::Turn => {
                    let mut t = turns.lock().unwrap_or_else(|p| p.into_inner());
                    let slot = &mut t[i.min(63)];
                    *slot += 1;
                    *slot - 1
                }
            };
            let reply = &rule.replies[n % rule.replies.len()];
            let messages: Vec<ChatMessage> = v
                .get("messages")
                .and_then(|m| serde_json::from_value(m.clone()).ok())
                .unwrap_or_default();
            let usage = Usage {
                prompt_tokens: request_tokens(&messages),
                completion_tokens: reply.split_whitespace().count() as u64,
            };
            let payload = serde_json::json!({
                "id": format!("scripted-{k}"), "object": "chat.completion",
                "model": v.get("model").cloned().unwrap_or_default(),
                "choices": [{"index": 0, "finish_reason": "stop",
                             "message": {"role": "assistant", "content": reply}}],
                "usage": {"prompt_tokens": usage.prompt_tokens,
                          "completion_tokens": usage.completion_tokens,
                          "total_tokens": usage.prompt_tokens + usage.completion_tokens}
            })
            .to_string();
            seen.log
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .push((v, usage));
            (200, payload)
        }
    };
    seen.in_flight.fetch_sub(1, Ordering::SeqCst);
    let mut out = stream;
    write!(
        out,
        "HTTP/1.1 {status} X\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{payload}",
        payload.len()
    )?;
    out.flush()
}
