//! Homes on several floors: one [`SceneSampler`] per level, on that level's view of the scene
//! ([`Scene::level_view`]: its rooms and objects only), its maps and its scene graph, and the
//! stairs as portals between the levels' navigable maps ([`MultiLevelMap`]).
//!
//! A path across floors is the walk on the start's level to the foot (or head) of a flight,
//! the flight itself (the foot, one point on each tread, the head: `y` rising on the way up)
//! and the walk on the goal's level. Its length is the route's through [`MultiLevelMap`], so
//! `info.geodesic_distance` counts the flight as [`Stairs::walk_length`].
//!
//! Single-storey homes never come here: their episodes are sampled exactly as before.

use glam::Vec2;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::sync::{Arc, OnceLock};
use vlnverse_env::geodesic::{
    polyline_length, DistanceField, GeodesicPath, LevelPoint, LevelRoute, MultiLevelMap, Portal,
    RouteLeg,
};
use vlnverse_env::occupancy::OccupancyMaps;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{LevelId, Scene, SemanticClass, Stairs};
use vlnverse_instructions::storeys::Flight;
use vlnverse_score::{DataError, Result};

use super::presets::SamplingConfig;
use super::sampler::{string_pull, Rejections, SceneSampler};
use super::seed::derive_seed;

/// One level of a home as a single-storey scene: its view, maps and graph.
pub struct LevelData {
    /// The level's view of the scene ([`Scene::level_view`]).
    pub scene: Scene,
    /// The level's maps ([`vlnverse_env::occupancy::build_level_maps`]).
    pub maps: OccupancyMaps,
    /// The graph of the level's view.
    pub graph: SceneGraph,
    /// [`LevelData::off_stairs`], built when first asked for.
    off_stairs: OnceLock<(Scene, SceneGraph)>,
}

impl LevelData {
    /// The levels of a multi-level scene from its level maps (one per level, lowest first).
    pub fn of_scene(scene: &Scene, maps: Vec<OccupancyMaps>) -> Result<Vec<LevelData>> {
        maps.into_iter()
            .enumerate()
            .map(|(k, maps)| {
                let view = scene.level_view(k as LevelId).ok_or_else(|| {
                    DataError::invalid(
                        "scene",
                        &scene.id,
                        format!("has maps of level {k} but no such level"),
                    )
                })?;
                let graph = SceneGraph::build(&view);
                Ok(LevelData {
                    scene: view,
                    maps,
                    graph,
                    off_stairs: OnceLock::new(),
                })
            })
            .collect()
    }
}

impl LevelData {
    /// The level's view without its flights of stairs, and its graph: what a walk off a flight
    /// is described on, so that it does not name the stairs it has just left as a landmark.
    pub fn off_stairs(&self) -> &(Scene, SceneGraph) {
        self.off_stairs.get_or_init(|| {
            let mut bare = self.scene.clone();
            bare.objects.retain(|o| o.class != SemanticClass::Stairs);
            let graph = SceneGraph::build(&bare);
            (bare, graph)
        })
    }
}

/// A walk on one level inside a path across floors.
#[derive(Clone, Debug, PartialEq)]
pub struct Walk {
    /// The level.
    pub level: LevelId,
    /// Index of the walk's first point in [`FloorPath::points`].
    pub first: usize,
    /// Its points on the floor `(x, z)`, first to last.
    pub points: Vec<Vec2>,
    /// Its length (m).
    pub length: f32,
}

/// A path that may cross floors.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorPath {
    /// The reference path: 3-D points, flights included.
    pub points: Vec<[f32; 3]>,
    /// Geodesic length (m), flights counted as their walk length.
    pub length: f32,
    /// The walks in order; `walks.len() == flights.len() + 1`.
    pub walks: Vec<Walk>,
    /// The flights between the walks, in order, with the heading of the walk off each one and
    /// the flight's number of steps.
    pub flights: Vec<(Flight, Vec2, u32)>,
}

impl FloorPath {
    /// Whether the path takes the stairs.
    pub fn crosses(&self) -> bool {
        !self.flights.is_empty()
    }

    /// The level of its start and of its end.
    pub fn levels(&self) -> (LevelId, LevelId) {
        let first = self.walks.first().map_or(0, |w| w.level);
        let last = self.walks.last().map_or(first, |w| w.level);
        (first, last)
    }
}

