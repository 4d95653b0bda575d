//! Path sampling on a scene's navigable map.
//!
//! - Free points are navigable cell centres (the navigable map is already dilated by the agent
//!   radius and reduced to its largest island, so every free point reaches every other).
//! - Fine paths: start and goal drawn uniformly among free points, joined by the any-angle A*
//!   of [`vlnverse_env::geodesic::shortest_path`] (line-of-sight smoothed, so each segment is
//!   free for the agent on the navigable map).
//! - Object goals: a target is an object (not structure) with a unique referring expression and
//!   a goal point: the free point nearest to its footprint, within `goal_max_distance`, that
//!   sees the object on the raw occupancy map (so never behind a wall). The agent faces the
//!   object there. Paths to a target come from its [`DistanceField`] (cached per target), so
//!   each start costs O(path).
//! - Every rejected sample is counted by [`Reject`] reason.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::sync::Arc;

use glam::Vec2;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vlnverse_env::geodesic::{polyline_length, shortest_path, DistanceField, GeodesicPath};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::occupancy::OccupancyMaps;
use vlnverse_env::scene_graph::{yaw_from_direction, SceneGraph};
use vlnverse_env::{ClassKind, ObjectId, Scene, SceneObject};

use super::presets::{SamplingConfig, TaskConfig};
use vlnverse_score::Result;

/// Why a sample was thrown away.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reject {
    /// Start and goal are not connected.
    NoPath,
    /// The geodesic path is shorter than the task's `min_length`.
    TooShort,
    /// The geodesic path is longer than the task's `max_length`.
    TooLong,
    /// An object that no description singles out (counted once per object and scene).
    TargetNotUnique,
    /// An object with no navigable point in sight within `goal_max_distance`.
    NoGoalPoint,
    /// A long-horizon sub-goal equal or too close to an earlier one.
    DuplicateGoal,
    /// The instruction generator could not describe the sample.
    Instruction,
}

impl Reject {
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Reject::NoPath => "no_path",
            Reject::TooShort => "too_short",
            Reject::TooLong => "too_long",
            Reject::TargetNotUnique => "target_not_unique",
            Reject::NoGoalPoint => "no_goal_point",
            Reject::DuplicateGoal => "duplicate_goal",
            Reject::Instruction => "instruction",
        }
    }
}

/// Rejected samples by reason.
pub type Rejections = BTreeMap<Reject, u64>;

/// A target object with the point an agent reaches it from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TargetSpot {
    /// The object.
    pub object: ObjectId,
    /// Goal point `(x, z)`, a navigable cell centre.
    pub goal: Vec2,
    /// Yaw facing the object from the goal.
    pub yaw: f32,
}

/// A sampled path.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledPath {
    /// Waypoints `(x, z)`, start first, goal last.
    pub points: Vec<Vec2>,
    /// Geodesic length (m).
    pub length: f32,
}

/// Samples paths in one scene (one thread; fields are cached per target).
pub struct SceneSampler<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// Its maps.
    pub maps: &'a OccupancyMaps,
    /// Its scene graph.
    pub graph: &'a SceneGraph,
    free: Vec<Vec2>,
    targets: Vec<TargetSpot>,
    /// Each target's weight in [`SceneSampler::draw_target`], in the order of `targets`.
    weights: Vec<f64>,
    fields: RefCell<BTreeMap<usize, Arc<DistanceField>>>,
    /// Rejections found while choosing targets.
    pub target_rejections: Rejections,
}

/// Weight of a small object against a piece of furniture when a target is drawn.
const SMALL_TARGET_WEIGHT: f64 = 1.0 / 3.0;

fn footprint(o: &SceneObject) -> (Vec2, Vec2) {
    (
        Vec2::new(o.bbox.min[0], o.bbox.min[2]),
        Vec2::new(o.bbox.max[0], o.bbox.max[2]),
    )
}

