//! `cargo xtask score`: score trajectories recorded elsewhere (a real robot, another simulator)
//! with the benchmark's metrics, writing the same files as `cargo xtask evaluate`
//! (`summary.json`, `episodes.csv`, `report.md`).

use std::path::PathBuf;

use crate::split_args::SplitArgs;
use anyhow::Context as _;
use vlnverse_score::lock::{check_score_folder, write_score_file};
use vlnverse_score::metrics::{MetricsConfig, DEFAULT_START_TOLERANCE};
use vlnverse_score::report::write_run;
use vlnverse_score::{score_with, trajectory, ScoreOptions};

/// Arguments of `cargo xtask score`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dataset, task and split.
    #[command(flatten)]
    pub data: SplitArgs,
    /// Trajectory file: JSON lines, or the VLN-CE inference format.
    #[arg(long)]
    pub trajectories: PathBuf,
    /// Output folder of the run.
    #[arg(long)]
    pub out: PathBuf,
    /// Row label in report.md (default: the trajectory file's stem).
    #[arg(long)]
    pub method: Option<String>,
    /// Setting label in report.md (e.g. strict, telhop).
    #[arg(long)]
    pub setting: Option<String>,
    /// Score episodes without a trajectory as failures instead of stopping with an error.
    #[arg(long)]
    pub allow_missing: bool,
    /// A noticeable collision fails the episode (the Strict rule applied after the fact).
    #[arg(long)]
    pub fail_on_collision: bool,
    /// Success distance in metres.
    #[arg(long, default_value_t = 3.0)]
    pub success_distance: f32,
    /// Straight-line instead of geodesic distances (no navigable maps needed).
    #[arg(long)]
    pub euclidean: bool,
    /// How far (m, horizontally) a trajectory's first position may lie from the episode's
    /// start position; raise it for real robots whose start pose is only roughly the episode's.
    #[arg(long, default_value_t = DEFAULT_START_TOLERANCE)]
    pub start_tolerance: f32,
    /// Overwrite a `summary.json` in `--out` that an earlier `score` did not write.
    #[arg(long)]
    pub force: bool,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_score_folder(&args.out, args.force)?;
    let options = ScoreOptions {
        metrics: MetricsConfig {
            success_distance: args.success_distance,
            fail_on_collision: args.fail_on_collision,
            ..Default::default()
        },
        euclidean: args.euclidean,
        allow_missing: args.allow_missing,
        start_tolerance: args.start_tolerance,
    };
    let trajectories = trajectory::read_trajectories(&args.trajectories)?;
    // Trajectories of an evaluation's run folder: say when that run is of another benchmark.
    if let Some(w) = args
        .trajectories
        .parent()
        .and_then(vlnverse_score::report::version_warning)
    {
        tracing::warn!("{w}");
    }
    tracing::info!(
        "scoring {} trajectories on {}/{}",
        trajectories.len(),
        args.data.task,
        args.data.split
    );
    let pb = crate::progress::bar(trajectories.len() as u64, "scoring");
    let scored = score_with(
        &args.data.dataset,
        args.data.task,
        args.data.split,
        trajectories,
        &options,
        &|n| pb.inc(n as u64),
    )
    .with_context(|| format!("scoring {}", args.trajectories.display()))?;
    pb.finish_and_clear();
    let method = args.method.clone().unwrap_or_else(|| {
        args.trajectories
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "trajectories".into())
    });
    let run = scored.run_summary(&method, args.setting.as_deref());
    // Checked again under the lock: an evaluation may have started meanwhile.
    let _lock = vlnverse_score::OutputLock::acquire(&args.out, "score")?;
    check_score_folder(&args.out, args.force)?;
    write_score_file(
        &args.out,
        &args.trajectories,
        &args.data.dataset,
        args.data.task,
        args.data.split,
    )?;
    write_run(&args.out, &run, &scored.metrics)?;
    let s = &run.summary;
    println!(
        "{} episodes: SR {:.2}%  SPL {:.2}%  NE {}  nDTW {:.2}%  ({} unreachable) -> {}",
        s.episodes,
        100.0 * s.sr,
        100.0 * s.spl,
        s.ne.map_or_else(|| "-".into(), |v| format!("{v:.2} m")),
        100.0 * s.ndtw,
        s.unreachable,
        args.out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_score::{dataset, Episode, EpisodeInfo, Goal, Split, Task};

    /// A fine test split under `dir` with one episode `id`: from the origin `length` metres
    /// along +X.
    fn straight_episode(dir: &std::path::Path, id: u64, length: f32) {
        let goal = [length, 0.0, 0.0];
        let ep = Episode {
            episode_id: id,
            trajectory_id: id,
            scene_id: "s".into(),
            goals: vec![Goal {
                position: goal,
                radius: 3.0,
                object_id: None,
            }],
            reference_path: vec![[0.0, 0.0, 0.0], goal],
            instruction: vlnverse_score::Instruction {
                instruction_text: "Walk ahead.".into(),
                ..Default::default()
            },
            info: EpisodeInfo {
                geodesic_distance: length,
                ..Default::default()
            },
            ..Default::default()
        };
        dataset::write_split(dir, Task::Fine, Split::Test, &[ep]).unwrap();
    }

    /// Arguments scoring `trajectories` on the fine test split of `dataset` into `out`, with
    /// the CLI's defaults (Euclidean success at 3 m, as `straight_episode` has no maps).
    fn score_args(dataset: &std::path::Path, trajectories: PathBuf, out: PathBuf) -> Args {
        Args {
            data: SplitArgs {
                dataset: dataset.to_path_buf(),
                task: Task::Fine,
                split: Split::Test,
            },
            trajectories,
            out,
            method: None,
            setting: None,
            allow_missing: false,
            fail_on_collision: false,
            success_distance: 3.0,
            euclidean: true,
            start_tolerance: DEFAULT_START_TOLERANCE,
            force: false,
        }
    }

    #[test]
    fn score_writes_the_run_files_and_names_bad_input() {
        let dir = tempfile::tempdir().unwrap();
        straight_episode(dir.path(), 5, 2.0);
        let traj = dir.path().join("robot.jsonl");
        std::fs::write(
            &traj,
            "{\"episode_id\": 5, \"positions\": [[0,0,0],[1,0,0],[2,0,0]], \"stopped\": true}\n",
        )
        .unwrap();
        let args = |trajectories: PathBuf, out: PathBuf| score_args(dir.path(), trajectories, out);
        let out = dir.path().join("run");
        run(args(traj, out.clone())).unwrap();
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["sr"], 1.0);
        assert_eq!(summary["method"], "robot");
        let report = std::fs::read_to_string(out.join("report.md")).unwrap();
        assert!(
            report.contains("| robot | - | 2.00 | 0.00 | 100.00 |"),
            "{report}"
        );

        let bad = dir.path().join("bad.jsonl");
        std::fs::write(
            &bad,
            "{\"episode_id\": 5, \"positions\": 3, \"stopped\": true}\n",
        )
        .unwrap();
        let err = format!("{:#}", run(args(bad, out.clone())).unwrap_err());
        assert!(err.contains("bad.jsonl") && err.contains("line 1"), "{err}");
        let unknown = dir.path().join("unknown.jsonl");
        std::fs::write(
            &unknown,
            "{\"episode_id\": 9, \"positions\": [[0, 0, 0]], \"stopped\": true}\n",
        )
        .unwrap();
        let err = format!("{:#}", run(args(unknown, out.clone())).unwrap_err());
        assert!(err.contains("9") && err.contains("no episode"), "{err}");

        // An empty file, and a trajectory without positions, are refused.
        let empty = dir.path().join("empty.jsonl");
        std::fs::write(&empty, "").unwrap();
        let err = format!("{:#}", run(args(empty, out.clone())).unwrap_err());
        assert!(
            err.contains("empty.jsonl") && err.contains("no trajectories"),
            "{err}"
        );
        let no_positions = dir.path().join("no_positions.jsonl");
        std::fs::write(
            &no_positions,
            "{\"episode_id\": 1, \"positions\": [], \"stopped\": true}\n",
        )
        .unwrap();
        let err = format!("{:#}", run(args(no_positions, out.clone())).unwrap_err());
        assert!(err.contains("`positions` is empty"), "{err}");
    }

    #[test]
    fn score_never_writes_into_an_evaluation_or_over_a_summary_of_something_else() {
        let dir = tempfile::tempdir().unwrap();
        straight_episode(dir.path(), 5, 2.0);
        let traj = dir.path().join("robot.jsonl");
        std::fs::write(
            &traj,
            "{\"episode_id\": 5, \"positions\": [[0,0,0],[2,0,0]], \"stopped\": true}\n",
        )
        .unwrap();
        let args = |out: PathBuf, force: bool| Args {
            force,
            ..score_args(dir.path(), traj.clone(), out)
        };
        let listing = |d: &std::path::Path| {
            let mut v: Vec<String> = std::fs::read_dir(d)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        };
        // An evaluation's folder (finished: run.json and trajectories), even with --force.
        let eval = dir.path().join("eval");
        std::fs::create_dir(&eval).unwrap();
        std::fs::write(eval.join("run.json"), "{}").unwrap();
        std::fs::write(eval.join("trajectories.jsonl"), "").unwrap();
        let before = listing(&eval);
        for force in [false, true] {
            let err = format!("{:#}", run(args(eval.clone(), force)).unwrap_err());
            assert!(
                err.contains("evaluation") && err.contains("run.json"),
                "{err}"
            );
        }
        assert_eq!(listing(&eval), before, "nothing was added");
        // An evaluation still writing holds the lock.
        let busy = dir.path().join("busy");
        let _held = vlnverse_score::OutputLock::acquire(&busy, "evaluate").unwrap();
        let err = format!("{:#}", run(args(busy.clone(), false)).unwrap_err());
        assert!(err.contains("another job"), "{err}");
        assert!(!busy.join("summary.json").exists());
        // Someone else's summary.json is kept unless --force.
        let other = dir.path().join("other");
        std::fs::create_dir(&other).unwrap();
        std::fs::write(other.join("summary.json"), "mine").unwrap();
        let err = format!("{:#}", run(args(other.clone(), false)).unwrap_err());
        assert!(err.contains("--force"), "{err}");
        assert_eq!(std::fs::read(other.join("summary.json")).unwrap(), b"mine");
        run(args(other.clone(), true)).unwrap();
        assert_ne!(std::fs::read(other.join("summary.json")).unwrap(), b"mine");
        // Score's own folder is rescored without --force.
        let own = dir.path().join("own");
        run(args(own.clone(), false)).unwrap();
        run(args(own.clone(), false)).unwrap();
        assert!(own.join(vlnverse_score::lock::SCORE_FILE).is_file());
        // A dataset folder, and a file, are refused in words.
        let err = format!(
            "{:#}",
            run(args(dir.path().to_path_buf(), true)).unwrap_err()
        );
        assert!(err.contains("dataset folder"), "{err}");
        let err = format!("{:#}", run(args(traj.clone(), false)).unwrap_err());
        assert!(err.contains("is a file, not a folder"), "{err}");
    }

    #[test]
    fn score_refuses_trajectories_away_from_the_start_or_absurdly_far() {
        let dir = tempfile::tempdir().unwrap();
        straight_episode(dir.path(), 1, 5.0);
        let out = dir.path().join("run");
        let args = |name: &str, line: &str, tol: f32| {
            let traj = dir.path().join(name);
            std::fs::write(&traj, line).unwrap();
            Args {
                start_tolerance: tol,
                ..score_args(dir.path(), traj, out.clone())
            }
        };
        // Regression: a position 1e9 m away made nDTW resampling loop forever.
        let far = "{\"episode_id\":1,\"positions\":[[0,0,0],[1e9,0,0]],\"stopped\":true}\n";
        let err = format!("{:#}", run(args("far.jsonl", far, 0.5)).unwrap_err());
        assert!(
            err.contains("episode 1") && err.contains("positions[1]") && err.contains("far.jsonl"),
            "{err}"
        );
        // Regression: a trajectory of just the goal scored SR 100 / SPL 100.
        let teleport = "{\"episode_id\":1,\"positions\":[[5,0,0]],\"stopped\":true}\n";
        let err = format!("{:#}", run(args("tp.jsonl", teleport, 0.5)).unwrap_err());
        assert!(
            err.contains("episode 1")
                && err.contains("[5.0, 0.0, 0.0]")
                && err.contains("[0.0, 0.0, 0.0]")
                && err.contains("--start-tolerance"),
            "{err}"
        );
        // A robot that started 0.4 m off (height ignored) is fine; a relaxed tolerance lets a
        // farther start through.
        let off = "{\"episode_id\":1,\"positions\":[[0.4,1.0,0],[5,0,0]],\"stopped\":true}\n";
        run(args("off.jsonl", off, 0.5)).unwrap();
        run(args("tp2.jsonl", teleport, 6.0)).unwrap();
    }
}
