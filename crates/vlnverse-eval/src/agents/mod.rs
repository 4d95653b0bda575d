//! Built-in agents: `oracle`, `random`, `forward`, `stop`, `semantic` and `external`.

mod control;
mod cues;
mod external;
mod forward;
mod oracle;
mod random;
mod semantic;
mod stop;

pub use control::{VelocityController, CONTROL_PERIOD, MODEL_DT, TURN_IN_PLACE};
pub use external::{
    command_files_hash, ExternalAgent, ExternalFactory, ObsEncoding, DEFAULT_EXTERNAL_TIMEOUT_S,
};
pub use forward::ForwardAgent;
pub use oracle::OracleAgent;
pub use random::RandomAgent;
pub use semantic::SemanticAgent;
pub use stop::StopAgent;

use glam::Vec2;

use crate::agent::{Agent, AgentFactory};
use crate::error::{Result, TaskError};

/// Names of the built-in agents.
pub const BUILTIN: [&str; 6] = [
    "oracle", "random", "forward", "stop", "semantic", "external",
];

/// A factory from a closure (for agents with no shared state).
pub struct FnFactory<F> {
    name: String,
    privileged: bool,
    fingerprint: Option<String>,
    make: F,
}

impl<F: Fn() -> Box<dyn Agent> + Sync> FnFactory<F> {
    /// A factory named `name` calling `make` for each agent.
    pub fn new(name: &str, privileged: bool, make: F) -> Self {
        FnFactory {
            name: name.to_string(),
            privileged,
            fingerprint: None,
            make,
        }
    }

    /// Record what the agent is (a version, a checkpoint hash): see
    /// [`AgentFactory::fingerprint`].
    pub fn with_fingerprint(mut self, fingerprint: impl Into<String>) -> Self {
        self.fingerprint = Some(fingerprint.into());
        self
    }
}

/// Any factory with a user-given version added to its fingerprint (`--agent-version`).
pub struct Versioned {
    inner: Box<dyn AgentFactory>,
    version: String,
}

impl Versioned {
    /// `inner`, fingerprinted with `version` as well.
    pub fn new(inner: Box<dyn AgentFactory>, version: &str) -> Self {
        Versioned {
            inner,
            version: version.to_string(),
        }
    }
}

impl AgentFactory for Versioned {
    fn name(&self) -> String {
        self.inner.name()
    }
    fn make(&self) -> Result<Box<dyn Agent>> {
        self.inner.make()
    }
    fn privileged(&self) -> bool {
        self.inner.privileged()
    }
    fn command(&self) -> Option<String> {
        self.inner.command()
    }
    fn fingerprint(&self) -> Option<String> {
        Some(match self.inner.fingerprint() {
            Some(f) => format!("{f}; version {}", self.version),
            None => format!("version {}", self.version),
        })
    }
}

impl<F: Fn() -> Box<dyn Agent> + Sync> AgentFactory for FnFactory<F> {
    fn name(&self) -> String {
        self.name.clone()
    }
    fn make(&self) -> Result<Box<dyn Agent>> {
        Ok((self.make)())
    }
    fn privileged(&self) -> bool {
        self.privileged
    }
    fn fingerprint(&self) -> Option<String> {
        self.fingerprint.clone()
    }
}

