//! Landmarks seen along a path, and the rooms a path passes through.

use super::spatial::{clamp_to_rect, footprint, segment_rect_closest, side_of_heading, Side};
use super::SceneGraph;
use crate::scene::{ObjectId, RoomId, Scene, SceneObject};
use crate::vocab::{ClassKind, SemanticClass};
use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

/// Smallest bounding-box extent (m) of furniture worth naming as a landmark.
pub const LANDMARK_MIN_FURNITURE_SIZE: f32 = 0.3;
/// Smallest bounding-box extent (m) of a small object worth naming as a landmark.
pub const LANDMARK_MIN_SMALL_SIZE: f32 = 0.5;
/// The visibility test aims at the object's footprint moved this far towards the viewer, so
/// that a line-of-sight test on an occupancy map does not hit the object's own cells.
pub const SIGHT_MARGIN: f32 = 0.15;
/// Sampling step (m) along path segments when looking for room changes.
const ROOM_SAMPLE_STEP: f32 = 0.25;

/// An object seen from a path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Landmark {
    /// The object.
    pub object: ObjectId,
    /// Index of the path segment (`path[i] -> path[i + 1]`) holding the closest point, or the
    /// last index when the closest point is the end of the path.
    pub path_index: usize,
    /// Side of the object's centre seen from the closest point, facing along that segment.
    pub side: Side,
    /// Distance (m) from the closest point to the object's footprint.
    pub distance: f32,
    /// Closest path point `(x, z)`.
    pub point: Vec2,
}

/// Whether an object is worth naming along a path: furniture (not rugs, runners or doormats:
/// the agent walks over them) at least 0.3 m across (`LANDMARK_MIN_FURNITURE_SIZE`), or a small
/// object at least 0.5 m (`LANDMARK_MIN_SMALL_SIZE`); never structure or unknown.
pub fn is_landmark(o: &SceneObject) -> bool {
    let size = o.bbox.size().max_element();
    match o.class.kind() {
        ClassKind::Furniture => {
            // A rug, a runner or a doormat lies flat underfoot: walked over, not passed on a side.
            !matches!(
                o.class,
                SemanticClass::Rug | SemanticClass::Runner | SemanticClass::Doormat
            ) && size >= LANDMARK_MIN_FURNITURE_SIZE
        }
        ClassKind::Small => size >= LANDMARK_MIN_SMALL_SIZE,
        ClassKind::Structure | ClassKind::Unknown => false,
    }
}

/// Unit heading of each segment `pts[i] -> pts[i + 1]`; zero-length segments borrow a
/// neighbour's heading (-Z when every segment is degenerate).
pub fn segment_headings(pts: &[Vec2]) -> Vec<Vec2> {
    let mut h: Vec<Option<Vec2>> = pts
        .windows(2)
        .map(|w| (w[1] - w[0]).try_normalize())
        .collect();
    let mut last = None;
    for x in h.iter_mut() {
        if x.is_none() {
            *x = last;
        }
        last = *x;
    }
    let mut next = None;
    for x in h.iter_mut().rev() {
        if x.is_none() {
            *x = next;
        }
        next = *x;
    }
    h.into_iter()
        .map(|x| x.unwrap_or(Vec2::new(0.0, -1.0)))
        .collect()
}

fn floor(p: Vec3) -> Vec2 {
    Vec2::new(p.x, p.z)
}

impl SceneGraph {
    /// Landmarks along `path` (3-D points, only x and z are used): every object passing
    /// [`is_landmark`] whose footprint comes within `max_distance` of the path and that
    /// `visible(path_point, object_point)` accepts (pass the occupancy map's line of sight;
    /// the object point is the footprint's nearest point moved 0.15 m (`SIGHT_MARGIN`) towards
    /// the path). Each object is reported once, at its closest path point; sorted by path index,
    /// then distance, then id. A path of fewer than two points has no heading and no landmarks.
    pub fn landmarks_along_path(
        &self,
        scene: &Scene,
        path: &[Vec3],
        visible: impl Fn(Vec2, Vec2) -> bool,
        max_distance: f32,
    ) -> Vec<Landmark> {
        if path.len() < 2 {
            return Vec::new();
        }
        let pts: Vec<Vec2> = path.iter().map(|&p| floor(p)).collect();
        let headings = segment_headings(&pts);
        let last = pts.len() - 1;
        let mut out = Vec::new();
        for o in scene.items().filter(|o| is_landmark(o)) {
            if self.object(o.id).is_none() {
                continue;
            }
            let (lo, hi) = footprint(&o.bbox);
            // (segment, t, distance); at equal distance a segment's start beats the previous
            // segment's end, so a landmark at a corner is described after the turn.
            let mut best: Option<(usize, f32, f32)> = None;
            for (i, w) in pts.windows(2).enumerate() {
                let (t, d) = segment_rect_closest(w[0], w[1], lo, hi);
                let better = match best {
                    None => true,
                    Some((_, bt, bd)) => d < bd - 1e-5 || (d <= bd + 1e-5 && bt >= 1.0 - 1e-6),
                };
                if better {
                    best = Some((i, t, d));
                }
            }
            let Some((seg, t, distance)) = best else {
                continue;
            };
            if distance > max_distance {
                continue;
            }
            let point = pts[seg].lerp(pts[seg + 1], t);
            let near = clamp_to_rect(point, lo, hi);
            let aim = match (point - near).try_normalize() {
                Some(dir) if distance > SIGHT_MARGIN => near + dir * SIGHT_MARGIN,
                _ => point,
            };
            if !visible(point, aim) {
                continue;
            }
            let center = (lo + hi) * 0.5;
            let path_index = if seg + 1 == last && t >= 1.0 - 1e-6 {
                last
            } else {
                seg
            };
            out.push(Landmark {
                object: o.id,
                path_index,
                side: side_of_heading(point, headings[seg], center),
                distance,
                point,
            });
        }
        out.sort_by(|a, b| {
            a.path_index
                .cmp(&b.path_index)
                .then(a.distance.total_cmp(&b.distance))
                .then(a.object.cmp(&b.object))
        });
        out
    }
}

/// Rooms a path passes through, as `(path_index, room)` at each change of room: the path enters
/// `room` on the segment `path[path_index] -> path[path_index + 1]` (or at the last point).
/// Segments are sampled every 25 cm; points outside every room (doorways, wall thickness) keep
/// the previous room.
pub fn rooms_along_path(scene: &Scene, path: &[Vec3]) -> Vec<(usize, RoomId)> {
    let mut out: Vec<(usize, RoomId)> = Vec::new();
    // The level of each point from its height (always level 0 in a single-storey scene).
    let mut visit = |i: usize, p: Vec2, y: f32| {
        if let Some(r) = scene.room_at_level(scene.level_at_height(y), p.x, p.y) {
            if out.last().is_none_or(|&(_, last)| last != r.id) {
                out.push((i, r.id));
            }
        }
    };
    for (i, w) in path.windows(2).enumerate() {
        let (a, b) = (floor(w[0]), floor(w[1]));
        let steps = ((b - a).length() / ROOM_SAMPLE_STEP).ceil().max(1.0) as usize;
        for k in 0..steps {
            let t = k as f32 / steps as f32;
            visit(i, a.lerp(b, t), w[0].y + (w[1].y - w[0].y) * t);
        }
    }
    if let Some(&p) = path.last() {
        visit(path.len() - 1, floor(p), p.y);
    }
    out
}
