//! A run's episodes held compactly while it runs: grouped by scene, each group's episodes as
//! deflated JSON, unpacked when a worker reaches that scene. A train split's episodes as
//! `Episode` values take about 1.3 kB each (coarse train of the `vlnverse` preset: ~16 MB for
//! 11,895), which an evaluation would hold from start to end; packed they take about 100
//! bytes each (1.2 MB), so that its memory does not grow with the size of the split.

use std::collections::BTreeMap;
use std::io::{Read, Write};
use std::sync::{Arc, Mutex, PoisonError};

use flate2::read::DeflateDecoder;
use flate2::write::DeflateEncoder;
use flate2::Compression;
use vlnverse_env::cache::ByteLru;
use vlnverse_score::episode::Episode;

use crate::error::{Result, TaskError};

/// Where an episode is in a [`EpisodeStore`]: its group and its place there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Slot {
    group: u32,
    index: u32,
}

impl Slot {
    /// The episode's scene, as the rank of its id among the store's scenes.
    pub(crate) fn scene(self) -> u32 {
        self.group
    }
}

/// Episodes packed by scene; see the module doc.
pub(crate) struct EpisodeStore {
    /// Per episode in split order: its id and slot.
    order: Vec<(u64, Slot)>,
    /// Each scene's episodes (split order) as deflated JSON, scenes in scene-id order.
    groups: Vec<Box<[u8]>>,
    /// Groups unpacked lately, by group index, each counted as one (so at most `keep`).
    open: Mutex<ByteLru<Vec<Episode>>>,
}

impl EpisodeStore {
    /// Pack `episodes` (split order), keeping up to `keep` unpacked groups at a time (one per
    /// worker and one more serve a run in scene order).
    pub(crate) fn pack(episodes: Vec<Episode>, keep: usize) -> Result<Self> {
        let mut order = vec![(0, Slot { group: 0, index: 0 }); episodes.len()];
        // Each episode with its place in split order, by scene.
        let mut by_scene: BTreeMap<String, Vec<(usize, Episode)>> = BTreeMap::new();
        for (i, e) in episodes.into_iter().enumerate() {
            by_scene.entry(e.scene_id.clone()).or_default().push((i, e));
        }
        let groups = by_scene
            .into_values()
            .enumerate()
            .map(|(g, members)| {
                let group: Vec<Episode> = members
                    .into_iter()
                    .enumerate()
                    .map(|(k, (i, e))| {
                        let slot = Slot {
                            group: g as u32,
                            index: k as u32,
                        };
                        order[i] = (e.episode_id, slot);
                        e
                    })
                    .collect();
                deflate(&group)
            })
            .collect::<Result<_>>()?;
        Ok(EpisodeStore {
            order,
            groups,
            open: Mutex::new(ByteLru::new(keep.max(1))),
        })
    }

    /// Episodes held.
    pub(crate) fn len(&self) -> usize {
        self.order.len()
    }

    /// Id and slot of each episode, in split order.
    pub(crate) fn in_split_order(&self) -> impl Iterator<Item = (u64, Slot)> + '_ {
        self.order.iter().copied()
    }

    /// Slots in scene order (groups in scene-id order, split order within a scene), the
    /// order a run goes through them.
    pub(crate) fn in_scene_order(&self) -> Vec<(u64, Slot)> {
        let mut v = self.order.clone();
        v.sort_by_key(|(_, s)| (s.group, s.index));
        v
    }

    /// The episode in `slot`, with the rest of its scene's episodes (unpacked on first use).
    pub(crate) fn get(&self, slot: Slot) -> Result<EpisodeRef> {
        Ok(EpisodeRef {
            group: self.group(slot.group)?,
            index: slot.index as usize,
        })
    }

    /// The episode with this id, if held.
    pub(crate) fn find(&self, id: u64) -> Result<Option<EpisodeRef>> {
        match self.order.iter().find(|(e, _)| *e == id) {
            Some(&(_, slot)) => self.get(slot).map(Some),
            None => Ok(None),
        }
    }

    fn group(&self, g: u32) -> Result<Arc<Vec<Episode>>> {
        let lock = || self.open.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(hit) = lock().get(u64::from(g)) {
            return Ok(hit);
        }
        // Unpacked outside the lock: two threads may both unpack a group; either copy serves.
        let eps = Arc::new(inflate(&self.groups[g as usize])?);
        lock().insert(u64::from(g), eps.clone(), 1);
        Ok(eps)
    }
}

