#![doc = include_str!("../README.md")]

//! Dataset generation: path sampling, the five tasks' episodes, splits, presets and the
//! sharded, resumable pipeline behind `cargo xtask generate | merge | stats`.
//!
//! - `presets`: `configs/generate/{tiny,vlnverse}.toml` ([`GenerateConfig`]), validated.
//! - `splits`: scene-disjoint splits and the exact allocation of episodes to scenes
//!   ([`plan`]); ids are fixed before anything is sampled.
//! - `sampler`: start/goal sampling on the navigable map, target objects and their goal
//!   points, rejection counts.
//! - `episodes`: the episodes of one scene and task; `reference_image`: the visual
//!   reference PNGs.
//! - `pipeline`: [`run`] (parallel over scenes, one part file per scene and task),
//!   [`assemble`], [`merge`], [`FolderSource`] (scenes from a folder).
//! - `request`: a run as plain data ([`GenerateRequest`]: preset or config file, procedural
//!   homes or a scene folder, tasks, shard), shared by the CLI and the Python package.
//! - `llm_stage` (feature `llm`): the LLM stage of `[instructions.llm]`, with views rendered
//!   along the path for the describer.
//! - [`stats`]: dataset statistics, plots and a markdown summary.
//!
//! Every random choice is seeded from (global seed, scene index, task, split, trajectory), so
//! the output is byte-identical on any number of threads and when sharded and merged.

mod cross;
mod episodes;
mod floors;
#[cfg(feature = "llm")]
mod llm_stage;
mod pipeline;
mod presets;
mod reference_image;
mod request;
mod sampler;
mod seed;
mod splits;
pub mod stats;

pub use episodes::{ScenePart, SceneTaskContext, Stage, StageTimes, Unfit, GOAL_RADIUS};
pub use floors::{flight_points, FloorPath, Floors, LevelData, Walk};
#[cfg(feature = "llm")]
pub use llm_stage::{LLM_CACHE_DIR, LLM_REPORT_FILE};
pub use pipeline::{
    assemble, assemble_report, check_merge_inputs, check_shard, merge, part_path, read_manifest,
    read_shard, remove_leftovers, run, shard_list, FolderSource, GenerateSummary, GenerationReport,
    Manifest, RunOptions, ShardId, Skip, TaskReport, MANIFEST_FILE, PARTS_DIR, REPORT_FILE,
    SHARD_FILE,
};
pub use presets::{
    episodes_per_trajectory, GenerateConfig, GeneratePreset, ImageConfig, InstructionsConfig,
    LlmSection, SamplingConfig, SceneSplits, SplitCounts, TaskConfig, TasksConfig,
    MAX_EPISODES_PER_SPLIT, MAX_SCENES,
};
pub use reference_image::{ReferenceRenderer, MAX_PITCH};
pub use request::{GenerateRequest, PreparedRun};
pub use sampler::{Reject, Rejections, SampledPath, SceneSampler, TargetSpot};
pub use splits::{assign_scene_splits, plan, spread, CellShare, Plan, ScenePlan};
