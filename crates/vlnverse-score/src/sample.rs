//! Seeded episode samples spread over scenes: the zero-shot protocol of the paper evaluates
//! 200 test trajectories drawn at random; `evaluate --sample N --seed S` draws them here.
//!
//! The draw is a pure function of (episode ids, scene ids, seed), independent of any random
//! number crate's version: every episode gets a key from a 64-bit mix of the seed and its id,
//! every scene one from the seed and its name. Scenes take turns in key order, each giving its
//! lowest-key episode not yet taken, until N are chosen; so a sample covers as many scenes as
//! it can and never takes a second episode of a scene before every scene gave one. The result
//! keeps the split file's order.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::episode::Episode;

/// How many episodes to draw and with which seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Sample {
    /// Episodes to draw (all of them when the split has fewer).
    pub count: usize,
    /// Seed of the draw.
    pub seed: u64,
}

/// SplitMix64's finaliser: a well-mixed 64-bit key.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// FNV-1a of a scene id.
fn fnv(s: &str) -> u64 {
    s.bytes().fold(0xCBF2_9CE4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

/// The episodes `sample` draws from `episodes`, in their original order.
pub fn sample_episodes(episodes: Vec<Episode>, sample: Sample) -> Vec<Episode> {
    if sample.count >= episodes.len() {
        return episodes;
    }
    // Per scene: (key, index) of its episodes, lowest key first.
    let mut scenes: BTreeMap<&str, Vec<(u64, usize)>> = BTreeMap::new();
    for (i, e) in episodes.iter().enumerate() {
        let key = mix(sample.seed ^ mix(e.episode_id));
        scenes.entry(&e.scene_id).or_default().push((key, i));
    }
    let mut order: Vec<(u64, Vec<(u64, usize)>)> = scenes
        .into_iter()
        .map(|(id, mut eps)| {
            eps.sort_unstable();
            (mix(sample.seed.rotate_left(17) ^ fnv(id)), eps)
        })
        .collect();
    order.sort_unstable_by_key(|s| s.0);
    let mut chosen = vec![false; episodes.len()];
    let mut left = sample.count;
    'rounds: for round in 0.. {
        let mut any = false;
        for (_, eps) in &order {
            if let Some(&(_, i)) = eps.get(round) {
                chosen[i] = true;
                any = true;
                left -= 1;
                if left == 0 {
                    break 'rounds;
                }
            }
        }
        if !any {
            break;
        }
    }
    episodes
        .into_iter()
        .zip(chosen)
        .filter_map(|(e, c)| c.then_some(e))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eps(per_scene: &[usize]) -> Vec<Episode> {
        let mut out = Vec::new();
        let mut id = 1;
        for (s, &n) in per_scene.iter().enumerate() {
            for _ in 0..n {
                let mut e: Episode = serde_json::from_value(serde_json::json!({
                    "episode_id": id, "scene_id": format!("scene_{s}"),
                    "start_position": [0.0, 0.0, 0.0], "start_rotation": [0.0, 0.0, 0.0, 1.0],
                    "goals": [{"position": [1.0, 0.0, 0.0], "radius": 3.0}],
                    "instruction": {"instruction_text": "go"},
                    "reference_path": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                    "info": {"geodesic_distance": 1.0}
                }))
                .unwrap();
                e.trajectory_id = id;
                out.push(e);
                id += 1;
            }
        }
        out
    }

    #[test]
    fn spreads_over_scenes_before_repeating_one() {
        let all = eps(&[30, 2, 5, 1, 12]);
        let got = sample_episodes(all.clone(), Sample { count: 7, seed: 3 });
        assert_eq!(got.len(), 7);
        let per = |s: &str| got.iter().filter(|e| e.scene_id == s).count();
        // Five scenes, seven episodes: every scene gives one, two give a second.
        for s in 0..5 {
            assert!((1..=2).contains(&per(&format!("scene_{s}"))), "{s}");
        }
        // File order kept.
        assert!(got.windows(2).all(|w| w[0].episode_id < w[1].episode_id));
    }

    #[test]
    fn the_seed_decides_and_the_same_seed_repeats() {
        let all = eps(&[40, 40, 40]);
        let ids = |seed| {
            sample_episodes(all.clone(), Sample { count: 10, seed })
                .iter()
                .map(|e| e.episode_id)
                .collect::<Vec<_>>()
        };
        assert_eq!(ids(1), ids(1));
        assert_ne!(ids(1), ids(2));
        assert_eq!(
            sample_episodes(
                all.clone(),
                Sample {
                    count: 500,
                    seed: 1
                }
            )
            .len(),
            120
        );
    }
}
