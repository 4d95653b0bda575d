//! Review: a person pages through generated episodes (instruction, start view, goal view,
//! top-down path) and marks each accepted, rejected or edited (a corrected instruction). The
//! decisions live in a review file; [`apply_review`] (behind `cargo xtask review`) makes the
//! reviewed copy of the dataset.
//!
//! The review file (JSON, rewritten atomically after every decision, sorted so it is
//! deterministic):
//!
//! ```json
//! {
//!   "format": "vlnverse-review/1",
//!   "dataset": "/abs/path/datasets/tiny",
//!   "decisions": [
//!     {"task": "fine", "split": "val_unseen", "episode_id": 3, "decision": "rejected"},
//!     {"task": "fine", "split": "val_unseen", "episode_id": 4, "decision": "edited",
//!      "instruction_text": "Walk past the sofa and stop at the door."}
//!   ]
//! }
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use axum::extract::{Query, State};
use axum::http::header;
use axum::response::IntoResponse;
use axum::Json;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use vlnverse_task::vocab::{Vocab, VOCAB_FILE};
use vlnverse_task::{dataset, Episode, Split, Task};

use crate::app::{lock, App};
use crate::error::{ApiError, ApiResult};
use crate::frames::{episode_topdown, png, render_view, yaw_towards, ViewKind};

/// Format tag of review files.
pub const REVIEW_FORMAT: &str = "vlnverse-review/1";

/// What the reviewer decided about one episode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Kept as it is.
    Accepted,
    /// Dropped from the reviewed copy.
    Rejected,
    /// Kept with a corrected instruction.
    Edited,
}

/// One decision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Decision {
    /// Task of the episode.
    pub task: Task,
    /// Split of the episode.
    pub split: Split,
    /// The episode.
    pub episode_id: u64,
    /// The verdict.
    pub decision: Verdict,
    /// The corrected instruction (`edited` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub instruction_text: Option<String>,
}

impl Decision {
    /// Check that an edit carries its text and nothing else does.
    pub fn validate(&self) -> Result<(), String> {
        let who = format!("{}/{} episode {}", self.task, self.split, self.episode_id);
        match (self.decision, &self.instruction_text) {
            (Verdict::Edited, Some(t)) if !t.trim().is_empty() => Ok(()),
            (Verdict::Edited, _) => Err(format!(
                "{who}: field `instruction_text` is missing or empty; an `edited` decision needs the corrected instruction"
            )),
            (_, Some(_)) => Err(format!(
                "{who}: field `instruction_text` is only allowed with decision `edited`"
            )),
            _ => Ok(()),
        }
    }
}

/// The review file's content.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReviewDoc {
    /// [`REVIEW_FORMAT`].
    pub format: String,
    /// The dataset reviewed (informative).
    pub dataset: String,
    /// Decisions, sorted by task, split and episode id.
    pub decisions: Vec<Decision>,
}

/// Errors of the review file and of applying it.
#[derive(Debug, thiserror::Error)]
pub enum ReviewError {
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What failed.
        message: String,
    },
    /// The review file's content is wrong.
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the field and value.
        message: String,
    },
}

