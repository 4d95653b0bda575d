//! Episode assembly of the five tasks in one scene: sample trajectories, describe them, render
//! reference images, number the episodes from the plan.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::{Quat, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::floors::Floors;
use super::presets::{episodes_per_trajectory, GenerateConfig};
use super::reference_image::ReferenceRenderer;
use super::sampler::{Reject, Rejections, SampledPath, SceneSampler, TargetSpot};
use super::seed::derive_seed;
use super::splits::CellShare;
use vlnverse_instructions::{offset_grounding, InstructionGenerator, PathContext};
use vlnverse_score::dataset::write_atomic;
use vlnverse_score::episode::{Episode, EpisodeInfo, Goal, Instruction, Split, Style, Task};
use vlnverse_score::Result;

/// Success radius written into goals (the paper's 3 m).
pub const GOAL_RADIUS: f32 = vlnverse_score::episode::DEFAULT_GOAL_RADIUS;

/// Stages of the pipeline, timed separately.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// Building scenes (procedural generation or loading).
    Scenes,
    /// Occupancy maps and scene graphs.
    Maps,
    /// Path sampling (A*, distance fields, targets).
    Sampling,
    /// Instruction generation.
    Instructions,
    /// Reference images (ray casting and PNG encoding).
    Images,
    /// Writing scene folders, parts, images and split files.
    Writing,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Stage; 6] = [
        Stage::Scenes,
        Stage::Maps,
        Stage::Sampling,
        Stage::Instructions,
        Stage::Images,
        Stage::Writing,
    ];

    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Scenes => "scenes",
            Stage::Maps => "maps",
            Stage::Sampling => "sampling",
            Stage::Instructions => "instructions",
            Stage::Images => "images",
            Stage::Writing => "writing",
        }
    }
}

/// Thread time spent per stage (summed over worker threads).
#[derive(Debug, Default)]
pub struct StageTimes {
    nanos: [AtomicU64; 6],
}

impl StageTimes {
    /// Add `d` to `stage`.
    pub fn add(&self, stage: Stage, d: Duration) {
        self.nanos[stage as usize].fetch_add(d.as_nanos() as u64, Ordering::Relaxed);
    }

    /// Run `f`, charging its time to `stage`.
    pub fn time<T>(&self, stage: Stage, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let out = f();
        self.add(stage, t.elapsed());
        out
    }

    /// Seconds per stage, in pipeline order.
    pub fn seconds(&self) -> Vec<(Stage, f64)> {
        Stage::ALL
            .iter()
            .map(|&s| {
                (
                    s,
                    self.nanos[s as usize].load(Ordering::Relaxed) as f64 * 1e-9,
                )
            })
            .collect()
    }
}

/// The episodes of one task generated in one scene (a part file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScenePart {
    /// Scene id.
    pub scene_id: String,
    /// The task.
    pub task: Task,
    /// Episodes by split, in id order.
    pub episodes: BTreeMap<Split, Vec<Episode>>,
    /// Rejected samples by reason.
    pub rejections: Rejections,
    /// Why the scene provides no episodes of this task (then `episodes` is empty); absent for
    /// a part that has its planned episodes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub skipped: Option<String>,
}

/// Why a scene cannot provide the episodes of a task (the scene is skipped for that task).
#[derive(Clone, Debug, PartialEq)]
pub struct Unfit {
    /// One line, e.g. `long_horizon needs 2 distinct targets, found 1`.
    pub reason: String,
    /// Rejected samples up to the failure.
    pub rejections: Rejections,
}

/// Everything needed to generate episodes in one scene.
pub struct SceneTaskContext<'a> {
    /// The sampler (scene, maps, graph, targets).
    pub sampler: &'a SceneSampler<'a>,
    /// Index of the scene in its source (enters every seed).
    pub scene_index: usize,
    /// The config.
    pub config: &'a GenerateConfig,
    /// The instruction generator.
    pub instructions: &'a dyn InstructionGenerator,
    /// Dataset folder (reference images are written under it).
    pub out: &'a Path,
    /// Stage timers.
    pub times: &'a StageTimes,
    /// A home on several floors: the samplers of its levels and the map across them (then
    /// every task samples through `cross`); `None` for a single-storey home.
    pub floors: Option<&'a Floors<'a>>,
}