impl<'a> SceneSampler<'a> {
    /// Prepare the free points and the targets of a scene (`seed` picks the targets when
    /// there are more than `cfg.max_targets`).
    pub fn new(
        scene: &'a Scene,
        maps: &'a OccupancyMaps,
        graph: &'a SceneGraph,
        cfg: &SamplingConfig,
        seed: u64,
    ) -> Self {
        let nav = &maps.navigable;
        let free: Vec<Vec2> = nav
            .free_cells()
            .map(|(c, r)| nav.cell_center(c, r))
            .collect();
        let mut rejections = Rejections::new();
        let mut targets = Vec::new();
        for o in scene.items() {
            if graph.object(o.id).is_none() {
                continue;
            }
            if graph.referring_expression(scene, o.id).is_none() {
                *rejections.entry(Reject::TargetNotUnique).or_default() += 1;
                continue;
            }
            match goal_spot(scene, maps, o, cfg) {
                Some(spot) => targets.push(spot),
                None => *rejections.entry(Reject::NoGoalPoint).or_default() += 1,
            }
        }
        if cfg.max_targets > 0 && targets.len() > cfg.max_targets {
            targets.shuffle(&mut ChaCha8Rng::seed_from_u64(seed));
            targets.truncate(cfg.max_targets);
            targets.sort_by_key(|t| t.object);
        }
        let weights = targets
            .iter()
            .map(|t| match scene.object(t.object).map(|o| o.class.kind()) {
                Some(ClassKind::Small) => SMALL_TARGET_WEIGHT,
                _ => 1.0,
            })
            .collect();
        SceneSampler {
            scene,
            maps,
            graph,
            free,
            targets,
            weights,
            fields: RefCell::new(BTreeMap::new()),
            target_rejections: rejections,
        }
    }

    /// Leave out the targets of `objects` (e.g. the flights of stairs of a home on several
    /// floors, objects that span two floors).
    pub fn drop_targets(&mut self, objects: &[ObjectId]) {
        let keep: Vec<bool> = self
            .targets
            .iter()
            .map(|t| !objects.contains(&t.object))
            .collect();
        let mut k = keep.iter();
        self.targets.retain(|_| *k.next().unwrap_or(&true));
        let mut k = keep.iter();
        self.weights.retain(|_| *k.next().unwrap_or(&true));
    }

    /// The usable targets, by object id.
    pub fn targets(&self) -> &[TargetSpot] {
        &self.targets
    }

    /// A target drawn at random: a small object (a cup, a book) is drawn a third as often as
    /// furniture, as people send someone to the sofa more often than to the cup on it, and
    /// homes hold more small objects than furniture.
    pub fn draw_target(&self, rng: &mut ChaCha8Rng) -> Option<TargetSpot> {
        let total: f64 = self.weights.iter().sum();
        if self.targets.is_empty() || total <= 0.0 {
            return None;
        }
        let mut x = rng.random_range(0.0..total);
        for (t, w) in self.targets.iter().zip(&self.weights) {
            x -= w;
            if x < 0.0 {
                return Some(*t);
            }
        }
        self.targets.last().copied()
    }

    /// Number of navigable points.
    pub fn free_points(&self) -> usize {
        self.free.len()
    }

    /// A uniformly drawn navigable point (None on an empty map).
    pub fn random_point(&self, rng: &mut ChaCha8Rng) -> Option<Vec2> {
        if self.free.is_empty() {
            return None;
        }
        Some(self.free[rng.random_range(0..self.free.len())])
    }

    /// Distance field towards a target's goal point (cached).
    pub fn field(&self, spot: &TargetSpot) -> Result<Arc<DistanceField>> {
        self.field_at(spot.goal)
    }

    /// Distance field towards a point of this map, e.g. the end of a flight of stairs (cached
    /// by the point's cell, as the fields of targets are).
    pub fn field_at(&self, goal: Vec2) -> Result<Arc<DistanceField>> {
        let nav = &self.maps.navigable;
        let key = nav
            .world_to_cell(goal)
            .map(|(c, r)| nav.index(c, r))
            .unwrap_or(usize::MAX);
        if let Some(f) = self.fields.borrow().get(&key) {
            return Ok(f.clone());
        }
        let f = Arc::new(DistanceField::new(nav, goal)?);
        self.fields.borrow_mut().insert(key, f.clone());
        Ok(f)
    }

    /// Path from `start` to a target's goal point within the task's length limits.
    pub fn path_to_target(
        &self,
        start: Vec2,
        spot: &TargetSpot,
        task: &TaskConfig,
    ) -> Result<std::result::Result<SampledPath, Reject>> {
        let field = self.field(spot)?;
        let Some(d) = field.distance(start).meters() else {
            return Ok(Err(Reject::NoPath));
        };
        if let Some(r) = check_length(d, task) {
            return Ok(Err(r));
        }
        let Some(p) = field.path(start) else {
            return Ok(Err(Reject::NoPath));
        };
        let points = string_pull(&self.maps.navigable, &p.points);
        let length = polyline_length(&points);
        if let Some(r) = check_length(length, task) {
            return Ok(Err(r));
        }
        Ok(Ok(SampledPath { points, length }))
    }

