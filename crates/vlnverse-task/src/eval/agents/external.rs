//! `external`: placeholder (being written).

use crate::error::{Result, TaskError};
use crate::eval::agent::{Agent, AgentFactory};

/// Subprocess agents.
pub struct ExternalFactory {
    cmd: String,
}

impl ExternalFactory {
    /// Agents running `cmd` through `sh -c`.
    pub fn new(cmd: &str) -> Self {
        ExternalFactory { cmd: cmd.into() }
    }
}

impl AgentFactory for ExternalFactory {
    fn name(&self) -> String {
        "external".into()
    }
    fn make(&self) -> Result<Box<dyn Agent>> {
        Err(TaskError::invalid("agent_cmd", &self.cmd, "not yet"))
    }
}
