//! What each episode cost: `mllm.jsonl` in the run folder (one line per episode) and the
//! totals in `summary.json` under `mllm`.
//!
//! `summary.json` gets only what follows from the replies (tokens, calls, corrective retries,
//! fallbacks, questions), so a rerun served from the reply cache writes the same bytes; the
//! traffic of this run (requests sent, cache hits, transport retries, latency) is in
//! `mllm.jsonl` alone.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use vlnverse_eval::{Result, TaskError};
use vlnverse_score::dataset::write_atomic;
use vlnverse_score::RunSummary;

/// The per-episode file of the run folder.
pub const ACCOUNTING_FILE: &str = "mllm.jsonl";

/// What one episode cost.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct EpisodeStats {
    /// Episode id.
    pub episode_id: u64,
    /// Steps at which the model was asked for a move (the others ran queued moves).
    pub decisions: u64,
    /// Replies the agent got (sent or from the cache).
    pub calls: u64,
    /// Tokens of the requests, as the endpoint reported them.
    pub prompt_tokens: u64,
    /// Tokens of the replies.
    pub completion_tokens: u64,
    /// Replies the endpoint gave without token counts.
    pub calls_without_usage: u64,
    /// Corrective retries after a reply with no readable move.
    pub parse_retries: u64,
    /// Moves that were the configured fallback (unusable reply or failed call).
    pub fallbacks: u64,
    /// Calls that failed after all transport retries.
    pub failed_calls: u64,
    /// Questions put to the dialogue oracle.
    pub asks: u64,
    /// Requests sent over the network (this run).
    pub requests: u64,
    /// Replies taken from the cache (this run).
    pub cache_hits: u64,
    /// Extra HTTP attempts after transport errors, 429 or 5xx (this run).
    pub transport_retries: u64,
    /// Wall time of the sent requests, summed (ms, this run).
    pub latency_ms: f64,
}

impl EpisodeStats {
    fn add(&mut self, o: &EpisodeStats) {
        self.decisions += o.decisions;
        self.calls += o.calls;
        self.prompt_tokens += o.prompt_tokens;
        self.completion_tokens += o.completion_tokens;
        self.calls_without_usage += o.calls_without_usage;
        self.parse_retries += o.parse_retries;
        self.fallbacks += o.fallbacks;
        self.failed_calls += o.failed_calls;
        self.asks += o.asks;
        self.requests += o.requests;
        self.cache_hits += o.cache_hits;
        self.transport_retries += o.transport_retries;
        self.latency_ms += o.latency_ms;
    }
}

/// Totals over a run's episodes: the `mllm` object of `summary.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Totals {
    /// Model the run used.
    pub model: String,
    /// Episodes counted.
    pub episodes: u64,
    /// Model decisions.
    pub decisions: u64,
    /// Replies received.
    pub calls: u64,
    /// Request tokens.
    pub prompt_tokens: u64,
    /// Reply tokens.
    pub completion_tokens: u64,
    /// Replies without token counts.
    pub calls_without_usage: u64,
    /// Corrective retries.
    pub parse_retries: u64,
    /// Fallback moves.
    pub fallbacks: u64,
    /// Failed calls.
    pub failed_calls: u64,
    /// Questions asked.
    pub asks: u64,
    /// Request plus reply tokens per episode.
    pub tokens_per_episode: f64,
}

/// The traffic of a run: the `mllm.jsonl` columns `summary.json` leaves out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Traffic {
    /// Requests sent.
    pub requests: u64,
    /// Cache hits.
    pub cache_hits: u64,
    /// Transport retries.
    pub transport_retries: u64,
    /// Mean latency of a sent request (ms).
    pub mean_latency_ms: f64,
}

