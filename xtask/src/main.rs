//! `cargo xtask ...`: the VLNVerse-rs command line. Each subcommand lives in its own module and
//! wires the library crates into one job; library code never prints, this binary does.

use clap::{Parser, Subcommand};

mod cmd_bench;
mod cmd_evaluate;
mod cmd_export;
mod cmd_generate;
mod cmd_import;
mod cmd_merge;
mod cmd_render;
mod cmd_results;
mod cmd_review;
mod cmd_scene_info;
mod cmd_scenes;
mod cmd_score;
mod cmd_serve;
mod cmd_stats;
mod cmd_test;
mod cmd_topdown;
mod malloc_arena;
mod progress;
mod split_args;

/// VLNVerse-rs: scenes, datasets and evaluation for vision-language navigation.
#[derive(Parser)]
#[command(name = "cargo xtask", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Generate procedural homes (scene files, occupancy maps, scene graphs).
    Scenes(cmd_scenes::Args),
    /// Print statistics of a folder of scenes (navigable area, rooms, objects by class).
    SceneInfo(cmd_scene_info::Args),
    /// Draw a top-down PNG of a scene.
    Topdown(cmd_topdown::Args),
    /// Render the sensors of an agent placed in a scene.
    Render(cmd_render::Args),
    /// Import a glTF/GLB or OBJ home as a scene folder.
    Import(cmd_import::Args),
    /// Generate a VLN dataset (scenes, episodes of the five tasks).
    Generate(cmd_generate::Args),
    /// Join dataset parts generated with `--shard K/N` into one dataset.
    Merge(cmd_merge::Args),
    /// Statistics and plots of a generated dataset.
    Stats(cmd_stats::Args),
    /// Evaluate an agent on a dataset split.
    Evaluate(Box<cmd_evaluate::Args>),
    /// Score trajectories recorded elsewhere with the benchmark's metrics.
    Score(cmd_score::Args),
    /// Export observations along teacher trajectories as an offline dataset (LeRobot layout).
    Export(cmd_export::Args),
    /// Apply review decisions (from the web app's Review mode) to make a reviewed dataset copy.
    Review(cmd_review::Args),
    /// Serve the web app: drive episodes, replay runs, review generated instructions.
    Serve(cmd_serve::Args),
    /// Regenerate the docs' deterministic result tables (`--check`: fail where they differ).
    Results(cmd_results::Args),
    /// Run the benchmarks that print figures (scenes, geodesic, physics, rendering, metrics).
    Bench(cmd_bench::Args),
    /// Run every test: Rust (cargo test) and Python (the vlnverse package, pytest).
    Test(cmd_test::Args),
}

fn main() {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_target(false)
        .init();
    let cli = Cli::parse();
    if let Command::Evaluate(_) = &cli.command {
        malloc_arena::one_arena();
    }
    let result = match cli.command {
        Command::Scenes(a) => cmd_scenes::run(a),
        Command::SceneInfo(a) => cmd_scene_info::run(a),
        Command::Topdown(a) => cmd_topdown::run(a),
        Command::Render(a) => cmd_render::run(a),
        Command::Import(a) => cmd_import::run(a),
        Command::Generate(a) => cmd_generate::run(a),
        Command::Merge(a) => cmd_merge::run(a),
        Command::Stats(a) => cmd_stats::run(a),
        Command::Evaluate(a) => cmd_evaluate::run(*a),
        Command::Score(a) => cmd_score::run(a),
        Command::Export(a) => cmd_export::run(a),
        Command::Review(a) => cmd_review::run(a),
        Command::Serve(a) => cmd_serve::run(a),
        Command::Results(a) => cmd_results::run(a),
        Command::Bench(a) => cmd_bench::run(a),
        Command::Test(a) => cmd_test::run_tests(a),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
