//! `cargo xtask scenes`: generate procedural homes and write one complete folder per scene
//! (`scene.glb`, `scene.json`, `scene_graph.json`, `occupancy.{pgm,yaml}`,
//! `navigable.{pgm,yaml}`), in parallel, resuming where an earlier run stopped.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use vlnverse_env::io::{write_source_bundles, BundleOutcome};
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset, ProcgenConfig};

/// Arguments of `cargo xtask scenes`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Shipped preset: `tiny` (a handful of homes) or `vlnverse` (the 263-home world).
    #[arg(long, default_value = "tiny")]
    pub preset: Preset,
    /// A procgen TOML config to use instead of the preset.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Override the base seed of the config.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Only the first N scenes.
    #[arg(long)]
    pub count: Option<usize>,
    /// Worker threads (default: all cores). Output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Output folder; scene `<id>` goes to `<out>/<id>/`.
    #[arg(long, default_value = "datasets/scenes")]
    pub out: PathBuf,
    /// Rewrite scenes whose folder is already complete.
    #[arg(long)]
    pub force: bool,
}

/// What a run did.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Scenes written.
    pub written: usize,
    /// Complete scenes left alone.
    pub skipped: usize,
    /// Total navigable area of the written scenes (m^2).
    pub navigable_m2: f64,
    /// Seconds taken.
    pub seconds: f64,
}

/// Generate the scenes; returns what happened (used by `run` and the tests).
pub fn generate(args: &Args, show_progress: bool) -> anyhow::Result<Summary> {
    let start = Instant::now();
    let mut config = match &args.config {
        Some(p) => ProcgenConfig::from_toml_file(p)?,
        None => args.preset.config()?,
    };
    if let Some(seed) = args.seed {
        config.scenes.seed = seed;
    }
    if let Some(n) = args.count {
        config.scenes.count = config.scenes.count.min(n);
    }
    let generator = HomeGenerator::new(config)?;
    let occupancy = OccupancyConfig::default();
    let indices: Vec<usize> = (0..generator.len()).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")?;
    let pb = crate::progress::bar(indices.len() as u64, "scenes");
    if !show_progress {
        pb.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let outcomes = pool.install(|| {
        write_source_bundles(
            &generator,
            &indices,
            &args.out,
            &occupancy,
            args.force,
            &|_| pb.inc(1),
        )
    });
    pb.finish_and_clear();
    let outcomes = outcomes?;
    let mut s = Summary {
        written: 0,
        skipped: 0,
        navigable_m2: 0.0,
        seconds: 0.0,
    };
    for o in &outcomes {
        match o {
            BundleOutcome::Written { navigable_m2, .. } => {
                s.written += 1;
                s.navigable_m2 += *navigable_m2 as f64;
            }
            BundleOutcome::Skipped { .. } => s.skipped += 1,
        }
    }
    s.seconds = start.elapsed().as_secs_f64();
    Ok(s)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let s = generate(&args, true)?;
    let threads = args.threads.unwrap_or_else(rayon::current_num_threads);
    println!(
        "scenes: {} written, {} complete skipped -> {} ({:.2} s, {}, mean navigable {:.1} m2)",
        s.written,
        s.skipped,
        args.out.display(),
        s.seconds,
        crate::progress::threads(threads),
        if s.written > 0 {
            s.navigable_m2 / s.written as f64
        } else {
            0.0
        }
    );
    Ok(())
}
