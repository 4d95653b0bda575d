//! Route geometry in the words of directions: headings along a path, named turns and sides.
//! Shared by the instruction generator and the dialogue oracle, which both describe a route.

use crate::episode::Side;
use glam::Vec2;
use serde::{Deserialize, Serialize};
use vlnverse_env::scene_graph::Side as EnvSide;

/// Floor points `(x, z)` of 3-D path points.
pub fn floor_points(path: &[[f32; 3]]) -> Vec<Vec2> {
    path.iter().map(|p| Vec2::new(p[0], p[2])).collect()
}

/// Signed turn angle in degrees from heading `from` to heading `to`: positive to the right,
/// negative to the left, in `[-180, 180]`.
pub fn signed_turn_deg(from: Vec2, to: Vec2) -> f32 {
    let f = from.try_normalize().unwrap_or(Vec2::new(0.0, -1.0));
    // Right of a heading (x, z) is (-z, x) (as in the scene graph's `side_of`).
    let right = Vec2::new(-f.y, f.x);
    to.dot(right).atan2(to.dot(f)).to_degrees()
}

/// Angle thresholds (degrees) that name a change of heading.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TurnConfig {
    /// Below this the walk counts as straight on.
    pub slight_deg: f32,
    /// From `slight_deg` to this: a slight turn; above: a turn.
    pub turn_deg: f32,
    /// From this on: turning around.
    pub around_deg: f32,
}

impl Default for TurnConfig {
    fn default() -> Self {
        TurnConfig {
            slight_deg: 25.0,
            turn_deg: 65.0,
            around_deg: 150.0,
        }
    }
}

/// A named change of heading.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Turn {
    /// No turn worth naming.
    Straight,
    /// A slight turn; the side is [`Side::Left`] or [`Side::Right`].
    Slight(Side),
    /// A clear turn; the side is [`Side::Left`] or [`Side::Right`].
    Turn(Side),
    /// Turning around.
    Around,
}

/// Name the change of heading from `from` to `to`.
pub fn classify_turn(from: Vec2, to: Vec2, cfg: &TurnConfig) -> Turn {
    let a = signed_turn_deg(from, to);
    let side = if a > 0.0 { Side::Right } else { Side::Left };
    let m = a.abs();
    if m < cfg.slight_deg {
        Turn::Straight
    } else if m < cfg.turn_deg {
        Turn::Slight(side)
    } else if m < cfg.around_deg {
        Turn::Turn(side)
    } else {
        Turn::Around
    }
}

/// The task layer's side of the scene graph's side.
pub fn env_side(s: EnvSide) -> Side {
    match s {
        EnvSide::Left => Side::Left,
        EnvSide::Right => Side::Right,
        EnvSide::Ahead => Side::Ahead,
        EnvSide::Behind => Side::Behind,
    }
}

/// Word for a left / right side ("left", "right"; "ahead", "behind" otherwise).
pub fn side_word(s: Side) -> &'static str {
    match s {
        Side::Left => "left",
        Side::Right => "right",
        Side::Ahead => "ahead",
        Side::Behind => "behind",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turn_signs_follow_side_of() {
        // Heading -Z; +X is on the right, so turning towards +X is a right turn.
        let fwd = Vec2::new(0.0, -1.0);
        let cfg = TurnConfig::default();
        assert_eq!(
            classify_turn(fwd, Vec2::new(1.0, 0.0), &cfg),
            Turn::Turn(Side::Right)
        );
        assert_eq!(
            classify_turn(fwd, Vec2::new(-1.0, 0.0), &cfg),
            Turn::Turn(Side::Left)
        );
        assert_eq!(
            classify_turn(fwd, Vec2::new(0.6, -1.0), &cfg),
            Turn::Slight(Side::Right)
        );
        assert_eq!(classify_turn(fwd, Vec2::new(0.0, 1.0), &cfg), Turn::Around);
        assert_eq!(classify_turn(fwd, fwd, &cfg), Turn::Straight);
        // Consistent with the scene graph's side_of for the same heading.
        let s = vlnverse_env::scene_graph::side_of_heading(Vec2::ZERO, fwd, Vec2::new(1.0, 0.0));
        assert_eq!(env_side(s), Side::Right);
    }
}
