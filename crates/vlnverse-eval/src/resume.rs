//! Resuming an interrupted run: every finished episode is appended to `RUN/progress.jsonl`
//! (one JSON line, flushed and fsynced); a restart skips those episodes, and the final files
//! are rebuilt from it. A half-written last line (the process was killed mid-write) is cut off.
//! `RUN/run.json` records what the run is (agent, setting, task, split, dataset, protocol) so
//! that a different run is never mixed into the same folder.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use crate::error::{Result, TaskError};
use vlnverse_score::metrics::EpisodeMetrics;
use vlnverse_score::trajectory::Trajectory;

/// One finished episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRecord {
    /// Episode id.
    pub episode_id: u64,
    /// What the agent did.
    pub trajectory: Trajectory,
    /// Its metrics.
    pub metrics: EpisodeMetrics,
    /// Why the episode ended early, when it failed (Strict collision).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
}

/// Name of the progress file in a run folder.
pub const PROGRESS_FILE: &str = "progress.jsonl";
/// Name of the run identity file.
pub const RUN_FILE: &str = "run.json";

/// Read `progress.jsonl` (missing file = nothing done). A last line without its newline or
/// that does not parse is dropped and cut from the file; a bad line before it is an error
/// naming the line.
pub fn load_progress(path: &Path) -> Result<Vec<EpisodeRecord>> {
    let text = match std::fs::read(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(TaskError::io(path, e)),
    };
    let mut out = Vec::new();
    let mut good = 0usize;
    let mut pos = 0usize;
    let mut line_no = 0usize;
    while pos < text.len() {
        line_no += 1;
        let end = text[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|i| pos + i);
        let (line, next) = match end {
            Some(e) => (&text[pos..e], e + 1),
            None => (&text[pos..], text.len()),
        };
        let complete = end.is_some();
        if line.iter().all(u8::is_ascii_whitespace) {
            pos = next;
            if complete {
                good = next;
            }
            continue;
        }
        match (serde_json::from_slice::<EpisodeRecord>(line), complete) {
            (Ok(r), true) => {
                out.push(r);
                good = next;
            }
            (Err(e), true) if next < text.len() => {
                return Err(TaskError::parse(path, format!("line {line_no}"), e));
            }
            _ => {
                tracing::warn!(file = %path.display(), line = line_no, "dropping a half-written last line");
                break;
            }
        }
        pos = next;
    }
    if good < text.len() {
        let f = OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| TaskError::io(path, e))?;
        f.set_len(good as u64).map_err(|e| TaskError::io(path, e))?;
    }
    Ok(out)
}

/// Appends finished episodes to `progress.jsonl`, one fsynced line each (thread-safe).
pub struct ProgressLog {
    path: PathBuf,
    file: Mutex<File>,
}

impl ProgressLog {
    /// Open (create) the log for appending.
    pub fn open(path: &Path) -> Result<Self> {
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(|e| TaskError::io(path, e))?;
        Ok(ProgressLog {
            path: path.to_path_buf(),
            file: Mutex::new(file),
        })
    }

    /// Append one record and make it durable.
    pub fn append(&self, rec: &EpisodeRecord) -> Result<()> {
        let mut line = serde_json::to_string(rec)
            .map_err(|e| TaskError::invalid("episode record", rec.episode_id, e.to_string()))?;
        line.push('\n');
        let mut f = self
            .file
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        f.write_all(line.as_bytes())
            .and_then(|_| f.sync_data())
            .map_err(|e| TaskError::io(&self.path, e))
    }
}

/// Write `run.json`, or check that the existing one describes the same run. `identity` lists
/// the keys in the order they are compared; the error names the first key that differs, with
/// the value now and the value in the file.
pub fn check_or_write_identity(dir: &Path, identity: &[(&str, serde_json::Value)]) -> Result<()> {
    let path = dir.join(RUN_FILE);
    match std::fs::read(&path) {
        Ok(bytes) => {
            let old: serde_json::Value = serde_json::from_slice(&bytes)
                .map_err(|e| TaskError::parse(&path, format!("line {}", e.line()), e))?;
            let differing = identity
                .iter()
                .find(|(k, v)| old.get(*k) != Some(v))
                .map(|(k, v)| {
                    (
                        k.to_string(),
                        v.to_string(),
                        old.get(*k).map(|o| o.to_string()),
                    )
                })
                .or_else(|| {
                    // A key of the file that this run does not have.
                    old.as_object()?
                        .iter()
                        .find(|(k, _)| !identity.iter().any(|(n, _)| n == k))
                        .map(|(k, v)| (k.clone(), "<none>".into(), Some(v.to_string())))
                });
            if let Some((key, now, before)) = differing {
                return Err(TaskError::parse(
                    &path,
                    format!("field `{key}`"),
                    format!(
                        "this folder holds another run: `{key}` is {now} now but {} in the \
                         folder's run; choose another --out, or --fresh to start over",
                        before.unwrap_or_else(|| "<missing>".into())
                    ),
                ));
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let map: serde_json::Map<String, serde_json::Value> = identity
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect();
            let mut s = serde_json::to_string_pretty(&map)
                .map_err(|e| TaskError::invalid("run", "identity", e.to_string()))?;
            s.push('\n');
            Ok(vlnverse_score::dataset::write_atomic(&path, s.as_bytes())?)
        }
        Err(e) => Err(TaskError::io(&path, e)),
    }
}