/// The points of a flight from its foot to its head: the foot, the centre of each tread at its
/// top (`y` rising by `rise` a step), the head. The flat approach before the first riser and
/// after the last is split evenly between the two ends, as the generator lays flights out.
pub fn flight_points(s: &Stairs) -> Vec<[f32; 3]> {
    let foot = Vec2::new(s.foot[0], s.foot[2]);
    let head = Vec2::new(s.head[0], s.head[2]);
    let span = foot.distance(head);
    let dir = if span > 1e-6 {
        (head - foot) / span
    } else {
        Vec2::ZERO
    };
    let treads = s.steps.saturating_sub(1);
    let flight = treads as f32 * s.run;
    let approach = ((span - flight) * 0.5).max(0.0);
    let mut out = vec![s.foot];
    for k in 1..=treads {
        let along = (approach + (k as f32 - 0.5) * s.run).min(span);
        let p = foot + dir * along;
        out.push([p.x, s.foot[1] + k as f32 * s.rise, p.y]);
    }
    out.push(s.head);
    out
}

/// How flight `p` takes a walk from level `from` to level `to`: the end entered, the end left
/// and whether it goes up; `None` when it does not join the two levels.
fn crossing(p: &Portal, from: LevelId, to: LevelId) -> Option<(LevelPoint, LevelPoint, bool)> {
    if p.lower.level == from && p.upper.level == to {
        Some((p.lower, p.upper, true))
    } else if p.upper.level == from && p.lower.level == to {
        Some((p.upper, p.lower, false))
    } else {
        None
    }
}

/// Per-level samplers of a multi-level home and the map across its floors.
pub struct Floors<'a> {
    /// The whole scene (reference images are rendered in it).
    pub scene: &'a Scene,
    /// One sampler per level, lowest first.
    pub samplers: Vec<SceneSampler<'a>>,
    /// The levels' navigable maps joined by the stairs.
    pub map: MultiLevelMap,
    /// The levels' data, lowest first.
    pub levels: &'a [LevelData],
}

impl<'a> Floors<'a> {
    /// Samplers on each level (`seed` picks the targets of each) and the map across floors.
    pub fn new(
        scene: &'a Scene,
        levels: &'a [LevelData],
        cfg: &SamplingConfig,
        seed: u64,
    ) -> Result<Self> {
        // A flight spans two floors: its goal point and the objects "next to" it may lie a floor
        // apart, so it is a landmark, never a target.
        let flights: Vec<_> = scene
            .storeys
            .stairs
            .iter()
            .filter_map(|s| s.object)
            .collect();
        let samplers = levels
            .iter()
            .enumerate()
            .map(|(k, l)| {
                let mut s = SceneSampler::new(
                    &l.scene,
                    &l.maps,
                    &l.graph,
                    cfg,
                    derive_seed(seed, &[k as u64]),
                );
                s.drop_targets(&flights);
                s
            })
            .collect();
        let portals = scene.storeys.stairs.iter().map(Portal::of_stairs).collect();
        let navs = levels.iter().map(|l| l.maps.navigable.clone()).collect();
        let map = MultiLevelMap::new(navs, portals)
            .map_err(|e| DataError::invalid("scene", &scene.id, e.to_string()))?;
        Ok(Floors {
            scene,
            samplers,
            map,
            levels,
        })
    }

    /// The rejections found while choosing targets, over every level.
    pub fn target_rejections(&self) -> Rejections {
        let mut out = Rejections::new();
        for s in &self.samplers {
            for (r, c) in &s.target_rejections {
                *out.entry(*r).or_default() += c;
            }
        }
        out
    }

    /// The floor height of a level.
    pub fn height(&self, level: LevelId) -> f32 {
        self.levels
            .get(level as usize)
            .map_or(self.scene.floor_height, |l| l.scene.floor_height)
    }

