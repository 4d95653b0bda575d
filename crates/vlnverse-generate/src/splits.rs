//! Scene-disjoint splits and the exact allocation of episodes to scenes.
//!
//! Scenes are shuffled with the global seed and cut into train / val_unseen / test; each
//! (task, split) cell picks its scenes from the split's pool (val_seen from the train scenes)
//! and spreads its trajectories over them (`base = T / S` each, one more for `T % S` of them,
//! chosen by the seed), so the totals are exactly the config's. Episode and trajectory ids are
//! offsets in scene order, known before anything is generated, so they never depend on
//! sharding or threads.

use std::collections::BTreeMap;

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::presets::{episodes_per_trajectory, GenerateConfig};
use super::seed::derive_seed;
use vlnverse_score::episode::{Split, Task};

/// One (task, split) share of one scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellShare {
    /// The task.
    pub task: Task,
    /// The split.
    pub split: Split,
    /// Trajectories to sample in this scene.
    pub trajectories: usize,
    /// Episode id of the scene's first episode in the split file.
    pub first_episode_id: u64,
    /// Trajectory id of the scene's first trajectory in the split file.
    pub first_trajectory_id: u64,
}

impl CellShare {
    /// Episodes this share produces.
    pub fn episodes(&self) -> usize {
        self.trajectories * episodes_per_trajectory(self.task)
    }
}

/// What one scene has to produce.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScenePlan {
    /// Index of the scene in its source.
    pub index: usize,
    /// Its scene-disjoint split (train, val_unseen or test).
    pub split: Split,
    /// Its shares, sorted by (task, split).
    pub shares: Vec<CellShare>,
}

/// The allocation of a whole dataset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    /// One entry per scene, by index.
    pub scenes: Vec<ScenePlan>,
}

impl Plan {
    /// Episodes of a (task, split) cell.
    pub fn episodes(&self, task: Task, split: Split) -> usize {
        self.shares(task, split).map(|s| s.episodes()).sum()
    }

    /// Scenes contributing to a (task, split) cell.
    pub fn scene_count(&self, task: Task, split: Split) -> usize {
        self.shares(task, split)
            .filter(|s| s.trajectories > 0)
            .count()
    }

    fn shares(&self, task: Task, split: Split) -> impl Iterator<Item = &CellShare> + '_ {
        self.scenes
            .iter()
            .flat_map(|p| p.shares.iter())
            .filter(move |s| s.task == task && s.split == split)
    }

    /// Total episodes of the given tasks.
    pub fn total_episodes(&self, tasks: &[Task]) -> usize {
        tasks
            .iter()
            .flat_map(|&t| Split::ALL.map(|s| self.episodes(t, s)))
            .sum()
    }
}

/// Split of every scene: a seeded shuffle cut into train, val_unseen and test.
pub fn assign_scene_splits(cfg: &GenerateConfig) -> Vec<Split> {
    let n = cfg.splits.total();
    let mut order: Vec<usize> = (0..n).collect();
    order.shuffle(&mut ChaCha8Rng::seed_from_u64(derive_seed(
        cfg.seed,
        &[0x5EED_5011, n as u64],
    )));
    let mut out = vec![Split::Train; n];
    for (k, &i) in order.iter().enumerate() {
        out[i] = if k < cfg.splits.train {
            Split::Train
        } else if k < cfg.splits.train + cfg.splits.val_unseen {
            Split::ValUnseen
        } else {
            Split::Test
        };
    }
    out
}

/// Spread `total` over `slots` as evenly as possible: `total / slots` each, one more for
/// `total % slots` slots picked by `seed`. The result sums to `total` exactly.
pub fn spread(total: usize, slots: usize, seed: u64) -> Vec<usize> {
    if slots == 0 {
        return Vec::new();
    }
    let mut out = vec![total / slots; slots];
    let mut order: Vec<usize> = (0..slots).collect();
    order.shuffle(&mut ChaCha8Rng::seed_from_u64(seed));
    for &i in order.iter().take(total % slots) {
        out[i] += 1;
    }
    out
}

/// The allocation of `cfg` over its scenes for `tasks` (validated config assumed).
pub fn plan(cfg: &GenerateConfig, tasks: &[Task]) -> Plan {
    let splits = assign_scene_splits(cfg);
    let n = splits.len();
    let mut per_scene: Vec<BTreeMap<(Task, Split), usize>> = vec![BTreeMap::new(); n];
    for &task in tasks {
        let t = cfg.tasks.get(task);
        let per = episodes_per_trajectory(task);
        for split in Split::ALL {
            let pool_split = if split == Split::ValSeen {
                Split::Train
            } else {
                split
            };
            let mut pool: Vec<usize> = (0..n).filter(|&i| splits[i] == pool_split).collect();
            let want = t.scenes.get(split).min(pool.len());
            // Tasks drawn as another share its allocation (and so its episode ids).
            let drawn_as = cfg.tasks.sampled_as(task);
            let cell_seed = derive_seed(cfg.seed, &[0xCE11, drawn_as as u64, split as u64]);
            if want < pool.len() {
                pool.shuffle(&mut ChaCha8Rng::seed_from_u64(cell_seed));
                pool.truncate(want);
                pool.sort_unstable();
            }
            let counts = spread(t.episodes.get(split) / per, pool.len(), cell_seed ^ 1);
            for (&scene, &c) in pool.iter().zip(&counts) {
                per_scene[scene].insert((task, split), c);
            }
        }
    }
    // Ids: offsets in scene order within each (task, split) file.
    let mut next: BTreeMap<(Task, Split), (u64, u64)> = BTreeMap::new();
    let scenes = (0..n)
        .map(|i| {
            let shares = per_scene[i]
                .iter()
                .map(|(&(task, split), &trajectories)| {
                    let e = next.entry((task, split)).or_insert((0, 0));
                    let share = CellShare {
                        task,
                        split,
                        trajectories,
                        first_episode_id: e.0,
                        first_trajectory_id: e.1,
                    };
                    e.0 += share.episodes() as u64;
                    e.1 += trajectories as u64;
                    share
                })
                .collect();
            ScenePlan {
                index: i,
                split: splits[i],
                shares,
            }
        })
        .collect();
    Plan { scenes }
}
