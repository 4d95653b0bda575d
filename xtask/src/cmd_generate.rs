//! `cargo xtask generate`: a VLN dataset of the five tasks (scenes, episodes, reference
//! images), in parallel over scenes, resumable, shardable (`--shard K/N`, joined by
//! `cargo xtask merge`). Prints a per-stage time breakdown at the end.

use std::path::PathBuf;
use std::str::FromStr;
use std::time::Instant;

use anyhow::Context;
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_task::generate::{
    run as run_pipeline, FolderSource, GenerateConfig, GeneratePreset, GenerateSummary, RunOptions,
    StageTimes,
};
use vlnverse_task::instructions::TemplateGenerator;
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
        vlnverse_task::generate::pipeline::shard_list(n)
    );
    Ok((k, n))
}

/// The config, the scene source and the tasks of a run.
pub fn setup(args: &Args) -> anyhow::Result<(GenerateConfig, Box<dyn SceneSource>, Vec<Task>)> {
    // Where the config came from, named in its errors.
    let (mut cfg, origin) = match &args.config {
        Some(p) => (GenerateConfig::from_toml_file(p)?, p.clone()),
        None => {
            let preset = GeneratePreset::from_str(&args.preset)?;
            let origin = PathBuf::from(format!("configs/generate/{}.toml", preset.name()));
            (preset.config()?, origin)
        }
    };
    if let Some(seed) = args.seed {
        cfg.seed = seed;
    }
    let source: Box<dyn SceneSource> = match &args.scenes_from {
        Some(dir) => {
            let s = FolderSource::new(dir)?;
            cfg = cfg.rescaled(s.len());
            cfg.validate_in(&origin).with_context(|| {
                format!(
                    "the config rescaled to the {} scenes of {}",
                    s.len(),
                    dir.display()
                )
            })?;
            Box::new(s)
        }
        None => {
            let preset = Preset::from_str(&cfg.scene_preset).with_context(|| {
                format!(
                    "{}: field `scene_preset` = `{}`",
                    origin.display(),
                    cfg.scene_preset
                )
            })?;
            let source = HomeGenerator::from_preset(preset)?;
            anyhow::ensure!(
                source.len() == cfg.splits.total(),
                "{}: field `splits` = {} scenes, but scene preset `{}` makes {}; make \
                 [splits] add up to {} or use --scenes-from",
                origin.display(),
                cfg.splits.total(),
                cfg.scene_preset,
                source.len(),
                source.len()
            );
            Box::new(source)
        }
    };
    let tasks = if args.tasks.is_empty() {
        Task::ALL.to_vec()
    } else {
        args.tasks
            .iter()
            .map(|t| Task::from_str(t.trim()))
            .collect::<Result<Vec<_>, _>>()?
    };
    Ok((cfg, source, tasks))
}

/// Generate; returns the summary and the stage times (used by `run` and the tests).
pub fn generate(
    args: &Args,
    show_progress: bool,
) -> anyhow::Result<(GenerateSummary, StageTimes, f64)> {
    let start = Instant::now();
    let (cfg, source, tasks) = setup(args)?;
    let shard = match &args.shard {
        Some(s) => parse_shard(s)?,
        None => (0, 1),
    };
    let opts = RunOptions {
        out: args.out.clone(),
        tasks,
        shard,
        occupancy: OccupancyConfig::default(),
    };
    let instructions = TemplateGenerator::default();
    let times = StageTimes::default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")?;
    let mine = (0..source.len()).filter(|i| i % shard.1 == shard.0).count();
    let pb = crate::progress::bar(mine as u64, "scenes");
    if !show_progress {
        pb.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let summary = pool.install(|| {
        run_pipeline(source.as_ref(), &cfg, &opts, &instructions, &times, &|_| {
            pb.inc(1)
        })
    });
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
