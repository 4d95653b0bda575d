//! [`PhysicsCache`]: physics worlds shared by content, so that every [`crate::RapierSimulator`]
//! of a process builds a scene's static colliders once, whoever calls it (an evaluation's
//! workers, a batch of environments, a user's wrapper that only forwards `reset`).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, PoisonError};

use vlnverse_env::cache::ByteLru;
use vlnverse_env::Scene;

use crate::config::AgentConfig;
use crate::error::Result;
use crate::world::{approx_bytes, content_key, PhysicsScene};

/// Environment variable with the megabytes of physics worlds kept by [`PhysicsCache::global`]
/// (default [`DEFAULT_BUDGET_MB`]; 0 keeps none beyond the scenes in use).
pub const PHYSICS_CACHE_MB_VAR: &str = "VLNVERSE_PHYSICS_CACHE_MB";
/// Megabytes of physics worlds kept by [`PhysicsCache::global`] unless
/// [`PHYSICS_CACHE_MB_VAR`] says otherwise.
pub const DEFAULT_BUDGET_MB: usize = 512;

/// One key's world: built by the first caller while the others of the same key wait (a build
/// never enters rayon, so waiting cannot deadlock a pool), other keys go on meanwhile.
type Slot = Mutex<Option<Arc<PhysicsScene>>>;

/// Physics worlds keyed by the content they were built from (scene and embodiment), least
/// recently used dropped past a byte budget (the newest is always kept: the slots live in a
/// [`ByteLru`]). A world still in use by a simulator stays alive after it leaves the cache.
pub struct PhysicsCache {
    budget: usize,
    slots: Mutex<ByteLru<Slot>>,
    builds: AtomicU64,
    hits: AtomicU64,
}

impl std::fmt::Debug for PhysicsCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PhysicsCache")
            .field("budget", &self.budget)
            .field("builds", &self.builds())
            .field("hits", &self.hits())
            .finish_non_exhaustive()
    }
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl PhysicsCache {
    /// An empty cache holding up to `budget_bytes` of worlds.
    pub fn new(budget_bytes: usize) -> Self {
        PhysicsCache {
            budget: budget_bytes,
            // ByteLru keeps nothing at budget 0; this cache keeps the newest world whatever
            // the budget, so that equal scenes reset one after the other share it.
            slots: Mutex::new(ByteLru::new(budget_bytes.max(1))),
            builds: AtomicU64::new(0),
            hits: AtomicU64::new(0),
        }
    }

    /// The process-wide cache that [`crate::RapierSimulator::new`] uses (budget from
    /// [`PHYSICS_CACHE_MB_VAR`], read once).
    pub fn global() -> Arc<PhysicsCache> {
        static GLOBAL: OnceLock<Arc<PhysicsCache>> = OnceLock::new();
        GLOBAL
            .get_or_init(|| {
                let budget =
                    vlnverse_env::cache::budget_from_env(PHYSICS_CACHE_MB_VAR, DEFAULT_BUDGET_MB);
                Arc::new(PhysicsCache::new(budget))
            })
            .clone()
    }

    /// The world of `scene` for an agent of embodiment `agent` (`agent_key`: its key), built
    /// if no equal scene was built before.
    pub(crate) fn get(
        &self,
        scene: &Scene,
        agent: &AgentConfig,
        agent_key: u64,
    ) -> Result<Arc<PhysicsScene>> {
        let key = content_key(scene, agent_key);
        let slot = {
            let mut slots = lock(&self.slots);
            match slots.get(key) {
                Some(slot) => slot,
                None => {
                    let slot = Arc::new(Slot::default());
                    slots.insert(key, slot.clone(), approx_bytes(scene));
                    slot
                }
            }
        };
        let mut world = lock(&slot);
        if let Some(w) = world.as_ref() {
            self.hits.fetch_add(1, Ordering::Relaxed);
            return Ok(w.clone());
        }
        let built = Arc::new(PhysicsScene::build(scene, agent)?);
        self.builds.fetch_add(1, Ordering::Relaxed);
        *world = Some(built.clone());
        Ok(built)
    }

    /// Worlds built so far (a scene seen before is not built again while it is kept).
    pub fn builds(&self) -> u64 {
        self.builds.load(Ordering::Relaxed)
    }

    /// Resets served from the cache so far.
    pub fn hits(&self) -> u64 {
        self.hits.load(Ordering::Relaxed)
    }

    /// Worlds kept now.
    pub fn len(&self) -> usize {
        lock(&self.slots).len()
    }

    /// Whether no world is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::agent_key;

    fn scene(id: &str) -> Scene {
        Scene {
            format_version: 1,
            id: id.into(),
            source: "test".into(),
            seed: None,
            floor_height: 0.0,
            rooms: vec![],
            doors: vec![],
            objects: vec![],
            storeys: Default::default(),
        }
    }

    #[test]
    fn equal_scenes_share_one_world_and_the_budget_drops_the_oldest() {
        let agent = AgentConfig::default();
        let key = agent_key(&agent);
        let cache = PhysicsCache::new(1);
        let a = cache.get(&scene("a"), &agent, key).unwrap();
        let again = cache.get(&scene("a").clone(), &agent, key).unwrap();
        assert!(Arc::ptr_eq(&a, &again));
        assert_eq!((cache.builds(), cache.hits(), cache.len()), (1, 1, 1));
        // Over the budget: the newest stays alone.
        cache.get(&scene("b"), &agent, key).unwrap();
        assert_eq!((cache.builds(), cache.len()), (2, 1));
        cache.get(&scene("a"), &agent, key).unwrap();
        assert_eq!(cache.builds(), 3);
    }

    #[test]
    fn another_embodiment_is_another_world() {
        let agent = AgentConfig::default();
        let mut other = agent.clone();
        other.name = format!("{}-tall", agent.name);
        let cache = PhysicsCache::new(1 << 20);
        cache.get(&scene("a"), &agent, agent_key(&agent)).unwrap();
        cache.get(&scene("a"), &other, agent_key(&other)).unwrap();
        assert_eq!(cache.builds(), 2);
    }
}