/// Sum per-episode records.
pub fn totals(model: &str, records: &[EpisodeStats]) -> (Totals, Traffic) {
    let mut sum = EpisodeStats::default();
    for r in records {
        sum.add(r);
    }
    let n = records.len() as u64;
    let t = Totals {
        model: model.to_string(),
        episodes: n,
        decisions: sum.decisions,
        calls: sum.calls,
        prompt_tokens: sum.prompt_tokens,
        completion_tokens: sum.completion_tokens,
        calls_without_usage: sum.calls_without_usage,
        parse_retries: sum.parse_retries,
        fallbacks: sum.fallbacks,
        failed_calls: sum.failed_calls,
        asks: sum.asks,
        tokens_per_episode: if n == 0 {
            0.0
        } else {
            (sum.prompt_tokens + sum.completion_tokens) as f64 / n as f64
        },
    };
    let traffic = Traffic {
        requests: sum.requests,
        cache_hits: sum.cache_hits,
        transport_retries: sum.transport_retries,
        mean_latency_ms: if sum.requests == 0 {
            0.0
        } else {
            sum.latency_ms / sum.requests as f64
        },
    };
    (t, traffic)
}

/// Read `mllm.jsonl` (empty when absent).
pub fn read_records(run_dir: &Path) -> Result<Vec<EpisodeStats>> {
    let path = run_dir.join(ACCOUNTING_FILE);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(TaskError::io(&path, e)),
    };
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l)
                .map_err(|e| TaskError::parse(&path, format!("line {}", i + 1), e))
        })
        .collect()
}

#[derive(Serialize)]
struct WithMllm<'a> {
    #[serde(flatten)]
    run: &'a RunSummary,
    mllm: &'a Totals,
}

/// Merge `new` records into the run folder's `mllm.jsonl` (an episode run again replaces its
/// line; lines in episode order), keep only the episodes of `summary.json`'s run when
/// `episodes` is given, and add the totals to `summary.json`. Both files are written
/// atomically.
pub fn write_accounting(
    run_dir: &Path,
    model: &str,
    new: &[EpisodeStats],
    episodes: Option<&[u64]>,
) -> Result<(Totals, Traffic)> {
    let mut all: BTreeMap<u64, EpisodeStats> = read_records(run_dir)?
        .into_iter()
        .map(|r| (r.episode_id, r))
        .collect();
    for r in new {
        all.insert(r.episode_id, r.clone());
    }
    if let Some(keep) = episodes {
        all.retain(|id, _| keep.contains(id));
    }
    let records: Vec<EpisodeStats> = all.into_values().collect();
    let mut text = String::new();
    for r in &records {
        text.push_str(
            &serde_json::to_string(r)
                .map_err(|e| TaskError::invalid("mllm.jsonl", r.episode_id, e.to_string()))?,
        );
        text.push('\n');
    }
    write_atomic(&run_dir.join(ACCOUNTING_FILE), text.as_bytes())?;
    let (t, traffic) = totals(model, &records);
    let summary_path = run_dir.join("summary.json");
    if let Ok(bytes) = std::fs::read(&summary_path) {
        let run: RunSummary = serde_json::from_slice(&bytes)
            .map_err(|e| TaskError::parse(&summary_path, "summary", e))?;
        let mut json = serde_json::to_string_pretty(&WithMllm {
            run: &run,
            mllm: &t,
        })
        .map_err(|e| TaskError::invalid("summary.json", "mllm", e.to_string()))?;
        json.push('\n');
        write_atomic(&summary_path, json.as_bytes())?;
    }
    Ok((t, traffic))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_merge_by_episode_and_totals_sum() {
        let dir = tempfile::tempdir().unwrap();
        let r = |id, p, c| EpisodeStats {
            episode_id: id,
            calls: 2,
            prompt_tokens: p,
            completion_tokens: c,
            requests: 2,
            latency_ms: 10.0,
            ..Default::default()
        };
        write_accounting(dir.path(), "m", &[r(2, 100, 10), r(1, 50, 5)], None).unwrap();
        // Episode 2 again (a resumed run) replaces its line; 3 is new.
        let (t, traffic) =
            write_accounting(dir.path(), "m", &[r(2, 7, 1), r(3, 1, 1)], None).unwrap();
        let back = read_records(dir.path()).unwrap();
        let ids: Vec<u64> = back.iter().map(|r| r.episode_id).collect();
        assert_eq!(ids, [1, 2, 3]);
        assert_eq!((t.prompt_tokens, t.completion_tokens), (58, 7));
        assert_eq!((t.episodes, t.calls), (3, 6));
        assert_eq!(traffic.mean_latency_ms, 5.0);
        let (t, _) = write_accounting(dir.path(), "m", &[], Some(&[1])).unwrap();
        assert_eq!((t.episodes, t.prompt_tokens), (1, 50));
    }
}
