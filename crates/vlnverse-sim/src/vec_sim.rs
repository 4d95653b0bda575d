//! [`VecSimulator`]: many environments stepped in parallel with rayon.

use crate::error::{Result, SimError};
use crate::simulator::{Simulator, StepOutcome};
use crate::{Action, RapierSimulator, SimConfig};
use rayon::prelude::*;
use vlnverse_env::{Pose, Scene};

/// A batch of simulators of any [`Simulator`] type (default [`RapierSimulator`]). Environments
/// reset in the same scene share what their backend builds from it (Rapier: the static
/// colliders, through its [`crate::PhysicsCache`], are built once); each environment steps on
/// its own, so results are the same whatever the number of threads.
pub struct VecSimulator<S: Simulator = RapierSimulator> {
    envs: Vec<S>,
    pool: Option<rayon::ThreadPool>,
}

impl<S: Simulator> std::fmt::Debug for VecSimulator<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VecSimulator")
            .field("envs", &self.envs.len())
            .finish_non_exhaustive()
    }
}

impl VecSimulator<RapierSimulator> {
    /// `n` Rapier environments with the same settings, stepped on `threads` threads (None:
    /// rayon's global pool).
    pub fn new(n: usize, cfg: SimConfig, threads: Option<usize>) -> Result<Self> {
        let envs = (0..n)
            .map(|_| RapierSimulator::new(cfg.clone()))
            .collect::<Result<Vec<_>>>()?;
        VecSimulator::from_envs(envs, threads)
    }
}

impl<S: Simulator> VecSimulator<S> {
    /// A batch of given environments (any backend), stepped on `threads` threads (None:
    /// rayon's global pool).
    pub fn from_envs(envs: Vec<S>, threads: Option<usize>) -> Result<Self> {
        let pool = match threads {
            Some(t) => Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .map_err(|e| SimError::invalid("threads", t, e.to_string()))?,
            ),
            None => None,
        };
        Ok(VecSimulator { envs, pool })
    }

    /// Number of environments.
    pub fn len(&self) -> usize {
        self.envs.len()
    }

    /// Whether there are no environments.
    pub fn is_empty(&self) -> bool {
        self.envs.is_empty()
    }

    /// The environments.
    pub fn envs(&self) -> &[S] {
        &self.envs
    }

    /// The environments, mutably (reset one, snapshot one...).
    pub fn envs_mut(&mut self) -> &mut [S] {
        &mut self.envs
    }

    /// Reset every environment in `scene`, environment `i` at `starts[i]`.
    pub fn reset_all(&mut self, scene: &Scene, starts: &[Pose]) -> Result<Vec<Pose>> {
        self.check_len("starts", starts.len())?;
        self.envs
            .iter_mut()
            .zip(starts)
            .map(|(e, s)| e.reset(scene, *s))
            .collect()
    }

    /// Step environment `i` with `actions[i]`, all in parallel.
    pub fn step(&mut self, actions: &[Action]) -> Result<Vec<Result<StepOutcome>>> {
        self.check_len("actions", actions.len())?;
        let envs = &mut self.envs;
        let mut run = move || {
            envs.par_iter_mut()
                .zip(actions.par_iter())
                .map(|(e, a)| e.step(*a))
                .collect()
        };
        Ok(match &self.pool {
            Some(p) => p.install(run),
            None => run(),
        })
    }

    fn check_len(&self, what: &str, n: usize) -> Result<()> {
        if n != self.envs.len() {
            return Err(SimError::action(
                format!("{what}.len"),
                n,
                format!(
                    "must equal the number of environments ({})",
                    self.envs.len()
                ),
            ));
        }
        Ok(())
    }
}
