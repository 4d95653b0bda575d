//! The geodesic distance to one goal from anywhere in a home on several floors, and the way
//! there: what an evaluation needs per goal (scoring, the teacher) where [`DistanceField`] serves
//! a single floor.
//!
//! A point is placed on a level by its height (the highest floor at or below it, with a 0.25 m
//! tolerance, as [`crate::Scene::level_at_height`]), or on a flight when it stands over the
//! flight's run between the two floors. Its distance to the goal is the least of: the walk on
//! the goal's level (when it is on it), and for each end of a flight on its level the walk to
//! that end plus the flight plus the distance from the flight's other end to the goal
//! ([`MultiLevelMap::geodesic_distance`]). On a flight it is the rest of the flight either way
//! plus the distance from that end. A point on the wrong floor right below the goal is thus far
//! from it: a success radius counts on the goal's floor only.

use std::sync::Arc;

use glam::Vec2;

use super::{DistanceField, GeodesicDistance, LevelPoint, MultiLevelMap};
use crate::error::Result;
use crate::scene::LevelId;

/// Extra half-width around a flight's walking line inside which a point counts as on it (m).
const FLIGHT_MARGIN: f32 = 0.35;
/// How far ahead along a flight's line [`Guide::Flight::aim`] lies (m).
const AIM_AHEAD: f32 = 0.5;
/// Height above the lower floor and below the upper one from which a point over a flight's run
/// stands on the flight (m; a tread is at least a riser above the floor).
const ON_FLIGHT: f32 = 0.05;
/// Height tolerance of a level's floor (m), as `Scene::level_at_height`.
const FLOOR_TOLERANCE: f32 = 0.25;

/// Where to go next from a point, toward the goal.
#[derive(Clone, Debug)]
pub enum Guide {
    /// Walk on the current level down this field (toward the goal on the goal's level, or
    /// toward the end of the flight to take), `rest` metres more from its target to the goal.
    Walk {
        /// The field to follow on this level.
        field: Arc<DistanceField>,
        /// Distance from the field's target to the goal (0 on the goal's level).
        rest: f32,
    },
    /// Take the flight: walk straight toward `to` (its other end, in plan) on the flight.
    Flight {
        /// Id of the stairs.
        stairs: u32,
        /// Whether the flight is climbed.
        up: bool,
        /// The end the walk on the flight heads for `(x, z)`.
        to: Vec2,
        /// Where to walk now `(x, z)`: a point on the flight's line a little ahead of the
        /// point's place along it, so a walk that started off the line comes back onto it
        /// before the body meets the flight's sides.
        aim: Vec2,
        /// Height of the floor at `to`.
        to_height: f32,
    },
}

/// One end of a flight as a way to the goal.
#[derive(Clone, Debug)]
struct Exit {
    /// The level of this end.
    level: LevelId,
    /// Index of the portal.
    portal: usize,
    /// Whether this end is the foot (the flight is then climbed).
    foot: bool,
    /// The field on `level` toward this end.
    field: Arc<DistanceField>,
    /// From this end to the goal: the flight and the rest (m).
    rest: f32,
}

/// Distance to one goal across the floors of a home (see the module notes).
#[derive(Clone, Debug)]
pub struct LevelField {
    heights: Vec<f32>,
    goal_level: LevelId,
    goal: Arc<DistanceField>,
    exits: Vec<Exit>,
    /// Per portal: the flight's ends `[foot, head]` in plan, their floor heights, its half
    /// width, its cost, and the distance from each end to the goal.
    flights: Vec<FlightInfo>,
}

#[derive(Clone, Debug)]
struct FlightInfo {
    stairs: u32,
    ends: [Vec2; 2],
    heights: [f32; 2],
    half_width: f32,
    cost: f32,
    to_goal: [Option<f32>; 2],
}

