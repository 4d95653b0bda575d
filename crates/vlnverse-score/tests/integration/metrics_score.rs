//! Scoring a hand-made dataset end to end on a navigable map, and the run files.

use std::path::Path;

use glam::Vec2;
use vlnverse_env::occupancy::{CellState, GridMap};
use vlnverse_score::dataset::{read_split, write_split};
use vlnverse_score::metrics::{match_trajectories, score_all, GoalDistances, MetricsConfig};
use vlnverse_score::report::{
    episodes_csv, markdown_table, write_run, ReportRow, RunSummary, CSV_HEADER,
};
use vlnverse_score::score::{navigable_map_path, score_on_maps};
use vlnverse_score::trajectory::read_trajectories;
use vlnverse_score::{Episode, EpisodeInfo, Goal, Instruction, Split, Style, Task};

/// A 10 m x 10 m room (0.1 m cells, origin at world (0, 0)) split by a wall at x = 5.0..5.2 m
/// running from z = 0 to z = 8 m; the only way around is the gap at z = 8..10 m.
fn write_map(dir: &Path, scene: &str) {
    let mut map = GridMap::new(100, 100, 0.1, Vec2::ZERO, CellState::Free).unwrap();
    for row in 0..80 {
        for col in 50..52 {
            map.set(col, row, CellState::Occupied);
        }
    }
    map.save_ros(dir.join("scenes").join(scene), "navigable")
        .unwrap();
}

fn episode(id: u64, start: [f32; 3], goal: [f32; 3], style: Style) -> Episode {
    Episode {
        episode_id: id,
        trajectory_id: id / 3,
        scene_id: "walled".into(),
        start_position: start,
        start_rotation: [0.0, 0.0, 0.0, 1.0],
        goals: vec![Goal {
            position: goal,
            radius: 3.0,
            object_id: Some(3),
        }],
        instruction: Instruction {
            instruction_text: "Go around the wall to the lamp.".into(),
            style: Some(style),
            ..Default::default()
        },
        reference_path: vec![start, [4.8, 0.0, 8.6], [5.4, 0.0, 8.6], goal],
        info: EpisodeInfo {
            geodesic_distance: 15.0,
            ..Default::default()
        },
        task: Task::Coarse,
        target_object_id: Some(3),
        reference_image: None,
        sub_goals: vec![],
        oracle_budget: None,
    }
}

