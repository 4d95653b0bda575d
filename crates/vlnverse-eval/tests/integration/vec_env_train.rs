//! Train order: each environment draws its episodes from its own seeded generator, and the
//! homes of the episodes drawn ahead are prepared on a thread of their own. Drawing ahead and
//! preparing change nothing: the same episodes, in the same order, with the same pixels as an
//! environment that is handed that list of episodes.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_eval::{EnvAction, EpisodeOrder, EvalConfig, RapierVecEnv, VecEnvConfig};
use vlnverse_score::{Split, Task};
use vlnverse_sensors::Backend;

use crate::eval_support::make_dataset;

fn config(dir: &std::path::Path, order: EpisodeOrder, envs: usize) -> VecEnvConfig {
    let rig = dir.join("rig.toml");
    std::fs::write(
        &rig,
        "seed = 0\n\n[[sensors]]\ntype = \"rgb\"\nwidth = 40\nheight = 30\nhfov_deg = 90.0\n\n[[sensors]]\ntype = \"depth\"\nwidth = 40\nheight = 30\nhfov_deg = 90.0\n",
    )
    .unwrap();
    let protocol = EvalConfig {
        rig: rig.display().to_string(),
        backend: Some(Backend::Raster),
        seed: 11,
        max_steps: 3,
        ..EvalConfig::default()
    };
    VecEnvConfig {
        dataset: dir.to_path_buf(),
        task: Task::Fine,
        split: Split::Test,
        protocol,
        num_envs: envs,
        order,
        episode_ids: None,
        reward: Default::default(),
        home_repeat: 1,
    }
}

/// Episode ids and the observations at every reset and step of environment `i`, for
/// `resets` episodes of at most 3 steps each.
type Trace = Vec<(u64, vlnverse_sensors::Observations)>;

fn run(env: &mut RapierVecEnv, resets: usize) -> Vec<Trace> {
    let n = env.num_envs();
    let mut traces: Vec<Trace> = vec![Vec::new(); n];
    let mut last = env.reset_all().unwrap();
    let mut begun = vec![1; n];
    while begun.iter().any(|&b| b < resets) {
        for (t, s) in traces.iter_mut().zip(&last) {
            t.push((s.info.episode_id, s.observations.clone()));
        }
        let actions = last
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let over = s.info.terminated || s.info.truncated;
                if over {
                    begun[i] += 1;
                }
                (!over).then_some(EnvAction::Act(s.info.expert_action))
            })
            .collect();
        last = env.step(actions).unwrap();
    }
    traces
}

/// The per-environment seed of train order (splitmix64 of the protocol seed and the index).
fn splitmix(seed: u64, i: u64) -> u64 {
    let mut z = seed ^ i.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[test]
fn train_order_draws_from_each_environments_generator_and_prepared_homes_change_no_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let episodes = make_dataset(dir.path(), Task::Fine, 4, 3, 5);
    let mut train = RapierVecEnv::new(config(dir.path(), EpisodeOrder::Train, 2)).unwrap();
    let traces = run(&mut train, 6);
    for (i, trace) in traces.iter().enumerate() {
        // The draws of environment i's generator, one per episode begun.
        let mut rng = ChaCha8Rng::seed_from_u64(splitmix(11, i as u64));
        let mut ids: Vec<u64> = Vec::new();
        for (id, _) in trace {
            if ids.last() != Some(id) || ids.is_empty() {
                ids.push(*id);
            }
        }
        let drawn: Vec<u64> = (0..ids.len())
            .map(|_| episodes[rng.random_range(0..episodes.len())].episode_id)
            .collect();
        // Consecutive draws of one episode merge in `ids`: compare without repeats.
        let mut dedup = drawn.clone();
        dedup.dedup();
        assert_eq!(ids, dedup[..ids.len()], "environment {i}");
        // The same episodes handed in as a list, one environment, nothing drawn ahead.
        let mut cfg = config(dir.path(), EpisodeOrder::Eval, 1);
        cfg.episode_ids = Some(drawn.clone());
        let mut listed = RapierVecEnv::new(cfg).unwrap();
        let want = run(&mut listed, drawn.len());
        let got: Vec<_> = trace.iter().take(want[0].len()).cloned().collect();
        assert_eq!(got.len(), want[0].len(), "environment {i}");
        assert!(got == want[0], "environment {i}: other episodes or pixels");
    }
}

#[test]
fn home_repeat_keeps_each_environment_in_one_home_for_that_many_episodes() {
    let dir = tempfile::tempdir().unwrap();
    let episodes = make_dataset(dir.path(), Task::Fine, 4, 3, 5);
    let home: std::collections::HashMap<u64, String> = episodes
        .iter()
        .map(|e| (e.episode_id, e.scene_id.clone()))
        .collect();
    let mut cfg = config(dir.path(), EpisodeOrder::Train, 2);
    cfg.home_repeat = 3;
    let mut env = RapierVecEnv::new(cfg).unwrap();
    let mut visited = std::collections::BTreeSet::new();
    for i in 0..2 {
        let ids: Vec<u64> = (0..12)
            .map(|_| env.reset_env(i).unwrap().info.episode_id)
            .collect();
        // A visit of 3 in a home of 3 episodes: each of them once.
        for (k, visit) in ids.chunks(3).enumerate() {
            let homes: Vec<&String> = visit.iter().map(|id| &home[id]).collect();
            assert!(
                homes.iter().all(|h| *h == homes[0]),
                "environment {i}, visit {k}: {homes:?}"
            );
            let distinct: std::collections::BTreeSet<_> = visit.iter().collect();
            assert_eq!(distinct.len(), 3, "environment {i}, visit {k}: {visit:?}");
            visited.insert(homes[0].clone());
        }
    }
    assert!(visited.len() > 1, "every visit went to {visited:?}");

    let mut cfg = config(dir.path(), EpisodeOrder::Train, 1);
    cfg.home_repeat = 0;
    let err = RapierVecEnv::new(cfg)
        .err()
        .expect("home_repeat 0 is refused");
    assert!(err.to_string().contains("home_repeat"), "{err}");
}