impl FlightInfo {
    /// The point [`AIM_AHEAD`] along the flight's line (up: toward the head) from `q`'s
    /// projection on it, within the line's ends.
    fn aim(&self, q: Vec2, up: bool) -> Vec2 {
        let (a, b) = (self.ends[0], self.ends[1]);
        let ab = b - a;
        let len = ab.length();
        if len < 1e-6 {
            return b;
        }
        let t = (q - a).dot(ab) / (len * len);
        let step = AIM_AHEAD / len;
        let t = if up { t + step } else { t - step };
        a + ab * t.clamp(0.0, 1.0)
    }
}

/// The navigable map of the goal's level; an error naming the level when `map` has none.
fn goal_map(map: &MultiLevelMap, goal: LevelPoint) -> Result<&crate::occupancy::GridMap> {
    map.level(goal.level).ok_or_else(|| {
        crate::EnvError::invalid(
            "goal level",
            goal.level,
            format!("the scene has {} levels", map.level_count()),
        )
    })
}

impl LevelField {
    /// The field toward `goal` in `map`; `heights` are the levels' floor heights (lowest first)
    /// and `half_widths` each portal's half width (m), in the order of `map.portals()`.
    pub fn new(
        map: &MultiLevelMap,
        heights: &[f32],
        half_widths: &[f32],
        goal: LevelPoint,
    ) -> Result<LevelField> {
        let goal_field = Arc::new(DistanceField::new(goal_map(map, goal)?, goal.point)?);
        Self::with_goal_field(map, heights, half_widths, goal, goal_field)
    }

    /// [`LevelField::new`] with the goal's field on its level already built (e.g. cached by
    /// an evaluation): `goal_field` must be `DistanceField::new(level map, goal.point)` on the
    /// map of `goal.level`. The fields toward the stairs' ends come from `map`, which builds
    /// each once ([`MultiLevelMap::end_field`]), so a new goal costs no sweep at all here.
    pub fn with_goal_field(
        map: &MultiLevelMap,
        heights: &[f32],
        half_widths: &[f32],
        goal: LevelPoint,
        goal_field: Arc<DistanceField>,
    ) -> Result<LevelField> {
        goal_map(map, goal)?;
        let mut exits = Vec::new();
        let mut flights = Vec::new();
        for (i, p) in map.portals().iter().enumerate() {
            let d = |end: LevelPoint| -> Result<Option<f32>> {
                Ok(map.geodesic_distance(end, goal)?.meters())
            };
            let to_goal = [d(p.lower)?, d(p.upper)?];
            for (foot, here, other) in [(true, p.lower, 1), (false, p.upper, 0)] {
                let Some(beyond) = to_goal[other] else {
                    continue;
                };
                let Some(field) = map.end_field(i, !foot) else {
                    continue;
                };
                exits.push(Exit {
                    level: here.level,
                    portal: i,
                    foot,
                    field,
                    rest: p.cost + beyond,
                });
            }
            let h = |l: LevelId| heights.get(l as usize).copied().unwrap_or(0.0);
            flights.push(FlightInfo {
                stairs: p.stairs,
                ends: [p.lower.point, p.upper.point],
                heights: [h(p.lower.level), h(p.upper.level)],
                half_width: half_widths.get(i).copied().unwrap_or(0.5),
                cost: p.cost,
                to_goal,
            });
        }
        Ok(LevelField {
            heights: heights.to_vec(),
            goal_level: goal.level,
            goal: goal_field,
            exits,
            flights,
        })
    }

    /// The level of a point at height `y`.
    pub fn level_at(&self, y: f32) -> LevelId {
        let mut out = 0;
        for (k, h) in self.heights.iter().enumerate() {
            if *h <= y + FLOOR_TOLERANCE {
                out = k as LevelId;
            }
        }
        out
    }

    /// The goal's level.
    pub fn goal_level(&self) -> LevelId {
        self.goal_level
    }

    /// The field on the goal's level.
    pub fn goal_field(&self) -> &Arc<DistanceField> {
        &self.goal
    }

