//! `cargo xtask merge`: join dataset folders generated with `--shard K/N` into one dataset,
//! byte-identical to a single run.

use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `cargo xtask merge`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Output dataset folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Shard folders (each written by `cargo xtask generate --shard K/N`).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let t = Instant::now();
    let n = vlnverse_task::generate::merge(&args.out, &args.parts)?;
    println!(
        "merge: {} part folders -> {} ({n} episodes, {:.2} s)",
        args.parts.len(),
        args.out.display(),
        t.elapsed().as_secs_f64()
    );
    Ok(())
}
