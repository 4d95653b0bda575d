//! [`VecSimulator`]: many environments stepped in parallel with rayon.

use crate::error::{Result, SimError};
use crate::simulator::{Simulator, StepOutcome};
use crate::world::PhysicsScene;
use crate::{Action, RapierSimulator, SimConfig};
use rayon::prelude::*;
use std::sync::Arc;
use vlnverse_env::{Pose, Scene};

/// A batch of [`RapierSimulator`]s. Environments in the same scene share one
/// [`PhysicsScene`] (static colliders are built once); each environment steps on its own, so
/// results are the same whatever the number of threads.
pub struct VecSimulator {
    envs: Vec<RapierSimulator>,
    pool: Option<rayon::ThreadPool>,
}

impl std::fmt::Debug for VecSimulator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VecSimulator")
            .field("envs", &self.envs.len())
            .finish_non_exhaustive()
    }
}

impl VecSimulator {
    /// `n` environments with the same settings, stepped on `threads` threads (None: rayon's
    /// global pool).
    pub fn new(n: usize, cfg: SimConfig, threads: Option<usize>) -> Result<Self> {
        let envs = (0..n)
            .map(|_| RapierSimulator::new(cfg.clone()))
            .collect::<Result<Vec<_>>>()?;
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
    pub fn envs(&self) -> &[RapierSimulator] {
        &self.envs
    }

    /// The environments, mutably (reset one, snapshot one...).
    pub fn envs_mut(&mut self) -> &mut [RapierSimulator] {
        &mut self.envs
    }

    /// Reset every environment in `scene`, environment `i` at `starts[i]`; the physics world
    /// is built once and shared.
    pub fn reset_all(&mut self, scene: &Scene, starts: &[Pose]) -> Result<Vec<Pose>> {
        self.check_len("starts", starts.len())?;
        let Some(first) = self.envs.first() else {
            return Ok(vec![]);
        };
        let physics = Arc::new(PhysicsScene::build(scene, &first.config().agent)?);
        self.envs
            .iter_mut()
            .zip(starts)
            .map(|(e, s)| e.reset_in(Arc::clone(&physics), *s))
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