    /// A fine-grained path: free start and goal, A* between them, within the length limits.
    pub fn fine_path(
        &self,
        rng: &mut ChaCha8Rng,
        task: &TaskConfig,
    ) -> Result<std::result::Result<SampledPath, Reject>> {
        let (Some(a), Some(b)) = (self.random_point(rng), self.random_point(rng)) else {
            return Ok(Err(Reject::NoPath));
        };
        // The geodesic is never shorter than the straight line: skip the search.
        if a.distance(b) > task.max_length {
            return Ok(Err(Reject::TooLong));
        }
        let Some(p) = shortest_path(&self.maps.navigable, a, b)? else {
            return Ok(Err(Reject::NoPath));
        };
        if let Some(r) = check_length(p.length, task) {
            return Ok(Err(r));
        }
        Ok(Ok(to_sampled(p)))
    }
}

fn to_sampled(p: GeodesicPath) -> SampledPath {
    SampledPath {
        length: p.length,
        points: p.points,
    }
}

/// Greedy line-of-sight smoothing: from each kept point jump to the last point of the run of
/// later points that stay in sight (linear in the number of points). Consecutive output points
/// always see each other when consecutive input points do.
pub fn string_pull(map: &GridMap, pts: &[Vec2]) -> Vec<Vec2> {
    let mut out = vlnverse_env::geodesic::string_pull(map, pts);
    out.dedup();
    out
}

/// Why a path of length `d` does not fit the task's length limits, if it does not.
pub(crate) fn check_length(d: f32, task: &TaskConfig) -> Option<Reject> {
    if d < task.min_length {
        Some(Reject::TooShort)
    } else if d > task.max_length {
        Some(Reject::TooLong)
    } else {
        None
    }
}

/// The object an object rests on, down to the one standing on the floor.
fn base_object<'s>(scene: &'s Scene, o: &'s SceneObject) -> &'s SceneObject {
    let mut cur = o;
    for _ in 0..8 {
        match cur.supported_by.and_then(|s| scene.object(s)) {
            Some(s) if !s.is_structure() => cur = s,
            _ => break,
        }
    }
    cur
}

/// The goal point of an object: the navigable cell centre nearest to its footprint within
/// `goal_max_distance` (at least `goal_min_distance`), from which the footprint of the object
/// it stands on is in sight on the raw occupancy map.
pub fn goal_spot(
    scene: &Scene,
    maps: &OccupancyMaps,
    o: &SceneObject,
    cfg: &SamplingConfig,
) -> Option<TargetSpot> {
    let nav = &maps.navigable;
    let (lo, hi) = footprint(o);
    let (blo, bhi) = footprint(base_object(scene, o));
    let reach = cfg.goal_max_distance;
    let clamp_cell = |q: Vec2| {
        let u = ((q - nav.origin) / nav.resolution).floor();
        (
            u.x.clamp(0.0, nav.width.saturating_sub(1) as f32) as u32,
            u.y.clamp(0.0, nav.height.saturating_sub(1) as f32) as u32,
        )
    };
    if nav.width == 0 || nav.height == 0 {
        return None;
    }
    let c0 = clamp_cell(lo - Vec2::splat(reach));
    let c1 = clamp_cell(hi + Vec2::splat(reach));
    let mut cands: Vec<(f32, u32, u32)> = Vec::new();
    for row in c0.1..=c1.1 {
        for col in c0.0..=c1.0 {
            if !nav.is_free(col, row) {
                continue;
            }
            let p = nav.cell_center(col, row);
            let d = p.distance(p.clamp(lo, hi));
            if d <= reach && d >= cfg.goal_min_distance {
                cands.push((d, row, col));
            }
        }
    }
    cands.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.1, a.2).cmp(&(b.1, b.2))));
    let centre = (lo + hi) * 0.5;
    for (_, row, col) in cands.into_iter().take(64) {
        let p = nav.cell_center(col, row);
        let near = p.clamp(blo, bhi);
        let gap = p.distance(near);
        // Aim just short of the base footprint so its own cells do not block the view.
        let aim = if gap > 0.2 {
            near + (p - near) * (0.15 / gap)
        } else {
            p
        };
        if maps.occupancy.line_of_sight(p, aim) {
            let dir = centre - p;
            let yaw = if dir.length_squared() > 1e-8 {
                yaw_from_direction(dir)
            } else {
                0.0
            };
            return Some(TargetSpot {
                object: o.id,
                goal: p,
                yaw,
            });
        }
    }
    None
}
