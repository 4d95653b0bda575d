//! Split files: `DIR/<task>/<split>/<split>.json.gz`, gzip-compressed `{"episodes": [...]}`.
//!
//! Writing is deterministic (fixed compression level, zero timestamp and unknown OS in the gzip
//! header, struct field order, shortest float formatting) and atomic (a temporary file in the same
//! folder, then a rename), so the same episodes always give the same bytes and a reader never sees
//! half a file.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use flate2::{read::GzDecoder, Compression, GzBuilder};
use serde::Deserialize;

use crate::episode::{Dataset, Episode, Split, Task};
use crate::error::{DataError, Result};

/// Compression level of split files (fixed so bytes do not depend on flate2 defaults).
pub const GZIP_LEVEL: u32 = 6;

/// Path of a split file: `dir/<task>/<split>/<split>.json.gz`.
pub fn split_path(dir: &Path, task: Task, split: Split) -> PathBuf {
    dir.join(task.name())
        .join(split.name())
        .join(format!("{}.json.gz", split.name()))
}

/// Serialize episodes to the gzip bytes of a split file.
pub fn to_gzip_bytes(episodes: &[Episode]) -> Result<Vec<u8>> {
    #[derive(serde::Serialize)]
    struct Borrowed<'a> {
        episodes: &'a [Episode],
    }
    let json = serde_json::to_vec(&Borrowed { episodes })
        .map_err(|e| DataError::invalid("episodes", "<episodes>", e.to_string()))?;
    gzip(&json)
}

/// Gzip `data` deterministically (no file name, mtime 0, OS byte 255 = unknown).
pub fn gzip(data: &[u8]) -> Result<Vec<u8>> {
    let mut enc = GzBuilder::new().mtime(0).operating_system(255).write(
        Vec::with_capacity(data.len() / 4 + 64),
        Compression::new(GZIP_LEVEL),
    );
    enc.write_all(data)
        .and_then(|_| enc.finish())
        .map_err(|e| DataError::io("<memory>", e))
}

/// Write `bytes` to `path` atomically: a temporary file next to it, then a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| DataError::io(dir, e))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    std::fs::write(&tmp, bytes).map_err(|e| DataError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        DataError::io(path, e)
    })
}

/// Write the split file of `task`/`split` under `dir`; returns its path.
pub fn write_split(dir: &Path, task: Task, split: Split, episodes: &[Episode]) -> Result<PathBuf> {
    let path = split_path(dir, task, split);
    write_atomic(&path, &to_gzip_bytes(episodes)?)?;
    Ok(path)
}

/// Read the split file of `task`/`split` under `dir`.
pub fn read_split(dir: &Path, task: Task, split: Split) -> Result<Vec<Episode>> {
    let path = split_path(dir, task, split);
    let episodes = read_file(&path)?;
    check_task(&path, task, &episodes)?;
    Ok(episodes)
}

/// Every episode of `task`'s split file says it is of `task` (an episode of another task would
/// be run and scored by the wrong rules).
pub fn check_task(path: &Path, task: Task, episodes: &[Episode]) -> Result<()> {
    match episodes.iter().position(|e| e.task != task) {
        Some(i) => Err(DataError::parse(
            path,
            format!("episodes[{i}].task"),
            format!(
                "{:?} in a split file of task {:?} (episode_id {})",
                episodes[i].task.name(),
                task.name(),
                episodes[i].episode_id
            ),
        )),
        None => Ok(()),
    }
}

/// Read a split file (`.json.gz`, or plain `.json`), with errors naming the file, the episode
/// index and the field.
pub fn read_file(path: &Path) -> Result<Vec<Episode>> {
    let raw = std::fs::read(path).map_err(|e| DataError::io(path, e))?;
    let gzipped = raw.starts_with(&[0x1f, 0x8b]);
    let json = if gzipped {
        let mut out = Vec::with_capacity(raw.len() * 6);
        GzDecoder::new(&raw[..])
            .read_to_end(&mut out)
            .map_err(|e| DataError::parse(path, "gzip stream", e))?;
        out
    } else {
        raw
    };
    parse_episodes(path, &json, gzipped)
}

/// Parse the JSON of a split file; `path` only names the source in errors.
pub fn from_json_bytes(path: &Path, json: &[u8]) -> Result<Vec<Episode>> {
    parse_episodes(path, json, false)
}