fn io_err(path: &Path, e: impl std::fmt::Display) -> ReviewError {
    ReviewError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Read and check a review file.
pub fn read_review(path: &Path) -> Result<ReviewDoc, ReviewError> {
    let text = std::fs::read_to_string(path).map_err(|e| io_err(path, e))?;
    let doc: ReviewDoc = serde_json::from_str(&text).map_err(|e| ReviewError::Invalid {
        path: path.to_path_buf(),
        message: format!("line {}, column {}: {e}", e.line(), e.column()),
    })?;
    let invalid = |message: String| ReviewError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    if doc.format != REVIEW_FORMAT {
        return Err(invalid(format!(
            "field `format` is `{}`; expected `{REVIEW_FORMAT}`",
            doc.format
        )));
    }
    let mut seen = std::collections::BTreeSet::new();
    for (i, d) in doc.decisions.iter().enumerate() {
        d.validate()
            .map_err(|m| invalid(format!("decisions[{i}]: {m}")))?;
        if !seen.insert((d.task, d.split, d.episode_id)) {
            return Err(invalid(format!(
                "decisions[{i}]: a second decision for {}/{} episode {}",
                d.task, d.split, d.episode_id
            )));
        }
    }
    Ok(doc)
}

/// The review file the server keeps: decisions in memory, written through on every change.
#[derive(Debug)]
pub struct ReviewFile {
    /// Where it is written.
    pub path: PathBuf,
    dataset: String,
    decisions: BTreeMap<(Task, Split, u64), Decision>,
}

impl ReviewFile {
    /// Open (or start) the review file at `path` for `dataset`.
    pub fn open(path: &Path, dataset: &Path) -> Result<Self, ReviewError> {
        let decisions = if path.is_file() {
            read_review(path)?
                .decisions
                .into_iter()
                .map(|d| ((d.task, d.split, d.episode_id), d))
                .collect()
        } else {
            BTreeMap::new()
        };
        Ok(ReviewFile {
            path: path.to_path_buf(),
            dataset: dataset.display().to_string(),
            decisions,
        })
    }

    /// The document as written.
    pub fn doc(&self) -> ReviewDoc {
        ReviewDoc {
            format: REVIEW_FORMAT.into(),
            dataset: self.dataset.clone(),
            decisions: self.decisions.values().cloned().collect(),
        }
    }

    /// The decision about an episode.
    pub fn get(&self, task: Task, split: Split, id: u64) -> Option<&Decision> {
        self.decisions.get(&(task, split, id))
    }

    /// Record a decision and rewrite the file atomically.
    pub fn set(&mut self, d: Decision) -> Result<(), ReviewError> {
        d.validate().map_err(|message| ReviewError::Invalid {
            path: self.path.clone(),
            message,
        })?;
        let key = (d.task, d.split, d.episode_id);
        let old = self.decisions.insert(key, d);
        let text = serde_json::to_string_pretty(&self.doc()).unwrap_or_default() + "\n";
        if let Err(e) = dataset::write_atomic(&self.path, text.as_bytes()) {
            match old {
                Some(o) => self.decisions.insert(key, o),
                None => self.decisions.remove(&key),
            };
            return Err(io_err(&self.path, e));
        }
        Ok(())
    }
}

/// What [`apply_review`] did, per split (also written as `review_report.json` in the copy).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ReviewReport {
    /// Per `task/split`: episodes before, accepted, edited, rejected, kept without a decision,
    /// after.
    pub splits: BTreeMap<String, SplitCounts>,
}

/// Counts of one split.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SplitCounts {
    /// Episodes in the original split.
    pub before: usize,
    /// Marked accepted.
    pub accepted: usize,
    /// Marked edited (kept, instruction replaced).
    pub edited: usize,
    /// Marked rejected (dropped).
    pub rejected: usize,
    /// Without a decision (kept, or dropped with `require_all`).
    pub undecided: usize,
    /// Episodes in the reviewed split.
    pub after: usize,
}

/// Copy the folder `from` to `to`, leaving out `skip` (the copy itself when it lies inside).
fn copy_tree(from: &Path, to: &Path, skip: &Path) -> Result<(), ReviewError> {
    std::fs::create_dir_all(to).map_err(|e| io_err(to, e))?;
    let mut entries: Vec<_> = std::fs::read_dir(from)
        .map_err(|e| io_err(from, e))?
        .collect::<Result<_, _>>()
        .map_err(|e| io_err(from, e))?;
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let src = e.path();
        if src.canonicalize().is_ok_and(|c| c == skip) {
            continue;
        }
        let dst = to.join(e.file_name());
        let ty = e.file_type().map_err(|err| io_err(&src, err))?;
        if ty.is_dir() {
            copy_tree(&src, &dst, skip)?;
        } else {
            std::fs::copy(&src, &dst).map_err(|err| io_err(&src, err))?;
        }
    }
    Ok(())
}

