//! The task layer of VLNVerse-rs under one name: a thin facade over the crates that do the work.
//!
//! - [`instructions`] (`vlnverse-instructions`): route and goal descriptions grounded in the
//!   scene graph, the `InstructionGenerator` swap point, an optional LLM stage.
//! - [`generate`] (`vlnverse-generate`): the five tasks' episodes, splits, presets, the sharded
//!   pipeline.
//! - [`eval`] (`vlnverse-eval`): the protocol, the episode loop, the resumable runner, the agents,
//!   the vector env and the dialogue oracle.
//! - The benchmark's data and scoring (`vlnverse-score`): [`dataset`], [`episode`], [`metrics`],
//!   [`trajectory`], ... at the root, as before.
//!
//! Depend on the crate you need instead when you need one: scoring alone compiles no physics
//! and no renderer, generation no physics, evaluation no instruction generator.
//! [`prelude`] brings the names most programs use.

pub use vlnverse_eval as eval;
pub use vlnverse_eval::oracle;
pub use vlnverse_generate as generate;
pub use vlnverse_instructions as instructions;

pub use vlnverse_score::{
    dataset, episode, metrics, report, route, sample, score, trajectory, vocab,
};

pub use vlnverse_eval::{
    evaluate, evaluate_with, run_episode, Agent, AgentFactory, EvalConfig, EvalOutcome,
    EvalRequest, FnFactory, Result, TaskError,
};
pub use vlnverse_generate::pipeline::run as generate;
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
