#![doc = include_str!("../README.md")]

pub mod dataset;
pub mod episode;
pub mod error;
pub mod eval;
pub mod generate;
pub mod instructions;
pub mod metrics;
pub mod oracle;
pub mod report;
pub mod score;
pub mod trajectory;

pub use episode::{
    Dataset, Episode, EpisodeInfo, Goal, GroundedObject, Instruction, Role, Side, Split, Style,
    Task,
};
pub use error::{Result, TaskError};
pub use metrics::{
    aggregate, score_episode, EpisodeMetrics, GoalDistance, GoalDistances, MetricsConfig, Summary,
};
pub use trajectory::Trajectory;