/// Apply the decisions of `review` to `dataset`, writing the reviewed copy to `out`: rejected
/// episodes are dropped, edited ones get their new instruction (its tokens re-encoded with the
/// dataset's `vocab.txt` when it has one, else dropped), undecided ones are kept (dropped when
/// `require_all`). Everything else is copied as it is. The copy is built next to `out` and
/// renamed into place, so `out` is either complete or absent; an existing `out` is refused.
/// Every decision must name an episode of the dataset.
pub fn apply_review(
    dataset: &Path,
    review: &Path,
    out: &Path,
    require_all: bool,
) -> Result<ReviewReport, ReviewError> {
    let doc = read_review(review)?;
    if out.exists() {
        return Err(io_err(
            out,
            "already exists; choose a new folder for the reviewed copy",
        ));
    }
    if !dataset.join("scenes").is_dir() {
        return Err(io_err(dataset, "is not a dataset folder (no scenes/)"));
    }
    let mut by_split: BTreeMap<(Task, Split), BTreeMap<u64, &Decision>> = BTreeMap::new();
    for d in &doc.decisions {
        by_split
            .entry((d.task, d.split))
            .or_default()
            .insert(d.episode_id, d);
    }
    let vocab_path = dataset.join(VOCAB_FILE);
    let vocab = if vocab_path.is_file() {
        Some(Vocab::load(&vocab_path).map_err(|e| io_err(&vocab_path, e))?)
    } else {
        None
    };
    // Check every decision before writing anything.
    let mut rewritten: Vec<(Task, Split, Vec<Episode>, SplitCounts)> = Vec::new();
    for task in Task::ALL {
        for split in Split::ALL {
            let path = dataset::split_path(dataset, task, split);
            let decided = by_split.remove(&(task, split)).unwrap_or_default();
            if !path.is_file() {
                if let Some((id, _)) = decided.iter().next() {
                    return Err(ReviewError::Invalid {
                        path: review.to_path_buf(),
                        message: format!(
                            "a decision names {task}/{split} episode {id}, but the dataset has no such split ({})",
                            path.display()
                        ),
                    });
                }
                continue;
            }
            if decided.is_empty() && !require_all {
                continue;
            }
            let eps = dataset::read_split(dataset, task, split).map_err(|e| io_err(&path, e))?;
            let ids: std::collections::BTreeSet<u64> = eps.iter().map(|e| e.episode_id).collect();
            if let Some(id) = decided.keys().find(|id| !ids.contains(id)) {
                return Err(ReviewError::Invalid {
                    path: review.to_path_buf(),
                    message: format!(
                        "field `episode_id` = {id}: no such episode in {task}/{split} ({})",
                        path.display()
                    ),
                });
            }
            let mut counts = SplitCounts {
                before: eps.len(),
                ..Default::default()
            };
            let mut kept = Vec::with_capacity(eps.len());
            for mut ep in eps {
                match decided.get(&ep.episode_id) {
                    Some(d) => match d.decision {
                        Verdict::Accepted => {
                            counts.accepted += 1;
                            kept.push(ep);
                        }
                        Verdict::Rejected => counts.rejected += 1,
                        Verdict::Edited => {
                            counts.edited += 1;
                            let text = d.instruction_text.clone().unwrap_or_default();
                            ep.instruction.instruction_tokens =
                                match (&vocab, &ep.instruction.instruction_tokens) {
                                    (Some(v), Some(old)) => Some(v.encode(&text, old.len())),
                                    _ => None,
                                };
                            ep.instruction.instruction_text = text;
                            kept.push(ep);
                        }
                    },
                    None => {
                        counts.undecided += 1;
                        if !require_all {
                            kept.push(ep);
                        }
                    }
                }
            }
            counts.after = kept.len();
            rewritten.push((task, split, kept, counts));
        }
    }
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "reviewed".into());
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let tmp = parent.join(format!(".{name}.partial{}", std::process::id()));
    if tmp.exists() {
        std::fs::remove_dir_all(&tmp).map_err(|e| io_err(&tmp, e))?;
    }
    let build = || -> Result<ReviewReport, ReviewError> {
        std::fs::create_dir_all(&tmp).map_err(|e| io_err(&tmp, e))?;
        let skip = tmp.canonicalize().map_err(|e| io_err(&tmp, e))?;
        copy_tree(dataset, &tmp, &skip)?;
        let mut report = ReviewReport::default();
        for (task, split, eps, counts) in &rewritten {
            dataset::write_split(&tmp, *task, *split, eps)
                .map_err(|e| io_err(&dataset::split_path(&tmp, *task, *split), e))?;
            report.splits.insert(format!("{task}/{split}"), *counts);
        }
        let text = serde_json::to_string_pretty(&report).unwrap_or_default() + "\n";
        let path = tmp.join("review_report.json");
        dataset::write_atomic(&path, text.as_bytes()).map_err(|e| io_err(&path, e))?;
        Ok(report)
    };
    let report = match build() {
        Ok(r) => r,
        Err(e) => {
            let _ = std::fs::remove_dir_all(&tmp);
            return Err(e);
        }
    };
    std::fs::rename(&tmp, out).map_err(|e| io_err(out, e))?;
    Ok(report)
}

/// Query naming one split.
#[derive(Debug, Default, Deserialize)]
pub struct SplitQuery {
    /// Task name.
    pub task: Option<String>,
    /// Split name.
    pub split: Option<String>,
}

/// Query naming one episode (and, for views, which one).
#[derive(Debug, Default, Deserialize)]
pub struct EpisodeQuery {
    /// Task name.
    pub task: Option<String>,
    /// Split name.
    pub split: Option<String>,
    /// Episode id.
    pub id: Option<String>,
    /// `start` or `goal` (views).
    pub at: Option<String>,
    /// `rgb` or `depth` (views).
    pub view: Option<ViewKind>,
}

fn need<'a>(v: &'a Option<String>, name: &str) -> ApiResult<&'a str> {
    v.as_deref()
        .filter(|s| !s.is_empty())
        .ok_or_else(|| ApiError::bad_request(format!("missing query parameter `{name}`")))
}

