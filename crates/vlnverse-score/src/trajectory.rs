//! Trajectories: what an agent did in one episode, and the files they come in.
//!
//! Two input formats are read by [`read_trajectories`]:
//! - JSON lines, one trajectory per line: `{"episode_id": 7, "positions": [[x,y,z], ...],
//!   "stopped": true, "collisions": 0, "steps": 41}` (`collisions` defaults to 0, `steps` to
//!   `len(positions) - 1`; optional `headings` (radians, one per position), `stops` (indices into
//!   `positions` where the agent issued STOP, for long-horizon sub-goals) and `actions`);
//! - the VLN-CE inference format: one JSON object keyed by episode id,
//!   `{"7": [{"position": [x,y,z], "heading": h, "stop": false}, ...]}`.
//!
//! [`write_jsonl`] writes the first format.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::dataset::write_atomic;
use crate::error::{DataError, Result};

/// Largest absolute coordinate (m) a trajectory position may have; anything farther is a unit
/// or export error (millimetres, an uninitialised value), rejected when reading.
pub const MAX_COORDINATE: f32 = 1e5;

/// What an agent did in one episode.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Trajectory {
    /// The episode it belongs to.
    pub episode_id: u64,
    /// Floor positions, the start first, one per step (or per recorded sample).
    pub positions: Vec<[f32; 3]>,
    /// Heading (yaw, radians) at each position, when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub headings: Option<Vec<f32>>,
    /// Whether the episode ended with the agent's STOP (not a step limit or a failure).
    pub stopped: bool,
    /// Noticeable collisions.
    #[serde(default)]
    pub collisions: u32,
    /// Actions taken (STOP included).
    pub steps: u32,
    /// Indices into `positions` where the agent issued STOP, in order. Long-horizon agents stop
    /// once per sub-goal; empty means "only the final stop, if `stopped`".
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stops: Vec<u32>,
    /// Action names, when recorded. A simulator's own names are borrowed (`"move_forward"`), so
    /// the records of a long evaluation do not hold a string allocation per step; names read
    /// from a file are owned.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actions: Option<Vec<Cow<'static, str>>>,
}

impl Trajectory {
    /// A trajectory from positions alone: `steps = len - 1`, no collisions.
    pub fn from_positions(episode_id: u64, positions: Vec<[f32; 3]>, stopped: bool) -> Self {
        let steps = positions.len().saturating_sub(1) as u32;
        Trajectory {
            episode_id,
            positions,
            stopped,
            steps,
            ..Default::default()
        }
    }

    /// Indices of the positions where the agent declared a goal reached: `stops`, plus the last
    /// position when the episode ended with STOP and `stops` does not already end there.
    pub fn stop_indices(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.stops.iter().map(|&i| i as usize).collect();
        if self.stopped && !self.positions.is_empty() {
            let last = self.positions.len() - 1;
            if out.last() != Some(&last) {
                out.push(last);
            }
        }
        out
    }

    /// Check internal consistency (stop indices and headings match the positions; positions
    /// are finite and within [`MAX_COORDINATE`] of the origin).
    pub fn validate(&self) -> std::result::Result<(), String> {
        if self.positions.is_empty() {
            return Err(format!(
                "episode {}: field `positions` is empty; a trajectory starts with the start \
                 position",
                self.episode_id
            ));
        }
        if let Some(h) = &self.headings {
            if h.len() != self.positions.len() {
                return Err(format!(
                    "field `headings`: {} values for {} positions",
                    h.len(),
                    self.positions.len()
                ));
            }
        }
        if let Some(&bad) = self
            .stops
            .iter()
            .find(|&&i| i as usize >= self.positions.len())
        {
            return Err(format!(
                "field `stops`: index {bad} is past the last position ({})",
                self.positions.len().saturating_sub(1)
            ));
        }
        if self.stops.windows(2).any(|w| w[0] > w[1]) {
            return Err("field `stops`: indices must not decrease".into());
        }
        if let Some((i, p)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| p.iter().any(|c| !c.is_finite() || c.abs() > MAX_COORDINATE))
        {
            let what = if p.iter().all(|c| c.is_finite()) {
                format!("a coordinate is farther than {MAX_COORDINATE} m from the origin")
            } else {
                "a coordinate is not a finite number".to_string()
            };
            return Err(format!(
                "episode {}: field `positions[{i}]` = {p:?}: {what}",
                self.episode_id
            ));
        }
        Ok(())
    }
}

/// Read a trajectory file in either format (see the module doc). Errors name the file, the line
/// (JSON lines) or episode key (VLN-CE), and the field.
pub fn read_trajectories(path: &Path) -> Result<Vec<Trajectory>> {
    let text = std::fs::read_to_string(path).map_err(|e| DataError::io(path, e))?;
    parse_trajectories(path, &text)
}

/// Parse the text of a trajectory file; `path` only names the source in errors.
pub fn parse_trajectories(path: &Path, text: &str) -> Result<Vec<Trajectory>> {
    // A whole-file object without the keys of a JSON-lines record is the VLN-CE format; JSON
    // lines with more than one line never parse as a single value.
    if let Ok(Value::Object(map)) = serde_json::from_str::<Value>(text) {
        let record_keys = ["episode_id", "positions", "stopped"];
        if !record_keys.iter().any(|k| map.contains_key(*k)) {
            return parse_vlnce(path, map);
        }
    }
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let lineno = i + 1;
        let err = |msg: String| DataError::parse(path, format!("line {lineno}"), msg);
        let value: Value = serde_json::from_str(line).map_err(|e| err(json_hint(line, &e)))?;
        let Value::Object(obj) = value else {
            return Err(err("expected a JSON object".into()));
        };
        let t = trajectory_from_object(&obj).map_err(err)?;
        out.push(t);
    }
    if out.is_empty() {
        return Err(DataError::parse(
            path,
            "top level",
            "no trajectories in the file (expected JSON lines, one trajectory per line, or a \
             VLN-CE object keyed by episode id)",
        ));
    }
    Ok(out)
}

