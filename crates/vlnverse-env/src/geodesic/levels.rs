//! Geodesic distance across the levels of a home: one navigable map per level
//! ([`crate::occupancy::build_level_maps`]) joined by the stairs as portals.
//!
//! A flight of stairs is a portal between its `foot` (on the lower level) and its `head` (on the
//! upper level) that costs [`Stairs::walk_length`]. The shortest route between two points is
//! found by Dijkstra over the two points and the portal ends, the legs on one level being
//! [`shortest_path`] queries on that level's map (computed once each, on demand). With both
//! points on one level and no stairs this is exactly [`shortest_path`] on that level.

use std::sync::{Arc, OnceLock};

use super::{check_finite, shortest_path, DistanceField, GeodesicDistance, GeodesicPath};
use crate::error::{EnvError, Result};
use crate::occupancy::{build_level_maps, GridMap, OccupancyConfig};
use crate::scene::{LevelId, Scene, Stairs};
use glam::Vec2;

/// A point on the floor of one level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelPoint {
    /// The level.
    pub level: LevelId,
    /// `(x, z)` on that level's floor.
    pub point: Vec2,
}

impl LevelPoint {
    /// A point on `level` at `(x, z)`.
    pub fn new(level: LevelId, x: f32, z: f32) -> Self {
        LevelPoint {
            level,
            point: Vec2::new(x, z),
        }
    }

    /// The point of a world position `[x, y, z]`: its level is the one whose floor is the
    /// highest at or below `y` ([`Scene::level_at_height`]).
    pub fn from_world(scene: &Scene, p: [f32; 3]) -> Self {
        LevelPoint::new(scene.level_at_height(p[1]), p[0], p[2])
    }
}

/// A stair between two levels as the route search sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Portal {
    /// Id of the stairs in the scene.
    pub stairs: u32,
    /// Where it is entered on the lower level (the foot).
    pub lower: LevelPoint,
    /// Where it is left on the upper level (the head).
    pub upper: LevelPoint,
    /// Length of the walk along it (m).
    pub cost: f32,
}

impl Portal {
    /// The portal of a flight of stairs.
    pub fn of_stairs(s: &Stairs) -> Portal {
        Portal {
            stairs: s.id,
            lower: LevelPoint::new(s.levels[0], s.foot[0], s.foot[2]),
            upper: LevelPoint::new(s.levels[1], s.head[0], s.head[2]),
            cost: s.walk_length(),
        }
    }
}

/// One piece of a route across levels.
#[derive(Clone, Debug, PartialEq)]
pub enum RouteLeg {
    /// A walk on one level's floor.
    Walk {
        /// The level.
        level: LevelId,
        /// The path on its navigable map.
        path: GeodesicPath,
    },
    /// A flight of stairs, up or down.
    Stairs {
        /// Id of the stairs.
        stairs: u32,
        /// Whether the flight is climbed (false: walked down).
        up: bool,
        /// Length of the walk along it (m).
        length: f32,
    },
}

impl RouteLeg {
    /// Length of the leg (m).
    pub fn length(&self) -> f32 {
        match self {
            RouteLeg::Walk { path, .. } => path.length,
            RouteLeg::Stairs { length, .. } => *length,
        }
    }
}

/// A shortest route across levels: its legs in order and its length.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelRoute {
    /// Walks and flights, from the start to the goal.
    pub legs: Vec<RouteLeg>,
    /// Total length (m).
    pub length: f32,
}

impl LevelRoute {
    /// How many flights of stairs the route takes.
    pub fn stairs_taken(&self) -> usize {
        self.legs
            .iter()
            .filter(|l| matches!(l, RouteLeg::Stairs { .. }))
            .count()
    }
}

/// The navigable maps of every level of a scene and the stairs between them.
#[derive(Clone, Debug)]
pub struct MultiLevelMap {
    levels: Vec<GridMap>,
    portals: Vec<Portal>,
    /// Per portal, the fields toward its `[lower, upper]` end on that end's level, built when
    /// first asked for ([`MultiLevelMap::end_field`]): they do not depend on any goal, so every
    /// goal's [`super::LevelField`] in the home shares them.
    end_fields: Vec<[OnceLock<Arc<DistanceField>>; 2]>,
}

impl MultiLevelMap {
    /// From one navigable map per level (the lowest first) and the scene's stairs. An error when
    /// a stair names a level that has no map.
    pub fn new(levels: Vec<GridMap>, portals: Vec<Portal>) -> Result<Self> {
        for p in &portals {
            for end in [p.lower, p.upper] {
                if end.level as usize >= levels.len() {
                    return Err(EnvError::invalid(
                        format!("stairs[{}].levels", p.stairs),
                        end.level,
                        format!("there are maps of {} levels", levels.len()),
                    ));
                }
                check_finite("stairs point", end.point)?;
            }
            if !(p.cost.is_finite() && p.cost >= 0.0) {
                return Err(EnvError::invalid(
                    format!("stairs[{}] walk length", p.stairs),
                    p.cost,
                    "must be a finite length",
                ));
            }
        }
        let end_fields = portals.iter().map(|_| Default::default()).collect();
        Ok(MultiLevelMap {
            levels,
            portals,
            end_fields,
        })
    }

