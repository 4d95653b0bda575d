//! End to end on a real third-party home (issue 7): `cargo xtask import` of the AWS RoboMaker
//! small house with the shipped mapping, `generate --scenes-from` of a few episodes of all five
//! tasks on it, and the oracle agent under `evaluate` (telhop, rendered; strict, unrendered),
//! all through the real binary. Skipped with a message when `../shared/scenes/` is absent.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::Vec2;
use vlnverse_env::occupancy::GridMap;
use vlnverse_task::dataset::read_split;
use vlnverse_task::{Split, Task};

const SCENE_ID: &str = "aws_small_house_yup";

/// The workspace root: configs are looked up relative to it.
fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn aws_glb() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/scenes/aws_small_house/aws_small_house_yup.glb"
    ))
}

/// Run the xtask binary from the workspace root; panics with its output when it fails.
fn xtask(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .current_dir(root())
        .env("RUST_LOG", "warn")
        .output()
        .expect("run xtask");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "xtask {args:?} failed:\n{stdout}\n{stderr}"
    );
    stdout
}

/// A small generation config for one scene: every task in the `train` split only, a few
/// trajectories each (coarse, visual reference and dialogue write 3 episodes per trajectory).
const CONFIG: &str = r#"
name = "real_scene_e2e"
seed = 11
scene_preset = "tiny"

[splits]
train = 1
val_unseen = 0
test = 0

[sampling]
max_attempts = 400
goal_max_distance = 1.0
goal_min_distance = 0.0

[image]
width = 64
height = 64
hfov_deg = 90.0
camera_height = 1.25

[tasks.fine]
min_length = 3.0
max_length = 20.0
episodes = { train = 3, val_seen = 0, val_unseen = 0, test = 0 }
scenes = { train = 1, val_seen = 0, val_unseen = 0, test = 0 }

[tasks.coarse]
min_length = 2.5
max_length = 25.0
episodes = { train = 6, val_seen = 0, val_unseen = 0, test = 0 }
scenes = { train = 1, val_seen = 0, val_unseen = 0, test = 0 }

[tasks.visual_reference]
min_length = 2.5
max_length = 25.0
episodes = { train = 6, val_seen = 0, val_unseen = 0, test = 0 }
scenes = { train = 1, val_seen = 0, val_unseen = 0, test = 0 }

[tasks.long_horizon]
min_length = 1.5
max_length = 20.0
sub_tasks_min = 2
sub_tasks_max = 3
episodes = { train = 3, val_seen = 0, val_unseen = 0, test = 0 }
scenes = { train = 1, val_seen = 0, val_unseen = 0, test = 0 }

[tasks.dialogue]
min_length = 2.5
max_length = 25.0
oracle_budget = 5
episodes = { train = 6, val_seen = 0, val_unseen = 0, test = 0 }
scenes = { train = 1, val_seen = 0, val_unseen = 0, test = 0 }
"#;

fn expected_episodes(task: Task) -> usize {
    match task {
        Task::Fine | Task::LongHorizon => 3,
        Task::Coarse | Task::VisualReference | Task::Dialogue => 6,
    }
}

fn navigable(map: &GridMap, p: [f32; 3]) -> bool {
    map.is_free_at(Vec2::new(p[0], p[2]))
}

/// `summary.json` of an evaluation run: (episodes, SR, unreachable).
fn summary(run: &Path) -> (u64, f64, u64) {
    let path = run.join("summary.json");
    let text = std::fs::read_to_string(&path).expect("summary.json");
    let v: serde_json::Value = serde_json::from_str(&text).expect("summary.json is JSON");
    let num = |k: &str| {
        v[k].as_f64()
            .unwrap_or_else(|| panic!("{}: no number `{k}`", path.display()))
    };
    (num("episodes") as u64, num("sr"), num("unreachable") as u64)
}

#[test]
fn aws_house_import_generate_all_tasks_and_oracle_succeeds() {
    let glb = aws_glb();
    if !glb.is_file() {
        eprintln!(
            "skipped: {} is absent (the shared real scenes are not checked out)",
            glb.display()
        );
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let scenes = tmp.path().join("scenes");
    let ds = tmp.path().join("ds");
    let cfg = tmp.path().join("gen.toml");
    std::fs::write(&cfg, CONFIG).unwrap();

    let out = xtask(&[
        "import",
        "--input",
        glb.to_str().unwrap(),
        "--mapping",
        "configs/import/aws_small_house.toml",
        "--out",
        scenes.to_str().unwrap(),
    ]);
    assert!(out.contains("19.00 x 3.00 x 11.40 m"), "{out}");
    assert!(scenes.join(SCENE_ID).join("navigable.yaml").is_file());

    xtask(&[
        "generate",
        "--config",
        cfg.to_str().unwrap(),
        "--scenes-from",
        scenes.to_str().unwrap(),
        "--threads",
        "2",
        "--out",
        ds.to_str().unwrap(),
    ]);
    // The dataset carries its own copy of the imported scene; episodes are checked against it.
    let map = GridMap::load_ros(ds.join("scenes").join(SCENE_ID).join("navigable.yaml"))
        .expect("navigable map of the scene in the dataset");

    for task in Task::ALL {
        let eps = read_split(&ds, task, Split::Train).expect("train split");
        assert_eq!(eps.len(), expected_episodes(task), "{task}: episodes");
        for e in &eps {
            let id = format!("{task} episode {}", e.episode_id);
            assert_eq!(e.scene_id, SCENE_ID, "{id}");
            assert!(
                navigable(&map, e.start_position),
                "{id}: start {:?}",
                e.start_position
            );
            assert!(!e.goals.is_empty(), "{id}: no goal");
            for g in e.goal_sequence() {
                assert!(navigable(&map, g.position), "{id}: goal {:?}", g.position);
            }
            let end = *e.reference_path.last().expect("reference path");
            assert!(navigable(&map, end), "{id}: path end {end:?}");
            assert!(!e.instruction.instruction_text.is_empty(), "{id}");
        }
        if task == Task::LongHorizon {
            assert!(
                eps.iter().all(|e| e.sub_goals.len() >= 2),
                "long-horizon sub-goals"
            );
        }

        for (setting, render) in [("telhop", true), ("strict", false)] {
            let run = tmp.path().join(format!("run-{task}-{setting}"));
            let mut args = vec![
                "evaluate",
                "--dataset",
                ds.to_str().unwrap(),
                "--task",
                task.name(),
                "--split",
                "train",
                "--agent",
                "oracle",
                "--setting",
                setting,
                "--threads",
                "2",
                "--out",
                run.to_str().unwrap(),
            ];
            if !render {
                args.push("--no-render");
            }
            let out = xtask(&args);
            let (n, sr, unreachable) = summary(&run);
            eprintln!("{}", out.trim());
            assert_eq!(
                n as usize,
                eps.len(),
                "{task} {setting}: episodes evaluated"
            );
            assert_eq!(unreachable, 0, "{task} {setting}: unreachable goals");
            assert!(sr >= 0.9, "{task} {setting}: oracle SR {sr}");
        }
    }
}
