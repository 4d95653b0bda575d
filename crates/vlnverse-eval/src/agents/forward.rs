//! `forward`: walks straight until a move is blocked, then turns (90 degrees, alternating
//! sides by a seeded coin); stops on the last allowed step. In the continuous space it drives
//! at top speed and makes the quarter turn with velocity commands
//! ([`super::control::VelocityController`]); a command that achieves less than half of its
//! commanded displacement counts as blocked.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_sim::{Action, AgentConfig};

use super::control::VelocityController;
use super::wrap_angle;
use crate::agent::{Agent, EpisodeInputs, StepInput};
use crate::error::Result;
use crate::protocol::ActionSpace;

/// Heading error (rad) at which a continuous quarter turn is done.
const TURN_DONE: f32 = 0.05;

/// Straight ahead, turning away from obstacles.
#[derive(Debug, Clone)]
pub struct ForwardAgent {
    agent: AgentConfig,
    max_steps: u32,
    turns_left: u32,
    turn_left: bool,
    rng: ChaCha8Rng,
    space: ActionSpace,
    control: VelocityController,
    /// Continuous space: the heading a quarter turn is heading for.
    turn_to: Option<f32>,
}

impl Default for ForwardAgent {
    fn default() -> Self {
        ForwardAgent {
            agent: AgentConfig::default(),
            max_steps: 200,
            turns_left: 0,
            turn_left: true,
            rng: ChaCha8Rng::seed_from_u64(0),
            space: ActionSpace::Discrete,
            control: VelocityController::default(),
            turn_to: None,
        }
    }
}

impl ForwardAgent {
    fn blocked(step: &StepInput) -> bool {
        step.last.is_some_and(|last| {
            let cmd = glam::Vec2::from_array(last.commanded).length();
            let got = glam::Vec2::from_array(last.achieved).length();
            cmd > 0.0 && (last.collided || got < 0.5 * cmd)
        })
    }

    fn act_continuous(&mut self, step: &StepInput) -> Action {
        let yaw = step.pose.yaw();
        let blocked = step.last.is_some_and(|last| {
            let cmd = glam::Vec2::from_array(last.commanded).length();
            let got = glam::Vec2::from_array(last.achieved).length();
            cmd > 0.05 && got < 0.5 * cmd
        });
        if self.turn_to.is_none() && blocked {
            let sign = if self.rng.random::<bool>() { 1.0 } else { -1.0 };
            self.turn_to = Some(wrap_angle(yaw + sign * std::f32::consts::FRAC_PI_2));
        }
        if let Some(to) = self.turn_to {
            let err = wrap_angle(to - yaw);
            if err.abs() > TURN_DONE || self.control.omega().abs() > 0.1 {
                return self.control.turn(err);
            }
            self.turn_to = None;
        }
        self.control.cruise(self.agent.max_linear_speed)
    }
}

impl Agent for ForwardAgent {
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.max_steps = inputs.max_steps;
        self.turns_left = 0;
        self.rng = ChaCha8Rng::seed_from_u64(inputs.seed);
        self.space = inputs.action_space;
        self.control = VelocityController::new(&inputs.agent);
        self.turn_to = None;
        Ok(())
    }
    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        if step.step + 1 >= self.max_steps {
            return Ok(Action::Stop);
        }
        if self.space == ActionSpace::Continuous {
            return Ok(self.act_continuous(step));
        }
        if self.turns_left == 0 && Self::blocked(step) {
            let quarter = std::f32::consts::FRAC_PI_2 / self.agent.turn_angle();
            self.turns_left = quarter.round().max(1.0) as u32;
            self.turn_left = self.rng.random::<bool>();
        }
        if self.turns_left > 0 {
            self.turns_left -= 1;
            return Ok(if self.turn_left {
                Action::left(&self.agent)
            } else {
                Action::right(&self.agent)
            });
        }
        Ok(Action::forward(&self.agent))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::test_support::{inputs, step_input};
    use vlnverse_sim::StepOutcome;

    #[test]
    fn continuous_commands_turn_a_quarter_when_blocked() {
        let mut a = ForwardAgent::default();
        a.reset(&inputs(ActionSpace::Continuous)).unwrap();
        let obs = vlnverse_sensors::Observations::new();
        let first = a.act(&mut step_input(0, &obs, None)).unwrap();
        assert!(matches!(first, Action::Velocity { v, omega, .. } if v > 0.0 && omega == 0.0));
        let blocked = StepOutcome {
            commanded: [0.0, -0.4],
            achieved: [0.0, -0.01],
            collided: true,
            ..Default::default()
        };
        let turn = a.act(&mut step_input(1, &obs, Some(&blocked))).unwrap();
        let Action::Velocity { v, omega, .. } = turn else {
            panic!("{turn:?}");
        };
        assert!(v == 0.0 && omega.abs() > 0.5, "turns in place: {turn:?}");
        assert!(ActionSpace::Continuous.allows(&turn));
    }
}
