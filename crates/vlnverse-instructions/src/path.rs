//! Path geometry of the generators and the grounding check: walls, visibility, footprints.

use glam::Vec2;
use vlnverse_env::occupancy::GridMap;
pub(crate) use vlnverse_env::scene_graph::{direction_of_yaw, segment_headings};
use vlnverse_env::Scene;
pub(crate) use vlnverse_score::route::{
    classify_turn, env_side, floor_points, side_word, signed_turn_deg, Turn, TurnConfig,
};

/// Whether the segment `a..b` crosses the rectangle `[lo, hi]` (slab test).
pub(crate) fn segment_hits_rect(a: Vec2, b: Vec2, lo: Vec2, hi: Vec2) -> bool {
    vlnverse_env::scene_graph::segment_enters_rect(a, b, lo, hi).is_some()
}

/// Footprints `(min, max)` of the scene's walls.
pub(crate) fn wall_rects(scene: &Scene) -> Vec<(Vec2, Vec2)> {
    scene
        .objects
        .iter()
        .filter(|o| o.class == vlnverse_env::SemanticClass::Wall)
        .map(|o| {
            (
                Vec2::new(o.bbox.min[0], o.bbox.min[2]),
                Vec2::new(o.bbox.max[0], o.bbox.max[2]),
            )
        })
        .collect()
}

/// Whether `b` (a point just in front of an object) can be seen from the path point `a`: the
/// navigable map is free along the sight line except its last `slack` metres (the navigable map
/// is dilated by the agent radius around every obstacle, the object included), and no wall
/// footprint crosses it.
pub(crate) fn visible(map: &GridMap, walls: &[(Vec2, Vec2)], a: Vec2, b: Vec2, slack: f32) -> bool {
    if walls
        .iter()
        .any(|&(lo, hi)| segment_hits_rect(a, b, lo, hi))
    {
        return false;
    }
    let d = b - a;
    let len = d.length();
    if len <= slack {
        return true;
    }
    map.line_of_sight(a, a + d * ((len - slack) / len))
}

/// Distance from `p` to the rectangle `[lo, hi]`.
pub(crate) fn rect_distance(p: Vec2, lo: Vec2, hi: Vec2) -> f32 {
    (p.clamp(lo, hi) - p).length()
}

/// Footprint `(min, max)` of an object's box.
pub(crate) fn footprint(o: &vlnverse_env::SceneObject) -> (Vec2, Vec2) {
    (
        Vec2::new(o.bbox.min[0], o.bbox.min[2]),
        Vec2::new(o.bbox.max[0], o.bbox.max[2]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_rect_crossing() {
        let (lo, hi) = (Vec2::new(1.0, -1.0), Vec2::new(1.1, 1.0));
        assert!(segment_hits_rect(Vec2::ZERO, Vec2::new(2.0, 0.0), lo, hi));
        assert!(!segment_hits_rect(Vec2::ZERO, Vec2::new(0.9, 0.0), lo, hi));
        assert!(!segment_hits_rect(
            Vec2::new(0.0, 2.0),
            Vec2::new(2.0, 2.0),
            lo,
            hi
        ));
    }
}
