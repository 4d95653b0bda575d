//! Export a few episodes of a dataset as a LeRobot dataset and print what was written.
//!
//! ```sh
//! cargo xtask generate --preset tiny --out datasets/tiny
//! cargo run --release -p vlnverse-export --example export_tiny -- datasets/tiny runs/lerobot-tiny
//! ```

use std::path::PathBuf;

use vlnverse_export::{export, ExportRequest, ExportSummary};
use vlnverse_task::{Split, Task};

/// Export the first `episodes` episodes of `dataset`'s fine-grained `val_unseen` split to `out`.
pub fn run(
    dataset: PathBuf,
    out: PathBuf,
    episodes: usize,
) -> vlnverse_export::Result<ExportSummary> {
    let mut req = ExportRequest::new(dataset, Task::Fine, Split::ValUnseen, out);
    req.episodes = Some(episodes);
    export(&req, &|_| {})
}

#[allow(dead_code)]
fn main() {
    let mut args = std::env::args().skip(1);
    let (Some(dataset), Some(out)) = (args.next(), args.next()) else {
        eprintln!("usage: export_tiny DATASET OUT [EPISODES]");
        std::process::exit(2);
    };
    let episodes = args.next().and_then(|n| n.parse().ok()).unwrap_or(2);
    match run(dataset.into(), out.into(), episodes) {
        Ok(s) => println!(
            "{} episodes, {} frames, {:.1} MB of data -> {}",
            s.episodes,
            s.frames,
            s.data_bytes as f64 / 1e6,
            s.out.display()
        ),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
