#![doc = include_str!("../README.md")]

pub mod error;
pub mod eval;
pub mod generate;
pub mod instructions;
pub mod oracle;

/// The benchmark's data and scoring live in `vlnverse-score` (no physics, no graphics); they
/// are re-exported here under the same paths.
pub use vlnverse_score::{dataset, episode, metrics, report, sample, score, trajectory, vocab};

pub use episode::{
    Dataset, Episode, EpisodeInfo, Goal, GroundedObject, Instruction, Role, Side, Split, Style,
    Task,
};
pub use error::{Result, TaskError};
pub use eval::{
    evaluate, evaluate_with, run_episode, Agent, AgentFactory, EvalConfig, EvalOutcome,
    EvalRequest, FnFactory,
};
pub use generate::pipeline::run as generate;
pub use metrics::{
    aggregate, score_episode, EpisodeMetrics, GoalDistance, GoalDistances, MetricsConfig, Summary,
};
pub use trajectory::Trajectory;
pub use vlnverse_score::{OutputLock, ScoreError};
