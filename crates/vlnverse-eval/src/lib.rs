#![doc = include_str!("../README.md")]

mod agent;
pub mod agents;
mod end_fields;
mod episode_loop;
mod episode_store;
mod error;
pub mod oracle;
mod plots;
mod protocol;
mod resume;
mod runner;
mod scene_context;
mod vec_env;

pub use agent::{
    Agent, AgentFactory, EpisodeInputs, OracleHandle, Privileged, StepInput, SubGoalProgress,
};
pub use agents::FnFactory;
pub use episode_loop::{
    check_episode, run_episode, ActionKind, Applied, DialogueHandle, EpisodeCheckError,
    EpisodeSettings, EpisodeState, Unrunnable, NOT_UNDERSTOOD,
};
pub use error::{Result, TaskError};
pub use protocol::{ActionSpace, EvalConfig, LlmSection, Setting};
pub use resume::{
    check_unchanged, episode_fingerprint, EpisodeRecord, ProgressLog, LATER_KEYS, PROGRESS_FILE,
    RETIRED_KEYS, RUN_FILE,
};
pub use runner::{
    check_run_folder, check_split, configured_renderer, evaluate, evaluate_with,
    evaluation_renderer, evaluation_simulator, finish_run, open_run, rapier_simulator,
    run_identity, select_episodes, sim_config, DefaultRenderers, DefaultSimulators, EvalOutcome,
    EvalRequest, LayerIdentity, Layers, RendererFactory, SimulatorFactory, EVAL_PHYSICS_CACHE_MB,
    MAX_THREADS, RUN_FILES,
};
pub use scene_context::{SceneCache, SceneContext};
pub use vec_env::{
    EnvAction, EnvStep, EpisodeOrder, RapierVecEnv, RewardConfig, StepInfo, VecEnv, VecEnvConfig,
    DEFAULT_HOME_REPEAT, MAX_ENVS,
};
