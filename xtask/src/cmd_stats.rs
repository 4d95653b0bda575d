//! `cargo xtask stats DIR`: the paper's dataset statistics (navigable area, rooms, path length,
//! instruction length per task and style, landmark vocabulary, distinct words, largest sentence
//! skeleton share per task) as PNG charts and a markdown summary under `DIR/stats/`.
//! `--samples N` also prints N seeded random instructions per task and style;
//! `--samples-into FILE` writes them into FILE between the `<!-- samples:begin -->` and
//! `<!-- samples:end -->` markers (how `docs/instructions.md` is made).

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
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    anyhow::ensure!(args.dir.is_dir(), "{}: not a folder", args.dir.display());
    let md = vlnverse_task::generate::stats::write_stats(&args.dir)?;
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
