//! Generation configs and the allocation of episodes to scenes: the vlnverse preset reproduces
//! the paper's Table 2 exactly; bad configs give errors naming file, field and value.

use std::collections::BTreeSet;
use std::path::Path;

use proptest::prelude::*;
use vlnverse_generate::episodes_per_trajectory;
use vlnverse_generate::{assign_scene_splits, plan, spread};
use vlnverse_generate::{GenerateConfig, GeneratePreset};
use vlnverse_score::{Split, Task};

/// Table 2 of the VLNVerse paper: (episodes, scenes) per task and split.
const TABLE2: [(Task, [(usize, usize); 4]); 5] = [
    (Task::Fine, [(3963, 177), (423, 157), (825, 33), (1325, 53)]),
    (
        Task::Coarse,
        [(11895, 177), (1269, 162), (2505, 33), (3975, 53)],
    ),
    (
        Task::VisualReference,
        [(11895, 177), (1269, 162), (2505, 33), (3975, 53)],
    ),
    (
        Task::LongHorizon,
        [(11946, 177), (1329, 177), (2475, 33), (3975, 53)],
    ),
    (
        Task::Dialogue,
        [(11895, 177), (1269, 162), (2505, 33), (3975, 53)],
    ),
];

#[test]
fn vlnverse_plan_has_table2_counts_exactly() {
    let cfg = GeneratePreset::Vlnverse.config().unwrap();
    let p = plan(&cfg, &Task::ALL);
    assert_eq!(p.scenes.len(), 263);
    for (task, cells) in TABLE2 {
        for (split, (episodes, scenes)) in Split::ALL.into_iter().zip(cells) {
            assert_eq!(p.episodes(task, split), episodes, "{task} {split} episodes");
            assert_eq!(p.scene_count(task, split), scenes, "{task} {split} scenes");
        }
    }
    assert_eq!(p.total_episodes(&Task::ALL), 85_193);
}

#[test]
fn vlnverse_splits_are_scene_disjoint_and_val_seen_uses_train_scenes() {
    let cfg = GeneratePreset::Vlnverse.config().unwrap();
    let splits = assign_scene_splits(&cfg);
    let count = |s: Split| splits.iter().filter(|&&x| x == s).count();
    assert_eq!(
        (
            count(Split::Train),
            count(Split::ValUnseen),
            count(Split::Test)
        ),
        (177, 33, 53)
    );
    let p = plan(&cfg, &Task::ALL);
    for sp in &p.scenes {
        for share in &sp.shares {
            let pool = match share.split {
                Split::ValSeen => Split::Train,
                s => s,
            };
            assert_eq!(sp.split, pool, "scene {} has {share:?}", sp.index);
            assert!(share.trajectories > 0);
        }
    }
}

#[test]
fn episode_ids_are_contiguous_in_scene_order() {
    let cfg = GeneratePreset::Vlnverse.config().unwrap();
    let p = plan(&cfg, &Task::ALL);
    for task in Task::ALL {
        for split in Split::ALL {
            let mut next = 0;
            for sp in &p.scenes {
                for s in sp
                    .shares
                    .iter()
                    .filter(|s| s.task == task && s.split == split)
                {
                    assert_eq!(s.first_episode_id, next);
                    assert_eq!(s.episodes(), s.trajectories * episodes_per_trajectory(task));
                    next += s.episodes() as u64;
                }
            }
            assert_eq!(next as usize, p.episodes(task, split));
        }
    }
}

#[test]
fn plan_depends_only_on_the_config() {
    let cfg = GeneratePreset::Vlnverse.config().unwrap();
    assert_eq!(plan(&cfg, &Task::ALL), plan(&cfg, &Task::ALL));
    let mut other = cfg.clone();
    other.seed += 1;
    assert_ne!(assign_scene_splits(&cfg), assign_scene_splits(&other));
    // Generating a subset of tasks does not move the others' episodes.
    let sub = plan(&cfg, &[Task::Fine]);
    let full = plan(&cfg, &Task::ALL);
    for (a, b) in sub.scenes.iter().zip(&full.scenes) {
        let fine: Vec<_> = b.shares.iter().filter(|s| s.task == Task::Fine).collect();
        assert_eq!(a.shares.iter().collect::<Vec<_>>(), fine);
    }
}

#[test]
fn tiny_preset_is_valid_and_small() {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    let p = plan(&cfg, &Task::ALL);
    let total = p.total_episodes(&Task::ALL);
    assert!((100..1000).contains(&total), "{total}");
    assert_eq!(p.scenes.len(), 5);
}

