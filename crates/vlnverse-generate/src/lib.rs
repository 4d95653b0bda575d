#![doc = include_str!("../README.md")]

//! Dataset generation: path sampling, the five tasks' episodes, splits, presets and the
//! sharded, resumable pipeline behind `cargo xtask generate | merge | stats`.
//!
//! - [`presets`]: `configs/generate/{tiny,vlnverse}.toml` ([`GenerateConfig`]), validated.
//! - [`splits`]: scene-disjoint splits and the exact allocation of episodes to scenes
//!   ([`plan`]); ids are fixed before anything is sampled.
//! - [`sampler`]: start/goal sampling on the navigable map, target objects and their goal
//!   points, rejection counts.
//! - [`episodes`]: the episodes of one scene and task; [`reference_image`]: the visual
//!   reference PNGs.
//! - [`pipeline`]: [`run`] (parallel over scenes, one part file per scene and task),
//!   [`assemble`], [`merge`], [`FolderSource`] (scenes from a folder).
//! - [`request`]: a run as plain data ([`GenerateRequest`]: preset or config file, procedural
//!   homes or a scene folder, tasks, shard), shared by the CLI and the Python package.
//! - `llm_stage` (feature `llm`): the LLM stage of `[instructions.llm]`, with views rendered
//!   along the path for the describer.
//! - [`stats`]: dataset statistics, plots and a markdown summary.
//!
//! Every random choice is seeded from (global seed, scene index, task, split, trajectory), so
//! the output is byte-identical on any number of threads and when sharded and merged.

pub mod episodes;
#[cfg(feature = "llm")]
pub mod llm_stage;
pub mod pipeline;
pub mod presets;
pub mod reference_image;
pub mod request;
pub mod sampler;
pub mod seed;
pub mod splits;
pub mod stats;

pub use episodes::{ScenePart, Stage, StageTimes, Unfit};
pub use pipeline::{
    assemble, merge, run, FolderSource, GenerateSummary, GenerationReport, Manifest, RunOptions,
    Skip,
};
pub use presets::{GenerateConfig, GeneratePreset};
pub use request::{GenerateRequest, PreparedRun};
pub use sampler::{Reject, SceneSampler};
pub use splits::{plan, Plan};
