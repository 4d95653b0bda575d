//! `cargo xtask generate`: a VLN dataset of the five tasks (scenes, episodes, reference
//! images), in parallel over scenes, resumable, shardable (`--shard K/N`, joined by
//! `cargo xtask merge`). Prints a per-stage time breakdown at the end.

use std::path::PathBuf;
use std::str::FromStr;
use std::time::Instant;

use anyhow::Context;
use vlnverse_task::generate::{GenerateRequest, GenerateSummary, StageTimes};
use vlnverse_task::Task;

/// Arguments of `cargo xtask generate`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Shipped preset: `tiny` (seconds) or `vlnverse` (the paper's Table 2).
    #[arg(long, default_value = "tiny")]
    pub preset: String,
    /// A generation TOML config to use instead of the preset.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Override the global seed.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Output folder.
    #[arg(long, default_value = "datasets/tiny")]
    pub out: PathBuf,
    /// Comma-separated tasks (fine,coarse,visual_reference,long_horizon,dialogue); default all.
    #[arg(long, value_delimiter = ',')]
    pub tasks: Vec<String>,
    /// Handle only the scenes with index % N == K (`K/N`); K counts from 0 (Slurm array
    /// style), so two shards are `0/2` and `1/2`. Join the shard folders with `merge`.
    #[arg(long)]
    pub shard: Option<String>,
    /// Worker threads (default: all cores). Output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Build episodes on the scene folders under DIR (e.g. imported scenes) instead of
    /// procedural homes; the config's counts are rescaled to their number.
    #[arg(long)]
    pub scenes_from: Option<PathBuf>,
}

/// Parse `K/N`.
pub fn parse_shard(s: &str) -> anyhow::Result<(usize, usize)> {
    let (k, n) = s
        .split_once('/')
        .with_context(|| format!("--shard `{s}`: expected K/N, e.g. 0/4"))?;
    let k: usize = k
        .trim()
        .parse()
        .with_context(|| format!("--shard `{s}`: K is not a number"))?;
    let n: usize = n
        .trim()
        .parse()
        .with_context(|| format!("--shard `{s}`: N is not a number"))?;
    anyhow::ensure!(
        n > 0,
        "--shard {s}: N (the number of shards) must be at least 1"
    );
    anyhow::ensure!(
        k < n,
        "--shard {s}: K counts from 0, so use {}",
        vlnverse_task::generate::shard_list(n)
    );
    Ok((k, n))
}

/// The run these arguments describe.
pub fn request(args: &Args) -> anyhow::Result<GenerateRequest> {
    let tasks = args
        .tasks
        .iter()
        .map(|t| Task::from_str(t.trim()))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(GenerateRequest {
        preset: args.preset.clone(),
        config: args.config.clone(),
        seed: args.seed,
        out: args.out.clone(),
        tasks,
        shard: match &args.shard {
            Some(s) => parse_shard(s)?,
            None => (0, 1),
        },
        scenes_from: args.scenes_from.clone(),
    })
}

/// Generate; returns the summary and the stage times (used by `run` and the tests).
pub fn generate(
    args: &Args,
    show_progress: bool,
) -> anyhow::Result<(GenerateSummary, StageTimes, f64)> {
    let start = Instant::now();
    let run = request(args)?.prepare()?;
    let times = StageTimes::default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")?;
    let pb = crate::progress::bar(run.scenes_in_shard() as u64, "scenes");
    if !show_progress {
        pb.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let summary = pool.install(|| run.run(&times, &|_| pb.inc(1)));
    pb.finish_and_clear();
    Ok((summary?, times, start.elapsed().as_secs_f64()))
}

/// Print the per-stage breakdown (thread seconds, summed over workers).
pub fn print_breakdown(times: &StageTimes, wall: f64) {
    let stages = times.seconds();
    let total: f64 = stages.iter().map(|s| s.1).sum();
    println!("stage breakdown (thread-seconds summed over workers; wall {wall:.2} s):");
    for (stage, s) in stages {
        println!(
            "  {:<13} {:>9.2} s  {:>5.1}%",
            stage.name(),
            s,
            if total > 0.0 { 100.0 * s / total } else { 0.0 }
        );
    }
}

/// `, N scene/task pairs skipped (see warnings)` when scenes were skipped for a task.
fn skipped_note(s: &GenerateSummary) -> String {
    match s.skipped.len() {
        0 => String::new(),
        n => format!(
            ", {n} scene/task pair{} skipped (see warnings above)",
            if n == 1 { "" } else { "s" }
        ),
    }
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (s, times, wall) = generate(&args, true)?;
    for skip in &s.skipped {
        eprintln!("warning: {skip}");
    }
    let threads = args.threads.unwrap_or_else(rayon::current_num_threads);
    if s.assembled {
        println!(
            "generate: {} scenes ({} already complete), {} episodes{} -> {} ({wall:.2} s, {})",
            s.scenes_done,
            s.scenes_skipped,
            s.episodes,
            skipped_note(&s),
            args.out.display(),
            crate::progress::threads(threads)
        );
    } else {
        println!(
            "generate: shard {} done: {} scenes ({} already complete){} -> {} ({wall:.2} s); join the shards with `cargo xtask merge`",
            args.shard.as_deref().unwrap_or("0/1"),
            s.scenes_done,
            s.scenes_skipped,
            skipped_note(&s),
            args.out.display()
        );
    }
    print_breakdown(&times, wall);
    Ok(())
}
