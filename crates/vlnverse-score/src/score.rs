//! Scoring a split on the scenes' navigable maps: geodesic distances come from one
//! [`DistanceField`] per goal, built on `DIR/scenes/<scene_id>/navigable.yaml`.
//!
//! Episodes are processed scene by scene, in chunks of at most [`MAX_FIELDS_PER_CHUNK`] distinct
//! goals, so memory stays bounded however large the split is; fields are built and episodes
//! scored in parallel (rayon). Results come back in input order.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec2;
use rayon::prelude::*;
use vlnverse_env::geodesic::{DistanceField, LevelField, LevelPoint, MultiLevelMap, Portal};
use vlnverse_env::occupancy::{level_map_file, GridMap};

use crate::episode::{Episode, Split, Task};
use crate::error::{DataError, Result};
use crate::metrics::{
    aggregate, check_starts, match_trajectories, score_all, score_episode, EpisodeMetrics,
    GoalDistance, GoalDistances, MetricsConfig, Nearest, Summary, DEFAULT_START_TOLERANCE,
};
use crate::report::RunSummary;
use crate::trajectory::Trajectory;

/// How [`score_with`] scores; the default is the benchmark's protocol (geodesic distances on the
/// navigable maps, every episode needs a trajectory, starts within
/// [`DEFAULT_START_TOLERANCE`]).
#[derive(Clone, Debug)]
pub struct ScoreOptions {
    /// Success distance, collision rule, ...
    pub metrics: MetricsConfig,
    /// Straight-line instead of geodesic distances (no navigable maps needed).
    pub euclidean: bool,
    /// Score episodes without a trajectory as failures instead of refusing the file.
    pub allow_missing: bool,
    /// How far (m, horizontally) a trajectory may start from its episode's start.
    pub start_tolerance: f32,
}

impl Default for ScoreOptions {
    fn default() -> Self {
        ScoreOptions {
            metrics: MetricsConfig::default(),
            euclidean: false,
            allow_missing: false,
            start_tolerance: DEFAULT_START_TOLERANCE,
        }
    }
}

/// A scored split: one [`EpisodeMetrics`] per episode, in the split file's order (each tagged
/// with the split), and their [`Summary`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Scored {
    /// The task scored.
    pub task: Task,
    /// The split scored.
    pub split: Split,
    /// Per-episode metrics.
    pub metrics: Vec<EpisodeMetrics>,
    /// The split's aggregate.
    pub summary: Summary,
}

impl Scored {
    /// `summary.json`'s content for this split, under the row label `method` (and `setting`).
    pub fn run_summary(&self, method: &str, setting: Option<&str>) -> RunSummary {
        RunSummary::with_summary(
            method,
            setting,
            self.task,
            self.split,
            self.summary.clone(),
            &self.metrics,
        )
    }
}

/// Score `trajectories` (any order, one per episode) against `task`/`split` of the dataset in
/// `dataset` with the benchmark's protocol: the one call behind `cargo xtask score`.
///
/// ```no_run
/// use vlnverse_score::{read_trajectories, score, Split, Task};
/// let trajectories = read_trajectories("runs/mine/trajectories.jsonl".as_ref())?;
/// let scored = score("datasets/tiny".as_ref(), Task::Fine, Split::ValUnseen, trajectories)?;
/// println!("SR {:.3}", scored.summary.sr);
/// # Ok::<(), vlnverse_score::DataError>(())
/// ```
pub fn score(
    dataset: &Path,
    task: Task,
    split: Split,
    trajectories: Vec<Trajectory>,
) -> Result<Scored> {
    score_with(
        dataset,
        task,
        split,
        trajectories,
        &ScoreOptions::default(),
        &|_| {},
    )
}

/// [`score`] with options; `on_done(n)` is called after each chunk of `n` scored episodes.
pub fn score_with(
    dataset: &Path,
    task: Task,
    split: Split,
    trajectories: Vec<Trajectory>,
    options: &ScoreOptions,
    on_done: &(dyn Fn(usize) + Sync),
) -> Result<Scored> {
    options.metrics.validate()?;
    let episodes = crate::dataset::read_split(dataset, task, split)?;
    let trajectories = match_trajectories(&episodes, trajectories, options.allow_missing)?;
    check_starts(&episodes, &trajectories, options.start_tolerance)?;
    let mut metrics = if options.euclidean {
        let m = score_all(
            &episodes,
            &trajectories,
            &GoalDistances::euclidean,
            &options.metrics,
        );
        on_done(m.len());
        m
    } else {
        score_on_maps(dataset, &episodes, &trajectories, &options.metrics, on_done)?
    };
    for m in &mut metrics {
        m.split = Some(split);
    }
    let summary = aggregate(&metrics);
    Ok(Scored {
        task,
        split,
        metrics,
        summary,
    })
}

