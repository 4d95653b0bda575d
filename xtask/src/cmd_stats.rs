//! `cargo xtask stats DIR`: the paper's dataset statistics (navigable area, rooms, path length,
//! instruction length per task and style, landmark vocabulary, distinct words, largest sentence
//! skeleton share per task) as PNG charts and a markdown summary under `DIR/stats/`.
//! `--samples N` also prints N seeded random instructions per task and style;
//! `--samples-into FILE` writes them into FILE between the `<!-- samples:begin -->` and
//! `<!-- samples:end -->` markers (how `docs/instructions.md` is made).
//! `--reference FILE` (human instructions, one per line) adds the naturalness figures: each
//! task's perplexity under a word-bigram model of FILE, its ratio to the perplexity of held-out
//! human instructions (every tenth line of FILE, or `--heldout FILE2`) and its OOV share.

use std::path::PathBuf;

const BEGIN: &str = "<!-- samples:begin -->";
const END: &str = "<!-- samples:end -->";

/// Arguments of `cargo xtask stats`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Dataset folder (written by `cargo xtask generate`).
    pub dir: PathBuf,
    /// Also draw this many random instructions per task and style.
    #[arg(long)]
    pub samples: Option<usize>,
    /// Seed of the sample draw.
    #[arg(long, default_value_t = 13)]
    pub seed: u64,
    /// Write the samples into this markdown file between the sample markers instead of
    /// printing them.
    #[arg(long, requires = "samples")]
    pub samples_into: Option<PathBuf>,
    /// Human instructions, one per line: fit a word-bigram model on them and report each
    /// task's perplexity, its ratio to held-out human text and the out-of-vocabulary share.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Held-out human instructions for --reference (default: every tenth line of it, which is
    /// then left out of the fit).
    #[arg(long, requires = "reference")]
    pub heldout: Option<PathBuf>,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::ensure!(args.dir.is_dir(), "{}: not a folder", args.dir.display());
    let naturalness = match &args.reference {
        Some(r) => Some(
            vlnverse_task::generate::stats::naturalness(&args.dir, r, args.heldout.as_deref())
                .map_err(|e| anyhow::anyhow!("--reference: {e}"))?,
        ),
        None => None,
    };
    let md = vlnverse_task::generate::stats::write_stats_with(&args.dir, naturalness.as_ref())?;
    println!("{md}");
    println!("stats -> {}", args.dir.join("stats").display());
    if let Some(n) = args.samples {
        let samples = vlnverse_task::generate::stats::samples_markdown(&args.dir, n, args.seed)?;
        match &args.samples_into {
            None => println!("{samples}"),
            Some(file) => {
                let page = std::fs::read_to_string(file)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
                let (Some(a), Some(b)) = (page.find(BEGIN), page.find(END)) else {
                    anyhow::bail!(
                        "{}: no `{BEGIN}` ... `{END}` markers to write the samples between",
                        file.display()
                    );
                };
                anyhow::ensure!(a < b, "{}: sample markers out of order", file.display());
                let new = format!("{}{BEGIN}\n\n{samples}{}", &page[..a], &page[b..]);
                std::fs::write(file, new)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
                println!("samples -> {}", file.display());
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(dir: PathBuf, reference: PathBuf) -> Args {
        Args {
            dir,
            samples: None,
            seed: 13,
            samples_into: None,
            reference: Some(reference),
            heldout: None,
        }
    }

    #[test]
    fn a_missing_or_empty_reference_is_refused_by_name() {
        let d = tempfile::tempdir().unwrap();
        let missing = d.path().join("no-such-r2r.txt");
        let err = format!("{:#}", run(args(d.path().into(), missing)).unwrap_err());
        assert!(
            err.contains("--reference") && err.contains("no-such-r2r.txt"),
            "{err}"
        );
        let empty = d.path().join("empty.txt");
        std::fs::write(&empty, "\n  \n").unwrap();
        let err = format!("{:#}", run(args(d.path().into(), empty)).unwrap_err());
        assert!(
            err.contains("empty.txt") && err.contains("no instructions"),
            "{err}"
        );
        let short = d.path().join("short.txt");
        std::fs::write(&short, "walk past the sofa\nturn left\n").unwrap();
        let err = format!("{:#}", run(args(d.path().into(), short)).unwrap_err());
        assert!(
            err.contains("short.txt") && err.contains("--heldout"),
            "{err}"
        );
    }
}
