//! Resuming an interrupted run: every finished episode is appended to `RUN/progress.jsonl`
//! (one JSON line, flushed and fsynced); a restart skips those episodes, and the final files
//! are rebuilt from it. A half-written last line (the process was killed mid-write) is cut off.
//! `RUN/run.json` records what the run is (agent, setting, task, split, dataset, protocol) so
//! that a different run is never mixed into the same folder, and each finished episode's line
//! carries a hash of the episode as it was run ([`episode_fingerprint`]), so a resume after
//! that episode was edited in the split file is refused ([`check_unchanged`]) while edits to
//! episodes the run has not reached are simply run as they are now.

use std::collections::BTreeMap;
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use crate::error::{Result, TaskError};
use vlnverse_score::metrics::EpisodeMetrics;
use vlnverse_score::trajectory::Trajectory;
use vlnverse_score::Episode;
use vlnverse_sim::Failure;

/// One finished episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct EpisodeRecord {
    /// Episode id.
    pub episode_id: u64,
    /// What the agent did.
    pub trajectory: Trajectory,
    /// Its metrics.
    pub metrics: EpisodeMetrics,
    /// Why the episode ended early, when it failed (Strict collision). Written as an object
    /// (`{"type": "collision", "hit": [2]}`); runs written before held that object's JSON
    /// text as a string, which is still read.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "failure_then_or_now"
    )]
    pub failure: Option<Failure>,
    /// [`episode_fingerprint`] of the episode as it was run (set by [`ProgressLog::append`];
    /// records of older runs have none and are not checked).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub episode_fingerprint: Option<String>,
}

impl EpisodeRecord {
    /// A record of a finished episode.
    pub fn new(
        episode_id: u64,
        trajectory: Trajectory,
        metrics: EpisodeMetrics,
        failure: Option<Failure>,
    ) -> Self {
        EpisodeRecord {
            episode_id,
            trajectory,
            metrics,
            failure,
            episode_fingerprint: None,
        }
    }
}

/// A stable hash (hex) of one episode as the split file holds it: start, goals, instruction,
/// path and the rest.
pub fn episode_fingerprint(ep: &Episode) -> Result<String> {
    fingerprint_key(ep).map(fingerprint_text)
}

/// [`episode_fingerprint`] as a number (a log keeps one per episode of its run).
fn fingerprint_key(ep: &Episode) -> Result<u64> {
    let json = serde_json::to_vec(ep)
        .map_err(|e| TaskError::invalid("episode", ep.episode_id, e.to_string()))?;
    let mut key = vlnverse_env::cache::ContentKey::new();
    key.bytes(&json);
    Ok(key.finish())
}

/// A fingerprint as `run.json` and the log write it.
fn fingerprint_text(key: u64) -> String {
    format!("{key:016x}")
}

/// Refuse a resume in which an episode already finished in the folder (`done`) is not the
/// same episode in the split file now (`episodes`, the episodes of this call, read from
/// `split_file`): its result would mix two versions of the split. The error names the
/// episode, its index and `episode_fingerprint`.
pub fn check_unchanged(
    split_file: &Path,
    episodes: &[Episode],
    done: &BTreeMap<u64, EpisodeRecord>,
) -> Result<()> {
    for (i, ep) in episodes.iter().enumerate() {
        let Some(then) = done
            .get(&ep.episode_id)
            .and_then(|r| r.episode_fingerprint.as_deref())
        else {
            continue;
        };
        let now = episode_fingerprint(ep)?;
        if now != then {
            return Err(TaskError::invalid(
                format!(
                    "{}: episode {} (episodes[{i}]).episode_fingerprint",
                    split_file.display(),
                    ep.episode_id
                ),
                &now,
                format!(
                    "the episode changed in the split file since this folder's run finished it \
                     (then {then}); resuming would mix two versions of the split: choose \
                     another --out, or --fresh to start over"
                ),
            ));
        }
    }
    Ok(())
}