/// Distinct goals whose distance fields are alive at once.
pub const MAX_FIELDS_PER_CHUNK: usize = 32;

/// `dataset_dir/scenes/<scene_id>/navigable.yaml`.
pub fn navigable_map_path(dataset_dir: &Path, scene_id: &str) -> PathBuf {
    dataset_dir
        .join("scenes")
        .join(scene_id)
        .join("navigable.yaml")
}

/// A goal's floor point `(x, z)` as exact bits, to share fields between episodes.
type GoalKey = (u32, u32);

fn key(p: [f32; 3]) -> GoalKey {
    (p[0].to_bits(), p[2].to_bits())
}

fn episode_keys(ep: &Episode) -> impl Iterator<Item = GoalKey> + '_ {
    ep.goals
        .iter()
        .chain(&ep.sub_goals)
        .map(|g| key(g.position))
}

/// Score `episodes[i]` with `trajectories[i]` using geodesic distances on each scene's navigable
/// map under `dataset_dir`. `on_done(n)` is called after each chunk of `n` scored episodes
/// (for progress bars).
pub fn score_on_maps(
    dataset_dir: &Path,
    episodes: &[Episode],
    trajectories: &[Trajectory],
    cfg: &MetricsConfig,
    on_done: &(dyn Fn(usize) + Sync),
) -> Result<Vec<EpisodeMetrics>> {
    if episodes.len() != trajectories.len() {
        return Err(DataError::invalid(
            "trajectories",
            trajectories.len(),
            format!("expected one per episode ({})", episodes.len()),
        ));
    }
    let mut by_scene: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (i, ep) in episodes.iter().enumerate() {
        by_scene.entry(ep.scene_id.as_str()).or_default().push(i);
    }
    let mut out: Vec<Option<EpisodeMetrics>> = vec![None; episodes.len()];
    for (scene, mut idxs) in by_scene {
        if let Some(levels) = scene_levels(dataset_dir, scene)? {
            let scored = score_across_floors(&levels, episodes, trajectories, &idxs, cfg)?;
            for (i, m) in scored {
                out[i] = Some(m);
            }
            on_done(idxs.len());
            continue;
        }
        let path = navigable_map_path(dataset_dir, scene);
        let map = GridMap::load_ros(&path)?;
        // Episodes sharing goals (the three coarse styles of a path) end up in one chunk.
        idxs.sort_by_key(|&i| (episode_keys(&episodes[i]).next(), i));
        for chunk in chunks(episodes, &idxs) {
            let keys: BTreeSet<GoalKey> = chunk
                .iter()
                .flat_map(|&i| episode_keys(&episodes[i]))
                .collect();
            let fields: BTreeMap<GoalKey, Arc<DistanceField>> = keys
                .into_par_iter()
                .map(|k| {
                    let goal = Vec2::new(f32::from_bits(k.0), f32::from_bits(k.1));
                    DistanceField::new(&map, goal).map(|f| (k, Arc::new(f)))
                })
                .collect::<std::result::Result<_, _>>()?;
            let scored: Vec<(usize, EpisodeMetrics)> = chunk
                .par_iter()
                .map(|&i| {
                    let d = distances(&episodes[i], &fields);
                    (i, score_episode(&episodes[i], &trajectories[i], &d, cfg))
                })
                .collect();
            for (i, m) in scored {
                out[i] = Some(m);
            }
            on_done(chunk.len());
        }
    }
    Ok(out.into_iter().flatten().collect())
}

/// A home on several floors: its levels' floor heights, flights' half widths and the map
/// across its floors.
struct SceneLevels {
    heights: Vec<f32>,
    half_widths: Vec<f32>,
    map: MultiLevelMap,
}

/// The levels of `dataset_dir/scenes/<scene_id>/` when it is a home on several floors (its
/// folder holds `navigable_level1.yaml`); `None` for a single-storey scene (not even its
/// `scene.json` is read then).
fn scene_levels(dataset_dir: &Path, scene_id: &str) -> Result<Option<SceneLevels>> {
    let dir = dataset_dir.join("scenes").join(scene_id);
    if !dir.join(level_map_file("navigable", 1, "yaml")).is_file() {
        return Ok(None);
    }
    let json = dir.join(vlnverse_env::io::SCENE_JSON);
    let bytes = std::fs::read(&json).map_err(|e| DataError::io(&json, e))?;
    let scene = vlnverse_env::io::json::scene_from_json(&bytes, &json)?;
    let mut maps = Vec::new();
    for k in 0..scene.level_count() as u32 {
        let file = if k == 0 {
            navigable_map_path(dataset_dir, scene_id)
        } else {
            dir.join(level_map_file("navigable", k, "yaml"))
        };
        maps.push(GridMap::load_ros(&file)?);
    }
    let portals = scene.storeys.stairs.iter().map(Portal::of_stairs).collect();
    let map = MultiLevelMap::new(maps, portals)
        .map_err(|e| DataError::invalid("scene", scene_id, e.to_string()))?;
    Ok(Some(SceneLevels {
        heights: (0..scene.level_count() as u32)
            .map(|l| scene.level_height(l).unwrap_or(scene.floor_height))
            .collect(),
        half_widths: scene.storeys.stairs.iter().map(|s| 0.5 * s.width).collect(),
        map,
    }))
}

