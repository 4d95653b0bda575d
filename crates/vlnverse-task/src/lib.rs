#![doc = include_str!("../README.md")]

pub use vlnverse_eval as eval;
pub use vlnverse_eval::oracle;
pub use vlnverse_generate as generate;
pub use vlnverse_instructions as instructions;

pub use vlnverse_score::{
    dataset, episode, lock, metrics, report, route, sample, score, trajectory, vocab,
};

pub use vlnverse_eval::{
    evaluate, evaluate_with, run_episode, Agent, AgentFactory, EvalConfig, EvalOutcome,
    EvalRequest, FnFactory, Result, TaskError,
};
pub use vlnverse_generate::run as generate;
pub use vlnverse_score::{
    aggregate, score_episode, DataError, Dataset, Episode, EpisodeInfo, EpisodeMetrics, Goal,
    GoalDistance, GoalDistances, GroundedObject, Instruction, MetricsConfig, OutputLock, Role,
    Side, Split, Style, Summary, Task, Trajectory,
};

/// The names most programs use: `use vlnverse_task::prelude::*;`.
pub mod prelude {
    pub use vlnverse_eval::{
        evaluate, Agent, AgentFactory, EvalConfig, EvalRequest, FnFactory, StepInput, TaskError,
    };
    pub use vlnverse_generate::GenerateRequest;
    pub use vlnverse_instructions::{InstructionGenerator, TemplateGenerator};
    pub use vlnverse_score::{Episode, Split, Summary, Task, Trajectory};
}
