//! Python's action encodings and the simulator's [`Action`].
//!
//! - discrete: an integer in VLN-CE's order: 0 stop, 1 move forward, 2 turn left, 3 turn
//!   right, 4 look up, 5 look down, 6 ask (dialogue only: "which way?");
//! - continuous: `[v, omega, stop]`, forward speed (m/s) and yaw rate (rad/s, counter-
//!   clockwise) held for one control period; `stop >= 0.5` stops;
//! - waypoint: `[x, z, stop]`, a floor point in world coordinates, driven to (Strict,
//!   lenient) or hopped to (Tel-Hop); `stop >= 0.5` stops.

use vlnverse_sim::{Action, AgentConfig, WaypointMode};
use vlnverse_task::eval::agents::CONTROL_PERIOD;
use vlnverse_task::eval::{ActionSpace, EnvAction, Setting};

/// The question a discrete `ask` (id 6) puts to the oracle.
pub const ASK_QUESTION: &str = "which way?";

/// Discrete actions offered (7 with `ask`).
pub fn discrete_count(ask: bool) -> usize {
    if ask {
        7
    } else {
        6
    }
}

/// How one batch's actions are read.
#[derive(Debug, Clone)]
pub struct Codec {
    pub space: ActionSpace,
    pub setting: Setting,
    pub agent: AgentConfig,
    pub ask: bool,
}

impl Codec {
    /// A discrete id as an action; errors name the value.
    pub fn discrete(&self, env: usize, id: i64) -> Result<EnvAction, String> {
        let a = &self.agent;
        Ok(EnvAction::Act(match id {
            0 => Action::Stop,
            1 => Action::forward(a),
            2 => Action::left(a),
            3 => Action::right(a),
            4 => Action::LookUp,
            5 => Action::LookDown,
            6 if self.ask => return Ok(EnvAction::Ask(ASK_QUESTION.into())),
            _ => {
                return Err(format!(
                    "actions[{env}] = {id}: not in Discrete({}) (0 stop, 1 forward, 2 left, \
                     3 right, 4 look up, 5 look down{})",
                    discrete_count(self.ask),
                    if self.ask { ", 6 ask" } else { "" }
                ))
            }
        }))
    }

    /// A `[a, b, stop]` row as an action; NaN or infinity is an error naming the value.
    pub fn boxed(&self, env: usize, row: &[f32]) -> Result<EnvAction, String> {
        if row.len() != 3 {
            return Err(format!(
                "actions[{env}] has {} values, expected 3",
                row.len()
            ));
        }
        if let Some(i) = row.iter().position(|v| !v.is_finite()) {
            return Err(format!(
                "actions[{env}][{i}] = {}: actions must be finite numbers",
                row[i]
            ));
        }
        if row[2] >= 0.5 {
            return Ok(EnvAction::Act(Action::Stop));
        }
        Ok(EnvAction::Act(match self.space {
            ActionSpace::Continuous => Action::Velocity {
                v: row[0],
                omega: row[1],
                duration: CONTROL_PERIOD,
            },
            _ => Action::Waypoint {
                x: row[0],
                z: row[1],
                mode: if self.setting == Setting::Telhop {
                    WaypointMode::TelHop
                } else {
                    WaypointMode::Drive
                },
            },
        }))
    }

    /// The teacher's action in Python's encoding: a discrete id, or a `[a, b, stop]` row
    /// (`pos` = the agent's floor point, for a discrete move in a box space).
    pub fn encode(&self, a: &Action) -> Encoded {
        match self.space {
            ActionSpace::Discrete => Encoded::Id(match a {
                Action::Stop => 0,
                Action::MoveForward(_) => 1,
                Action::TurnLeft(_) => 2,
                Action::TurnRight(_) => 3,
                Action::LookUp => 4,
                Action::LookDown => 5,
                // Not produced by the teacher in the discrete space.
                Action::Velocity { .. } | Action::Waypoint { .. } => 0,
            }),
            _ => Encoded::Row(match *a {
                Action::Stop => [0.0, 0.0, 1.0],
                Action::Velocity { v, omega, .. } => [v, omega, 0.0],
                Action::Waypoint { x, z, .. } => [x, z, 0.0],
                // Not produced by the teacher in the box spaces: no motion.
                _ => [0.0, 0.0, 0.0],
            }),
        }
    }
}

/// An encoded teacher action.
pub enum Encoded {
    Id(i64),
    Row([f32; 3]),
}
