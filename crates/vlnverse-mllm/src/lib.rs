#![doc = include_str!("../README.md")]

mod accounting;
mod agent;
mod config;
pub mod dry;
mod images;
pub mod map;
pub mod parse;
mod prompt;
pub mod scripted;

pub use accounting::{
    read_records, totals, write_accounting, EpisodeStats, Totals, Traffic, ACCOUNTING_FILE,
};
pub use agent::{
    clearance, image_part, ChatBackend, MllmAgent, MllmFactory, DEPTH_SENSOR, PANORAMA_SENSOR,
    RGB_SENSOR,
};
pub use config::{ActionFormat, Fallback, History, ImageFormat, MllmConfig, View};
pub use images::{encode, Encoded};
pub use map::{DepthCamera, ExploredMap};

/// The example config shipped with the crate (`configs/mllm.toml`), every field at its default.
pub const EXAMPLE_CONFIG: &str = include_str!("../configs/mllm.toml");
