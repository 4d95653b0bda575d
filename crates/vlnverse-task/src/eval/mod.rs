//! Evaluation: the protocol (`configs/eval/*.toml`), the [`Agent`] trait and the built-in
//! agents, the parallel, resumable evaluation loop behind `cargo xtask evaluate`, and the
//! JSON-lines protocol of external agents (docs/agents.md).

pub mod agent;
pub mod agents;
pub mod episode_loop;
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
pub use episode_loop::{run_episode, Applied, EpisodeSettings, EpisodeState};
pub use protocol::{ActionSpace, EvalConfig, Setting};
pub use resume::EpisodeRecord;
pub use runner::{
    configured_renderer, evaluate, evaluate_with, rapier_simulator, EvalOutcome, EvalRequest,
    RendererFactory, SimulatorFactory,
};
pub use scene_context::{SceneCache, SceneContext};
pub use vec_env::{
    EnvAction, EnvStep, EpisodeOrder, RapierVecEnv, RewardConfig, StepInfo, VecEnv, VecEnvConfig,
};
