#![doc = include_str!("../README.md")]

pub mod app;
mod assets;
pub mod drive;
pub mod error;
pub mod files;
pub mod frames;
pub mod replay;
pub mod review;
pub mod server;

pub use app::{App, ServerConfig};
pub use error::{ApiError, ApiResult};
pub use review::{apply_review, read_review, Decision, ReviewReport, Verdict};
pub use server::{router, rss_bytes, run_server, serve_on};
