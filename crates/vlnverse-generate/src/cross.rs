//! Episodes in a home on several floors, for every task: start and goal on one level drawn
//! uniformly, or (a trajectory drawn to cross floors, with probability
//! `sampling.cross_floor_share`) on two different levels, the path then taking the stairs
//! ([`super::floors`]). A crossing trajectory that finds no valid sample in the first half of
//! its attempts falls back to one floor, so a home never fails a task for it.
//!
//! - Positions carry their level's floor height; the reference path is 3-D (the flight's points
//!   rise tread by tread); `info.geodesic_distance` is the route's length across floors.
//! - Instructions: each walk is described on its own level's view of the scene (rooms and
//!   landmarks of that floor only), the walks joined by stair sentences
//!   ([`vlnverse_instructions::storeys`]); a coarse goal on another floor is led by "Go
//!   upstairs." and the like. Grounded path indices point into the whole reference path.
//! - `info.levels`: the level of the start and of each goal (sub-goals for long-horizon
//!   episodes), written only for homes on several floors.

use glam::{Vec2, Vec3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::geodesic::LevelPoint;
use vlnverse_env::LevelId;
use vlnverse_instructions::storeys::{goal_across, join_walks};
use vlnverse_instructions::{check_grounding, offset_grounding, PathContext};
use vlnverse_score::episode::{
    Episode, EpisodeInfo, Goal, GroundedObject, Instruction, Style, Task,
};
use vlnverse_score::Result;

use super::episodes::{heading_yaw, stops_the_run, yaw_quat, SceneTaskContext, Stage, GOAL_RADIUS};
use super::floors::{FloorPath, Floors, Walk};
use super::presets::TaskConfig;
use super::reference_image::ReferenceRenderer;
use super::sampler::{check_length, Reject, TargetSpot};
use super::seed::derive_seed;
use super::splits::CellShare;

/// Walks shorter than this are not described (the start is at the stairs already).
const MIN_WALK: f32 = 0.5;
/// How far a grounded object may be from its path point (m), as the generator's own check.
const GROUNDING_REACH: f32 = 3.0;

type Made<T> = Result<std::result::Result<T, Reject>>;

/// Keep grounding exact on the whole path. An object grounded at the last point of a walk
/// that is not the last was placed facing along that walk's last segment; on the whole path
/// that point is followed by the flight, so its stated side may not hold there. Such an
/// entry moves to the walk's last segment (the point before), and keeps no side when that does
/// not hold either ([`check_grounding`] decides).
fn settle_grounding(f: &Floors<'_>, path: &[[f32; 3]], ins: &mut Instruction) {
    let l = &f.levels[0];
    let ctx = PathContext {
        scene: f.scene,
        graph: &l.graph,
        navigable: &l.maps.navigable,
        path,
        start_yaw: 0.0,
        whole_home: None,
    };
    let holds = |g: &GroundedObject| {
        let one = Instruction {
            grounding: vec![g.clone()],
            ..Instruction::default()
        };
        check_grounding(&ctx, &one, GROUNDING_REACH).is_empty()
    };
    for g in &mut ins.grounding {
        if holds(g) {
            continue;
        }
        if let Some(i) = g.path_index.filter(|&i| i > 0) {
            let before = GroundedObject {
                path_index: Some(i - 1),
                ..g.clone()
            };
            if holds(&before) {
                *g = before;
                continue;
            }
        }
        g.side = None;
    }
}

/// An instruction error: the run stops or the sample is rejected.
fn instruction<T>(r: Result<T>) -> Made<T> {
    match r {
        Ok(i) => Ok(Ok(i)),
        Err(e) if stops_the_run(&e) => Err(e),
        Err(_) => Ok(Err(Reject::Instruction)),
    }
}

impl SceneTaskContext<'_> {
    fn goal_on(f: &Floors<'_>, level: LevelId, p: Vec2, object: Option<u32>) -> Goal {
        Goal {
            position: [p.x, f.height(level), p.y],
            radius: GOAL_RADIUS,
            object_id: object,
        }
    }

    /// The context a walk is described in: its level's view (without the flights when
    /// `off_flight`), maps and graph, the walk's points and heading.
    fn walk_ctx<'p>(
        f: &'p Floors<'_>,
        walk: &Walk,
        path: &'p [[f32; 3]],
        start_yaw: f32,
        off_flight: bool,
    ) -> PathContext<'p> {
        let l = &f.levels[walk.level as usize];
        let (scene, graph) = if off_flight {
            let (s, g) = l.off_stairs();
            (s, g)
        } else {
            (&l.scene, &l.graph)
        };
        PathContext {
            scene,
            graph,
            navigable: &l.maps.navigable,
            path,
            start_yaw,
            whole_home: Some(f.scene),
        }
    }

    /// The heading at the start of walk `i`: `start_yaw` for the first, the flight's direction
    /// for the others.
    fn walk_yaw(path: &FloorPath, i: usize, start_yaw: f32) -> f32 {
        match i.checked_sub(1) {
            Some(j) => heading_yaw(Vec2::ZERO, path.flights[j].1, start_yaw),
            None => start_yaw,
        }
    }

    /// A 3-D copy of a walk's points at its level's height.
    fn walk3(f: &Floors<'_>, walk: &Walk) -> Vec<[f32; 3]> {
        let y = f.height(walk.level);
        walk.points.iter().map(|p| [p.x, y, p.y]).collect()
    }

    fn floor_episode(
        &self,
        f: &Floors<'_>,
        task: Task,
        path: &FloorPath,
        start_yaw: f32,
        goal: Goal,
        instruction: Instruction,
        levels: &[LevelId],
    ) -> Episode {
        let mut info = EpisodeInfo {
            geodesic_distance: path.length,
            ..EpisodeInfo::default()
        };
        info.extra
            .insert("levels".into(), serde_json::json!(levels));
        Episode {
            episode_id: 0,
            trajectory_id: 0,
            scene_id: f.scene.id.clone(),
            start_position: path.points[0],
            start_rotation: yaw_quat(start_yaw),
            goals: vec![goal],
            instruction,
            reference_path: path.points.clone(),
            info,
            task,
            target_object_id: None,
            reference_image: None,
            sub_goals: Vec::new(),
            oracle_budget: None,
        }
    }

    /// Fine-grained episodes in a home on several floors.
    pub(crate) fn fine_floors(
        &self,
        f: &Floors<'_>,
        rng: &mut ChaCha8Rng,
        seed: u64,
        cross: bool,
    ) -> Made<Vec<Episode>> {
        let task = &self.config.tasks.fine;
        let sampled = self.times.time(Stage::Sampling, || -> Made<FloorPath> {
            let (la, lb) = f.draw_levels(rng, cross);
            if la == lb {
                return Ok(f
                    .sampler(la)
                    .fine_path(rng, task)?
                    .map(|p| f.on_level(la, &p.points, p.length)));
            }
            let (Some(a), Some(b)) = (
                f.sampler(la).random_point(rng),
                f.sampler(lb).random_point(rng),
            ) else {
                return Ok(Err(Reject::NoPath));
            };
            // The straight line and the flight bound the walk from below: skip the rest.
            if f.lower_bound(la, a, lb, b) > task.max_length {
                return Ok(Err(Reject::TooLong));
            }
            let Some(p) = f.path_by_fields(
                LevelPoint {
                    level: la,
                    point: a,
                },
                LevelPoint {
                    level: lb,
                    point: b,
                },
                None,
            )?
            else {
                return Ok(Err(Reject::NoPath));
            };
            Ok(match check_length(p.length, task) {
                Some(r) => Err(r),
                None => Ok(p),
            })
        })?;
        let path = match sampled {
            Ok(p) => p,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let ins = self
            .times
            .time(Stage::Instructions, || -> Made<Instruction> {
                let mut walks = Vec::with_capacity(path.walks.len());
                for (i, w) in path.walks.iter().enumerate() {
                    if path.crosses() && (w.length < MIN_WALK || w.points.len() < 2) {
                        walks.push(None);
                        continue;
                    }
                    let w3 = Self::walk3(f, w);
                    // A walk off the flight that ends the route names no stairs on its way.
                    let off = i > 0 && i + 1 == path.walks.len();
                    let yaw = Self::walk_yaw(&path, i, start_yaw);
                    let ctx = Self::walk_ctx(f, w, &w3, yaw, off);
                    let mut ins = match instruction(
                        self.instructions.fine(&ctx, derive_seed(seed, &[i as u64])),
                    )? {
                        Ok(i) => i,
                        Err(r) => return Ok(Err(r)),
                    };
                    offset_grounding(&mut ins, w.first as u32);
                    walks.push(Some(ins));
                }
                if !path.crosses() {
                    return Ok(Ok(walks.pop().flatten().unwrap_or_default()));
                }
                let flights: Vec<_> = path.flights.iter().map(|x| (x.0, x.2)).collect();
                instruction(join_walks(&walks, &flights, seed))
            })?;
        let mut ins = match ins {
            Ok(i) => i,
            Err(r) => return Ok(Err(r)),
        };
        if path.crosses() {
            settle_grounding(f, &path.points, &mut ins);
        }
        let (la, lb) = path.levels();
        let end = path.walks.last().and_then(|w| w.points.last().copied());
        let goal = Self::goal_on(f, lb, end.unwrap_or(Vec2::ZERO), None);
        Ok(Ok(vec![self.floor_episode(
            f,
            Task::Fine,
            &path,
            start_yaw,
            goal,
            ins,
            &[la, lb],
        )]))
    }

    /// A path from `start` on `from` to a target on `to` within the task's limits.
    fn path_to_target_floors(
        f: &Floors<'_>,
        from: LevelId,
        start: Vec2,
        to: LevelId,
        spot: &TargetSpot,
        task: &TaskConfig,
    ) -> Made<FloorPath> {
        if from == to {
            return Ok(f
                .sampler(to)
                .path_to_target(start, spot, task)?
                .map(|p| f.on_level(to, &p.points, p.length)));
        }
        if f.lower_bound(from, start, to, spot.goal) > task.max_length {
            return Ok(Err(Reject::TooLong));
        }
        let field = f.sampler(to).field(spot)?;
        let Some(p) = f.path_by_fields(
            LevelPoint {
                level: from,
                point: start,
            },
            LevelPoint {
                level: to,
                point: spot.goal,
            },
            Some(&field),
        )?
        else {
            return Ok(Err(Reject::NoPath));
        };
        Ok(match check_length(p.length, task) {
            Some(r) => Err(r),
            None => Ok(p),
        })
    }

    /// The coarse instruction of a path to `target` in one style: the description on the
    /// goal's level (its last walk), led by a stair sentence when the path crosses floors;
    /// grounding offset by `offset` more (for a leg of a longer path).
    fn coarse_floors_ins(
        &self,
        f: &Floors<'_>,
        path: &FloorPath,
        start_yaw: f32,
        target: u32,
        style: Style,
        seed: u64,
        offset: u32,
    ) -> Made<Instruction> {
        let last = path.walks.len() - 1;
        let w = &path.walks[last];
        let w3 = Self::walk3(f, w);
        let ctx = Self::walk_ctx(f, w, &w3, Self::walk_yaw(path, last, start_yaw), false);
        let mut ins = match instruction(self.instructions.coarse(&ctx, target, style, seed))? {
            Ok(i) => i,
            Err(r) => return Ok(Err(r)),
        };
        offset_grounding(&mut ins, w.first as u32 + offset);
        if let Some((flight, _, _)) = path.flights.last() {
            ins = goal_across(&ins, *flight, seed);
        }
        Ok(Ok(ins))
    }

    /// Coarse, visual-reference and dialogue episodes in a home on several floors.
    pub(crate) fn coarse_floors(
        &self,
        f: &Floors<'_>,
        share: &CellShare,
        rng: &mut ChaCha8Rng,
        (seed, cross): (u64, bool),
        first_id: u64,
        renderer: Option<&ReferenceRenderer>,
    ) -> Made<Vec<Episode>> {
        let task_cfg = self.config.tasks.get(share.task);
        let sampled = self.times.time(Stage::Sampling, || -> Made<_> {
            let (ls, lt) = f.draw_levels(rng, cross);
            let Some(spot) = f.sampler(lt).draw_target(rng) else {
                return Ok(Err(Reject::NoGoalPoint));
            };
            let Some(start) = f.sampler(ls).random_point(rng) else {
                return Ok(Err(Reject::NoPath));
            };
            Ok(
                Self::path_to_target_floors(f, ls, start, lt, &spot, task_cfg)?
                    .map(|p| (spot, p, ls, lt)),
            )
        })?;
        let (spot, path, ls, lt) = match sampled {
            Ok(x) => x,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let mut out = Vec::with_capacity(3);
        for (j, style) in Style::ALL.into_iter().enumerate() {
            let ins = self.times.time(Stage::Instructions, || {
                self.coarse_floors_ins(
                    f,
                    &path,
                    start_yaw,
                    spot.object,
                    style,
                    derive_seed(seed, &[j as u64]),
                    0,
                )
            })?;
            let ins = match ins {
                Ok(i) => i,
                Err(r) => return Ok(Err(r)),
            };
            let goal = Self::goal_on(f, lt, spot.goal, Some(spot.object));
            let mut ep = self.floor_episode(f, share.task, &path, start_yaw, goal, ins, &[ls, lt]);
            ep.target_object_id = Some(spot.object);
            if share.task == Task::Dialogue {
                ep.oracle_budget = Some(task_cfg.oracle_budget);
            }
            out.push(ep);
        }
        if let Some(r) = renderer {
            let floor = f.height(lt);
            let centre = f
                .scene
                .object(spot.object)
                .map(|o| o.bbox.center())
                .unwrap_or(Vec3::new(spot.goal.x, floor, spot.goal.y));
            let png = self
                .times
                .time(Stage::Images, || r.render_png_on(floor, spot.goal, centre))?;
            self.write_images(share, first_id, &mut out, &png)?;
        }
        Ok(Ok(out))
    }

    /// Long-horizon episodes in a home on several floors: when `cross`, one leg (drawn) goes
    /// to a target on another level, the others stay on the level they start on.
    pub(crate) fn long_horizon_floors(
        &self,
        f: &Floors<'_>,
        rng: &mut ChaCha8Rng,
        seed: u64,
        cross: bool,
    ) -> Made<Vec<Episode>> {
        let cfg = &self.config.tasks.long_horizon;
        let n = rng.random_range(cfg.sub_tasks_min..=cfg.sub_tasks_max);
        let cross_leg = rng.random_range(0..n);
        type Leg = (TargetSpot, LevelId, FloorPath);
        let legs = self
            .times
            .time(Stage::Sampling, || -> Made<(LevelId, Vec<Leg>)> {
                let l0 = f.draw_level(rng);
                let Some(start) = f.sampler(l0).random_point(rng) else {
                    return Ok(Err(Reject::NoPath));
                };
                let mut legs: Vec<Leg> = Vec::with_capacity(n);
                let (mut at, mut level) = (start, l0);
                for i in 0..n {
                    let to = if cross && i == cross_leg {
                        f.other_level(level, rng)
                    } else {
                        level
                    };
                    let Some(spot) = f.sampler(to).draw_target(rng) else {
                        return Ok(Err(Reject::NoGoalPoint));
                    };
                    let repeated = legs.iter().any(|(s, l, _)| {
                        s.object == spot.object
                            || (*l == to && s.goal.distance(spot.goal) < cfg.min_length.max(0.5))
                    }) || (l0 == to && start.distance(spot.goal) < 0.5);
                    if repeated {
                        return Ok(Err(Reject::DuplicateGoal));
                    }
                    match Self::path_to_target_floors(f, level, at, to, &spot, cfg)? {
                        Ok(p) => {
                            at = spot.goal;
                            level = to;
                            legs.push((spot, to, p));
                        }
                        Err(r) => return Ok(Err(r)),
                    }
                }
                Ok(Ok((l0, legs)))
            })?;
        let (l0, legs) = match legs {
            Ok(l) => l,
            Err(r) => return Ok(Err(r)),
        };
        let start_yaw = rng.random_range(0.0..std::f32::consts::TAU);
        let style = Style::ALL[rng.random_range(0..3)];
        let mut points: Vec<[f32; 3]> = Vec::new();
        let mut parts = Vec::with_capacity(legs.len());
        let mut yaw = start_yaw;
        let mut length = 0.0;
        for (i, (spot, _, leg)) in legs.iter().enumerate() {
            let offset = points.len().saturating_sub(1) as u32;
            let ins = self.times.time(Stage::Instructions, || {
                self.coarse_floors_ins(
                    f,
                    leg,
                    yaw,
                    spot.object,
                    style,
                    derive_seed(seed, &[i as u64]),
                    offset,
                )
            })?;
            match ins {
                Ok(i) => parts.push(i),
                Err(r) => return Ok(Err(r)),
            }
            let m = leg.points.len();
            if m >= 2 {
                let (a, b) = (leg.points[m - 2], leg.points[m - 1]);
                yaw = heading_yaw(Vec2::new(a[0], a[2]), Vec2::new(b[0], b[2]), yaw);
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
        let ins = match instruction(chained)? {
            Ok(i) => i,
            Err(r) => return Ok(Err(r)),
        };
        let whole = FloorPath {
            points,
            length,
            walks: Vec::new(),
            flights: Vec::new(),
        };
        let mut levels = vec![l0];
        levels.extend(legs.iter().map(|(_, l, _)| *l));
        let (last, last_level, _) = &legs[legs.len() - 1];
        let goal = Self::goal_on(f, *last_level, last.goal, Some(last.object));
        let mut ep =
            self.floor_episode(f, Task::LongHorizon, &whole, start_yaw, goal, ins, &levels);
        ep.sub_goals = legs
            .iter()
            .map(|(s, l, _)| Self::goal_on(f, *l, s.goal, Some(s.object)))
            .collect();
        ep.target_object_id = Some(last.object);
        ep.info.extra.insert(
            "sub_goal_distances".into(),
            serde_json::json!(legs
                .iter()
                .map(|(_, _, l)| (l.length as f64 * 1000.0).round() / 1000.0)
                .collect::<Vec<f64>>()),
        );
        Ok(Ok(vec![ep]))
    }
}
