//! Shared test support of the VLNVerse-rs crates (a dev-dependency only, never published): small
//! homes and paths from the `tiny` preset, small datasets of episodes, and a loopback stub of an
//! OpenAI-compatible chat endpoint.

pub mod datasets;
pub mod homes;
pub mod llm_stub;
