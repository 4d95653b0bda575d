//! Regressions from a new-user review: absurd positions, trajectories that do not begin at the
//! start, errors printed twice, and the CR column of report.md.

use std::path::Path;

use vlnverse_score::dataset::read_split;
use vlnverse_score::metrics::{
    check_starts, resample, Summary, DEFAULT_START_TOLERANCE, MAX_RESAMPLED_POINTS,
};
use vlnverse_score::report::{markdown_report, RunSummary};
use vlnverse_score::trajectory::parse_trajectories;
use vlnverse_score::{Episode, Split, Task, Trajectory};

#[test]
fn resample_of_a_huge_polyline_is_bounded_and_exact_at_the_ends() {
    // Regression: an f32 running total stopped growing past ~4e6 m and the loop never ended.
    let pts = [[0.0, 0.0, 0.0], [1e9, 0.0, 0.0]];
    let out = resample(&pts, 0.25);
    assert!(out.len() <= MAX_RESAMPLED_POINTS + 2, "{}", out.len());
    assert_eq!((out[0], out[out.len() - 1]), (pts[0], pts[1]));
    assert!(out.windows(2).all(|w| w[1][0] >= w[0][0]), "monotone");
    // Ordinary paths keep the 0.25 m spacing.
    let out = resample(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], 0.25);
    let xs: Vec<f32> = out.iter().map(|p| p[0]).collect();
    assert_eq!(xs, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    // Non-finite input comes back as it is instead of looping.
    let nan = [[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0]];
    assert_eq!(resample(&nan, 0.25).len(), 2);
}

#[test]
fn absurdly_far_or_non_finite_positions_are_refused_naming_episode_and_index() {
    let path = Path::new("robot.jsonl");
    let far = "{\"episode_id\":1,\"positions\":[[0,0,0],[1e9,0,0]],\"stopped\":true}\n";
    let err = parse_trajectories(path, far).unwrap_err().to_string();
    assert!(
        err.contains("robot.jsonl")
            && err.contains("line 1")
            && err.contains("episode 1")
            && err.contains("positions[1]")
            && err.contains("100000 m"),
        "{err}"
    );
    let vlnce = "{\"4\": [{\"position\": [0,0,0]}, {\"position\": [0,0,-2e5]}]}";
    let err = parse_trajectories(path, vlnce).unwrap_err().to_string();
    assert!(
        err.contains("episode 4") && err.contains("positions[1]"),
        "{err}"
    );
    // 1e5 m itself is allowed.
    let edge = "{\"episode_id\":1,\"positions\":[[0,0,0],[100000,0,0]],\"stopped\":true}\n";
    assert_eq!(parse_trajectories(path, edge).unwrap().len(), 1);
}

fn episode(id: u64, start: [f32; 3]) -> Episode {
    Episode {
        episode_id: id,
        start_position: start,
        ..Default::default()
    }
}

#[test]
fn trajectories_must_begin_at_the_episode_start() {
    let eps = [episode(3, [1.0, 0.0, 2.0]), episode(4, [0.0, 0.0, 0.0])];
    let ok = [
        // 0.3 m off horizontally, 1 m off in height (the robot's odometry frame): fine.
        Trajectory::from_positions(3, vec![[1.3, 1.0, 2.0], [5.0, 0.0, 2.0]], true),
        // A missing trajectory scored as a failure has no positions.
        Trajectory::from_positions(4, Vec::new(), false),
    ];
    check_starts(&eps, &ok, DEFAULT_START_TOLERANCE).unwrap();
    // Regression: a trajectory of just the goal scored SR 100 / SPL 100.
    let teleport = [
        ok[0].clone(),
        Trajectory::from_positions(4, vec![[6.0, 0.0, 0.0]], true),
    ];
    let err = check_starts(&eps, &teleport, DEFAULT_START_TOLERANCE)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("episode 4")
            && err.contains("[6.0, 0.0, 0.0]")
            && err.contains("[0.0, 0.0, 0.0]")
            && err.contains("6.00 m"),
        "{err}"
    );
    check_starts(&eps, &teleport, 6.5).unwrap();
    assert!(check_starts(&eps, &ok, f32::NAN).is_err());
}

#[test]
fn a_missing_split_file_names_the_os_error_once() {
    let dir = tempfile::tempdir().unwrap();
    let err = read_split(dir.path(), Task::Fine, Split::Test).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("test.json.gz"), "{msg}");
    // Printers that walk the source chain (anyhow's `{:#}`) must not repeat the OS error.
    let mut chain = msg.clone();
    let mut src = std::error::Error::source(&err);
    while let Some(e) = src {
        chain.push_str(&format!(": {e}"));
        src = e.source();
    }
    let os = std::io::Error::from(std::io::ErrorKind::NotFound).to_string();
    assert!(chain.contains("os error") || chain.contains(&os), "{chain}");
    let n = chain
        .matches("os error")
        .count()
        .max(chain.matches(&os).count());
    assert_eq!(n, 1, "{chain}");
}

#[test]
fn report_cr_column_is_labelled_as_percent() {
    let run = RunSummary {
        method: "robot".into(),
        setting: None,
        task: Task::Fine,
        split: Split::Test,
        summary: Summary {
            episodes: 1,
            cr: 0.0051,
            ..Default::default()
        },
        by_style: Default::default(),
        benchmark_version: None,
    };
    let md = markdown_report(&run);
    assert!(md.contains("CR (%)↓"), "{md}");
    assert!(md.contains("| 0.51 |"), "{md}");
    assert!(
        md.contains("per 100 actions") && !md.contains("per action."),
        "{md}"
    );
}