#[test]
fn score_on_the_navigable_map_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    write_map(dir.path(), "walled");
    assert!(navigable_map_path(dir.path(), "walled").exists());
    let (start, goal) = ([2.0, 0.0, 1.0], [7.0, 0.0, 1.0]);
    let eps = vec![
        episode(0, start, goal, Style::Formal),
        episode(1, start, goal, Style::Natural),
        episode(2, start, goal, Style::Casual),
    ];
    write_split(dir.path(), Task::Coarse, Split::Test, &eps).unwrap();
    // 0: stops behind the wall, 2 m from the goal in a straight line but ~14 m around it.
    // 1: goes around and stops 0.5 m from the goal.
    // 2 (VLN-CE would drop it; we flag it): ends outside the map, the goal is unreachable.
    let lines = [
        r#"{"episode_id": 1, "positions": [[2,0,1],[4.8,0,8.6],[5.4,0,8.6],[7,0,1.5]], "stopped": true, "collisions": 1, "steps": 40}"#,
        r#"{"episode_id": 0, "positions": [[2,0,1],[4.5,0,1]], "stopped": true}"#,
        r#"{"episode_id": 2, "positions": [[2,0,1],[-3,0,1]], "stopped": false}"#,
    ];
    let tfile = dir.path().join("robot.jsonl");
    std::fs::write(&tfile, lines.join("\n")).unwrap();

    let eps = read_split(dir.path(), Task::Coarse, Split::Test).unwrap();
    let trajs = match_trajectories(&eps, read_trajectories(&tfile).unwrap(), false).unwrap();
    let cfg = MetricsConfig::default();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let ms = score_on_maps(dir.path(), &eps, &trajs, &cfg, &|n| {
        done.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(done.into_inner(), 3);
    let ids: Vec<u64> = ms.iter().map(|m| m.episode_id).collect();
    assert_eq!(ids, [0, 1, 2], "input order");

    let behind = &ms[0];
    let ne = behind.ne.unwrap();
    assert!(ne > 13.0 && ne < 16.0, "geodesic NE around the wall: {ne}");
    assert!(!behind.success && !behind.oracle_success);
    let euclid = score_all(&eps, &trajs, &GoalDistances::euclidean, &cfg);
    assert!(
        euclid[0].success,
        "a straight-line NE would call it a success"
    );

    let around = &ms[1];
    assert!(around.success && around.oracle_success);
    assert!(
        (around.ne.unwrap() - 0.5).abs() < 0.15,
        "ne {:?}",
        around.ne
    );
    assert!(around.spl > 0.9 && around.spl <= 1.0, "spl {}", around.spl);
    assert_eq!(around.cr, 1.0 / 40.0);

    let outside = &ms[2];
    assert!(outside.unreachable && outside.ne.is_none() && !outside.success);

    // CR pools collisions over actions (the paper); the per-episode mean weighs a short
    // episode with many collisions as much as a long clean one.
    let mut short = ms[1].clone();
    (short.collisions, short.steps, short.cr) = (1, 2, 0.5);
    let mut long = ms[1].clone();
    (long.collisions, long.steps, long.cr) = (0, 8, 0.0);
    let s = vlnverse_score::metrics::aggregate(&[short, long]);
    assert!((s.cr - 0.1).abs() < 1e-12, "pooled cr {}", s.cr);
    assert!((s.cr_episode_mean - 0.25).abs() < 1e-12);

    let ms: Vec<_> = ms
        .into_iter()
        .map(|mut m| {
            m.split = Some(Split::Test);
            m
        })
        .collect();
    let run = RunSummary::new("robot", Some("telhop"), Task::Coarse, Split::Test, &ms);
    let s = &run.summary;
    assert_eq!((s.episodes, s.unreachable), (3, 1));
    assert!((s.sr - 1.0 / 3.0).abs() < 1e-12);
    assert!(s.ne.unwrap().is_finite());
    assert_eq!(run.by_style.len(), 3);
    assert_eq!(run.by_style["natural"].sr, 1.0);

    let out = dir.path().join("run");
    write_run(&out, &run, &ms).unwrap();
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    for key in [
        "episodes", "tl", "ne", "sr", "osr", "spl", "ndtw", "sdtw", "cr",
    ] {
        assert!(
            summary[key].is_number(),
            "summary.json key {key}: {summary}"
        );
    }
    assert!(
        summary.get("sr_1").is_none(),
        "no SR_n outside long-horizon"
    );
    assert_eq!(summary["task"], "coarse");
    let back: RunSummary = serde_json::from_value(summary).unwrap();
    assert_eq!((back.summary.episodes, back.by_style.len()), (3, 3));
    assert!((back.summary.tl - run.summary.tl).abs() < 1e-9);

    let csv = std::fs::read_to_string(out.join("episodes.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 4);
    assert_eq!(rows[0], CSV_HEADER);
    let cols = CSV_HEADER.split(',').count();
    assert!(rows.iter().all(|r| r.split(',').count() == cols));
    // Episode 2: empty NE cell, unreachable = 1.
    assert!(
        rows[3].starts_with("2,0,walled,coarse,test,casual,15,"),
        "{}",
        rows[3]
    );
    assert!(rows[3].contains(",,"), "{}", rows[3]);

    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("| Method | Setting | TL | NE↓ | SR↑ | OSR↑ | SPL↑ | nDTW↑ | CR (%)↓ |"));
    assert!(md.contains("| robot | telhop |"), "{md}");
    assert!(md.contains("33.33"), "SR in percent: {md}");
}

#[test]
fn missing_map_and_missing_trajectories_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let eps = vec![episode(0, [2.0, 0.0, 1.0], [7.0, 0.0, 1.0], Style::Formal)];
    let trajs = match_trajectories(&eps, vec![], true).unwrap();
    assert!(trajs[0].positions.is_empty() && !trajs[0].stopped);
    let err = score_on_maps(dir.path(), &eps, &trajs, &MetricsConfig::default(), &|_| {})
        .unwrap_err()
        .to_string();
    assert!(err.contains("scenes/walled/navigable.yaml"), "{err}");
    let err = match_trajectories(&eps, vec![], false)
        .unwrap_err()
        .to_string();
    assert!(err.contains("no trajectory") && err.contains('0'), "{err}");
}

#[test]
fn csv_quotes_and_long_horizon_columns() {
    let mut ep = episode(4, [0.0; 3], [1.0, 0.0, 0.0], Style::Formal);
    ep.scene_id = "a,\"b\"".into();
    let t = vlnverse_score::Trajectory::from_positions(4, vec![[0.0; 3]], true);
    let m = vlnverse_score::score_episode(
        &ep,
        &t,
        &GoalDistances::euclidean(&ep),
        &MetricsConfig::default(),
    );
    let csv = episodes_csv(std::slice::from_ref(&m));
    assert!(
        csv.lines()
            .nth(1)
            .unwrap()
            .starts_with("4,1,\"a,\"\"b\"\"\",coarse,,formal,"),
        "{csv}"
    );

    let mut lh = vlnverse_score::aggregate(&[m]);
    lh.sr_1 = Some(0.5);
    lh.sr_2 = Some(0.25);
    lh.sr_all = Some(0.125);
    let md = markdown_table(&[ReportRow {
        method: "oracle".into(),
        setting: None,
        summary: lh,
    }]);
    assert!(md.contains("SR1↑ | SR2↑ | SR3↑ | SR-All↑"), "{md}");
    assert!(md.contains("| 50.00 | 25.00 | - | 12.50 |"), "{md}");
}