    /// Where along flight `i` a point stands: `t` in [0, 1] from foot to head, when it is over
    /// the flight's run and between its two floors (not on either; with `floors`, on either
    /// too).
    fn on_flight(&self, i: usize, p: [f32; 3], floors: bool) -> Option<f32> {
        let f = &self.flights[i];
        let (a, b) = (f.ends[0], f.ends[1]);
        let q = Vec2::new(p[0], p[2]);
        let ab = b - a;
        let len2 = ab.length_squared();
        if len2 < 1e-8 {
            return None;
        }
        let t = (q - a).dot(ab) / len2;
        if !(0.0..=1.0).contains(&t) {
            return None;
        }
        let off = q.distance(a + ab * t);
        let between = if floors {
            p[1] > f.heights[0] - FLOOR_TOLERANCE && p[1] < f.heights[1] + FLOOR_TOLERANCE
        } else {
            p[1] > f.heights[0] + ON_FLIGHT && p[1] < f.heights[1] - ON_FLIGHT
        };
        (off <= f.half_width + FLIGHT_MARGIN && between).then_some(t)
    }

    /// The candidates from a point: (distance, guide). On a flight, its two ways; on a floor,
    /// the walk to the goal and to each flight's end on this floor; off the floor's map (the
    /// step between a floor and a flight's end, over the flight's run), the flight's ways.
    fn options(&self, p: [f32; 3]) -> Vec<(f32, Guide)> {
        let out = self.flight_options(p, false);
        if !out.is_empty() {
            return out;
        }
        let out = self.floor_options(p);
        if !out.is_empty() {
            return out;
        }
        self.flight_options(p, true)
    }

    /// Both ways along each flight the point stands on ([`Self::on_flight`]).
    fn flight_options(&self, p: [f32; 3], floors: bool) -> Vec<(f32, Guide)> {
        let mut out = Vec::new();
        for (i, f) in self.flights.iter().enumerate() {
            if let Some(t) = self.on_flight(i, p, floors) {
                for (end, rest, share, up) in [
                    (1, f.to_goal[1], 1.0 - t, true),
                    (0, f.to_goal[0], t, false),
                ] {
                    if let Some(r) = rest {
                        out.push((
                            share * f.cost + r,
                            Guide::Flight {
                                stairs: f.stairs,
                                up,
                                to: f.ends[end],
                                aim: f.aim(Vec2::new(p[0], p[2]), up),
                                to_height: f.heights[end],
                            },
                        ));
                    }
                }
            }
        }
        out
    }

    /// The walk on the point's floor to the goal and to each flight's end there.
    fn floor_options(&self, p: [f32; 3]) -> Vec<(f32, Guide)> {
        let q = Vec2::new(p[0], p[2]);
        let mut out = Vec::new();
        let level = self.level_at(p[1]);
        if level == self.goal_level {
            if let Some(d) = self.goal.distance(q).meters() {
                out.push((
                    d,
                    Guide::Walk {
                        field: self.goal.clone(),
                        rest: 0.0,
                    },
                ));
            }
        }
        for e in self.exits.iter().filter(|e| e.level == level) {
            let Some(d) = e.field.distance(q).meters() else {
                continue;
            };
            let f = &self.flights[e.portal];
            let (here, there) = if e.foot { (0, 1) } else { (1, 0) };
            // At the end (within a few centimetres): step onto the flight.
            let guide = if q.distance(f.ends[here]) < 0.3 || d < 0.3 {
                Guide::Flight {
                    stairs: f.stairs,
                    up: e.foot,
                    to: f.ends[there],
                    aim: f.aim(q, e.foot),
                    to_height: f.heights[there],
                }
            } else {
                Guide::Walk {
                    field: e.field.clone(),
                    rest: e.rest,
                }
            };
            out.push((d + e.rest, guide));
        }
        out
    }

    /// Geodesic distance from the 3-D point `p` to the goal, across floors.
    pub fn distance(&self, p: [f32; 3]) -> GeodesicDistance {
        match self
            .options(p)
            .into_iter()
            .map(|o| o.0)
            .min_by(f32::total_cmp)
        {
            Some(d) => GeodesicDistance::Reachable(d),
            None => GeodesicDistance::Unreachable,
        }
    }