/// An episode of a [`EpisodeStore`], holding its scene's unpacked group.
pub(crate) struct EpisodeRef {
    group: Arc<Vec<Episode>>,
    index: usize,
}

impl std::ops::Deref for EpisodeRef {
    type Target = Episode;
    fn deref(&self) -> &Episode {
        &self.group[self.index]
    }
}

fn deflate(group: &[Episode]) -> Result<Box<[u8]>> {
    let json = serde_json::to_vec(group).map_err(|e| pack_error(e.to_string()))?;
    let mut z = DeflateEncoder::new(Vec::with_capacity(json.len() / 8), Compression::fast());
    z.write_all(&json).map_err(|e| pack_error(e.to_string()))?;
    Ok(z.finish()
        .map_err(|e| pack_error(e.to_string()))?
        .into_boxed_slice())
}

fn inflate(packed: &[u8]) -> Result<Vec<Episode>> {
    let mut json = Vec::new();
    DeflateDecoder::new(packed)
        .read_to_end(&mut json)
        .map_err(|e| pack_error(e.to_string()))?;
    serde_json::from_slice(&json).map_err(|e| pack_error(e.to_string()))
}

/// Packing and unpacking are in memory and of values this crate wrote: a failure is a bug.
fn pack_error(msg: String) -> TaskError {
    TaskError::invalid("episode store", "<in memory>", msg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap as Map;
    use vlnverse_score::episode::{Goal, Instruction};

    fn episode(id: u64, scene: &str) -> Episode {
        let mut extra = Map::new();
        extra.insert("levels".to_string(), serde_json::json!([0, 1]));
        Episode {
            episode_id: id,
            trajectory_id: id / 3,
            scene_id: scene.to_string(),
            start_position: [0.1 * id as f32, 0.0, -1.0 / 3.0],
            start_rotation: [0.0, 0.382_683_43, 0.0, 0.923_879_5],
            goals: vec![Goal {
                position: [1.0e-7, 2.5, f32::MAX],
                radius: 3.0,
                object_id: Some(id as u32),
            }],
            instruction: Instruction {
                instruction_text: format!("Walk to the sofa number {id}."),
                ..Instruction::default()
            },
            reference_path: vec![[0.0, 0.0, 0.0], [f32::MIN_POSITIVE, 1.0, 7.123_456_7]],
            info: vlnverse_score::episode::EpisodeInfo {
                geodesic_distance: 4.2,
                extra,
            },
            ..Episode::default()
        }
    }

    /// Every episode comes back equal to what was packed, in its slot; split order and scene
    /// order are as the run needs them; a group evicted from the open list unpacks again.
    #[test]
    fn packed_episodes_come_back_equal_in_split_and_scene_order() {
        let scenes = ["home_b", "home_a", "home_c", "home_a", "home_b", "home_a"];
        let eps: Vec<Episode> = scenes
            .iter()
            .enumerate()
            .map(|(i, s)| episode(10 + i as u64, s))
            .collect();
        let store = EpisodeStore::pack(eps.clone(), 1).expect("pack");
        assert_eq!(store.len(), eps.len());
        let split: Vec<u64> = store.in_split_order().map(|(id, _)| id).collect();
        assert_eq!(split, eps.iter().map(|e| e.episode_id).collect::<Vec<_>>());
        for (id, slot) in store.in_split_order() {
            let back = store.get(slot).expect("unpack");
            let orig = eps.iter().find(|e| e.episode_id == id).expect("packed");
            assert_eq!(&*back, orig);
        }
        let scene_order: Vec<u64> = store.in_scene_order().iter().map(|(id, _)| *id).collect();
        assert_eq!(scene_order, vec![11, 13, 15, 10, 14, 12]);
        assert_eq!(
            store.find(14).expect("find").map(|e| e.episode_id),
            Some(14)
        );
        assert!(store.find(99).expect("find").is_none());
        assert!(store.open.lock().expect("lock").len() <= 1);
    }
}
