//! `semantic`: placeholder (being written).

use vlnverse_sim::Action;

use crate::error::Result;
use crate::eval::agent::{Agent, EpisodeInputs, StepInput};

/// Semantic-camera frontier explorer.
#[derive(Debug, Default)]
pub struct SemanticAgent;

impl Agent for SemanticAgent {
    fn reset(&mut self, _inputs: &EpisodeInputs) -> Result<()> {
        Ok(())
    }
    fn act(&mut self, _step: &mut StepInput) -> Result<Action> {
        Ok(Action::Stop)
    }
}