/// A failure as written now (an object) or by older runs (its JSON text as a string).
fn failure_then_or_now<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<Failure>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Either {
        Now(Failure),
        Then(String),
    }
    match Option::<Either>::deserialize(d)? {
        None => Ok(None),
        Some(Either::Now(f)) => Ok(Some(f)),
        Some(Either::Then(text)) => serde_json::from_str(&text).map(Some).map_err(|e| {
            serde::de::Error::custom(format!(
                "`failure` {text:?} is not a failure this version knows ({e}); \
                 rerun the folder with --fresh"
            ))
        }),
    }
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
    /// [`episode_fingerprint`] by episode id, stamped on each record appended.
    fingerprints: BTreeMap<u64, u64>,
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
            fingerprints: BTreeMap::new(),
        })
    }

    /// Stamp each record appended with the [`episode_fingerprint`] of its episode among
    /// `episodes` (the run's).
    pub fn for_episodes(mut self, episodes: &[Episode]) -> Result<Self> {
        for ep in episodes {
            self.fingerprints
                .insert(ep.episode_id, fingerprint_key(ep)?);
        }
        Ok(self)
    }

    /// Stamp `rec` with its episode's fingerprint (when the log has one), append it and
    /// make it durable.
    pub fn append(&self, rec: &mut EpisodeRecord) -> Result<()> {
        if let Some(&f) = self.fingerprints.get(&rec.episode_id) {
            rec.episode_fingerprint = Some(fingerprint_text(f));
        }
        let mut line = serde_json::to_string(&*rec)
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

/// Where each finished episode's line lies in `progress.jsonl`, so that a run's final files
/// are written from the log in split order, one episode at a time, instead of from every
/// finished episode's record held in memory until the end (a train split's trajectories run
/// to tens of megabytes). Built after the run's last append; an episode logged twice is read
/// from its last line, as [`load_progress`] keeps it.
pub(crate) struct ProgressLines {
    path: PathBuf,
    /// None when there is no log.
    file: Option<File>,
    /// Byte offset and length (newline excluded) of each episode's last line.
    at: std::collections::HashMap<u64, (u64, usize)>,
}

impl ProgressLines {
    /// Index the lines of the log at `path` (a missing file holds none). Every line must be
    /// whole: [`load_progress`] cut a half-written one before the run appended to it.
    pub(crate) fn index(path: &Path) -> Result<Self> {
        use std::io::BufRead;
        #[derive(Deserialize)]
        struct Id {
            episode_id: u64,
        }
        let file = match File::open(path) {
            Ok(f) => f,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(ProgressLines {
                    path: path.to_path_buf(),
                    file: None,
                    at: Default::default(),
                })
            }
            Err(e) => return Err(TaskError::io(path, e)),
        };
        let mut at = std::collections::HashMap::new();
        let mut reader = std::io::BufReader::new(&file);
        let mut line = Vec::new();
        let (mut pos, mut line_no) = (0u64, 0usize);
        loop {
            line.clear();
            let n = reader
                .read_until(b'\n', &mut line)
                .map_err(|e| TaskError::io(path, e))?;
            if n == 0 {
                break;
            }
            line_no += 1;
            let body = line.strip_suffix(b"\n").unwrap_or(&line);
            if !body.iter().all(u8::is_ascii_whitespace) {
                let id: Id = serde_json::from_slice(body)
                    .map_err(|e| TaskError::parse(path, format!("line {line_no}"), e))?;
                at.insert(id.episode_id, (pos, body.len()));
            }
            pos += n as u64;
        }
        drop(reader);
        Ok(ProgressLines {
            path: path.to_path_buf(),
            file: Some(file),
            at,
        })
    }

    /// The log's path.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Episode `id`'s line read as `T` (a whole [`EpisodeRecord`], or a part of it), `buf`
    /// reused for its bytes; `None` when the log holds no line of it.
    pub(crate) fn read<T: serde::de::DeserializeOwned>(
        &self,
        id: u64,
        buf: &mut Vec<u8>,
    ) -> Result<Option<T>> {
        use std::io::{Read, Seek, SeekFrom};
        let (Some(mut f), Some(&(offset, len))) = (self.file.as_ref(), self.at.get(&id)) else {
            return Ok(None);
        };
        buf.resize(len, 0);
        f.seek(SeekFrom::Start(offset))
            .and_then(|_| f.read_exact(buf))
            .map_err(|e| TaskError::io(&self.path, e))?;
        serde_json::from_slice(buf)
            .map(Some)
            .map_err(|e| TaskError::parse(&self.path, format!("episode {id}"), e))
    }
}

/// Keys an older `run.json` may hold that are no longer compared: `split_fingerprint` hashed
/// the whole split file, so an edit to an episode the run never reached refused the resume
/// (finished episodes are now checked one by one, [`check_unchanged`]).
pub const RETIRED_KEYS: [&str; 1] = ["split_fingerprint"];

/// Keys of `run.json` added after runs were first written: a `run.json` without one of them
/// (a run made before) is not compared on it; one that has it is.
pub const LATER_KEYS: [&str; 6] = [
    "benchmark_version",
    "simulator",
    "simulator_fingerprint",
    "renderer",
    "renderer_fingerprint",
    "rig_fingerprint",
];

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
                .find(|(k, v)| match old.get(*k) {
                    None => !LATER_KEYS.contains(k),
                    Some(o) => o != v,
                })
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
                        .filter(|(k, _)| !RETIRED_KEYS.contains(&k.as_str()))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The `failure` field of [`EpisodeRecord`] alone.
    #[derive(Debug, Serialize, Deserialize)]
    struct Only {
        #[serde(
            default,
            skip_serializing_if = "Option::is_none",
            deserialize_with = "failure_then_or_now"
        )]
        failure: Option<Failure>,
    }

    #[test]
    fn failures_are_read_as_written_now_and_as_older_runs_wrote_them() {
        let now = Failure::Collision { hit: vec![2, 5] };
        let text = serde_json::to_string(&Only {
            failure: Some(now.clone()),
        })
        .unwrap();
        assert_eq!(text, r#"{"failure":{"type":"collision","hit":[2,5]}}"#);
        let read = |t: &str| serde_json::from_str::<Only>(t).map(|o| o.failure);
        assert_eq!(read(&text).unwrap(), Some(now.clone()));
        // Older runs: the failure's JSON as a string.
        let old = r#"{"failure":"{\"type\":\"collision\",\"hit\":[2,5]}"}"#;
        assert_eq!(read(old).unwrap(), Some(now));
        assert_eq!(read("{}").unwrap(), None);
        assert_eq!(read(r#"{"failure":null}"#).unwrap(), None);
        // One this version does not know: refused, saying how to go on.
        let err = read(r#"{"failure":"{\"type\":\"fell\"}"}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("--fresh"), "{err}");
    }
}
