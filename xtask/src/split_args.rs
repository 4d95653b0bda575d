//! Arguments shared by the commands that read one split of a dataset (`evaluate`, `score`).

use std::path::PathBuf;

use vlnverse_task::{Split, Task};

/// Which split of which dataset a command reads.
#[derive(clap::Args, Debug, Clone)]
pub struct SplitArgs {
    /// Dataset folder (holds `<task>/<split>/<split>.json.gz` and `scenes/<scene_id>/`).
    #[arg(long)]
    pub dataset: PathBuf,
    /// Task: fine, coarse, visual_reference, long_horizon or dialogue.
    #[arg(long)]
    pub task: Task,
    /// Split: train, val_seen, val_unseen or test.
    #[arg(long)]
    pub split: Split,
}