fn episode_of(app: &App, q: &EpisodeQuery) -> ApiResult<(Task, Split, Arc<Vec<Episode>>, usize)> {
    let (task, split) = App::task_split(need(&q.task, "task")?, need(&q.split, "split")?)?;
    let id = App::parse_id(need(&q.id, "id")?)?;
    let (eps, k) = app.episode(task, split, id)?;
    Ok((task, split, eps, k))
}

/// `GET /api/review/episodes?task&split`: the episodes with their instruction and decision.
pub async fn review_list(
    State(app): State<Arc<App>>,
    Query(q): Query<SplitQuery>,
) -> ApiResult<Json<Value>> {
    let (task, split) = App::task_split(need(&q.task, "task")?, need(&q.split, "split")?)?;
    let eps = app.episodes(task, split)?;
    let review = lock(&app.review);
    let list: Vec<Value> = eps
        .iter()
        .map(|e| {
            let d = review.get(task, split, e.episode_id);
            json!({
                "episode_id": e.episode_id,
                "scene_id": e.scene_id,
                "instruction": e.instruction.instruction_text,
                "sub_instructions": e.instruction.sub_instructions,
                "style": e.style(),
                "geodesic_distance": e.info.geodesic_distance,
                "decision": d.map(|d| d.decision),
                "edited_instruction": d.and_then(|d| d.instruction_text.clone()),
            })
        })
        .collect();
    Ok(Json(json!({
        "task": task.name(),
        "split": split.name(),
        "review_file": review.path.display().to_string(),
        "episodes": list,
    })))
}

/// `GET /api/review/view?task&split&id&at=start|goal`: the view at the start pose, or at the
/// goal looking along the reference path's last segment.
pub async fn review_view(
    State(app): State<Arc<App>>,
    Query(q): Query<EpisodeQuery>,
) -> ApiResult<impl IntoResponse> {
    let bytes = tokio::task::spawn_blocking(move || {
        let (_, _, eps, k) = episode_of(&app, &q)?;
        let ep = &eps[k];
        let (pos, yaw) = match q.at.as_deref().unwrap_or("start") {
            "start" => {
                let rot = vlnverse_env::Pose {
                    position: ep.start_position,
                    rotation: ep.start_rotation,
                };
                (ep.start_position, rot.yaw())
            }
            "goal" => {
                let path = &ep.reference_path;
                let goal = path
                    .last()
                    .copied()
                    .or_else(|| ep.goal_sequence().last().map(|g| g.position))
                    .unwrap_or(ep.start_position);
                let from = if path.len() >= 2 {
                    path[path.len() - 2]
                } else {
                    ep.start_position
                };
                (goal, yaw_towards(from, goal))
            }
            other => {
                return Err(ApiError::bad_request(format!(
                    "invalid `at` = `{other}`: expected start or goal"
                )))
            }
        };
        let scene = app.scene(&ep.scene_id)?;
        app.with_viewer(|rig| {
            render_view(
                rig,
                &scene.scene,
                pos,
                yaw,
                q.view.unwrap_or_default(),
                app.cfg.jpeg_quality,
            )
        })
    })
    .await
    .map_err(|e| ApiError::internal(format!("review worker: {e}")))??;
    Ok(([(header::CONTENT_TYPE, "image/jpeg")], bytes))
}

/// `GET /api/review/topdown.png?task&split&id`: the reference path from above.
pub async fn review_topdown(
    State(app): State<Arc<App>>,
    Query(q): Query<EpisodeQuery>,
) -> ApiResult<impl IntoResponse> {
    let bytes = tokio::task::spawn_blocking(move || {
        let (_, _, eps, k) = episode_of(&app, &q)?;
        let ep = &eps[k];
        let scene = app.scene(&ep.scene_id)?;
        let (img, _) = episode_topdown(&scene.scene, Some(&scene.navigable), ep, None);
        png(&img)
    })
    .await
    .map_err(|e| ApiError::internal(format!("review worker: {e}")))??;
    Ok(([(header::CONTENT_TYPE, "image/png")], bytes))
}

/// `POST /api/review/decision` with a [`Decision`] as JSON: record it in the review file.
pub async fn review_decide(
    State(app): State<Arc<App>>,
    body: Result<Json<Decision>, axum::extract::rejection::JsonRejection>,
) -> ApiResult<Json<Value>> {
    let Json(d) = body.map_err(|e| ApiError::bad_request(e.body_text()))?;
    app.episode(d.task, d.split, d.episode_id)?;
    let mut review = lock(&app.review);
    review
        .set(d)
        .map_err(|e| ApiError::bad_request(e.to_string()))?;
    Ok(Json(json!({
        "review_file": review.path.display().to_string(),
        "decisions": review.doc().decisions.len(),
    })))
}

/// `GET /api/review/decisions`: the review file's content.
pub async fn review_decisions(State(app): State<Arc<App>>) -> ApiResult<Json<ReviewDoc>> {
    Ok(Json(lock(&app.review).doc()))
}
