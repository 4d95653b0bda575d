#![doc = include_str!("../README.md")]

pub mod dataset;
pub mod episode;
pub mod error;
pub mod lock;
pub mod metrics;
pub mod report;
pub mod route;
pub mod sample;
pub mod score;
pub mod trajectory;
pub mod vocab;

/// The benchmark's version: raised whenever the results a run gives can change (episodes and
/// their instructions, scene geometry, physics, rendering, the protocols, the metrics or the
/// reference agents). The evaluator records it in `run.json` and `summary.json`, resuming a run
/// of another version is refused, scoring or comparing one warns, and the result tables of the
/// docs mark learned-model rows made at another version as stale (`cargo xtask results`).
pub const BENCHMARK_VERSION: &str = "1";

pub use dataset::{read_split, split_path, write_split};
pub use episode::{
    Dataset, Episode, EpisodeInfo, Goal, GroundedObject, Instruction, Role, Side, Split, Style,
    Task,
};
pub use error::{DataError, Result};
pub use lock::OutputLock;
pub use metrics::{
    aggregate, score_all, score_episode, EpisodeMetrics, GoalDistance, GoalDistances,
    MetricsConfig, Summary,
};
pub use report::{write_run, RunSummary};
pub use sample::{sample_episodes, Sample};
pub use score::{score, score_on_maps, score_with, ScoreOptions, Scored};
pub use trajectory::{read_trajectories, write_jsonl, Trajectory};
pub use vocab::Vocab;
