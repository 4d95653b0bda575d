//! Doors counted along a walk, as people give them: "the second door on your left", "the last
//! door on your right". The door a path takes out of a room (a hallway, mostly) is counted
//! among the doorways of that room on the same side of the straight walk that leads to it.

use super::path::env_side;
use glam::Vec2;
use vlnverse_env::scene_graph::side_of_heading;
use vlnverse_env::{Door, RoomId, Scene};
use vlnverse_score::episode::Side;

/// Shortest straight walk along a hallway before a door taken off it is counted (m).
const MIN_WALK: f32 = 1.5;
/// How far the walk may stray from the straight line it is counted along (m).
const STRAY: f32 = 0.5;
/// How far from the walk's line a door in the same wall as the one taken may lie, more or
/// less than it (m).
const SAME_WALL: f32 = 0.6;
/// Least distance along the walk between two doors told apart (m).
const APART: f32 = 0.4;

/// The door a walk takes out of a room, counted along the walk.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NthDoor {
    /// 1 for the first door on that side, 2 for the second, ...
    pub ordinal: usize,
    /// Whether no other door of the room lies further along on that side.
    pub last: bool,
    /// The side of the walk the door is on (left or right).
    pub side: Side,
    /// Whether the doorway has a door leaf ("door") or not ("doorway").
    pub leaf: bool,
}

/// The straight walk through room `hall` (a hallway, mostly) that ends where the path `pts`
/// turns out of it on segment `entry` (`pts[entry]` in the room, the next room entered on the
/// way to `pts[entry + 1]`): from where the path came into the room (or started in it) to
/// `pts[entry]`. `None` when it is shorter than [`MIN_WALK`] or strays from the straight line
/// by more than [`STRAY`].
pub(crate) fn hall_walk(
    scene: &Scene,
    pts: &[Vec2],
    entry: usize,
    hall: RoomId,
) -> Option<(Vec2, Vec2)> {
    let in_hall = |p: Vec2| scene.room_at(p.x, p.y).map(|r| r.id) == Some(hall);
    let turn = *pts.get(entry)?;
    if !in_hall(turn) {
        return None;
    }
    // Back along the path while it stays in the hallway, then to where it came in.
    let mut a = entry;
    while a > 0 && in_hall(pts[a - 1]) {
        a -= 1;
    }
    let start = match a.checked_sub(1) {
        Some(b) => {
            let (p, q) = (pts[b], pts[a]);
            let steps = ((q - p).length() / 0.1).ceil().max(1.0) as usize;
            (0..=steps)
                .map(|k| p.lerp(q, k as f32 / steps as f32))
                .find(|&x| in_hall(x))
                .unwrap_or(q)
        }
        None => pts[a],
    };
    let walk = turn - start;
    if walk.length() < MIN_WALK {
        return None;
    }
    let h = walk.normalize();
    let strays = pts[a..=entry]
        .iter()
        .any(|&p| h.perp_dot(p - start).abs() > STRAY);
    (!strays).then_some((start, turn))
}

