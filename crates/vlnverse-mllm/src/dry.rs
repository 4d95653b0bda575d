//! The dry run: a backend that sends nothing. It prints every request (text in full, pictures
//! by type and size), answers a fixed walk that stops after a few decisions, and counts
//! estimated tokens, so one episode shows what a run sends and what a whole run would cost.
//!
//! Token estimates follow the common accounting of hosted vision models: about 4 characters
//! per text token, and per picture 85 tokens plus 170 per 512-pixel tile. Local servers count
//! differently; the estimate is for planning, not billing.

use std::io::Write;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Duration;

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use vlnverse_eval::Result;
use vlnverse_instructions::llm::{ChatMessage, ChatReply, Content, Part, Usage};
use vlnverse_score::Episode;

use crate::agent::ChatBackend;

/// Estimated tokens of a picture `w` x `h` pixels.
pub fn image_tokens(w: u32, h: u32) -> u64 {
    let tiles = w.div_ceil(512).max(1) * h.div_ceil(512).max(1);
    85 + 170 * u64::from(tiles)
}

/// Estimated tokens of a request.
pub fn request_tokens(messages: &[ChatMessage]) -> u64 {
    let mut t = 0u64;
    for m in messages {
        t += 4;
        match &m.content {
            Content::Text(s) => t += s.len().div_ceil(4) as u64,
            Content::Parts(parts) => {
                for p in parts {
                    match p {
                        Part::Text { text } => t += text.len().div_ceil(4) as u64,
                        Part::ImageUrl { image_url } => {
                            let (w, h) = data_url_size(&image_url.url).unwrap_or((512, 512));
                            t += image_tokens(w, h);
                        }
                    }
                }
            }
        }
    }
    t
}

fn data_url_size(url: &str) -> Option<(u32, u32)> {
    let b64 = url.split_once(";base64,")?.1;
    let bytes = STANDARD.decode(b64).ok()?;
    let img = image::load_from_memory(&bytes).ok()?;
    Some((img.width(), img.height()))
}

/// A backend that prints requests instead of sending them.
pub struct DryRun {
    out: Mutex<Box<dyn Write + Send>>,
    calls: AtomicU64,
    decisions: u64,
    reply_tokens: u64,
}

impl DryRun {
    /// Print to `out`; walk for `decisions` replies, then stop. `reply_tokens` is the estimate
    /// of one reply (more with chain of thought).
    pub fn new(out: Box<dyn Write + Send>, decisions: u64, reply_tokens: u64) -> Self {
        DryRun {
            out: Mutex::new(out),
            calls: AtomicU64::new(0),
            decisions,
            reply_tokens,
        }
    }
}

impl ChatBackend for DryRun {
    fn chat(&self, messages: &[ChatMessage], _seed: u64) -> Result<ChatReply> {
        let k = self.calls.fetch_add(1, Ordering::Relaxed);
        let tokens = request_tokens(messages);
        let mut out = self.out.lock().unwrap_or_else(|p| p.into_inner());
        let _ = writeln!(out, "===== request {} (about {tokens} tokens) =====", k + 1);
        for m in messages {
            // The system message is the same every time: print it once.
            if m.role == "system" && k > 0 {
                let _ = writeln!(out, "[system: as in request 1]");
                continue;
            }
            let _ = writeln!(out, "[{}]", m.role);
            match &m.content {
                Content::Text(s) => {
                    let _ = writeln!(out, "{s}");
                }
                Content::Parts(parts) => {
                    for p in parts {
                        match p {
                            Part::Text { text } => {
                                let _ = writeln!(out, "{text}");
                            }
                            Part::ImageUrl { image_url } => {
                                let mime = image_url
                                    .url
                                    .strip_prefix("data:")
                                    .and_then(|u| u.split(';').next())
                                    .unwrap_or("url");
                                let (w, h) = data_url_size(&image_url.url).unwrap_or((0, 0));
                                let _ = writeln!(
                                    out,
                                    "<picture {mime} {w}x{h}, {} bytes of base64>",
                                    image_url.url.len()
                                );
                            }
                        }
                    }
                }
            }
        }
        let text = if k + 1 >= self.decisions {
            "stop"
        } else if k % 3 == 2 {
            "turn left 30 degrees"
        } else {
            "move forward 50 cm"
        };
        let _ = writeln!(out, "[dry-run reply] {text}");
        Ok(ChatReply {
            text: text.into(),
            usage: Some(Usage {
                prompt_tokens: tokens,
                completion_tokens: self.reply_tokens,
            }),
            cached: false,
            attempts: 1,
            latency: Duration::ZERO,
        })
    }
}

/// Primitive moves along an episode's reference path (forward steps plus the turns between
/// its segments): the decisions of an agent whose every reply is one primitive.
pub fn reference_moves(ep: &Episode, step_m: f32, turn_deg: f32) -> u64 {
    let p = &ep.reference_path;
    let mut len = 0.0f32;
    let mut turn = 0.0f32;
    let mut last_dir: Option<f32> = None;
    for w in p.windows(2) {
        let (dx, dz) = (w[1][0] - w[0][0], w[1][2] - w[0][2]);
        let d = (dx * dx + dz * dz).sqrt();
        if d < 1e-4 {
            continue;
        }
        len += d;
        let dir = dx.atan2(dz);
        if let Some(prev) = last_dir {
            let mut a = (dir - prev).abs() % std::f32::consts::TAU;
            if a > std::f32::consts::PI {
                a = std::f32::consts::TAU - a;
            }
            turn += a;
        }
        last_dir = Some(dir);
    }
    (len / step_m).ceil() as u64 + (turn.to_degrees() / turn_deg).round() as u64 + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn token_estimates_count_text_and_tiles() {
        assert_eq!(image_tokens(224, 224), 255);
        assert_eq!(image_tokens(1024, 600), 85 + 170 * 4);
        let m = [
            ChatMessage::system("x".repeat(40)),
            ChatMessage::user("abcd"),
        ];
        assert_eq!(request_tokens(&m), 4 + 10 + 4 + 1);
    }

    #[test]
    fn moves_along_a_bent_path() {
        let ep = Episode {
            reference_path: vec![[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, -1.0]],
            ..Default::default()
        };
        // 2 m at 0.25 m a step, one 90 degree bend at 15 degrees a turn, and the stop.
        assert_eq!(reference_moves(&ep, 0.25, 15.0), 8 + 6 + 1);
    }
}
