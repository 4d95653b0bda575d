//! The Rust-only rate of a vector environment: `N` environments with the default RGB-D rig,
//! every environment following the teacher's action, with next-step autoreset.
//!
//! `cargo run --release -p vlnverse-eval --example vec_env_rate -- DATASET [N] [STEPS]`
//! (the Python benchmark `crates/vlnverse-py/bench/bench_vec.py` compares against it).

use std::path::PathBuf;
use std::time::Instant;

use vlnverse_eval::{EnvAction, EpisodeOrder, EvalConfig, RapierVecEnv, VecEnvConfig};
use vlnverse_score::{Split, Task};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let dataset = PathBuf::from(args.next().unwrap_or_else(|| "datasets/tiny".into()));
    let n: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(8);
    let steps: usize = args.next().map(|s| s.parse()).transpose()?.unwrap_or(200);
    let mut protocol = EvalConfig::for_setting(vlnverse_eval::Setting::Telhop);
    protocol.action_space = vlnverse_eval::ActionSpace::Discrete;
    let mut env = RapierVecEnv::new(VecEnvConfig {
        dataset,
        task: Task::Fine,
        split: Split::Train,
        protocol,
        num_envs: n,
        order: EpisodeOrder::Train,
        episode_ids: None,
        reward: Default::default(),
    })?;
    let mut last = env.reset_all()?;
    // Warm-up (scene loads), then the timed steps.
    let mut t0 = Instant::now();
    for k in 0..steps + 20 {
        if k == 20 {
            t0 = Instant::now();
        }
        let actions = last
            .iter()
            .map(|s| {
                let over = s.info.terminated || s.info.truncated;
                (!over).then_some(EnvAction::Act(s.info.expert_action))
            })
            .collect();
        last = env.step(actions)?;
    }
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "{n} envs: {:.0} steps/s ({} steps in {secs:.2} s)",
        (n * steps) as f64 / secs,
        n * steps
    );
    Ok(())
}
