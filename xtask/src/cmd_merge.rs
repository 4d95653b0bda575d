//! `cargo xtask merge`: join dataset folders generated with `--shard K/N` into one dataset,
//! byte-identical to a single run. The inputs are checked first (every shard of N given once,
//! complete, of one config and seed); a failed merge writes nothing into `--out`.

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
    let report = args.out.join(vlnverse_task::generate::REPORT_FILE);
    if let Ok(raw) = std::fs::read(&report) {
        if let Ok(r) = serde_json::from_slice::<vlnverse_task::generate::GenerationReport>(&raw) {
            for skip in &r.skipped {
                eprintln!("warning: {skip}");
            }
        }
    }
    println!(
        "merge: {} part folders -> {} ({n} episodes, {:.2} s)",
        args.parts.len(),
        args.out.display(),
        t.elapsed().as_secs_f64()
    );
    Ok(())
}