    /// Where to head from `p` on a shortest way to the goal; `None` when unreachable.
    pub fn guide(&self, p: [f32; 3]) -> Option<Guide> {
        self.options(p)
            .into_iter()
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|o| o.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::Portal;
    use crate::occupancy::{CellState, GridMap};

    /// Two 6 m floors, a wall across each with a gap, one flight between them.
    fn two_floors() -> MultiLevelMap {
        let floor = || {
            let mut m = GridMap::new(60, 60, 0.1, Vec2::ZERO, CellState::Free).unwrap();
            for col in 0..45 {
                m.set(col, 30, CellState::Occupied);
            }
            m
        };
        let portal = Portal {
            stairs: 7,
            lower: LevelPoint::new(0, 1.0, 5.0),
            upper: LevelPoint::new(1, 5.0, 1.0),
            cost: 4.0,
        };
        MultiLevelMap::new(vec![floor(), floor()], vec![portal]).unwrap()
    }

    fn probes() -> Vec<[f32; 3]> {
        let mut out = Vec::new();
        for y in [0.0, 1.5, 3.0] {
            for i in 0..12 {
                for j in 0..12 {
                    out.push([0.25 + 0.5 * i as f32, y, 0.25 + 0.5 * j as f32]);
                }
            }
        }
        out
    }

    #[test]
    fn a_given_goal_field_and_shared_stair_fields_give_the_same_field() {
        let heights = [0.0, 3.0];
        let half = [0.5];
        for goal in [LevelPoint::new(1, 2.0, 5.0), LevelPoint::new(0, 5.5, 0.5)] {
            // Alone on a fresh map, as before the sharing.
            let alone = LevelField::new(&two_floors(), &heights, &half, goal).unwrap();
            let shared_map = two_floors();
            // Another goal first, so the stairs' fields are already built.
            LevelField::new(&shared_map, &heights, &half, LevelPoint::new(0, 0.5, 0.5)).unwrap();
            let level = shared_map.level(goal.level).unwrap();
            let given = Arc::new(DistanceField::new(level, goal.point).unwrap());
            let shared =
                LevelField::with_goal_field(&shared_map, &heights, &half, goal, given).unwrap();
            for p in probes() {
                assert_eq!(alone.distance(p), shared.distance(p), "at {p:?}");
                let kind = |g: Option<Guide>| {
                    g.map(|g| match g {
                        Guide::Walk { rest, .. } => (0, rest.to_bits()),
                        Guide::Flight { up, aim, .. } => (1 + u32::from(up), aim.x.to_bits()),
                    })
                };
                assert_eq!(kind(alone.guide(p)), kind(shared.guide(p)), "at {p:?}");
            }
            assert!(alone.distance([0.5, 3.0, 5.5]).meters().is_some());
        }
    }

    #[test]
    fn the_stairs_fields_are_built_once_per_map() {
        let m = two_floors();
        let a = LevelField::new(&m, &[0.0, 3.0], &[0.5], LevelPoint::new(1, 2.0, 5.0)).unwrap();
        let b = LevelField::new(&m, &[0.0, 3.0], &[0.5], LevelPoint::new(1, 4.0, 5.5)).unwrap();
        // Both ends of the flight lead to either goal: the same two fields in both.
        assert_eq!((a.exits.len(), b.exits.len()), (2, 2));
        for (x, y) in a.exits.iter().zip(&b.exits) {
            assert!(Arc::ptr_eq(&x.field, &y.field));
            assert!(Arc::ptr_eq(&x.field, &m.end_field(0, !x.foot).unwrap()));
        }
        assert_eq!(
            m.end_field(0, false).unwrap().goal(),
            Some(Vec2::new(1.0, 5.0))
        );
        assert!(m.end_field(1, false).is_none());
    }

    #[test]
    fn a_goal_on_a_missing_level_is_an_error_naming_it() {
        let m = two_floors();
        let field = m.end_field(0, true).unwrap();
        let e = LevelField::with_goal_field(
            &m,
            &[0.0, 3.0],
            &[0.5],
            LevelPoint::new(4, 1.0, 1.0),
            field,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("goal level") && e.contains('4'), "{e}");
    }
}