proptest! {
    #[test]
    fn spread_sums_exactly_and_evenly(total in 0usize..5000, slots in 1usize..300, seed: u64) {
        let v = spread(total, slots, seed);
        prop_assert_eq!(v.len(), slots);
        prop_assert_eq!(v.iter().sum::<usize>(), total);
        let (lo, hi) = (v.iter().min().unwrap(), v.iter().max().unwrap());
        prop_assert!(hi - lo <= 1);
    }

    #[test]
    fn rescaled_configs_stay_valid(scenes in 1usize..400) {
        let cfg = GeneratePreset::Vlnverse.config().unwrap().rescaled(scenes);
        prop_assert_eq!(cfg.splits.total(), scenes);
        prop_assert!(cfg.validate().is_ok(), "{:?}", cfg.validate());
        let p = plan(&cfg, &Task::ALL);
        let used: BTreeSet<usize> = p.scenes.iter().filter(|s| !s.shares.is_empty()).map(|s| s.index).collect();
        prop_assert_eq!(used.len(), scenes);
    }
}

fn err_of(text: &str) -> String {
    GenerateConfig::from_toml_str(text, Path::new("configs/generate/bad.toml"))
        .unwrap_err()
        .to_string()
}

fn edit(from: &str, to: &str) -> String {
    let base = GeneratePreset::Vlnverse.toml();
    assert!(base.contains(from), "{from}");
    base.replacen(from, to, 1)
}

#[test]
fn huge_counts_are_refused_before_anything_is_allocated() {
    let e = err_of(&edit(
        "train = 11895, val_seen = 1269",
        "train = 1000000000, val_seen = 1269",
    ));
    assert!(
        e.contains("bad.toml")
            && e.contains("tasks.coarse.episodes.train")
            && e.contains("1000000000"),
        "{e}"
    );
    let e = err_of(&edit("train = 177\n", "train = 9000000000000000000\n"));
    assert!(e.contains("splits.train") && e.contains("at most"), "{e}");
}

#[test]
fn absurd_and_non_finite_values_are_refused_by_name() {
    for (from, to, field) in [
        (
            "max_attempts = 400",
            "max_attempts = 0",
            "sampling.max_attempts",
        ),
        (
            "max_attempts = 400",
            "max_attempts = 4000000000",
            "sampling.max_attempts",
        ),
        (
            "max_length = 20.0",
            "max_length = 1e30",
            "tasks.fine.max_length",
        ),
        (
            "max_length = 20.0",
            "max_length = inf",
            "tasks.fine.max_length",
        ),
        (
            "camera_height = 1.25",
            "camera_height = nan",
            "image.camera_height",
        ),
        (
            "camera_height = 1.25",
            "camera_height = 500.0",
            "image.camera_height",
        ),
        (
            "oracle_budget = 5",
            "oracle_budget = 4000000",
            "tasks.dialogue.oracle_budget",
        ),
        (
            "sub_tasks_max = 3",
            "sub_tasks_max = 50",
            "tasks.long_horizon.sub_tasks_min",
        ),
    ] {
        let e = err_of(&edit(from, to));
        assert!(e.contains("bad.toml") && e.contains(field), "{to}: {e}");
    }
}

#[test]
fn bad_configs_name_file_field_and_value() {
    let e = err_of(&edit("min_length = 5.0", "min_length = -2.0"));
    assert!(
        e.contains("bad.toml") && e.contains("tasks.fine.min_length") && e.contains("-2"),
        "{e}"
    );

    let e = err_of(&edit(
        "train = 11895, val_seen = 1269",
        "train = 11896, val_seen = 1269",
    ));
    assert!(
        e.contains("tasks.coarse.episodes.train")
            && e.contains("11896")
            && e.contains("multiple of 3"),
        "{e}"
    );

    let e = err_of(&edit(
        "scenes = { train = 177, val_seen = 157",
        "scenes = { train = 177, val_seen = 190",
    ));
    assert!(
        e.contains("tasks.fine.scenes.val_seen") && e.contains("190"),
        "{e}"
    );

    let e = err_of(&edit("max_length = 20.0", "max_length = 4.0"));
    assert!(
        e.contains("tasks.fine.max_length") && e.contains('4'),
        "{e}"
    );

    let e = err_of(&edit("hfov_deg = 90.0", "hfov_deg = 190.0"));
    assert!(e.contains("image.hfov_deg") && e.contains("190"), "{e}");

    let e = err_of(&edit("sub_tasks_min = 2", "sub_tasks_min = 1"));
    assert!(e.contains("tasks.long_horizon.sub_tasks_min"), "{e}");

    // Unknown and missing fields: the parser names them and the line.
    let e = err_of(&edit("seed = 2026", "seed = 2026\nsed = 3"));
    assert!(
        e.contains("bad.toml") && e.contains("sed") && e.contains("line"),
        "{e}"
    );
    let e = err_of(&edit("seed = 2026", ""));
    assert!(e.contains("seed"), "{e}");
    let e = err_of(&edit("seed = 2026", "seed = \"many\""));
    assert!(
        e.contains("bad.toml") && e.contains("line 8") && e.contains("seed"),
        "{e}"
    );
}

#[test]
fn presets_parse_by_name() {
    assert_eq!(
        "tiny".parse::<GeneratePreset>().unwrap(),
        GeneratePreset::Tiny
    );
    let e = "huge".parse::<GeneratePreset>().unwrap_err().to_string();
    assert!(e.contains("huge") && e.contains("tiny"), "{e}");
}
