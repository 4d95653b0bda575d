//! `random`: seeded random discrete actions (forward 70 %, left 14 %, right 14 %, stop 2 %).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_sim::{Action, AgentConfig};

use crate::error::Result;
use crate::eval::agent::{Agent, EpisodeInputs, StepInput};

/// Uniform-ish random policy, seeded per episode ([`EpisodeInputs::seed`]).
#[derive(Debug, Clone)]
pub struct RandomAgent {
    rng: ChaCha8Rng,
    agent: AgentConfig,
}

impl Default for RandomAgent {
    fn default() -> Self {
        RandomAgent {
            rng: ChaCha8Rng::seed_from_u64(0),
            agent: AgentConfig::default(),
        }
    }
}

impl Agent for RandomAgent {
    fn reset(&mut self, inputs: &EpisodeInputs) -> Result<()> {
        self.rng = ChaCha8Rng::seed_from_u64(inputs.seed);
        self.agent = inputs.agent.clone();
        Ok(())
    }
    fn act(&mut self, _step: &mut StepInput) -> Result<Action> {
        let r: f32 = self.rng.random();
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
