//! Viewpoint relations and footprint geometry.

use crate::scene::Aabb;
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// Where a target lies as seen from a viewpoint: four 90-degree sectors centred on the
/// viewing direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// More than 45 degrees to the left of the viewing direction, less than 135.
    Left,
    /// More than 45 degrees to the right of the viewing direction, less than 135.
    Right,
    /// Within 45 degrees of the viewing direction.
    Ahead,
    /// More than 135 degrees away from the viewing direction.
    Behind,
}

impl Side {
    /// Words used in text ("left", "ahead").
    pub fn words(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
            Side::Ahead => "ahead",
            Side::Behind => "behind",
        }
    }
}

/// Viewing direction `(x, z)` of a yaw (yaw 0 looks along -Z; counter-clockwise from above).
pub fn direction_of_yaw(yaw: f32) -> Vec2 {
    Vec2::new(-yaw.sin(), -yaw.cos())
}

/// Yaw that looks along the floor direction `dir = (x, z)` (inverse of `direction_of_yaw`).
pub fn yaw_from_direction(dir: Vec2) -> f32 {
    (-dir.x).atan2(-dir.y)
}

/// Side of `target` seen from `viewpoint` looking at `yaw`; all points are floor `(x, z)`.
/// At yaw 0 the agent looks along -Z, -X is on its left and +X on its right. A target at the
/// viewpoint itself counts as ahead.
pub fn side_of(viewpoint: Vec2, yaw: f32, target: Vec2) -> Side {
    side_of_heading(viewpoint, direction_of_yaw(yaw), target)
}

/// Like [`side_of`], with the viewing direction given as a floor vector `(x, z)` (any length;
/// a zero vector looks along -Z).
pub fn side_of_heading(viewpoint: Vec2, heading: Vec2, target: Vec2) -> Side {
    let fwd = heading.try_normalize().unwrap_or(Vec2::new(0.0, -1.0));
    // Right of a heading (x, z) is (-z, x): at -Z (0, -1) it gives +X.
    let right = Vec2::new(-fwd.y, fwd.x);
    let d = target - viewpoint;
    if d.length_squared() < 1e-12 {
        return Side::Ahead;
    }
    let (f, r) = (d.dot(fwd), d.dot(right));
    if f >= r.abs() {
        Side::Ahead
    } else if -f > r.abs() {
        Side::Behind
    } else if r > 0.0 {
        Side::Right
    } else {
        Side::Left
    }
}

/// Distance between the floor footprints (XZ rectangles) of two boxes; 0 when they overlap.
pub fn footprint_distance(a: &Aabb, b: &Aabb) -> f32 {
    let dx = (a.min[0] - b.max[0]).max(b.min[0] - a.max[0]).max(0.0);
    let dz = (a.min[2] - b.max[2]).max(b.min[2] - a.max[2]).max(0.0);
    (dx * dx + dz * dz).sqrt()
}

/// Footprint rectangle of a box as (min, max) floor points.
pub(crate) fn footprint(b: &Aabb) -> (Vec2, Vec2) {
    (Vec2::new(b.min[0], b.min[2]), Vec2::new(b.max[0], b.max[2]))
}

/// Closest point of the rectangle `[lo, hi]` to `p`.
pub(crate) fn clamp_to_rect(p: Vec2, lo: Vec2, hi: Vec2) -> Vec2 {
    p.clamp(lo, hi)
}

/// Closest pair between the segment `a..b` and the rectangle `[lo, hi]`: returns the
/// parameter `t` in `[0, 1]` of the point on the segment and the distance. When the minimum is
/// reached along a stretch (a segment parallel to a side, or crossing the rectangle), the point
/// of that stretch nearest to the rectangle's centre is returned, so that an object beside a
/// straight segment is seen square on.
pub(crate) fn segment_rect_closest(a: Vec2, b: Vec2, lo: Vec2, hi: Vec2) -> (f32, f32) {
    let d = b - a;
    let len2 = d.length_squared();
    let dist = |t: f32| {
        let p = a + d * t;
        (clamp_to_rect(p, lo, hi) - p).length()
    };
    let mut best = match segment_enters_rect(a, b, lo, hi) {
        Some(t) => (t, 0.0),
        None => {
            let mut best = (0.0f32, dist(0.0));
            let mut consider = |t: f32| {
                let dt = dist(t);
                if dt < best.1 - 1e-7 {
                    best = (t, dt);
                }
            };
            consider(1.0);
            if len2 > 1e-12 {
                for c in [lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)] {
                    consider(((c - a).dot(d) / len2).clamp(0.0, 1.0));
                }
            }
            best
        }
    };
    if len2 > 1e-12 {
        // The distance along the segment is convex, so its minimisers form an interval:
        // bisect from the best point towards the centre's projection to the interval's end.
        let center = (lo + hi) * 0.5;
        let target = ((center - a).dot(d) / len2).clamp(0.0, 1.0);
        let tol = best.1 + 1e-5;
        if dist(target) <= tol {
            best.0 = target;
        } else {
            let (mut inside, mut outside) = (best.0, target);
            for _ in 0..24 {
                let mid = 0.5 * (inside + outside);
                if dist(mid) <= tol {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            best.0 = inside;
        }
    }
    best
}

/// Parameter in `[0, 1]` where the floor segment `a..b` first touches the rectangle `[lo, hi]`
/// (slab test), if it does.
pub fn segment_enters_rect(a: Vec2, b: Vec2, lo: Vec2, hi: Vec2) -> Option<f32> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (o, v, l, h) in [(a.x, d.x, lo.x, hi.x), (a.y, d.y, lo.y, hi.y)] {
        if v.abs() < 1e-12 {
            if o < l || o > h {
                return None;
            }
        } else {
            let (mut ta, mut tb) = ((l - o) / v, (h - o) / v);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                return None;
            }
        }
    }
    Some(t0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_direction_round_trip() {
        for yaw in [-2.5f32, -1.0, 0.0, 0.7, 3.0] {
            let back = yaw_from_direction(direction_of_yaw(yaw));
            assert!((back - yaw).abs() < 1e-5, "{yaw} -> {back}");
        }
    }

    #[test]
    fn segment_rect_distance() {
        let (lo, hi) = (Vec2::new(1.0, 1.0), Vec2::new(2.0, 2.0));
        // Passing below the box at z = 0: closest at x in [1, 2], distance 1.
        let (t, d) = segment_rect_closest(Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0), lo, hi);
        assert!((d - 1.0).abs() < 1e-6);
        let x = 4.0 * t;
        assert!((1.0..=2.0).contains(&x), "x = {x}");
        // Crossing the box: distance 0, at the centre's projection x = 1.5.
        let (t, d) = segment_rect_closest(Vec2::new(0.0, 1.5), Vec2::new(4.0, 1.5), lo, hi);
        assert_eq!(d, 0.0);
        assert!((t - 0.375).abs() < 1e-6);
        // Parallel to a side: the point beside the centre, x = 1.5.
        let (t, d) = segment_rect_closest(Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0), lo, hi);
        assert!((d - 1.0).abs() < 1e-6);
        assert!((4.0 * t - 1.5).abs() < 1e-4, "t = {t}");
        // Past a corner: the corner's projection.
        let (t, d) = segment_rect_closest(Vec2::new(3.0, 0.0), Vec2::new(3.0, 4.0), lo, lo);
        assert!(
            (d - 2.0).abs() < 1e-6 && (4.0 * t - 1.0).abs() < 1e-4,
            "{t} {d}"
        );
    }
}
