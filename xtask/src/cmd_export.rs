//! `cargo xtask export`: observations along each episode's teacher trajectory as an offline
//! dataset (the LeRobot v3.0 layout; docs/export.md). Parallel, resumable, deterministic.

use std::path::PathBuf;
use std::str::FromStr;
use std::sync::Mutex;

use anyhow::Context;
use indicatif::ProgressBar;
use vlnverse_export::{export, ExportRequest, Phase, Progress};
use vlnverse_task::eval::Setting;
use vlnverse_task::{Split, Task};

/// Arguments of `cargo xtask export`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dataset folder (from `cargo xtask generate`).
    #[arg(long)]
    pub dataset: PathBuf,
    /// Task: fine, coarse, visual_reference, long_horizon or dialogue.
    #[arg(long)]
    pub task: String,
    /// Split: train, val_seen, val_unseen or test.
    #[arg(long)]
    pub split: String,
    /// Output format (only `lerobot`).
    #[arg(long, default_value = "lerobot")]
    pub format: String,
    /// Output folder: the LeRobot dataset root (`LeRobotDataset(repo_id, root=OUT)`).
    #[arg(long)]
    pub out: PathBuf,
    /// Only the first N episodes of the split.
    #[arg(long)]
    pub episodes: Option<usize>,
    /// Protocol seed (sensor noise).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Also render the 12-view RGB panorama (`observation.images.pano`).
    #[arg(long)]
    pub panorama: bool,
    /// Worker threads (default: all cores). The output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Setting the teacher acts under: telhop or strict.
    #[arg(long, default_value = "telhop")]
    pub setting: String,
}

/// The request these arguments describe.
pub fn request(args: &Args) -> anyhow::Result<ExportRequest> {
    anyhow::ensure!(
        args.format == "lerobot",
        "--format {}: the only format is `lerobot`",
        args.format
    );
    let task = Task::from_str(&args.task).with_context(|| format!("--task {}", args.task))?;
    let split = Split::from_str(&args.split).with_context(|| format!("--split {}", args.split))?;
    let setting =
        Setting::from_str(&args.setting).with_context(|| format!("--setting {}", args.setting))?;
    anyhow::ensure!(
        setting != Setting::Lenient,
        "--setting lenient: export the teacher under telhop or strict"
    );
    let mut req = ExportRequest::new(&args.dataset, task, split, &args.out);
    req.episodes = args.episodes;
    req.seed = args.seed;
    req.panorama = args.panorama;
    req.threads = args.threads;
    req.setting = setting;
    Ok(req)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let req = request(&args)?;
    let bar: Mutex<Option<(Phase, ProgressBar)>> = Mutex::new(None);
    let on_progress = |p: Progress| {
        let mut b = bar.lock().unwrap_or_else(|e| e.into_inner());
        if b.as_ref().is_none_or(|(phase, _)| *phase != p.phase) {
            if let Some((_, old)) = b.take() {
                old.finish_and_clear();
            }
            let label = match p.phase {
                Phase::Plan => "plan",
                Phase::Render => "episodes",
                Phase::Assemble => "assemble",
            };
            *b = Some((p.phase, crate::progress::bar(p.total as u64, label)));
        }
        if let Some((_, pb)) = b.as_ref() {
            pb.set_position(p.done as u64);
            if p.phase == Phase::Render {
                pb.set_message(format!("{} frames", p.frames));
            }
        }
    };
    let s = export(&req, &on_progress)?;
    if let Some((_, pb)) = bar.lock().unwrap_or_else(|e| e.into_inner()).take() {
        pb.finish_and_clear();
    }
    let [plan, render, assemble] = s.seconds;
    let fps = if render > 0.0 {
        s.rendered_frames as f64 / render
    } else {
        0.0
    };
    println!(
        "export: {} episodes ({} already done), {} frames -> {} ({:.1} MB of data, {:.0} kB/frame; {})",
        s.episodes,
        s.resumed,
        s.frames,
        s.out.display(),
        s.data_bytes as f64 / 1e6,
        s.data_bytes as f64 / 1e3 / s.frames.max(1) as f64,
        crate::progress::threads(s.threads)
    );
    println!(
        "  plan {plan:.2} s, render {render:.2} s ({} frames, {fps:.1} frames/s), assemble {assemble:.2} s",
        s.rendered_frames
    );
    let [sim, encode, write] = s.render_breakdown;
    let total = (sim + encode + write).max(1e-9);
    println!(
        "  render thread-seconds: simulate+render {sim:.2} s ({:.0}%), encode PNG+stats {encode:.2} s ({:.0}%), write Parquet {write:.2} s ({:.0}%)",
        100.0 * sim / total,
        100.0 * encode / total,
        100.0 * write / total
    );
    Ok(())
}