    /// Build every level's maps of a scene ([`build_level_maps`]) and join them by its stairs.
    pub fn from_scene(scene: &Scene, cfg: &OccupancyConfig) -> Result<Self> {
        let levels = build_level_maps(scene, cfg)?
            .into_iter()
            .map(|m| m.navigable)
            .collect();
        let portals = scene.storeys.stairs.iter().map(Portal::of_stairs).collect();
        Self::new(levels, portals)
    }

    /// The navigable map of a level.
    pub fn level(&self, level: LevelId) -> Option<&GridMap> {
        self.levels.get(level as usize)
    }

    /// Number of levels.
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// The portals (stairs).
    pub fn portals(&self) -> &[Portal] {
        &self.portals
    }

    /// The distance field toward end `upper` (false: the foot on the lower level, true: the
    /// head on the upper one) of portal `portal`, on that end's level; built on first use and
    /// kept, so it is computed once per home whatever the goals. `None` for a portal index out
    /// of range.
    pub fn end_field(&self, portal: usize, upper: bool) -> Option<Arc<DistanceField>> {
        let p = self.portals.get(portal)?;
        let end = if upper { p.upper } else { p.lower };
        let cell = &self.end_fields.get(portal)?[usize::from(upper)];
        let map = self.levels.get(end.level as usize)?;
        let field = cell.get_or_init(|| {
            // `new` checked the level and that the point is finite, the only error of
            // `DistanceField::new`; were it to fail anyway, the end is unreachable.
            Arc::new(
                DistanceField::new(map, end.point)
                    .unwrap_or_else(|_| DistanceField::from_root(map, None)),
            )
        });
        Some(field.clone())
    }

    /// The fields toward the portals' ends built so far, per portal `[lower, upper]` (`None`:
    /// not built), to keep beyond this map ([`MultiLevelMap::give_end_field`]).
    pub fn built_end_fields(&self) -> Vec<[Option<Arc<DistanceField>>; 2]> {
        self.end_fields
            .iter()
            .map(|ends| ends.each_ref().map(|c| c.get().cloned()))
            .collect()
    }

    /// Give end `upper` of portal `portal` a field built earlier, by another map of the same
    /// home (a home visited again): it is taken only when it is the field
    /// [`MultiLevelMap::end_field`] would build here (on this end's level map, toward this end's
    /// point) and none is built yet. Whether it was taken.
    pub fn give_end_field(&self, portal: usize, upper: bool, field: Arc<DistanceField>) -> bool {
        let (Some(p), Some(ends)) = (self.portals.get(portal), self.end_fields.get(portal)) else {
            return false;
        };
        let end = if upper { p.upper } else { p.lower };
        let fits = self
            .levels
            .get(end.level as usize)
            .is_some_and(|map| field.goal() == Some(end.point) && field.map() == map);
        fits && ends[usize::from(upper)].set(field).is_ok()
    }

    /// Geodesic distance between two points, across levels through the stairs.
    pub fn geodesic_distance(&self, a: LevelPoint, b: LevelPoint) -> Result<GeodesicDistance> {
        Ok(match self.shortest_route(a, b)? {
            Some(r) => GeodesicDistance::Reachable(r.length),
            None => GeodesicDistance::Unreachable,
        })
    }

