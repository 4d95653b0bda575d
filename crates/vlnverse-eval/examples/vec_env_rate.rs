//! The Rust-only rate of a vector environment: `N` environments with the default RGB-D rig,
//! every environment following the teacher's action, with next-step autoreset.
//!
//! `cargo run --release -p vlnverse-eval --example vec_env_rate -- DATASET [N] [STEPS] [REPEAT]`
//! (`REPEAT`: episodes an environment draws in one home before it moves on, default
//! [`vlnverse_eval::DEFAULT_HOME_REPEAT`]; 1 draws every episode from the whole split)
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
    let home_repeat: u32 = args
        .next()
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(vlnverse_eval::DEFAULT_HOME_REPEAT);
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
        home_repeat,
    })?;
    let mut last = env.reset_all()?;
    // Warm-up (scene loads), then the timed steps.
    let mut t0 = Instant::now();
    // Resets over the whole run (the `n` of `reset_all` included), to normalise a profile's
    // instructions per reset as well as per step.
    let mut resets = n;
    // What the environments did (episodes, steps, distances, rewards, actions): the same
    // config and seed must give the same digest, whatever the build.
    let mut digest = Digest(0xcbf2_9ce4_8422_2325);
    for s in &last {
        digest.add(s);
    }
    for k in 0..steps + 20 {
        if k == 20 {
            t0 = Instant::now();
        }
        let actions: Vec<_> = last
            .iter()
            .map(|s| {
                let over = s.info.terminated || s.info.truncated;
                (!over).then_some(EnvAction::Act(s.info.expert_action))
            })
            .collect();
        resets += actions.iter().filter(|a| a.is_none()).count();
        last = env.step(actions)?;
        for s in &last {
            digest.add(s);
        }
    }
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "{n} envs: {:.0} steps/s ({} steps in {secs:.2} s; {} batches and {resets} resets in all)",
        (n * steps) as f64 / secs,
        n * steps,
        steps + 20
    );
    println!("digest {:016x}", digest.0);
    Ok(())
}

/// FNV-style hash of every step's outcome.
struct Digest(u64);

impl Digest {
    fn word(&mut self, v: u64) {
        self.0 = (self.0 ^ v).wrapping_mul(0x0000_0100_0000_01b3);
    }

    fn add(&mut self, s: &vlnverse_eval::EnvStep) {
        let i = &s.info;
        self.word(i.episode_id);
        self.word(u64::from(i.steps));
        self.word(u64::from(i.distance_to_goal.to_bits()));
        self.word(u64::from(i.reward.to_bits()));
        for b in format!("{:?}", i.expert_action).bytes() {
            self.word(u64::from(b));
        }
        self.word(u64::from(i.terminated) << 1 | u64::from(i.truncated));
        for v in s.pose.position {
            self.word(u64::from(v.to_bits()));
        }
    }
}
