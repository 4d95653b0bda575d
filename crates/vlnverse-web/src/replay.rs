//! Replay: the evaluation runs the server was started with (`--runs`), their episodes with
//! metrics (`episodes.csv`), and each episode step by step: the first-person view at every
//! recorded pose, the top-down map with the reference and agent paths, the action taken.
//!
//! Views are drawn by the server's viewer rig from the recorded position and heading (the
//! trajectory does not record the camera pitch of look up/down, nor does the evaluation rig
//! render it).

use std::collections::BTreeMap;
use std::sync::Arc;

use axum::extract::{Path as UrlPath, Query, State};
use axum::http::header;
use axum::response::IntoResponse;
use axum::Json;
use serde_json::{json, Map, Value};
use vlnverse_task::{Split, Task, Trajectory};

use crate::app::App;
use crate::error::{ApiError, ApiResult};
use crate::frames::{episode_topdown, frame_json, png, render_view, ViewKind};

fn read_json(path: &std::path::Path) -> Value {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or(Value::Null)
}

/// Task and split of a run, from its `run.json` (or its `summary.json`).
/// Run `i`'s recorded trajectory of episode `id` (404 when the run has none).
fn recorded<'a>(
    app: &App,
    i: usize,
    trajs: &'a BTreeMap<u64, Trajectory>,
    id: u64,
) -> ApiResult<&'a Trajectory> {
    trajs.get(&id).ok_or_else(|| {
        ApiError::not_found(format!(
            "run `{}` has no trajectory for episode {id}",
            app.runs[i].name
        ))
    })
}

fn run_task_split(app: &App, i: usize) -> ApiResult<(Task, Split, Value)> {
    let run = app.run(i)?;
    let mut meta = read_json(&run.dir.join("run.json"));
    if meta.is_null() {
        meta = read_json(&run.dir.join("summary.json"));
    }
    let get = |k: &str| meta.get(k).and_then(Value::as_str).map(str::to_string);
    let (Some(t), Some(s)) = (get("task"), get("split")) else {
        return Err(ApiError::internal(format!(
            "run `{}`: neither run.json nor summary.json names its task and split",
            run.name
        )));
    };
    let (task, split) = App::task_split(&t, &s)?;
    Ok((task, split, meta))
}

/// `GET /api/runs`: the runs, with their protocol and summary.
pub async fn runs(State(app): State<Arc<App>>) -> ApiResult<Json<Value>> {
    let list: Vec<Value> = app
        .runs
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let meta = read_json(&r.dir.join("run.json"));
            let summary = read_json(&r.dir.join("summary.json"));
            let pick = |k: &str| meta.get(k).or_else(|| summary.get(k)).cloned().unwrap_or(Value::Null);
            json!({
                "index": i,
                "name": r.name,
                "task": pick("task"),
                "split": pick("split"),
                "setting": pick("setting"),
                "agent": meta.get("agent").or_else(|| summary.get("method")).cloned().unwrap_or(Value::Null),
                "summary": summary,
            })
        })
        .collect();
    Ok(Json(json!({ "runs": list })))
}

/// A CSV cell as a JSON number when it reads as one.
fn cell(s: &str) -> Value {
    if let Ok(i) = s.parse::<i64>() {
        return json!(i);
    }
    match s.parse::<f64>() {
        Ok(f) if f.is_finite() => json!(f),
        _ => json!(s),
    }
}

/// `GET /api/runs/{run}/episodes`: the rows of the run's `episodes.csv`.
pub async fn run_episodes(
    State(app): State<Arc<App>>,
    UrlPath(run): UrlPath<String>,
) -> ApiResult<Json<Value>> {
    let i = parse_run(&run)?;
    let r = app.run(i)?;
    let path = r.dir.join("episodes.csv");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| ApiError::not_found(format!("{}: {e}", path.display())))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let rows: Vec<Value> = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let m: Map<String, Value> = header
                .iter()
                .zip(l.split(','))
                .map(|(k, v)| (k.to_string(), cell(v)))
                .collect();
            Value::Object(m)
        })
        .collect();
    Ok(Json(
        json!({ "run": r.name, "columns": header, "episodes": rows }),
    ))
}

fn parse_run(s: &str) -> ApiResult<usize> {
    s.parse()
        .map_err(|_| ApiError::bad_request(format!("invalid run index `{s}`: expected 0, 1, ...")))
}