/// The door `door` that the path `pts` takes out of room `hall` on segment `entry` (see
/// [`hall_walk`]), counted among the room's doorways on the same side of the walk (in the
/// same wall, within [`SAME_WALL`] of the line it is in). Open-plan connections are neither
/// taken nor counted. `None` when there is no such walk, the door is not beside it, or
/// another door stands level with it.
pub(crate) fn nth_door(
    scene: &Scene,
    pts: &[Vec2],
    entry: usize,
    hall: RoomId,
    door: &Door,
) -> Option<NthDoor> {
    if door.open_plan {
        return None;
    }
    let (start, turn) = hall_walk(scene, pts, entry, hall)?;
    let h = (turn - start).normalize();
    let lateral = |p: Vec2| h.perp_dot(p - start);
    let along = |p: Vec2| h.dot(p - start);
    let centre = |d: &Door| Vec2::new(d.position[0], d.position[2]);
    let c = centre(door);
    let side = env_side(side_of_heading(turn, h, c));
    if !matches!(side, Side::Left | Side::Right) {
        return None;
    }
    let (t, s) = (along(c), lateral(c));
    let mates: Vec<(f32, f32)> = scene
        .doors
        .iter()
        .filter(|d| d.id != door.id && !d.open_plan && d.rooms.contains(&hall))
        .map(|d| (along(centre(d)), lateral(centre(d))))
        .filter(|&(_, sd)| sd * s > 0.0 && (sd - s).abs() < SAME_WALL)
        .collect();
    // A door level with the one taken could be either.
    if mates.iter().any(|&(td, _)| (td - t).abs() < APART) {
        return None;
    }
    let before = mates
        .iter()
        .filter(|&&(td, _)| td > APART && td < t)
        .count();
    let last = !mates.iter().any(|&(td, _)| td > t);
    Some(NthDoor {
        ordinal: before + 1,
        last,
        side,
        leaf: door.leaf.is_some(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::floor_points;
    use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
    use vlnverse_env::scene_graph::rooms_along_path;
    use vlnverse_env::{geodesic::shortest_path, SceneSource};
    use vlnverse_procgen::{HomeGenerator, Preset};

    /// Every door counted on the shortest paths between the rooms of the first homes of the
    /// preset (the tiny homes have no hallways, where most doors are counted): its side is the
    /// door's seen from the turn, and the doors before it on that side number one less than its
    /// ordinal.
    #[test]
    fn a_door_is_counted_on_its_own_side_among_the_doors_passed() {
        let g = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
        let mut counted = 0;
        let mut second = 0;
        for i in 0..16 {
            let scene = g.scene(i).unwrap();
            let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
            // A free cell of each room, the one nearest its corners' mean.
            let free: Vec<Vec2> = maps
                .navigable
                .free_cells()
                .map(|(c, r)| maps.navigable.cell_center(c, r))
                .collect();
            let centres: Vec<Vec2> = scene
                .rooms
                .iter()
                .filter_map(|r| {
                    let n = r.polygon.len() as f32;
                    let m = r.polygon.iter().map(|p| Vec2::from(*p)).sum::<Vec2>() / n;
                    free.iter()
                        .copied()
                        .filter(|p| r.contains(p.x, p.y))
                        .min_by(|a, b| a.distance(m).total_cmp(&b.distance(m)))
                })
                .collect();
            for &a in &centres {
                for &b in &centres {
                    let Ok(Some(p)) = shortest_path(&maps.navigable, a, b) else {
                        continue;
                    };
                    let path: Vec<[f32; 3]> = p.points.iter().map(|q| [q.x, 0.0, q.y]).collect();
                    let pts = floor_points(&path);
                    let path3: Vec<glam::Vec3> =
                        path.iter().map(|q| glam::Vec3::from(*q)).collect();
                    let rooms = rooms_along_path(&scene, &path3);
                    for w in rooms.windows(2) {
                        let (entry, from, to) = (w[1].0, w[0].1, w[1].1);
                        let at = pts[entry.min(pts.len() - 1)];
                        let Some(d) = crate::describe::door_between(&scene, from, to, at) else {
                            continue;
                        };
                        let Some(nth) = nth_door(&scene, &pts, entry, from, d) else {
                            continue;
                        };
                        counted += 1;
                        second += usize::from(nth.ordinal >= 2);
                        let c = Vec2::new(d.position[0], d.position[2]);
                        let (start, turn) = hall_walk(&scene, &pts, entry, from).unwrap();
                        let h = (turn - start).normalize();
                        // The side is the door's seen from the turn, facing along the walk.
                        assert_eq!(nth.side, env_side(side_of_heading(turn, h, c)));
                        assert!(nth.ordinal >= 1);
                        assert_eq!(nth.leaf, d.leaf.is_some());
                        // So many doors of the hallway lie on that side before it.
                        let lat = |q: Vec2| h.perp_dot(q - start);
                        let same = |x: &Door| {
                            let q = Vec2::new(x.position[0], x.position[2]);
                            x.id != d.id
                                && !x.open_plan
                                && x.rooms.contains(&from)
                                && lat(q) * lat(c) > 0.0
                                && (lat(q) - lat(c)).abs() < SAME_WALL
                                && h.dot(q - start) > APART
                                && h.dot(q - c) < 0.0
                        };
                        assert_eq!(
                            scene.doors.iter().filter(|x| same(x)).count() + 1,
                            nth.ordinal
                        );
                    }
                }
            }
        }
        assert!(
            counted > 0 && second > 0,
            "{counted} doors counted, {second} past the first"
        );
    }
}