/// [`from_json_bytes`] for JSON that came out of a gzip stream when `gzipped` (then a syntax
/// error is about the JSON inside, not about the compression).
fn parse_episodes(path: &Path, json: &[u8], gzipped: bool) -> Result<Vec<Episode>> {
    match serde_json::from_slice::<Dataset>(json) {
        Ok(d) => {
            check_unique_ids(path, &d.episodes)?;
            check_paths_stay_inside(path, &d.episodes)?;
            for (i, e) in d.episodes.iter().enumerate() {
                check_fields(e).map_err(|(field, msg)| {
                    DataError::parse(
                        path,
                        format!("episodes[{i}].{field} (episode_id {})", e.episode_id),
                        msg,
                    )
                })?;
            }
            Ok(d.episodes)
        }
        // Slow path only on failure: find which episode and field is wrong.
        Err(first) => Err(locate_error(path, json, gzipped, first)),
    }
}

/// Episode ids key results, resumes and scores: a repeated id would silently drop an episode.
fn check_unique_ids(path: &Path, episodes: &[Episode]) -> Result<()> {
    let mut seen = std::collections::HashMap::with_capacity(episodes.len());
    for (i, e) in episodes.iter().enumerate() {
        if let Some(first) = seen.insert(e.episode_id, i) {
            return Err(DataError::parse(
                path,
                format!("episodes[{i}].episode_id"),
                format!(
                    "episode_id {} is used twice (also by episodes[{first}]); ids must be unique",
                    e.episode_id
                ),
            ));
        }
    }
    Ok(())
}

/// How far a start rotation may be from a unit quaternion about +Y (in each of `|q| - 1`, `x`
/// and `z`): a float32 round trip stays far inside it; a tilted or unnormalised one does not.
pub const ROTATION_TOLERANCE: f32 = 1e-3;

/// The values of one episode that no scene is needed to judge: `Err((field, why))`.
/// Checked when a split file is read, so a malformed episode is refused by name instead of
/// being run or scored silently.
pub fn check_fields(e: &Episode) -> std::result::Result<(), (String, String)> {
    let bad = |field: &str, msg: String| Err((field.to_string(), msg));
    if e.instruction.instruction_text.trim().is_empty() {
        return bad(
            "instruction.instruction_text",
            "is empty; every episode needs an instruction".into(),
        );
    }
    let q = e.start_rotation;
    let norm = q.iter().map(|v| v * v).sum::<f32>().sqrt();
    if !q.iter().all(|v| v.is_finite())
        || (norm - 1.0).abs() > ROTATION_TOLERANCE
        || q[0].abs() > ROTATION_TOLERANCE
        || q[2].abs() > ROTATION_TOLERANCE
    {
        return bad(
            "start_rotation",
            format!(
                "{q:?} is not a unit quaternion [x, y, z, w] about the vertical axis \
                 (x and z 0, length 1, within {ROTATION_TOLERANCE}); the agent stands upright"
            ),
        );
    }
    if e.goals.is_empty() {
        return bad("goals", "is empty; an episode needs a goal".into());
    }
    for (name, goals) in [("goals", &e.goals), ("sub_goals", &e.sub_goals)] {
        for (j, g) in goals.iter().enumerate() {
            if !(g.radius.is_finite() && g.radius > 0.0) {
                return bad(
                    &format!("{name}[{j}].radius"),
                    format!("{} must be a positive number of metres", g.radius),
                );
            }
        }
    }
    if e.task == Task::LongHorizon && e.sub_goals.is_empty() {
        return bad(
            "sub_goals",
            "is empty; a long-horizon episode lists its goals in order".into(),
        );
    }
    let d = e.info.geodesic_distance;
    if !(d.is_finite() && d >= 0.0) {
        return bad(
            "info.geodesic_distance",
            format!("{d} must be a finite distance >= 0 (metres)"),
        );
    }
    if e.reference_path.is_empty() {
        return bad(
            "reference_path",
            "is empty; it runs from the start to the goal, both included".into(),
        );
    }
    Ok(())
}