/// `GET /api/runs/{run}/episodes/{id}`: the episode, its trajectory (positions, headings,
/// actions), its metrics row and the top-down map's world -> pixel mapping.
pub async fn run_episode(
    State(app): State<Arc<App>>,
    UrlPath((run, id)): UrlPath<(String, String)>,
) -> ApiResult<Json<Value>> {
    let i = parse_run(&run)?;
    let id = App::parse_id(&id)?;
    tokio::task::spawn_blocking(move || {
        let (task, split, _) = run_task_split(&app, i)?;
        let (eps, k) = app.episode(task, split, id)?;
        let ep = &eps[k];
        let trajs = app.run_trajectories(i)?;
        let traj = recorded(&app, i, &trajs, id)?;
        let scene = app.scene(&ep.scene_id)?;
        let (_, frame) = episode_topdown(
            &scene.scene,
            Some(&scene.navigable),
            ep,
            Some(&traj.positions),
        );
        Ok(Json(json!({
            "task": task.name(),
            "split": split.name(),
            "episode": {
                "episode_id": ep.episode_id,
                "scene_id": ep.scene_id,
                "instruction": ep.instruction.instruction_text,
                "sub_instructions": ep.instruction.sub_instructions,
                "reference_path": ep.reference_path,
            },
            "trajectory": traj,
            "topdown": frame_json(&frame),
        })))
    })
    .await
    .map_err(|e| ApiError::internal(format!("replay worker: {e}")))?
}

/// `GET /api/runs/{run}/episodes/{id}/topdown.png`.
pub async fn run_topdown(
    State(app): State<Arc<App>>,
    UrlPath((run, id)): UrlPath<(String, String)>,
) -> ApiResult<impl IntoResponse> {
    let i = parse_run(&run)?;
    let id = App::parse_id(&id)?;
    let bytes = tokio::task::spawn_blocking(move || {
        let (task, split, _) = run_task_split(&app, i)?;
        let (eps, k) = app.episode(task, split, id)?;
        let ep = &eps[k];
        let trajs = app.run_trajectories(i)?;
        let traj = trajs.get(&id).map(|t| t.positions.as_slice());
        let scene = app.scene(&ep.scene_id)?;
        let (img, _) = episode_topdown(&scene.scene, Some(&scene.navigable), ep, traj);
        png(&img)
    })
    .await
    .map_err(|e| ApiError::internal(format!("replay worker: {e}")))??;
    Ok(([(header::CONTENT_TYPE, "image/png")], bytes))
}

/// Query of the view endpoints.
#[derive(Debug, Default, serde::Deserialize)]
pub struct ViewQuery {
    /// `rgb` (default) or `depth`.
    pub view: Option<ViewKind>,
}

/// `GET /api/runs/{run}/episodes/{id}/view/{step}`: the first-person view at a recorded step.
pub async fn run_view(
    State(app): State<Arc<App>>,
    UrlPath((run, id, step)): UrlPath<(String, String, String)>,
    Query(q): Query<ViewQuery>,
) -> ApiResult<impl IntoResponse> {
    let i = parse_run(&run)?;
    let id = App::parse_id(&id)?;
    let step: usize = step
        .parse()
        .map_err(|_| ApiError::bad_request(format!("invalid step `{step}`: expected 0, 1, ...")))?;
    let bytes = tokio::task::spawn_blocking(move || {
        let (task, split, _) = run_task_split(&app, i)?;
        let (eps, k) = app.episode(task, split, id)?;
        let ep = &eps[k];
        let trajs = app.run_trajectories(i)?;
        let traj = recorded(&app, i, &trajs, id)?;
        let p = *traj.positions.get(step).ok_or_else(|| {
            ApiError::not_found(format!(
                "episode {id} has {} recorded positions; no step {step}",
                traj.positions.len()
            ))
        })?;
        let yaw = match &traj.headings {
            Some(h) => h.get(step).copied().unwrap_or(0.0),
            None if step + 1 < traj.positions.len() => {
                crate::frames::yaw_towards(p, traj.positions[step + 1])
            }
            None => 0.0,
        };
        let scene = app.scene(&ep.scene_id)?;
        app.with_viewer(|rig| {
            render_view(
                rig,
                &scene.scene,
                p,
                yaw,
                q.view.unwrap_or_default(),
                app.cfg.jpeg_quality,
            )
        })
    })
    .await
    .map_err(|e| ApiError::internal(format!("replay worker: {e}")))??;
    Ok(([(header::CONTENT_TYPE, "image/jpeg")], bytes))
}