/// Hard-link `src` to `dest` through a temporary name (atomic); false when links fail. The
/// temporary name, `.<file>.link<pid>`, starts with a dot so readers skip it, and a resumed run
/// removes it when a kill left it behind (see [`super::pipeline::remove_leftovers`]).
fn link_atomic(src: &Path, dest: &Path) -> bool {
    let name = dest
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dest.with_file_name(format!(".{name}.link{}", std::process::id()));
    let _ = std::fs::remove_file(&tmp);
    if std::fs::hard_link(src, &tmp).is_err() {
        return false;
    }
    let ok = std::fs::rename(&tmp, dest).is_ok();
    if !ok {
        let _ = std::fs::remove_file(&tmp);
    }
    ok
}

pub(crate) fn yaw_quat(yaw: f32) -> [f32; 4] {
    Quat::from_rotation_y(yaw).to_array()
}

pub(crate) fn heading_yaw(a: Vec2, b: Vec2, fallback: f32) -> f32 {
    let d = b - a;
    if d.length_squared() > 1e-10 {
        vlnverse_env::scene_graph::yaw_from_direction(d)
    } else {
        fallback
    }
}

impl SceneTaskContext<'_> {
    fn floor(&self) -> f32 {
        self.sampler.scene.floor_height
    }

    fn path3(&self, pts: &[Vec2]) -> Vec<[f32; 3]> {
        let y = self.floor();
        pts.iter().map(|p| [p.x, y, p.y]).collect()
    }

    fn goal(&self, p: Vec2, object: Option<u32>) -> Goal {
        Goal {
            position: [p.x, self.floor(), p.y],
            radius: GOAL_RADIUS,
            object_id: object,
        }
    }

    fn ctx<'p>(&'p self, path: &'p [[f32; 3]], start_yaw: f32) -> PathContext<'p> {
        PathContext {
            scene: self.sampler.scene,
            graph: self.sampler.graph,
            navigable: &self.sampler.maps.navigable,
            path,
            start_yaw,
            whole_home: None,
        }
    }

    pub(crate) fn fail(&self, share: &CellShare, k: usize, rej: &Rejections) -> Unfit {
        let reasons: Vec<String> = rej
            .iter()
            .map(|(r, n)| format!("{} {n}", r.name()))
            .collect();
        Unfit {
            reason: format!(
                "{} {} trajectory {k}: no valid sample in {} attempts ({} targets usable; \
                 rejected: {}); loosen tasks.{}.min_length/max_length or raise \
                 sampling.max_attempts",
                share.task,
                share.split,
                self.config.sampling.max_attempts,
                self.sampler.targets().len(),
                reasons.join(", "),
                share.task
            ),
            rejections: rej.clone(),
        }
    }

    /// What the scene lacks for `task`, before any sampling: navigable space for fine paths,
    /// one target object for the coarse-based tasks, `sub_tasks_min` distinct targets for
    /// long-horizon episodes. `None` when sampling may proceed.
    pub fn lacks(&self, task: Task) -> Option<String> {
        let samplers = match self.floors {
            Some(f) => f.samplers.iter().collect(),
            None => vec![self.sampler],
        };
        let targets: usize = samplers.iter().map(|s| s.targets().len()).sum();
        let need = match task {
            Task::Fine => {
                let free: usize = samplers.iter().map(|s| s.free_points()).sum();
                return (free < 2)
                    .then(|| format!("{task} needs 2 navigable cells for a path, found {free}"));
            }
            Task::LongHorizon => self.config.tasks.long_horizon.sub_tasks_min,
            Task::Coarse | Task::VisualReference | Task::Dialogue => 1,
        };
        (targets < need).then(|| {
            format!(
                "{task} needs {need} distinct target{}, found {targets} (targets: objects \
                 described uniquely, with a reachable goal point)",
                if need == 1 { "" } else { "s" }
            )
        })
    }

    /// Generate the episodes of one share (one task and split in this scene); `Ok(Err(_))`
    /// when a trajectory finds no valid sample (the scene cannot provide this task).
    pub fn generate_share(
        &self,
        share: &CellShare,
    ) -> Result<std::result::Result<(Vec<Episode>, Rejections), Unfit>> {
        let mut rejections = Rejections::new();
        let mut episodes = Vec::with_capacity(share.episodes());
        let renderer = if share.task == Task::VisualReference && share.trajectories > 0 {
            // A home on several floors is rendered whole (the view from upstairs).
            let scene = self.floors.map_or(self.sampler.scene, |f| f.scene);
            Some(self.times.time(Stage::Images, || {
                ReferenceRenderer::new(scene, &self.config.image)
            })?)
        } else {
            None
        };
        for k in 0..share.trajectories {
            // Visual-reference and dialogue trajectories are the coarse ones (`sampled_as`).
            let seed = derive_seed(
                self.config.seed,
                &[
                    self.scene_index as u64,
                    self.config.tasks.sampled_as(share.task) as u64,
                    share.split as u64,
                    k as u64,
                ],
            );
            let traj_id = share.first_trajectory_id + k as u64 + 1;
            let first_id =
                share.first_episode_id + (k * episodes_per_trajectory(share.task)) as u64 + 1;
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let mut done = false;
            // A home on several floors: whether this trajectory crosses floors is drawn once
            // (its own stream), and kept for the first half of the attempts (cross-floor paths
            // are long, so per-attempt draws would favour one floor).
            let cross = self.floors.is_some()
                && ChaCha8Rng::seed_from_u64(derive_seed(seed, &[0xC205_5F10])).random_bool(
                    f64::from(self.config.tasks.cross_floor_share(
                        self.config.tasks.sampled_as(share.task),
                        &self.config.sampling,
                    )),
                );
            let attempts = self.config.sampling.max_attempts;
            for attempt in 0..attempts {
                let cross = cross && attempt < attempts.div_ceil(2);
                let made = match (share.task, self.floors) {
                    (Task::Fine, None) => self.fine(&mut rng, seed)?,
                    (Task::LongHorizon, None) => self.long_horizon(&mut rng, seed)?,
                    (_, None) => self.coarse(share, &mut rng, seed, first_id, renderer.as_ref())?,
                    (Task::Fine, Some(f)) => self.fine_floors(f, &mut rng, seed, cross)?,
                    (Task::LongHorizon, Some(f)) => {
                        self.long_horizon_floors(f, &mut rng, seed, cross)?
                    }
                    (_, Some(f)) => self.coarse_floors(
                        f,
                        share,
                        &mut rng,
                        (seed, cross),
                        first_id,
                        renderer.as_ref(),
                    )?,
                };
                match made {
                    Ok(mut eps) => {
                        for (j, ep) in eps.iter_mut().enumerate() {
                            ep.episode_id = first_id + j as u64;
                            ep.trajectory_id = traj_id;
                        }
                        episodes.extend(eps);
                        done = true;
                        break;
                    }
                    Err(r) => *rejections.entry(r).or_default() += 1,
                }
            }
            if !done {
                return Ok(Err(self.fail(share, k, &rejections)));
            }
        }
        Ok(Ok((episodes, rejections)))
    }

    fn base_episode(
        &self,
        task: Task,
        path: &SampledPath,
        start_yaw: f32,
        goal: Goal,
        instruction: Instruction,
    ) -> Episode {
        Episode {
            episode_id: 0,
            trajectory_id: 0,
            scene_id: self.sampler.scene.id.clone(),
            start_position: [path.points[0].x, self.floor(), path.points[0].y],
            start_rotation: yaw_quat(start_yaw),
            goals: vec![goal],
            instruction,
            reference_path: self.path3(&path.points),
            info: EpisodeInfo {
                geodesic_distance: path.length,
                extra: BTreeMap::new(),
            },
            task,
            target_object_id: None,
            reference_image: None,
            sub_goals: Vec::new(),
            oracle_budget: None,
        }
    }

    fn fine(
        &self,
        rng: &mut ChaCha8Rng,
        seed: u64,
    ) -> Result<std::result::Result<Vec<Episode>, Reject>> {
        let task = &self.config.tasks.fine;
        let path = match self
            .times
            .time(Stage::Sampling, || self.sampler.fine_path(rng, task))?
        {
            Ok(p) => p,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let path3 = self.path3(&path.points);
        let ins = self.times.time(Stage::Instructions, || {
            self.instructions.fine(&self.ctx(&path3, start_yaw), seed)
        });
        let ins = match ins {
            Ok(i) => i,
            Err(e) if stops_the_run(&e) => return Err(e),
            Err(_) => return Ok(Err(Reject::Instruction)),
        };
        let goal = self.goal(*path.points.last().unwrap_or(&Vec2::ZERO), None);
        Ok(Ok(vec![self.base_episode(
            Task::Fine,
            &path,
            start_yaw,
            goal,
            ins,
        )]))
    }

    fn pick_target(&self, rng: &mut ChaCha8Rng) -> Option<TargetSpot> {
        self.sampler.draw_target(rng)
    }

    fn coarse(
        &self,
        share: &CellShare,
        rng: &mut ChaCha8Rng,
        seed: u64,
        first_id: u64,
        renderer: Option<&ReferenceRenderer>,
    ) -> Result<std::result::Result<Vec<Episode>, Reject>> {
        let task_cfg = self.config.tasks.get(share.task);
        let sampled = self.times.time(Stage::Sampling, || -> Result<_> {
            let Some(spot) = self.pick_target(rng) else {
                return Ok(Err(Reject::NoGoalPoint));
            };
            let Some(start) = self.sampler.random_point(rng) else {
                return Ok(Err(Reject::NoPath));
            };
            Ok(self
                .sampler
                .path_to_target(start, &spot, task_cfg)?
                .map(|p| (spot, p)))
        })?;
        let (spot, path) = match sampled {
            Ok(x) => x,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let path3 = self.path3(&path.points);
        let ctx = self.ctx(&path3, start_yaw);
        let mut out = Vec::with_capacity(3);
        for (j, style) in Style::ALL.into_iter().enumerate() {
            let ins = self.times.time(Stage::Instructions, || {
                self.instructions
                    .coarse(&ctx, spot.object, style, derive_seed(seed, &[j as u64]))
            });
            let ins = match ins {
                Ok(i) => i,
                Err(e) if stops_the_run(&e) => return Err(e),
                Err(_) => return Ok(Err(Reject::Instruction)),
            };
            let goal = self.goal(spot.goal, Some(spot.object));
            let mut ep = self.base_episode(share.task, &path, start_yaw, goal, ins);
            ep.target_object_id = Some(spot.object);
            if share.task == Task::Dialogue {
                ep.oracle_budget = Some(task_cfg.oracle_budget);
            }
            out.push(ep);
        }
        if let Some(r) = renderer {
            let centre = self
                .sampler
                .scene
                .object(spot.object)
                .map(|o| o.bbox.center())
                .unwrap_or(glam::Vec3::new(spot.goal.x, self.floor(), spot.goal.y));
            let png = self
                .times
                .time(Stage::Images, || r.render_png(spot.goal, centre))?;
            self.write_images(share, first_id, &mut out, &png)?;
        }
        Ok(Ok(out))
    }

    /// Write the reference image of the episodes of one coarse sample (ids from `first_id`).
    pub(crate) fn write_images(
        &self,
        share: &CellShare,
        first_id: u64,
        out: &mut [Episode],
        png: &[u8],
    ) -> Result<()> {
        self.times.time(Stage::Writing, || -> Result<()> {
            let mut first: Option<std::path::PathBuf> = None;
            for (j, ep) in out.iter_mut().enumerate() {
                let id = first_id + j as u64;
                let rel = format!("images/{id}.png");
                let file = self
                    .out
                    .join(Task::VisualReference.name())
                    .join(share.split.name())
                    .join(&rel);
                // The three styles share one view: hard links save disk and time.
                match &first {
                    Some(f) if link_atomic(f, &file) => {}
                    _ => write_atomic(&file, png)?,
                }
                first.get_or_insert(file);
                ep.reference_image = Some(rel);
            }
            Ok(())
        })
    }

    fn long_horizon(
        &self,
        rng: &mut ChaCha8Rng,
        seed: u64,
    ) -> Result<std::result::Result<Vec<Episode>, Reject>> {
        let cfg = &self.config.tasks.long_horizon;
        let n = rng.random_range(cfg.sub_tasks_min..=cfg.sub_tasks_max);
        let legs = self.times.time(Stage::Sampling, || -> Result<_> {
            let Some(start) = self.sampler.random_point(rng) else {
                return Ok(Err(Reject::NoPath));
            };
            let mut legs: Vec<(TargetSpot, SampledPath)> = Vec::with_capacity(n);
            let mut at = start;
            for _ in 0..n {
                let Some(spot) = self.pick_target(rng) else {
                    return Ok(Err(Reject::NoGoalPoint));
                };
                let repeated = legs.iter().any(|(s, _)| {
                    s.object == spot.object || s.goal.distance(spot.goal) < cfg.min_length.max(0.5)
                }) || start.distance(spot.goal) < 0.5;
                if repeated {
                    return Ok(Err(Reject::DuplicateGoal));
                }
                match self.sampler.path_to_target(at, &spot, cfg)? {
                    Ok(p) => {
                        at = spot.goal;
                        legs.push((spot, p));
                    }
                    Err(r) => return Ok(Err(r)),
                }
            }
            Ok(Ok(legs))
        })?;
        let legs = match legs {
            Ok(l) => l,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let style = Style::ALL[rng.random_range(0..3)];
        let mut points: Vec<Vec2> = Vec::new();
        let mut parts = Vec::with_capacity(legs.len());
        let mut yaw = start_yaw;
        let mut length = 0.0;
        for (i, (spot, leg)) in legs.iter().enumerate() {
            let offset = points.len().saturating_sub(1) as u32;
            let leg3 = self.path3(&leg.points);
            let ins = self.times.time(Stage::Instructions, || {
                self.instructions.coarse(
                    &self.ctx(&leg3, yaw),
                    spot.object,
                    style,
                    derive_seed(seed, &[i as u64]),
                )
            });
            let mut ins = match ins {
                Ok(i) => i,
                Err(e) if stops_the_run(&e) => return Err(e),
                Err(_) => return Ok(Err(Reject::Instruction)),
            };
            offset_grounding(&mut ins, offset);
            parts.push(ins);
            let m = leg.points.len();
            if m >= 2 {
                yaw = heading_yaw(leg.points[m - 2], leg.points[m - 1], yaw);
            }
            if points.is_empty() {
                points.extend_from_slice(&leg.points);
            } else {
                points.extend_from_slice(&leg.points[1..]);
            }
            length += leg.length;
        }
        let chained = self.times.time(Stage::Instructions, || {
            self.instructions.chain(&parts, derive_seed(seed, &[99]))
        });
        let ins = match chained {
            Ok(i) => i,
            Err(e) if stops_the_run(&e) => return Err(e),
            Err(_) => return Ok(Err(Reject::Instruction)),
        };
        let path = SampledPath { points, length };
        let last = legs[legs.len() - 1].0;
        let goal = self.goal(last.goal, Some(last.object));
        let mut ep = self.base_episode(Task::LongHorizon, &path, start_yaw, goal, ins);
        ep.sub_goals = legs
            .iter()
            .map(|(s, _)| self.goal(s.goal, Some(s.object)))
            .collect();
        ep.target_object_id = Some(last.object);
        ep.info.extra.insert(
            "sub_goal_distances".into(),
            serde_json::json!(legs
                .iter()
                .map(|(_, l)| (l.length as f64 * 1000.0).round() / 1000.0)
                .collect::<Vec<f64>>()),
        );
        Ok(Ok(vec![ep]))
    }
}

/// An instruction error that must end the run (the LLM stage under `on_reject = "error"`), not
/// count as one more unusable sample.
pub(crate) fn stops_the_run(e: &vlnverse_score::DataError) -> bool {
    #[cfg(feature = "llm")]
    {
        vlnverse_instructions::llm::stops_the_run(e)
    }
    #[cfg(not(feature = "llm"))]
    {
        let _ = e;
        false
    }
}
