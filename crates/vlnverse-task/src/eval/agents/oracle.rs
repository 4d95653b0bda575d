//! `oracle`: follows the geodesic shortest path to each goal (the upper bound of the table).
//!
//! Discrete space: turn toward the next waypoint of the goal's distance field until the heading
//! is within half a turn step, then move forward. Waypoint space: one waypoint action per
//! line-of-sight segment (a hop in Tel-Hop, a drive otherwise). It stops once the geodesic
//! distance to the goal is below `stop_within` (min(1 m, half the success distance)), so the
//! stop lands safely inside the success radius; long-horizon episodes get one STOP per goal.

use std::sync::Arc;

use glam::Vec2;
use vlnverse_env::geodesic::DistanceField;
use vlnverse_sim::{Action, AgentConfig, WaypointMode};

use super::{floor_point, wrap_angle, yaw_towards};
use crate::error::Result;
use crate::eval::agent::{Agent, EpisodeInputs, Privileged, StepInput};
use crate::eval::protocol::{ActionSpace, Setting};

/// The privileged shortest-path follower.
#[derive(Default)]
pub struct OracleAgent {
    fields: Vec<Arc<DistanceField>>,
    agent: AgentConfig,
    space: ActionSpace,
    setting: Setting,
    stop_within: f32,
}

impl Agent for OracleAgent {
    fn set_truth(&mut self, truth: &Privileged) {
        self.fields = truth.fields.to_vec();
    }

    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.space = inputs.action_space;
        self.setting = inputs.setting;
        self.stop_within = (0.5 * inputs.success_distance).min(1.0);
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        let k = step.sub_goal.current as usize;
        let Some(field) = self.fields.get(k).or(self.fields.last()) else {
            return Ok(Action::Stop);
        };
        let p = floor_point(&step.pose);
        let Some(d) = field.distance(p).meters() else {
            return Ok(Action::Stop);
        };
        if d <= self.stop_within {
            return Ok(Action::Stop);
        }
        let Some(mut w) = field.next_waypoint(p) else {
            return Ok(Action::Stop);
        };
        if w.distance(p) < 0.05 {
            // Standing on an anchor: look one further along the path.
            if let Some(path) = field.path(p) {
                if let Some(n) = path.points.iter().find(|q| q.distance(p) >= 0.05) {
                    w = *n;
                }
            }
        }
        if self.space == ActionSpace::Waypoint {
            let mode = if self.setting == Setting::Telhop {
                WaypointMode::TelHop
            } else {
                WaypointMode::Drive
            };
            return Ok(Action::Waypoint {
                x: w.x,
                z: w.y,
                mode,
            });
        }
        let v: Vec2 = w - p;
        let diff = wrap_angle(yaw_towards(v) - step.pose.yaw());
        let turn = self.agent.turn_angle();
        if diff.abs() > 0.5 * turn + 1e-4 {
            return Ok(if diff > 0.0 {
                Action::left(&self.agent)
            } else {
                Action::right(&self.agent)
            });
        }
        Ok(Action::forward(&self.agent))
    }
}
