//! `random`: seeded random actions (forward 70 %, left 14 %, right 14 %, stop 2 %). In the
//! continuous space the same choices are velocity commands of
//! [`super::control::CONTROL_PERIOD`] seconds: forward at a random 50-100 % of the top speed,
//! or a turn in place at a random 50-100 % of the top yaw rate.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_sim::{Action, AgentConfig};

use super::control::VelocityController;
use crate::agent::{Agent, EpisodeInputs, StepInput};
use crate::error::Result;
use crate::protocol::ActionSpace;

/// Uniform-ish random policy, seeded per episode ([`EpisodeInputs::seed`]).
#[derive(Debug, Clone)]
pub struct RandomAgent {
    rng: ChaCha8Rng,
    agent: AgentConfig,
    space: ActionSpace,
    control: VelocityController,
}

impl Default for RandomAgent {
    fn default() -> Self {
        RandomAgent {
            rng: ChaCha8Rng::seed_from_u64(0),
            agent: AgentConfig::default(),
            space: ActionSpace::Discrete,
            control: VelocityController::default(),
        }
    }
}

impl Agent for RandomAgent {
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.rng = ChaCha8Rng::seed_from_u64(inputs.seed);
        self.agent = inputs.agent.clone();
        self.space = inputs.action_space;
        self.control = VelocityController::new(&inputs.agent);
        Ok(())
    }
    fn act(&mut self, _step: &mut StepInput) -> Result<Action> {
        let r: f32 = self.rng.random();
        if self.space == ActionSpace::Continuous {
            let k = self.rng.random_range(0.5f32..=1.0);
            let (v, w) = (self.agent.max_linear_speed, self.agent.max_angular_speed());
            return Ok(if r < 0.02 {
                Action::Stop
            } else if r < 0.72 {
                self.control.command(k * v, 0.0)
            } else if r < 0.86 {
                self.control.command(0.0, k * w)
            } else {
                self.control.command(0.0, -k * w)
            });
        }
        Ok(if r < 0.02 {
            Action::Stop
        } else if r < 0.72 {
            Action::forward(&self.agent)
        } else if r < 0.86 {
            Action::left(&self.agent)
        } else {
            Action::right(&self.agent)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::test_support::{inputs, step_input};

    #[test]
    fn answers_in_the_episode_action_space() {
        for space in [
            ActionSpace::Discrete,
            ActionSpace::Continuous,
            ActionSpace::Waypoint,
        ] {
            let mut a = RandomAgent::default();
            a.reset(&inputs(space)).unwrap();
            let obs = vlnverse_sensors::Observations::new();
            for k in 0..200 {
                let act = a.act(&mut step_input(k, &obs, None)).unwrap();
                assert!(space.allows(&act), "{act:?} in {space:?}");
                assert!(act.validate().is_ok());
            }
        }
    }
}
