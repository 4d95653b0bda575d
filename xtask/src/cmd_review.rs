//! `cargo xtask review`: apply review decisions (the web app's Review mode writes them) to
//! make a reviewed copy of a dataset: rejected episodes dropped, edited instructions replaced.

use std::path::PathBuf;

/// Arguments of `cargo xtask review`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The dataset that was reviewed.
    #[arg(long)]
    pub dataset: PathBuf,
    /// The review file (`runs/web/review.json` by default in `cargo xtask serve`).
    #[arg(long)]
    pub decisions: PathBuf,
    /// Folder of the reviewed copy (must not exist).
    #[arg(long)]
    pub out: PathBuf,
    /// Keep only episodes marked accepted or edited (drop undecided ones too).
    #[arg(long)]
    pub require_all: bool,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let report =
        vlnverse_web::apply_review(&args.dataset, &args.decisions, &args.out, args.require_all)?;
    for (split, c) in &report.splits {
        println!(
            "{split}: {} -> {} episodes ({} accepted, {} edited, {} rejected, {} undecided)",
            c.before, c.after, c.accepted, c.edited, c.rejected, c.undecided
        );
    }
    println!("reviewed dataset written to {}", args.out.display());
    Ok(())
}