/// The factory of a built-in agent; `command` is the shell command of `external`, which gets
/// its observations as `cfg.external_observations` says.
pub fn builtin(
    name: &str,
    command: Option<&str>,
    cfg: &crate::EvalConfig,
) -> Result<Box<dyn AgentFactory>> {
    fn stamped<F: Fn() -> Box<dyn Agent> + Sync + 'static>(
        f: FnFactory<F>,
    ) -> Box<dyn AgentFactory> {
        let fp = format!(
            "built-in {} of vlnverse-task {}",
            f.name,
            env!("CARGO_PKG_VERSION")
        );
        Box::new(f.with_fingerprint(fp))
    }
    Ok(match name {
        "oracle" => stamped(FnFactory::new("oracle", true, || {
            Box::new(oracle::OracleAgent::default())
        })),
        "random" => stamped(FnFactory::new("random", false, || {
            Box::new(random::RandomAgent::default())
        })),
        "forward" => stamped(FnFactory::new("forward", false, || {
            Box::new(forward::ForwardAgent::default())
        })),
        "stop" => stamped(FnFactory::new("stop", false, || Box::new(stop::StopAgent))),
        "semantic" => stamped(FnFactory::new("semantic", false, || {
            Box::new(semantic::SemanticAgent::default())
        })),
        "external" => {
            let Some(cmd) = command.filter(|c| !c.trim().is_empty()) else {
                return Err(TaskError::invalid(
                    "agent_cmd",
                    "<none>",
                    "the external agent needs a command (--agent-cmd \"python3 examples/python/random_agent.py\")",
                ));
            };
            Box::new(
                external::ExternalFactory::new(cmd)
                    .with_encoding(cfg.external_observations)
                    .with_timeout(std::time::Duration::from_secs_f64(cfg.external_timeout_s)),
            )
        }
        _ => {
            return Err(TaskError::invalid(
                "agent",
                name,
                format!("expected one of {}", BUILTIN.join(", ")),
            ))
        }
    })
}

/// Yaw that faces the floor direction `d = (dx, dz)` (yaw 0 looks along -Z, counter-clockwise).
pub use vlnverse_env::scene_graph::yaw_from_direction as yaw_towards;

/// Angle wrapped into [-pi, pi].
pub fn wrap_angle(a: f32) -> f32 {
    let t = std::f32::consts::TAU;
    let r = (a + std::f32::consts::PI).rem_euclid(t) - std::f32::consts::PI;
    if r < -std::f32::consts::PI {
        r + t
    } else {
        r
    }
}

/// Floor point `(x, z)` of a pose.
pub fn floor_point(p: &vlnverse_env::Pose) -> Vec2 {
    Vec2::new(p.position[0], p.position[2])
}

/// Inputs for the agents' unit tests.
#[cfg(test)]
pub(crate) mod test_support {
    use crate::agent::{EpisodeInputs, StepInput, SubGoalProgress};
    use crate::protocol::{ActionSpace, Setting};
    use vlnverse_env::Pose;
    use vlnverse_score::episode::Task;
    use vlnverse_sensors::Observations;
    use vlnverse_sim::{AgentConfig, StepOutcome};

    /// A coarse episode at the origin facing -Z.
    pub fn inputs(space: ActionSpace) -> EpisodeInputs {
        EpisodeInputs {
            episode_id: 1,
            scene_id: "test".into(),
            task: Task::Coarse,
            instruction: "Find the sofa.".into(),
            sub_instructions: Vec::new(),
            reference_image: None,
            start: pose(),
            agent: AgentConfig::default(),
            action_space: space,
            setting: Setting::Lenient,
            success_distance: 3.0,
            max_steps: 200,
            oracle_budget: None,
            seed: 7,
        }
    }

    /// The origin, facing -Z.
    pub fn pose() -> Pose {
        Pose {
            position: [0.0; 3],
            rotation: [0.0, 0.0, 0.0, 1.0],
        }
    }

    /// Step `k` at the origin with no oracle.
    pub fn step_input<'a>(
        k: u32,
        obs: &'a Observations,
        last: Option<&'a StepOutcome>,
    ) -> StepInput<'a> {
        StepInput {
            step: k,
            observations: obs,
            pose: pose(),
            last,
            sub_goal: SubGoalProgress {
                current: 0,
                total: 1,
            },
            oracle: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_towards_follows_the_convention() {
        // Yaw 0 looks along -Z; a quarter turn left looks along -X.
        assert!(yaw_towards(Vec2::new(0.0, -1.0)).abs() < 1e-6);
        let left = yaw_towards(Vec2::new(-1.0, 0.0));
        assert!((left - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        assert!((wrap_angle(3.0 * std::f32::consts::PI).abs() - std::f32::consts::PI).abs() < 1e-5);
        assert!((wrap_angle(0.5 + std::f32::consts::TAU) - 0.5).abs() < 1e-5);
        assert!((wrap_angle(-0.5 - std::f32::consts::TAU) + 0.5).abs() < 1e-5);
    }
}
