//! Requests and rigs for the evaluation tests (the datasets come from `vlnverse-testkit`).
#![allow(dead_code)]

use std::path::Path;

use vlnverse_eval::{EvalConfig, EvalRequest};
use vlnverse_score::{Split, Task};
pub use vlnverse_testkit::datasets::{make_dataset, make_object_dataset};

/// A request for the fine-grained test split of the dataset in `dir`, written to `dir/out`.
pub fn fine_test(
    dir: &Path,
    out: &str,
    cfg: &EvalConfig,
    episodes: Option<usize>,
    threads: usize,
) -> EvalRequest {
    EvalRequest::new(dir.to_path_buf(), Task::Fine, Split::Test, dir.join(out))
        .episodes(episodes)
        .threads(threads)
        .config(cfg.clone())
}

/// A small, fast RGB-D rig on the ray caster (for tests that need pixels).
pub fn small_rig(dir: &Path) -> String {
    let path = dir.join("small_rig.toml");
    std::fs::write(
        &path,
        "backend = \"raycast\"\nseed = 0\n\n[[sensors]]\ntype = \"rgb\"\nwidth = 32\nheight = 24\nhfov_deg = 90.0\n\n[[sensors]]\ntype = \"depth\"\nwidth = 32\nheight = 24\nhfov_deg = 90.0\n",
    )
    .unwrap();
    path.display().to_string()
}
