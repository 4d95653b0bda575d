#![doc = include_str!("../README.md")]

pub mod error;
pub mod export;
pub mod lerobot;
pub mod stats;
pub mod table;
pub mod teacher;

pub use error::{ExportError, Result};
pub use export::{export, ExportRequest, ExportSummary, Phase, Progress};