    /// The shortest route between two points, across levels through the stairs; `Ok(None)`
    /// when unreachable (or a point is on a level without a map). An error only for non-finite
    /// coordinates.
    pub fn shortest_route(&self, a: LevelPoint, b: LevelPoint) -> Result<Option<LevelRoute>> {
        check_finite("start", a.point)?;
        check_finite("goal", b.point)?;
        if self.level(a.level).is_none() || self.level(b.level).is_none() {
            return Ok(None);
        }
        // Nodes: 0 the start, 1 the goal, then each portal's lower and upper end.
        let mut nodes = vec![a, b];
        for p in &self.portals {
            nodes.push(p.lower);
            nodes.push(p.upper);
        }
        let n = nodes.len();
        // Walks between nodes of one level, computed when Dijkstra first needs them.
        let mut walks: Vec<Option<Option<GeodesicPath>>> = vec![None; n * n];
        let mut dist = vec![f32::INFINITY; n];
        let mut prev: Vec<Option<(usize, bool)>> = vec![None; n];
        let mut done = vec![false; n];
        dist[0] = 0.0;
        // The handful of nodes makes a linear scan the simplest priority queue; ties go to the
        // lower index, so the route does not depend on anything but the inputs.
        while let Some(u) = (0..n)
            .filter(|&i| !done[i] && dist[i].is_finite())
            .min_by(|&i, &j| dist[i].total_cmp(&dist[j]).then(i.cmp(&j)))
        {
            done[u] = true;
            if u == 1 {
                break;
            }
            for v in 0..n {
                if done[v] || v == u {
                    continue;
                }
                // The portal edge between the two ends of one stair.
                if u >= 2 && v >= 2 && (u - 2) / 2 == (v - 2) / 2 {
                    let cost = self.portals[(u - 2) / 2].cost;
                    if dist[u] + cost < dist[v] {
                        dist[v] = dist[u] + cost;
                        prev[v] = Some((u, true));
                    }
                    continue;
                }
                if nodes[u].level != nodes[v].level {
                    continue;
                }
                let k = u * n + v;
                if walks[k].is_none() {
                    let map = &self.levels[nodes[u].level as usize];
                    walks[k] = Some(shortest_path(map, nodes[u].point, nodes[v].point)?);
                }
                if let Some(Some(p)) = &walks[k] {
                    if dist[u] + p.length < dist[v] {
                        dist[v] = dist[u] + p.length;
                        prev[v] = Some((u, false));
                    }
                }
            }
        }
        if !dist[1].is_finite() {
            return Ok(None);
        }
        let mut legs = Vec::new();
        let mut v = 1;
        while let Some((u, stair)) = prev[v] {
            if stair {
                let p = &self.portals[(u - 2) / 2];
                legs.push(RouteLeg::Stairs {
                    stairs: p.stairs,
                    up: (u - 2) % 2 == 0,
                    length: p.cost,
                });
            } else if let Some(Some(path)) = walks[u * n + v].take() {
                legs.push(RouteLeg::Walk {
                    level: nodes[u].level,
                    path,
                });
            }
            v = u;
        }
        legs.reverse();
        if legs.is_empty() {
            // Start and goal share a cell and the search never walked: the direct path.
            if let Some(path) = shortest_path(&self.levels[a.level as usize], a.point, b.point)? {
                legs.push(RouteLeg::Walk {
                    level: a.level,
                    path,
                });
            }
        }
        let length = legs.iter().map(RouteLeg::length).sum();
        Ok(Some(LevelRoute { legs, length }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::occupancy::CellState;

    fn open(w: u32) -> GridMap {
        GridMap::new(w, w, 0.1, Vec2::ZERO, CellState::Free).unwrap()
    }

    fn portal(foot: Vec2, head: Vec2, cost: f32) -> Portal {
        Portal {
            stairs: 0,
            lower: LevelPoint {
                level: 0,
                point: foot,
            },
            upper: LevelPoint {
                level: 1,
                point: head,
            },
            cost,
        }
    }

    #[test]
    fn across_levels_the_route_is_walk_stairs_walk() {
        let (foot, head) = (Vec2::new(1.0, 1.0), Vec2::new(8.0, 8.0));
        let m =
            MultiLevelMap::new(vec![open(100), open(100)], vec![portal(foot, head, 5.0)]).unwrap();
        let a = LevelPoint::new(0, 0.5, 0.5);
        let b = LevelPoint::new(1, 9.0, 9.0);
        let r = m.shortest_route(a, b).unwrap().unwrap();
        let want = a.point.distance(foot) + 5.0 + head.distance(b.point);
        assert!((r.length - want).abs() < 1e-4, "{} vs {want}", r.length);
        assert_eq!(r.legs.len(), 3);
        assert!(matches!(r.legs[1], RouteLeg::Stairs { up: true, .. }));
        // Down again: the same length, the flight walked down.
        let back = m.shortest_route(b, a).unwrap().unwrap();
        assert!((back.length - want).abs() < 1e-4);
        assert!(matches!(back.legs[1], RouteLeg::Stairs { up: false, .. }));
        // On one level the stairs are never a shortcut to take twice.
        let c = LevelPoint::new(0, 9.0, 9.0);
        let d = m.geodesic_distance(a, c).unwrap().meters().unwrap();
        assert!((d - a.point.distance(c.point)).abs() < 1e-4);
    }

    #[test]
    fn without_stairs_the_upper_level_is_unreachable_and_bad_levels_are_refused() {
        let m = MultiLevelMap::new(vec![open(20), open(20)], vec![]).unwrap();
        let a = LevelPoint::new(0, 0.5, 0.5);
        assert_eq!(
            m.geodesic_distance(a, LevelPoint::new(1, 1.0, 1.0))
                .unwrap(),
            GeodesicDistance::Unreachable
        );
        assert_eq!(
            m.geodesic_distance(a, LevelPoint::new(5, 1.0, 1.0))
                .unwrap(),
            GeodesicDistance::Unreachable
        );
        assert!(m
            .geodesic_distance(a, LevelPoint::new(0, f32::NAN, 1.0))
            .is_err());
        let bad = portal(Vec2::ONE, Vec2::ONE, 1.0);
        let e = MultiLevelMap::new(vec![open(20)], vec![bad])
            .unwrap_err()
            .to_string();
        assert!(e.contains("stairs[0].levels"), "{e}");
    }
}
