//! Integration tests of `xtask`, linked into one test binary (one link, shared fixtures).

mod crate_layers;
#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod malloc_arena;
mod real_scene_e2e;
mod scenes_cli;
