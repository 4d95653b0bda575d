#![doc = include_str!("../README.md")]

pub mod agent;
pub mod agents;
pub mod episode_loop;
pub mod error;
pub mod oracle;
pub mod plots;
pub mod protocol;
pub mod resume;
pub mod runner;
pub mod scene_context;
pub mod vec_env;

pub use agent::{
    Agent, AgentFactory, EpisodeInputs, OracleHandle, Privileged, StepInput, SubGoalProgress,
};
pub use agents::FnFactory;
pub use episode_loop::{
    run_episode, ActionKind, Applied, EpisodeCheckError, EpisodeSettings, EpisodeState, Unrunnable,
};
pub use error::{Result, TaskError};
pub use protocol::{ActionSpace, EvalConfig, Setting};
pub use resume::EpisodeRecord;
pub use runner::{
    configured_renderer, evaluate, evaluate_with, rapier_simulator, DefaultRenderers,
    DefaultSimulators, EvalOutcome, EvalRequest, LayerIdentity, Layers, RendererFactory,
    SimulatorFactory,
};
pub use scene_context::{SceneCache, SceneContext};
pub use vec_env::{
    EnvAction, EnvStep, EpisodeOrder, RapierVecEnv, RewardConfig, StepInfo, VecEnv, VecEnvConfig,
};
