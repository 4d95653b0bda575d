#![doc = include_str!("../README.md")]

mod client;
pub mod pickle;

pub use client::{
    action_code, EpisodeStart, HttpAgent, HttpAgentConfig, HttpFactory, MAX_RETRIES, MAX_TIMEOUT,
};