/// Score the episodes `idxs` of a home on several floors with distances across its floors
/// ([`LevelField`]: a success radius counts on the goal's floor only).
fn score_across_floors(
    levels: &SceneLevels,
    episodes: &[Episode],
    trajectories: &[Trajectory],
    idxs: &[usize],
    cfg: &MetricsConfig,
) -> Result<Vec<(usize, EpisodeMetrics)>> {
    let goals: BTreeSet<(u32, u32, u32)> = idxs
        .iter()
        .flat_map(|&i| episodes[i].goals.iter().chain(&episodes[i].sub_goals))
        .map(|g| {
            (
                g.position[0].to_bits(),
                g.position[1].to_bits(),
                g.position[2].to_bits(),
            )
        })
        .collect();
    let fields: BTreeMap<(u32, u32, u32), Arc<LevelField>> = goals
        .into_par_iter()
        .map(|k| {
            let p = [
                f32::from_bits(k.0),
                f32::from_bits(k.1),
                f32::from_bits(k.2),
            ];
            let goal = LevelPoint::new(level_of(&levels.heights, p[1]), p[0], p[2]);
            LevelField::new(&levels.map, &levels.heights, &levels.half_widths, goal)
                .map(|f| (k, Arc::new(f)))
                .map_err(DataError::from)
        })
        .collect::<Result<_>>()?;
    let field = |p: [f32; 3]| -> Arc<dyn GoalDistance> {
        let k = (p[0].to_bits(), p[1].to_bits(), p[2].to_bits());
        fields
            .get(&k)
            .map(|f| f.clone() as Arc<dyn GoalDistance>)
            .unwrap_or_else(|| Arc::new(crate::metrics::Euclidean(p)))
    };
    Ok(idxs
        .par_iter()
        .map(|&i| {
            let ep = &episodes[i];
            let goal = if ep.goals.len() == 1 {
                field(ep.goals[0].position)
            } else {
                Arc::new(Nearest(
                    ep.goals.iter().map(|g| field(g.position)).collect(),
                ))
            };
            let d = GoalDistances {
                goal,
                sub_goals: ep.sub_goals.iter().map(|g| field(g.position)).collect(),
            };
            (i, score_episode(ep, &trajectories[i], &d, cfg))
        })
        .collect())
}

/// The level whose floor is the highest at or below `y` (0.25 m tolerance, as
/// `Scene::level_at_height`).
fn level_of(heights: &[f32], y: f32) -> u32 {
    heights.iter().rposition(|h| *h <= y + 0.25).unwrap_or(0) as u32
}

/// Split a scene's episodes into runs with at most [`MAX_FIELDS_PER_CHUNK`] distinct goals.
fn chunks(episodes: &[Episode], idxs: &[usize]) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut cur: Vec<usize> = Vec::new();
    let mut seen: BTreeSet<GoalKey> = BTreeSet::new();
    for &i in idxs {
        let new: BTreeSet<GoalKey> = episode_keys(&episodes[i])
            .filter(|k| !seen.contains(k))
            .collect();
        if !cur.is_empty() && seen.len() + new.len() > MAX_FIELDS_PER_CHUNK {
            out.push(std::mem::take(&mut cur));
            seen.clear();
            seen.extend(episode_keys(&episodes[i]));
        } else {
            seen.extend(new);
        }
        cur.push(i);
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

fn distances(ep: &Episode, fields: &BTreeMap<GoalKey, Arc<DistanceField>>) -> GoalDistances {
    let field = |p: [f32; 3]| -> Arc<dyn GoalDistance> {
        // Every key of the chunk has a field; a missing one would be a bug, not user input.
        fields
            .get(&key(p))
            .map(|f| f.clone() as Arc<dyn GoalDistance>)
            .unwrap_or_else(|| Arc::new(crate::metrics::Euclidean(p)))
    };
    let goal = if ep.goals.len() == 1 {
        field(ep.goals[0].position)
    } else {
        Arc::new(Nearest(
            ep.goals.iter().map(|g| field(g.position)).collect(),
        ))
    };
    GoalDistances {
        goal,
        sub_goals: ep.sub_goals.iter().map(|g| field(g.position)).collect(),
    }
}