/// A JSON syntax error, with a hint when the text near it spells NaN or Infinity (what Python's
/// `json.dumps` writes for a float that is not finite; JSON has no such numbers).
fn json_hint(line: &str, e: &serde_json::Error) -> String {
    let col = e.column().saturating_sub(1).min(line.len());
    let from = (0..=col.saturating_sub(30))
        .rev()
        .find(|&i| line.is_char_boundary(i))
        .unwrap_or(0);
    let to = (col + 10..=line.len())
        .find(|&i| line.is_char_boundary(i))
        .unwrap_or(line.len());
    let near = &line[from..to];
    if ["NaN", "Infinity"].iter().any(|w| near.contains(w)) {
        return format!(
            "{e}: NaN and Infinity are not JSON numbers (near `{}`); a position must be \
             finite (Python: check the values before json.dumps, or use allow_nan=False)",
            near.trim()
        );
    }
    e.to_string()
}

fn field<T: serde::de::DeserializeOwned>(
    obj: &Map<String, Value>,
    key: &str,
) -> std::result::Result<Option<T>, String> {
    match obj.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => T::deserialize(v)
            .map(Some)
            .map_err(|e| format!("field `{key}`: {e} (value {})", short(v))),
    }
}

fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.len() > 60 {
        format!(
            "{}...",
            &s[..s.char_indices().nth(57).map_or(s.len(), |(i, _)| i)]
        )
    } else {
        s
    }
}

/// Episode ids are numbers; digit strings (VLN-CE keys) are accepted too.
fn episode_id(v: &Value) -> std::result::Result<u64, String> {
    match v {
        Value::Number(n) => n.as_u64(),
        Value::String(s) => s.trim().parse().ok(),
        _ => None,
    }
    .ok_or_else(|| {
        format!(
            "field `episode_id`: expected a non-negative integer, got {}",
            short(v)
        )
    })
}

fn trajectory_from_object(obj: &Map<String, Value>) -> std::result::Result<Trajectory, String> {
    let id = obj
        .get("episode_id")
        .ok_or_else(|| "missing field `episode_id`".to_string())
        .and_then(episode_id)?;
    let positions: Vec<[f32; 3]> =
        field(obj, "positions")?.ok_or_else(|| "missing field `positions`".to_string())?;
    let stopped: bool =
        field(obj, "stopped")?.ok_or_else(|| "missing field `stopped`".to_string())?;
    let default_steps = positions.len().saturating_sub(1) as u32;
    let t = Trajectory {
        episode_id: id,
        headings: field(obj, "headings")?,
        stopped,
        collisions: field(obj, "collisions")?.unwrap_or(0),
        steps: field(obj, "steps")?.unwrap_or(default_steps),
        stops: field(obj, "stops")?.unwrap_or_default(),
        actions: field(obj, "actions")?,
        positions,
    };
    t.validate()?;
    Ok(t)
}

fn parse_vlnce(path: &Path, map: Map<String, Value>) -> Result<Vec<Trajectory>> {
    #[derive(Deserialize)]
    struct Entry {
        position: [f32; 3],
        #[serde(default)]
        heading: Option<f32>,
        #[serde(default)]
        stop: bool,
    }
    // Sorted by id so output order does not depend on the file's key order.
    let mut by_id: BTreeMap<u64, Trajectory> = BTreeMap::new();
    for (key, value) in map {
        let err = |msg: String| DataError::parse(path, format!("episode `{key}`"), msg);
        let id = episode_id(&Value::String(key.clone())).map_err(err)?;
        let entries: Vec<Entry> = Vec::<Entry>::deserialize(&value).map_err(|e| {
            err(format!(
                "expected a list of {{position, heading, stop}}: {e}"
            ))
        })?;
        let headings: Option<Vec<f32>> = entries.iter().map(|e| e.heading).collect();
        let stopped = entries.last().is_some_and(|e| e.stop);
        let t = Trajectory {
            episode_id: id,
            steps: entries.len().saturating_sub(1) as u32,
            positions: entries.iter().map(|e| e.position).collect(),
            headings,
            stopped,
            ..Default::default()
        };
        // `validate` names the episode itself.
        t.validate()
            .map_err(|msg| DataError::parse(path, "trajectory", msg))?;
        by_id.insert(id, t);
    }
    if by_id.is_empty() {
        return Err(DataError::parse(
            path,
            "top level",
            "no trajectories in the file (an empty VLN-CE object)",
        ));
    }
    Ok(by_id.into_values().collect())
}

/// One JSON line (no newline) of a trajectory.
pub fn to_json_line(t: &Trajectory) -> String {
    // A struct of plain numbers and strings always serializes.
    serde_json::to_string(t).unwrap_or_default()
}

/// Write trajectories as JSON lines, atomically.
pub fn write_jsonl(path: &Path, trajectories: &[Trajectory]) -> Result<()> {
    let mut s = String::new();
    for t in trajectories {
        s.push_str(&to_json_line(t));
        s.push('\n');
    }
    write_atomic(path, s.as_bytes())
}
