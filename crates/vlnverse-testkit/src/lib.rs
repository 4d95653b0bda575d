//! Shared test support of the VLNVerse-rs crates (a dev-dependency only, never published): small
//! homes and paths from the `tiny` preset, small datasets of episodes, and a loopback stub of an
//! OpenAI-compatible chat endpoint; a textured GLB home built in memory; and (feature `import`)
//! the real homes of `../shared/scenes/` with their import options.

pub mod datasets;
pub mod homes;
pub mod llm_stub;
#[cfg(feature = "import")]
pub mod real_scenes;
pub mod textured_glb;
