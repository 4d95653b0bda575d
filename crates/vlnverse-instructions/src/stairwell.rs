//! The stairwell a walk on an upper floor goes past, as people name it: by its railing or
//! banister beside the path ("with the railing on your left", "past the stairwell on your
//! right"). The railings stand round the stairwell cut out of the upper floor.

use super::describe::Viewpoint;
use super::phrases::{self as ph, pick};
use glam::Vec2;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Scene, SceneObject, SemanticClass as C};
use vlnverse_score::episode::Side;

/// How near the path a railing passed must come (m).
const NEAR: f32 = 1.0;
/// Shortest segment along which a railing is said to be passed (m).
const MIN_SEGMENT: f32 = 1.0;

/// The first railing passed on the path segments `first..=last` of `pts` (within [`NEAR`] of
/// a segment at least [`MIN_SEGMENT`] long, on its left or right), with its side.
pub(crate) fn railing_beside<'s>(
    scene: &'s Scene,
    pts: &[Vec2],
    headings: &[Vec2],
    first: usize,
    last: usize,
) -> Option<(&'s SceneObject, Side)> {
    let railings: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.class == C::Railing)
        .collect();
    if railings.is_empty() {
        return None;
    }
    for seg in first..=last.min(pts.len().saturating_sub(2)) {
        if pts[seg].distance(pts[seg + 1]) < MIN_SEGMENT {
            continue;
        }
        let view = Viewpoint {
            pts,
            headings,
            index: seg,
        };
        for &o in &railings {
            if let Some((side @ (Side::Left | Side::Right), d)) = view.side_of(o) {
                if d <= NEAR {
                    return Some((o, side));
                }
            }
        }
    }
    None
}

/// The railing passed named as people do: "the railing", "the banister", "the stairwell".
pub(crate) fn railing_np(rng: &mut ChaCha8Rng) -> String {
    pick(rng, &ph::STAIRWELL).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::{env_side, footprint, rect_distance};
    use vlnverse_env::scene_graph::side_of_heading;
    use vlnverse_env::SceneSource;

    /// Least distance from the segment `a -> b` to the rectangle `[lo, hi]` (sampled).
    fn segment_distance(a: Vec2, b: Vec2, lo: Vec2, hi: Vec2) -> f32 {
        (0..=200)
            .map(|k| rect_distance(a.lerp(b, k as f32 / 200.0), lo, hi))
            .fold(f32::INFINITY, f32::min)
    }
    use vlnverse_procgen::{HomeGenerator, Preset};

    /// An upper floor of the preset's first two-storey homes.
    fn upper_floor() -> Scene {
        let g = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
        (0..g.len())
            .map(|i| g.scene(i).unwrap())
            .find(|s| s.objects.iter().any(|o| o.class == C::Railing))
            .expect("a home with railings")
    }

    #[test]
    fn a_railing_is_passed_on_the_side_it_stands_and_only_near_the_path() {
        let scene = upper_floor();
        let r = scene
            .objects
            .iter()
            .find(|o| o.class == C::Railing)
            .unwrap();
        let (lo, hi) = footprint(r);
        let c = (lo + hi) * 0.5;
        // Walk along the railing's long side, 60 cm off it, both ways.
        let along = if hi.x - lo.x > hi.y - lo.y {
            Vec2::X
        } else {
            Vec2::Y
        };
        let off = along.perp() * ((hi - lo).dot(along.perp()).abs() * 0.5 + 0.6);
        let len = (hi - lo).dot(along).abs().max(2.0);
        let seg = |a: Vec2, b: Vec2| [a, b];
        for pts in [
            seg(c + off - along * len, c + off + along * len),
            seg(c + off + along * len, c + off - along * len),
        ] {
            let h = [(pts[1] - pts[0]).normalize()];
            let (o, side) = railing_beside(&scene, &pts, &h, 0, 0).expect("the railing passed");
            let (olo, ohi) = footprint(o);
            let mid = pts[0].lerp(pts[1], 0.5);
            assert!(segment_distance(pts[0], pts[1], olo, ohi) <= NEAR);
            if o.id == r.id {
                let seen = env_side(side_of_heading(mid, h[0], c));
                assert_eq!(side, seen);
            }
        }
        // Far from every railing, nothing.
        let far = c + off * 10.0 + Vec2::splat(50.0);
        let pts = [far, far + Vec2::X * 3.0];
        assert!(railing_beside(&scene, &pts, &[Vec2::X], 0, 0).is_none());
    }
}