/// `scene_id` and `reference_image` name places inside the dataset folder: an absolute path or
/// a `..` would load scenes or read images from anywhere on the machine.
fn check_paths_stay_inside(path: &Path, episodes: &[Episode]) -> Result<()> {
    use std::path::Component;
    let escapes = |p: &str| {
        Path::new(p)
            .components()
            .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
    };
    for (i, e) in episodes.iter().enumerate() {
        if escapes(&e.scene_id) {
            return Err(DataError::parse(
                path,
                format!("episodes[{i}].scene_id"),
                format!(
                    "{:?} is not a scene folder name inside the dataset (no absolute path, \
                     no `..`)",
                    e.scene_id
                ),
            ));
        }
        if let Some(r) = e.reference_image.as_deref().filter(|r| escapes(r)) {
            return Err(DataError::parse(
                path,
                format!("episodes[{i}].reference_image"),
                format!("{r:?} must be a path relative to the split's folder, without `..`"),
            ));
        }
    }
    Ok(())
}

/// A hint for JSON that is not JSON: a split file that should have been gzip, or `NaN` /
/// `Infinity`, which JSON has no spelling for.
fn syntax_hint(path: &Path, json: &[u8], gzipped: bool, e: &serde_json::Error) -> String {
    let name = path.to_string_lossy();
    if name.ends_with(".gz") && !gzipped {
        return format!(
            "{e} (the file ends in .gz but is not gzip-compressed, and not valid JSON either)"
        );
    }
    let line = json
        .split(|&b| b == b'\n')
        .nth(e.line().saturating_sub(1))
        .unwrap_or_default();
    let col = e.column().saturating_sub(1).min(line.len());
    let near = String::from_utf8_lossy(&line[col.saturating_sub(40)..line.len().min(col + 20)]);
    if ["NaN", "Infinity", "inf"].iter().any(|w| near.contains(w)) {
        return format!(
            "{e}: NaN and Infinity are not JSON numbers (near `{}`)",
            near.trim()
        );
    }
    e.to_string()
}

fn locate_error(path: &Path, json: &[u8], gzipped: bool, first: serde_json::Error) -> DataError {
    let value: serde_json::Value = match serde_json::from_slice(json) {
        Ok(v) => v,
        Err(e) => {
            return DataError::parse(
                path,
                format!("line {} column {}", e.line(), e.column()),
                syntax_hint(path, json, gzipped, &e),
            )
        }
    };
    let Some(episodes) = value.get("episodes") else {
        return DataError::parse(path, "top level", "missing field `episodes`");
    };
    let Some(list) = episodes.as_array() else {
        return DataError::parse(path, "episodes", "expected a list of episodes");
    };
    for (i, ep) in list.iter().enumerate() {
        if let Err(e) = Episode::deserialize_value(ep) {
            let id = ep
                .get("episode_id")
                .map(|v| format!(" (episode_id {v})"))
                .unwrap_or_default();
            return DataError::parse(path, format!("episodes[{i}]{id}"), e);
        }
    }
    DataError::parse(path, format!("line {}", first.line()), first)
}

impl Episode {
    /// Deserialize one episode from a JSON value, naming the offending field on error
    /// (`instruction.style: unknown variant ...`).
    pub fn deserialize_value(value: &serde_json::Value) -> std::result::Result<Episode, String> {
        match Episode::deserialize(value) {
            Ok(ep) => Ok(ep),
            Err(e) => {
                let Some(obj) = value.as_object() else {
                    return Err(format!("expected an object: {e}"));
                };
                Err(find_field(obj, &e.to_string()).unwrap_or_else(|| e.to_string()))
            }
        }
    }
}

/// Walk the known nested keys to find the one whose value does not parse.
fn find_field(obj: &serde_json::Map<String, serde_json::Value>, msg: &str) -> Option<String> {
    use crate::episode::{EpisodeInfo, Goal, Instruction};
    fn check<T: serde::de::DeserializeOwned>(v: &serde_json::Value) -> Option<String> {
        T::deserialize(v).err().map(|e| e.to_string())
    }
    let checks: [(&str, fn(&serde_json::Value) -> Option<String>); 11] = [
        ("episode_id", check::<u64>),
        ("trajectory_id", check::<u64>),
        ("scene_id", check::<String>),
        ("start_position", check::<[f32; 3]>),
        ("start_rotation", check::<[f32; 4]>),
        ("goals", check::<Vec<Goal>>),
        ("instruction", check::<Instruction>),
        ("reference_path", check::<Vec<[f32; 3]>>),
        ("info", check::<EpisodeInfo>),
        ("task", check::<Task>),
        ("sub_goals", check::<Vec<Goal>>),
    ];
    for (key, f) in checks {
        if let Some(v) = obj.get(key) {
            if let Some(e) = f(v) {
                return Some(format!("field `{key}`: {e}"));
            }
        }
    }
    Some(msg.to_string())
}
