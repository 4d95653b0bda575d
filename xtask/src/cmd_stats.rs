//! `cargo xtask stats DIR`: the paper's dataset statistics (navigable area, rooms, path length,
//! instruction length per task and style, landmark vocabulary) as PNG charts and a markdown
//! summary under `DIR/stats/`.

use std::path::PathBuf;

/// Arguments of `cargo xtask stats`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Dataset folder (written by `cargo xtask generate`).
    pub dir: PathBuf,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::ensure!(args.dir.is_dir(), "{}: not a folder", args.dir.display());
    let md = vlnverse_task::generate::stats::write_stats(&args.dir)?;
    println!("{md}");
    println!("stats -> {}", args.dir.join("stats").display());
    Ok(())
}
