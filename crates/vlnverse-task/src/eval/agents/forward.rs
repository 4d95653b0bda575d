//! `forward`: walks straight until a move is blocked, then turns (90 degrees, alternating
//! sides by a seeded coin); stops on the last allowed step.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_sim::{Action, AgentConfig};

use crate::error::Result;
use crate::eval::agent::{Agent, EpisodeInputs, StepInput};

/// Straight ahead, turning away from obstacles.
#[derive(Debug, Clone)]
pub struct ForwardAgent {
    agent: AgentConfig,
    max_steps: u32,
    turns_left: u32,
    turn_left: bool,
    rng: ChaCha8Rng,
}

impl Default for ForwardAgent {
    fn default() -> Self {
        ForwardAgent {
            agent: AgentConfig::default(),
            max_steps: 200,
            turns_left: 0,
            turn_left: true,
            rng: ChaCha8Rng::seed_from_u64(0),
        }
    }
}

impl Agent for ForwardAgent {
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.agent = inputs.agent.clone();
        self.max_steps = inputs.max_steps;
        self.turns_left = 0;
        self.rng = ChaCha8Rng::seed_from_u64(inputs.seed);
        Ok(())
    }
    fn act(&mut self, step: &mut StepInput) -> Result<Action> {
        if step.step + 1 >= self.max_steps {
            return Ok(Action::Stop);
        }
        if self.turns_left == 0 {
            if let Some(last) = step.last {
                let cmd = glam::Vec2::from_array(last.commanded).length();
                let got = glam::Vec2::from_array(last.achieved).length();
                if cmd > 0.0 && (last.collided || got < 0.5 * cmd) {
                    let quarter = std::f32::consts::FRAC_PI_2 / self.agent.turn_angle();
                    self.turns_left = quarter.round().max(1.0) as u32;
                    self.turn_left = self.rng.random::<bool>();
                }
            }
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
