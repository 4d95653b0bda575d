//! `oracle`: follows the geodesic shortest path to each goal (the upper bound of the table).
//!
//! Discrete space: turn toward the next waypoint of the goal's distance field until the heading
//! is within half a turn step, then move forward; within one turn step it keeps going while a
//! step still gains nearly its full length on the geodesic distance (no zig-zag between two
//! headings), and off the navigable map it aims past the map's nearest edge (no stepping back
//! and forth over a narrow gap). Waypoint space: one waypoint action per
//! line-of-sight segment (a hop in Tel-Hop, a drive otherwise). Continuous space: velocity
//! commands from a turn-then-drive controller ([`super::control::VelocityController`]) on the
//! same geodesic path: it turns in place toward the next path corner, then drives at it,
//! braking (within the acceleration limits) so it can turn at the corner, and keeps its speed
//! through gentle corners and toward the goal. It stops once the geodesic
//! distance to the goal is below `stop_within` (min(1 m, half the success distance)), so the
//! stop lands safely inside the success radius; long-horizon episodes get one STOP per goal.
//!
//! In a home on several floors it follows the goal's field across floors
//! ([`vlnverse_env::geodesic::LevelField`]): on another floor than the goal it walks the same
//! way to the end of the flight to take, then along the flight from foot to head (or head to
//! foot) in a straight line, the simulator raising it tread by tread (Strict) or hopping it to
//! the flight's other end (a Tel-Hop waypoint there), and on the goal's floor as before.

use std::sync::Arc;

use glam::Vec2;
use vlnverse_env::geodesic::{DistanceField, Guide, LevelField};
use vlnverse_env::scene_graph::direction_of_yaw;
use vlnverse_sim::{Action, AgentConfig, WaypointMode};

use super::control::{VelocityController, TURN_IN_PLACE};
use super::{floor_point, wrap_angle, yaw_towards};
use crate::agent::{Agent, EpisodeInputs, Privileged, StepInput};
use crate::error::Result;
use crate::protocol::{ActionSpace, Setting};

/// The privileged shortest-path follower.
#[derive(Default)]
pub struct OracleAgent {
    fields: Vec<Arc<DistanceField>>,
    levels: Vec<Arc<LevelField>>,
    agent: AgentConfig,
    space: ActionSpace,
    setting: Setting,
    stop_within: f32,
    control: VelocityController,
}

impl Agent for OracleAgent {
    fn set_truth(&mut self, truth: &Privileged) {
        self.fields = truth.fields.to_vec();
        self.levels = truth.levels.to_vec();
    }

    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.space = inputs.action_space;
        self.setting = inputs.setting;
        self.stop_within = (0.5 * inputs.success_distance).min(1.0);
        self.control = VelocityController::new(&inputs.agent);
        Ok(())
    }

    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        let k = step.sub_goal.current as usize;
        let p = floor_point(&step.pose);
        if let Some(lf) = self.levels.get(k).or(self.levels.last()).cloned() {
            return Ok(self.act_across(&lf, p, step));
        }
        let Some(field) = self.fields.get(k).or(self.fields.last()).cloned() else {
            return Ok(Action::Stop);
        };
        let Some(d) = field.distance(p).meters() else {
            return Ok(Action::Stop);
        };
        if d <= self.stop_within {
            return Ok(Action::Stop);
        }
        Ok(self.follow(&field, p, d, step))
    }
}

impl OracleAgent {
    /// One action in a home on several floors: stop near the goal, else walk down the field
    /// the goal's field across floors points to, or along the flight to take.
    fn act_across(&mut self, lf: &LevelField, p: Vec2, step: &StepInput) -> Action {
        let at = step.pose.position;
        let Some(d) = lf.distance(at).meters() else {
            return Action::Stop;
        };
        if d <= self.stop_within {
            return Action::Stop;
        }
        match lf.guide(at) {
            None => Action::Stop,
            Some(Guide::Walk { field, .. }) => match field.distance(p).meters() {
                Some(dw) => self.follow(&field, p, dw, step),
                None => Action::Stop,
            },
            Some(Guide::Flight { to, aim, .. }) => self.toward(to, aim, p, step),
        }
    }

    /// Along a flight to its end `to`: a waypoint there (a hop, or a drive along the line), or
    /// walk at `aim` (a point on the flight's line just ahead): a velocity command at it, or
    /// turn toward it within half a turn step and step forward.
    fn toward(&mut self, to: Vec2, aim: Vec2, p: Vec2, step: &StepInput) -> Action {
        let yaw = step.pose.yaw();
        let err = wrap_angle(yaw_towards(aim - p) - yaw);
        match self.space {
            ActionSpace::Waypoint => Action::Waypoint {
                x: to.x,
                z: to.y,
                mode: if self.setting == Setting::Telhop {
                    WaypointMode::TelHop
                } else {
                    WaypointMode::Drive
                },
            },
            ActionSpace::Continuous => {
                self.control
                    .follow(err, aim.distance(p), self.agent.max_linear_speed)
            }
            ActionSpace::Discrete => {
                let turn = self.agent.turn_angle();
                if err.abs() > 0.5 * turn + 1e-4 {
                    if err > 0.0 {
                        Action::left(&self.agent)
                    } else {
                        Action::right(&self.agent)
                    }
                } else {
                    Action::forward(&self.agent)
                }
            }
        }
    }

