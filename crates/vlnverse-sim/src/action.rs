//! The three action spaces behind one enum: discrete, continuous velocity, waypoint.

use crate::error::{Result, SimError};
use serde::{Deserialize, Serialize};

/// Longest single forward move (m).
pub const MAX_FORWARD: f32 = 10.0;
/// Longest single velocity command (s).
pub const MAX_DURATION: f32 = 60.0;
/// Largest speed a velocity command may ask for before it is an error rather than clamped to
/// the agent's limits (m/s or rad/s).
pub const ABSURD_SPEED: f32 = 100.0;

/// How a waypoint is reached.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WaypointMode {
    /// Turn to face the waypoint, then move straight to it with collision handling.
    Drive,
    /// Teleport to the waypoint, then resolve it to the nearest free spot.
    TelHop,
}

/// One command to the agent. Angles in radians, distances in metres, times in seconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Action {
    /// End the episode here.
    Stop,
    /// Move along the heading by this distance (`[0, 10]` m).
    MoveForward(f32),
    /// Turn counter-clockwise (seen from above) by this angle (`[0, 2 pi]`).
    TurnLeft(f32),
    /// Turn clockwise by this angle (`[0, 2 pi]`).
    TurnRight(f32),
    /// Tilt the camera up by the agent's `look_angle_deg`.
    LookUp,
    /// Tilt the camera down by the agent's `look_angle_deg`.
    LookDown,
    /// Drive with forward speed `v` (m/s, may be negative) and yaw rate `omega` (rad/s,
    /// counter-clockwise) for `duration` seconds, through the physics engine. Speeds beyond
    /// the agent's limits are clamped; the acceleration limits apply.
    Velocity {
        /// Forward speed (m/s).
        v: f32,
        /// Yaw rate (rad/s).
        omega: f32,
        /// Duration (s), in `(0, 60]`.
        duration: f32,
    },
    /// Go to the floor point `(x, z)`.
    Waypoint {
        /// World x (m).
        x: f32,
        /// World z (m).
        z: f32,
        /// Drive there or hop there.
        mode: WaypointMode,
    },
}

impl Action {
    /// The discrete `MoveForward` of an agent (its `step_size`).
    pub fn forward(agent: &crate::AgentConfig) -> Action {
        Action::MoveForward(agent.step_size)
    }

    /// The discrete `TurnLeft` of an agent (its `turn_angle_deg`).
    pub fn left(agent: &crate::AgentConfig) -> Action {
        Action::TurnLeft(agent.turn_angle())
    }

    /// The discrete `TurnRight` of an agent (its `turn_angle_deg`).
    pub fn right(agent: &crate::AgentConfig) -> Action {
        Action::TurnRight(agent.turn_angle())
    }

    /// Reject NaN, infinite, negative or absurd parameters (scene bounds are checked by the
    /// simulator).
    pub fn validate(&self) -> Result<()> {
        match *self {
            Action::Stop | Action::LookUp | Action::LookDown => Ok(()),
            Action::MoveForward(d) => check("MoveForward.distance", d, 0.0, MAX_FORWARD),
            Action::TurnLeft(a) => check("TurnLeft.angle", a, 0.0, std::f32::consts::TAU),
            Action::TurnRight(a) => check("TurnRight.angle", a, 0.0, std::f32::consts::TAU),
            Action::Velocity { v, omega, duration } => {
                check("Velocity.v", v, -ABSURD_SPEED, ABSURD_SPEED)?;
                check("Velocity.omega", omega, -ABSURD_SPEED, ABSURD_SPEED)?;
                check("Velocity.duration", duration, 0.0, MAX_DURATION)?;
                if duration <= 0.0 {
                    return Err(SimError::action(
                        "Velocity.duration",
                        duration,
                        "must be positive",
                    ));
                }
                Ok(())
            }
            Action::Waypoint { x, z, .. } => {
                check("Waypoint.x", x, -1e6, 1e6)?;
                check("Waypoint.z", z, -1e6, 1e6)
            }
        }
    }
}

fn check(field: &str, v: f32, lo: f32, hi: f32) -> Result<()> {
    if !v.is_finite() || v < lo || v > hi {
        return Err(SimError::action(
            field,
            v,
            format!("must be finite and in [{lo}, {hi}]"),
        ));
    }
    Ok(())
}
