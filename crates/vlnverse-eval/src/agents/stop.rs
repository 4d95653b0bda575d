//! `stop`: stops at once (the trivial baseline: SR is the share of episodes starting in range).

use vlnverse_sim::Action;

use crate::agent::{Agent, EpisodeInputs, StepInput};
use crate::error::Result;

/// Issues STOP on the first step.
#[derive(Debug, Default, Clone, Copy)]
pub struct StopAgent;

impl Agent for StopAgent {
    fn reset(&mut self, _inputs: &EpisodeInputs) -> Result<()> {
        Ok(())
    }
    fn act(&mut self, _step: &mut StepInput) -> Result<Action> {
        Ok(Action::Stop)
    }
}