    /// One action down `field` from `p`, `d` metres from its target.
    fn follow(&mut self, field: &Arc<DistanceField>, p: Vec2, d: f32, step: &StepInput) -> Action {
        if self.space == ActionSpace::Continuous {
            return self.drive(field, p, step.pose.yaw());
        }
        let Some(mut w) = field.next_waypoint(p) else {
            return Action::Stop;
        };
        // Off the navigable map (in its clearance margin, where the body still fits) the first
        // waypoint is the map's nearest edge, often a few centimetres away: a whole step at it
        // overshoots, into the margin across a narrow gap (the agent then steps back and forth
        // over the gap until the step limit) or into what the margin keeps clear. Look past it.
        let near = if self.space == ActionSpace::Discrete && !field.map().is_free_at(p) {
            0.5 * self.agent.step_size
        } else {
            0.05
        };
        if w.distance(p) < near {
            // Standing on an anchor (or next to the map's edge): look one further along the path.
            if let Some(path) = field.path(p) {
                if let Some(n) = path.points.iter().find(|q| q.distance(p) >= near) {
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
            return Action::Waypoint {
                x: w.x,
                z: w.y,
                mode,
            };
        }
        let v: Vec2 = w - p;
        let yaw = step.pose.yaw();
        let diff = wrap_angle(yaw_towards(v) - yaw);
        let turn = self.agent.turn_angle();
        // Within one turn step of the path a forward step that still gains nearly its full
        // length on the geodesic distance is kept: turning whenever the error passes half a
        // step makes the agent zig-zag (one turn per step) when the path lies between two
        // reachable headings, which doubles the steps of a long walk.
        let straight_on = diff.abs() <= turn + 1e-4 && {
            let len = self.agent.step_size;
            let ahead = p + direction_of_yaw(yaw) * len;
            field
                .distance(ahead)
                .meters()
                .is_some_and(|da| d - da >= len * turn.cos() - 1e-3)
        };
        if diff.abs() > 0.5 * turn + 1e-4 && !straight_on {
            return if diff > 0.0 {
                Action::left(&self.agent)
            } else {
                Action::right(&self.agent)
            };
        }
        Action::forward(&self.agent)
    }

    /// Continuous space: one velocity command toward the next corner of the geodesic path.
    fn drive(&mut self, field: &DistanceField, p: Vec2, yaw: f32) -> Action {
        let Some(path) = field.path(p) else {
            return Action::Stop;
        };
        let mut ahead = path.points.iter().skip(1).filter(|q| q.distance(p) >= 0.05);
        let Some(&corner) = ahead.next() else {
            return Action::Stop;
        };
        let err = wrap_angle(yaw_towards(corner - p) - yaw);
        // Speed allowed at the corner: full toward the goal, less the sharper the next bend.
        let v_end = match ahead.next() {
            None => self.agent.max_linear_speed,
            Some(&next) => {
                let bend = wrap_angle(yaw_towards(next - corner) - yaw_towards(corner - p)).abs();
                self.agent.max_linear_speed * (1.0 - bend / TURN_IN_PLACE).max(0.0)
            }
        };
        self.control.follow(err, corner.distance(p), v_end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::cues::heading;
    use crate::agents::test_support::inputs;
    use glam::Quat;
    use vlnverse_env::occupancy::{CellState, GridMap};
    use vlnverse_env::Pose;
    use vlnverse_sensors::Observations;

    /// 10 m x 10 m of free floor with an (already agent-dilated) wall at z in [-1.2, -0.8]
    /// from x = -5 to x = 2.
    fn walled_map() -> GridMap {
        let mut m = GridMap::new(100, 100, 0.1, Vec2::new(-5.0, -5.0), CellState::Free).unwrap();
        for col in 0..70 {
            for row in 38..42 {
                m.set(col, row, CellState::Occupied);
            }
        }
        m
    }

    fn pose(p: Vec2, yaw: f32) -> Pose {
        Pose {
            position: [p.x, 0.0, p.y],
            rotation: Quat::from_rotation_y(yaw).to_array(),
        }
    }

    #[test]
    fn discrete_oracle_keeps_straight_on_a_path_between_two_headings() {
        // Open floor; the goal 10 m away at 8 degrees from the start heading, so no multiple
        // of the 15-degree turn points straight at it.
        let map = GridMap::new(300, 300, 0.1, Vec2::new(-15.0, -15.0), CellState::Free).unwrap();
        let goal = heading(8f32.to_radians()) * 10.0;
        let mut oracle = OracleAgent {
            fields: vec![Arc::new(DistanceField::new(&map, goal).unwrap())],
            ..Default::default()
        };
        oracle.reset(&inputs(ActionSpace::Discrete)).unwrap();
        let (p, steps, turns) = walk(&mut oracle, Vec2::ZERO, 0.0);
        assert!(
            p.distance(goal) <= 1.0,
            "stopped {} m away",
            p.distance(goal)
        );
        // 36 forward steps cover the 9 m to the stop radius; a zig-zag adds a turn per step.
        assert!(
            turns <= 4,
            "{turns} turns in {steps} steps on a straight path"
        );
    }

    /// Walk the discrete oracle kinematically (no collisions) from `p` facing `yaw` until it
    /// stops; the end point, the steps and the turns.
    fn walk(oracle: &mut OracleAgent, mut p: Vec2, mut yaw: f32) -> (Vec2, u32, u32) {
        let obs = Observations::new();
        let (mut steps, mut turns) = (0, 0);
        loop {
            let mut step = crate::agents::test_support::step_input(steps, &obs, None);
            step.pose = pose(p, yaw);
            match oracle.act(&mut step).unwrap() {
                Action::TurnLeft(a) => {
                    yaw += a;
                    turns += 1;
                }
                Action::TurnRight(a) => {
                    yaw -= a;
                    turns += 1;
                }
                Action::MoveForward(d) => p += heading(yaw) * d,
                Action::Stop => return (p, steps, turns),
                a => panic!("unexpected {a:?}"),
            }
            steps += 1;
            assert!(steps < 200, "no stop after 200 steps, at {p:?}");
        }
    }

    #[test]
    fn discrete_oracle_follows_a_narrow_gap_it_starts_beside() {
        // Navigable only along a 10 cm strip at z in [-0.05, 0.05]; the agent starts 6 cm
        // south of it (in the clearance margin) and the goal is 8 m along it.
        let mut map =
            GridMap::new(200, 100, 0.05, Vec2::new(-5.0, -2.5), CellState::Occupied).unwrap();
        for col in 0..200 {
            for row in 49..51 {
                map.set(col, row, CellState::Free);
            }
        }
        let goal = Vec2::new(-4.0, 0.0);
        let mut oracle = OracleAgent {
            fields: vec![Arc::new(DistanceField::new(&map, goal).unwrap())],
            ..Default::default()
        };
        oracle.reset(&inputs(ActionSpace::Discrete)).unwrap();
        let (end, steps, _) = walk(&mut oracle, Vec2::new(4.0, -0.11), 0.0);
        assert!(
            end.distance(goal) <= 1.0,
            "stopped {} m away",
            end.distance(goal)
        );
        assert!(steps <= 40, "{steps} steps for 8 m");
    }

    #[test]
    fn continuous_oracle_drives_around_the_wall_within_the_limits() {
        let map = walled_map();
        let goal = Vec2::new(0.0, -3.0);
        let mut oracle = OracleAgent {
            fields: vec![Arc::new(DistanceField::new(&map, goal).unwrap())],
            ..Default::default()
        };
        let ep = inputs(ActionSpace::Continuous);
        let cfg = ep.agent.clone();
        oracle.reset(&ep).unwrap();
        // Replay the simulator's velocity ramp kinematically (no collisions).
        let (mut p, mut yaw, mut v, mut w) = (Vec2::new(0.0, 1.0), 0.0f32, 0.0f32, 0.0f32);
        let dt = crate::agents::control::MODEL_DT;
        let obs = Observations::new();
        let mut stopped = false;
        for k in 0..200 {
            let mut step = crate::agents::test_support::step_input(k, &obs, None);
            step.pose = pose(p, yaw);
            let a = oracle.act(&mut step).unwrap();
            assert!(ActionSpace::Continuous.allows(&a), "{a:?}");
            let Action::Velocity {
                v: vc,
                omega,
                duration,
            } = a
            else {
                stopped = true;
                break;
            };
            assert!(vc.abs() <= cfg.max_linear_speed && omega.abs() <= cfg.max_angular_speed());
            for _ in 0..(duration / dt).round() as u32 {
                w += (omega - w).clamp(-cfg.max_angular_accel() * dt, cfg.max_angular_accel() * dt);
                v += (vc - v).clamp(-cfg.max_linear_accel * dt, cfg.max_linear_accel * dt);
                yaw += w * dt;
                p += heading(yaw) * v * dt;
                // The centre never enters the dilated wall (5 cm of corner cutting allowed).
                let inside = p.x < 2.0 - 0.05 && (p.y - -1.0).abs() < 0.2 - 0.05;
                assert!(!inside, "hit the wall at {p:?} on step {k}");
            }
        }
        assert!(stopped, "never stopped");
        assert!(
            p.distance(goal) <= 1.2,
            "stopped {} m from the goal",
            p.distance(goal)
        );
    }
}