    /// The sampler of a level.
    pub fn sampler(&self, level: LevelId) -> &SceneSampler<'a> {
        &self.samplers[(level as usize).min(self.samplers.len() - 1)]
    }

    /// A level drawn uniformly.
    pub fn draw_level(&self, rng: &mut ChaCha8Rng) -> LevelId {
        rng.random_range(0..self.samplers.len()) as LevelId
    }

    /// A level other than `level`, drawn uniformly (`level` itself in a one-level home).
    pub fn other_level(&self, level: LevelId, rng: &mut ChaCha8Rng) -> LevelId {
        let n = self.samplers.len() as LevelId;
        if n < 2 {
            return level;
        }
        (level + 1 + rng.random_range(0..n - 1)) % n
    }

    /// The start and goal levels of a sample: the same level drawn uniformly, or when `cross`
    /// two different ones.
    pub fn draw_levels(&self, rng: &mut ChaCha8Rng, cross: bool) -> (LevelId, LevelId) {
        let a = self.draw_level(rng);
        let b = if cross { self.other_level(a, rng) } else { a };
        (a, b)
    }

    /// The shortest path from `a` to `b` across floors, `None` when not connected.
    pub fn path(&self, a: LevelPoint, b: LevelPoint) -> Result<Option<FloorPath>> {
        let Some(route) = self
            .map
            .shortest_route(a, b)
            .map_err(|e| DataError::invalid("scene", &self.scene.id, e.to_string()))?
        else {
            return Ok(None);
        };
        self.route_path(&route).map(Some)
    }

    /// A path from `a` to `b` on another level through one flight joining the two, found with
    /// distance fields instead of searches (sampling tries hundreds of pairs a home): from the
    /// flight's near end (a field cached per end) and towards `b` (`towards_b`, a field
    /// towards `b` such as a target's, or else the flight's far end's field read at `b`). The
    /// flight with the shortest total is taken; each walk is the field's path string-pulled,
    /// as one-level paths are. `None` when no flight joins the levels or a walk is cut off.
    pub fn path_by_fields(
        &self,
        a: LevelPoint,
        b: LevelPoint,
        towards_b: Option<&DistanceField>,
    ) -> Result<Option<FloorPath>> {
        // The best flight so far: total length, the flight, its direction, the field from its
        // near end and (without `towards_b`) the field from its far end.
        type Best<'p> = (
            f32,
            &'p Portal,
            bool,
            Arc<DistanceField>,
            Option<Arc<DistanceField>>,
        );
        let mut best: Option<Best<'_>> = None;
        for p in self.map.portals() {
            let Some((enter, leave, up)) = crossing(p, a.level, b.level) else {
                continue;
            };
            let near = self.sampler(a.level).field_at(enter.point)?;
            let Some(d1) = near.distance(a.point).meters() else {
                continue;
            };
            let far = match towards_b {
                Some(_) => None,
                None => Some(self.sampler(b.level).field_at(leave.point)?),
            };
            let d2 = match (towards_b, &far) {
                (Some(f), _) => f.distance(leave.point).meters(),
                (None, Some(f)) => f.distance(b.point).meters(),
                (None, None) => None,
            };
            let Some(d2) = d2 else { continue };
            let total = d1 + p.cost + d2;
            if best.as_ref().is_none_or(|x| total < x.0) {
                best = Some((total, p, up, near, far));
            }
        }
        let Some((_, p, up, near, far)) = best else {
            return Ok(None);
        };
        let leave = if up { p.upper } else { p.lower };
        let walk = |level: LevelId, pts: Option<GeodesicPath>, reverse: bool| {
            pts.map(|g| {
                let mut pts = g.points;
                if reverse {
                    pts.reverse();
                }
                let points = string_pull(&self.sampler(level).maps.navigable, &pts);
                let length = polyline_length(&points);
                GeodesicPath { points, length }
            })
        };
        let first = walk(a.level, near.path(a.point), false);
        let second = match (towards_b, &far) {
            (Some(f), _) => walk(b.level, f.path(leave.point), false),
            (None, Some(f)) => walk(b.level, f.path(b.point), true),
            (None, None) => None,
        };
        let (Some(first), Some(second)) = (first, second) else {
            return Ok(None);
        };
        let route = LevelRoute {
            length: first.length + p.cost + second.length,
            legs: vec![
                RouteLeg::Walk {
                    level: a.level,
                    path: first,
                },
                RouteLeg::Stairs {
                    stairs: p.stairs,
                    up,
                    length: p.cost,
                },
                RouteLeg::Walk {
                    level: b.level,
                    path: second,
                },
            ],
        };
        self.route_path(&route).map(Some)
    }

    /// A bound from below on the walk from `a` on level `from` to `b` on level `to` through
    /// one flight: straight lines to and from its ends plus its length (infinite when no flight
    /// joins the levels).
    pub fn lower_bound(&self, from: LevelId, a: Vec2, to: LevelId, b: Vec2) -> f32 {
        self.map
            .portals()
            .iter()
            .filter_map(|p| {
                let (enter, leave, _) = crossing(p, from, to)?;
                Some(a.distance(enter.point) + p.cost + leave.point.distance(b))
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// The path of a route across floors: its walks' points at their floor's height and each
    /// flight's points on the treads.
    fn route_path(&self, route: &LevelRoute) -> Result<FloorPath> {
        let mut points: Vec<[f32; 3]> = Vec::new();
        let mut walks = Vec::new();
        let mut flights = Vec::new();
        let push = |points: &mut Vec<[f32; 3]>, p: [f32; 3]| {
            if points.last() != Some(&p) {
                points.push(p);
            }
        };
        for leg in &route.legs {
            match leg {
                RouteLeg::Walk { level, path } => {
                    let y = self.height(*level);
                    let first = match path.points.first() {
                        Some(p) if points.last() == Some(&[p.x, y, p.y]) => points.len() - 1,
                        _ => points.len(),
                    };
                    for p in &path.points {
                        push(&mut points, [p.x, y, p.y]);
                    }
                    walks.push(Walk {
                        level: *level,
                        first,
                        points: path.points.clone(),
                        length: path.length,
                    });
                }
                RouteLeg::Stairs { stairs, up, .. } => {
                    let s = self
                        .scene
                        .storeys
                        .stairs
                        .iter()
                        .find(|s| s.id == *stairs)
                        .ok_or_else(|| {
                            DataError::invalid(
                                "scene",
                                &self.scene.id,
                                format!("a route takes stairs {stairs}, which it lacks"),
                            )
                        })?;
                    let mut pts = flight_points(s);
                    if !up {
                        pts.reverse();
                    }
                    let n = pts.len();
                    let off = Vec2::new(pts[n - 1][0] - pts[0][0], pts[n - 1][2] - pts[0][2]);
                    for p in pts {
                        push(&mut points, p);
                    }
                    let flight = if *up { Flight::Up } else { Flight::Down };
                    flights.push((flight, off.normalize_or_zero(), s.steps));
                }
            }
        }
        if walks.len() != flights.len() + 1 {
            return Err(DataError::invalid(
                "scene",
                &self.scene.id,
                format!(
                    "a route across floors has {} walks for {} flights",
                    walks.len(),
                    flights.len()
                ),
            ));
        }
        Ok(FloorPath {
            points,
            length: route.length,
            walks,
            flights,
        })
    }

    /// A path on one level (no stairs) from sampled 2-D points.
    pub fn on_level(&self, level: LevelId, points: &[Vec2], length: f32) -> FloorPath {
        let y = self.height(level);
        FloorPath {
            points: points.iter().map(|p| [p.x, y, p.y]).collect(),
            length,
            walks: vec![Walk {
                level,
                first: 0,
                points: points.to_vec(),
                length,
            }],
            flights: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flight_rises_one_riser_a_tread_from_foot_to_head() {
        let s = Stairs {
            id: 0,
            levels: [0, 1],
            object: None,
            footprint: Vec::new(),
            foot: [0.0, 0.0, 0.0],
            head: [0.0, 2.8, 5.2],
            steps: 16,
            rise: 0.175,
            run: 0.28,
            width: 1.0,
        };
        let pts = flight_points(&s);
        assert_eq!(pts.len(), 17);
        assert_eq!(pts[0], s.foot);
        assert_eq!(pts[16], s.head);
        for w in pts.windows(2) {
            assert!(w[1][1] > w[0][1], "y rises: {w:?}");
            assert!(w[1][2] > w[0][2], "z goes on: {w:?}");
        }
        // The last tread is one riser below the upper floor.
        assert!((pts[15][1] - (2.8 - 0.175)).abs() < 1e-4);
        // Treads are `run` apart.
        assert!((pts[2][2] - pts[1][2] - 0.28).abs() < 1e-4);
    }
}
