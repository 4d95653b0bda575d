//! Velocity control for the built-in agents in the continuous action space.
//!
//! The simulator keeps the agent's forward speed and yaw rate between `Velocity` commands and
//! ramps them toward each command at the embodiment's acceleration limits, one physics step at a
//! time (`vlnverse-sim`'s `drive`). [`VelocityController`] replays that ramp for the commands it
//! issues, so it knows the speed and yaw rate it leaves behind, and picks each command by
//! prediction: the yaw rate whose turn, plus the turn needed to brake it afterwards, ends
//! closest to the wanted heading; the largest forward speed whose travel, plus its braking
//! distance, stays short of the next corner. Commands are clamped to the speed limits and the
//! wheel limits of a differential drive as the simulator would clamp them, and last
//! [`CONTROL_PERIOD`] seconds.

use vlnverse_sim::{Action, AgentConfig};

/// Duration of one velocity command (s): 30 physics steps of the default 1/60 s.
pub const CONTROL_PERIOD: f32 = 0.5;
/// Physics step the controller's ramp model assumes (the simulator's default `physics_dt`).
pub const MODEL_DT: f32 = 1.0 / 60.0;
/// Heading error (rad) above which [`VelocityController::follow`] turns in place.
pub const TURN_IN_PLACE: f32 = 0.35;
/// Largest sideways drift (m) one command may build up from the heading error.
const MAX_DRIFT: f32 = 0.1;
/// Candidates per command component.
const CANDIDATES: usize = 41;

/// Ramp `x` toward `target` by at most `acc * dt` per step for `steps` steps; returns the
/// integral (distance or angle) and the final value, as the simulator integrates them.
fn ramp(mut x: f32, target: f32, acc: f32, steps: u32) -> (f32, f32) {
    let mut sum = 0.0;
    for _ in 0..steps {
        x += (target - x).clamp(-acc * MODEL_DT, acc * MODEL_DT);
        sum += x * MODEL_DT;
    }
    (sum, x)
}

/// Distance (or angle) covered while braking from `x` to `floor` (same sign) at `acc`.
fn braking(x: f32, floor: f32, acc: f32) -> f32 {
    let (mut x, mut sum) = (x, 0.0);
    let step = acc * MODEL_DT;
    while x.abs() > floor.abs() + 1e-6 {
        x -= (x - floor).clamp(-step, step);
        sum += x * MODEL_DT;
    }
    sum
}

/// A predictive speed / yaw-rate controller that tracks the simulator's ramped state.
#[derive(Debug, Clone)]
pub struct VelocityController {
    agent: AgentConfig,
    speed: f32,
    omega: f32,
}

impl Default for VelocityController {
    fn default() -> Self {
        VelocityController::new(&AgentConfig::default())
    }
}

impl VelocityController {
    /// A controller at rest for an embodiment.
    pub fn new(agent: &AgentConfig) -> Self {
        VelocityController {
            agent: agent.clone(),
            speed: 0.0,
            omega: 0.0,
        }
    }

    /// Forward speed (m/s) the last command left the agent at.
    pub fn speed(&self) -> f32 {
        self.speed
    }

    /// Yaw rate (rad/s) the last command left the agent at.
    pub fn omega(&self) -> f32 {
        self.omega
    }

    fn steps() -> u32 {
        ((CONTROL_PERIOD / MODEL_DT).round() as u32).max(1)
    }

    /// `(v, omega)` clamped as the simulator clamps them (speed limits, then wheel limits).
    pub fn limit(&self, v: f32, omega: f32) -> (f32, f32) {
        let a = &self.agent;
        let mut v = v.clamp(-a.max_linear_speed, a.max_linear_speed);
        let mut w = omega.clamp(-a.max_angular_speed(), a.max_angular_speed());
        if let Some(d) = &a.differential_drive {
            let wheel = v.abs() + w.abs() * 0.5 * d.wheel_base;
            if wheel > d.max_wheel_speed {
                let k = d.max_wheel_speed / wheel;
                v *= k;
                w *= k;
            }
        }
        (v, w)
    }

    /// Issue `(v, omega)` (limited) for one control period and record the state it leaves.
    pub fn command(&mut self, v: f32, omega: f32) -> Action {
        let (v, omega) = self.limit(v, omega);
        let n = Self::steps();
        self.speed = ramp(self.speed, v, self.agent.max_linear_accel, n).1;
        self.omega = ramp(self.omega, omega, self.agent.max_angular_accel(), n).1;
        Action::Velocity {
            v,
            omega,
            duration: CONTROL_PERIOD,
        }
    }

    /// The yaw-rate command whose turn plus braking turn ends closest to `err` (rad, CCW).
    fn pick_omega(&self, err: f32) -> f32 {
        let (wmax, acc) = (
            self.agent.max_angular_speed(),
            self.agent.max_angular_accel(),
        );
        let n = Self::steps();
        let mut best = (f32::INFINITY, 0.0f32);
        for i in 0..CANDIDATES {
            let w = wmax * (2.0 * i as f32 / (CANDIDATES - 1) as f32 - 1.0);
            let (turned, after) = ramp(self.omega, w, acc, n);
            let miss = (err - turned - braking(after, 0.0, acc)).abs();
            // Prefer the gentler command on (near) ties.
            if miss + 1e-4 < best.0 || ((miss - best.0).abs() <= 1e-4 && w.abs() < best.1.abs()) {
                best = (miss, w);
            }
        }
        best.1
    }

    /// The largest forward speed whose travel plus braking to `v_end` stays within `room` (m).
    fn pick_speed(&self, room: f32, v_end: f32, cap: f32) -> f32 {
        let (vmax, acc) = (
            self.agent.max_linear_speed.min(cap),
            self.agent.max_linear_accel,
        );
        let n = Self::steps();
        let mut best = 0.0;
        for i in 0..CANDIDATES {
            let v = vmax * i as f32 / (CANDIDATES - 1) as f32;
            let (moved, after) = ramp(self.speed, v, acc, n);
            if moved + braking(after, v_end.min(after), acc) <= room {
                best = v;
            }
        }
        best
    }

    /// Turn in place by `err` (rad, counter-clockwise positive), braking any forward speed.
    pub fn turn(&mut self, err: f32) -> Action {
        let w = self.pick_omega(err);
        self.command(0.0, w)
    }

    /// Head for a point `dist` metres away at heading error `err` (rad, counter-clockwise
    /// positive), reaching it at `v_end` m/s at most: turns in place while `|err|` exceeds
    /// [`TURN_IN_PLACE`], else drives while correcting the heading.
    pub fn follow(&mut self, err: f32, dist: f32, v_end: f32) -> Action {
        let w = self.pick_omega(err);
        if err.abs() > TURN_IN_PLACE {
            return self.command(0.0, w);
        }
        let drift = err.abs().sin() * CONTROL_PERIOD;
        let cap = if drift > 1e-6 {
            MAX_DRIFT / drift
        } else {
            f32::INFINITY
        };
        let v = self.pick_speed(dist, v_end, cap);
        self.command(v, w)
    }

    /// Drive straight on at up to `cap` m/s (no corner ahead).
    pub fn cruise(&mut self, cap: f32) -> Action {
        let w = self.pick_omega(0.0);
        let v = self.pick_speed(f32::INFINITY, 0.0, cap);
        self.command(v, w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Replays the simulator's ramp over the issued commands: (yaw, distance, speed, omega).
    fn replay(actions: &[Action], agent: &AgentConfig) -> (f32, f32, f32, f32) {
        let (mut yaw, mut dist, mut v, mut w) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        let (la, aa) = (
            agent.max_linear_accel * MODEL_DT,
            agent.max_angular_accel() * MODEL_DT,
        );
        for a in actions {
            let Action::Velocity {
                v: vc,
                omega,
                duration,
            } = *a
            else {
                panic!("not a velocity command: {a:?}");
            };
            assert!(vc.abs() <= agent.max_linear_speed + 1e-6);
            assert!(omega.abs() <= agent.max_angular_speed() + 1e-6);
            for _ in 0..(duration / MODEL_DT).round() as u32 {
                w += (omega - w).clamp(-aa, aa);
                yaw += w * MODEL_DT;
                v += (vc - v).clamp(-la, la);
                dist += v * MODEL_DT;
            }
        }
        (yaw, dist, v, w)
    }

    #[test]
    fn turns_to_a_heading_and_comes_to_rest() {
        let agent = AgentConfig::default();
        let mut c = VelocityController::new(&agent);
        let target = 1.2f32;
        let mut actions = Vec::new();
        for _ in 0..12 {
            let yaw = replay(&actions, &agent).0;
            actions.push(c.turn(target - yaw));
        }
        let (yaw, _, v, w) = replay(&actions, &agent);
        assert!((yaw - target).abs() < 0.03, "yaw {yaw}");
        assert!(w.abs() < 1e-3 && v.abs() < 1e-3);
        assert!((c.omega() - w).abs() < 1e-4 && (c.speed() - v).abs() < 1e-4);
    }

    #[test]
    fn stops_short_of_a_corner() {
        let agent = AgentConfig::default();
        let mut c = VelocityController::new(&agent);
        let mut actions = Vec::new();
        for _ in 0..20 {
            let dist = replay(&actions, &agent).1;
            actions.push(c.follow(0.0, 3.0 - dist, 0.0));
        }
        let (_, dist, v, _) = replay(&actions, &agent);
        assert!(dist <= 3.0 + 1e-3 && dist > 2.7, "drove {dist} m of 3");
        assert!(v < 1e-3 && c.speed() < 1e-3);
    }

    #[test]
    fn wheel_limits_scale_both_components() {
        let agent = AgentConfig::profile("locobot").unwrap();
        let c = VelocityController::new(&agent);
        let (v, w) = c.limit(5.0, 5.0);
        let d = agent.differential_drive.unwrap();
        assert!(v.abs() + w.abs() * 0.5 * d.wheel_base <= d.max_wheel_speed + 1e-5);
    }
}
