//! Built-in agents on a small procgen dataset: the oracle reaches the goal, baselines do not.

use crate::eval_support;

use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, ActionSpace, EvalConfig, EvalRequest, Setting};
#[allow(unused_imports)]
use vlnverse_score::EpisodeMetrics;
use vlnverse_score::{Split, Task};
use vlnverse_sensors::Backend;

fn request(dir: &std::path::Path, out: &str, setting: Setting, space: ActionSpace) -> EvalRequest {
    EvalRequest::new(dir.to_path_buf(), Task::Fine, Split::Test, dir.join(out))
        .threads(2)
        .config(EvalConfig {
            setting,
            action_space: space,
            backend: Some(Backend::Raycast),
            render: false,
            plots: 2,
            ..Default::default()
        })
}

#[test]
fn oracle_succeeds_in_telhop_and_strict_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 3, 12, 7);
    assert!(eps.len() >= 30);
    let oracle = builtin("oracle", None, &EvalConfig::default()).unwrap();
    for (setting, space) in [
        (Setting::Telhop, ActionSpace::Waypoint),
        (Setting::Telhop, ActionSpace::Discrete),
    ] {
        let out = evaluate(
            &request(
                dir.path(),
                &format!("{setting}_{}", space.name()),
                setting,
                space,
            ),
            &*oracle,
        )
        .unwrap();
        let s = &out.summary.summary;
        eprintln!(
            "oracle {setting} {}: SR {:.3} SPL {:.3} nDTW {:.3} steps {:.1}",
            space.name(),
            s.sr,
            s.spl,
            s.ndtw,
            s.steps
        );
        assert_eq!(s.episodes, eps.len());
        assert!(
            s.sr >= 0.99,
            "oracle SR {} in {setting}/{}",
            s.sr,
            space.name()
        );
        assert!(s.spl > 0.8, "oracle SPL {}", s.spl);
    }
    let out = evaluate(
        &request(dir.path(), "strict", Setting::Strict, ActionSpace::Discrete),
        &*oracle,
    )
    .unwrap();
    let s = &out.summary.summary;
    eprintln!(
        "oracle strict discrete: SR {:.3} SPL {:.3} CR {:.4} collisions {:.2}",
        s.sr, s.spl, s.cr, s.collisions
    );
    assert!(s.sr > 0.5, "oracle SR in Strict {}", s.sr);
}

#[test]
fn baselines_fail_and_summary_is_the_mean_of_episodes() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 2, 15, 11);
    let cfg = EvalConfig::default();
    let mut srs = Vec::new();
    for name in ["random", "stop", "forward"] {
        let f = builtin(name, None, &cfg).unwrap();
        let out = evaluate(
            &request(dir.path(), name, Setting::Lenient, ActionSpace::Discrete),
            &*f,
        )
        .unwrap();
        let s = &out.summary.summary;
        eprintln!(
            "{name} lenient: SR {:.3} SPL {:.3} NE {:?} CR {:.3}",
            s.sr, s.spl, s.ne, s.cr
        );
        assert_eq!(s.episodes, eps.len());
        srs.push(s.sr);
        // summary.json holds plain means of the per-episode rows.
        let n = out.records.len() as f64;
        let mean = |f: &dyn Fn(&vlnverse_score::EpisodeMetrics) -> f64| {
            out.records.iter().map(|r| f(&r.metrics)).sum::<f64>() / n
        };
        let json: serde_json::Value = serde_json::from_slice(
            &std::fs::read(dir.path().join(name).join("summary.json")).unwrap(),
        )
        .unwrap();
        for (key, m) in [
            ("sr", mean(&|m| m.success as u8 as f64)),
            ("osr", mean(&|m| m.oracle_success as u8 as f64)),
            ("spl", mean(&|m| m.spl as f64)),
            ("ndtw", mean(&|m| m.ndtw as f64)),
            ("tl", mean(&|m| m.tl as f64)),
            ("cr_episode_mean", mean(&|m| m.cr as f64)),
        ] {
            let v = json[key].as_f64().unwrap();
            assert!((v - m).abs() < 1e-6, "{name}: {key} {v} vs mean {m}");
            assert!(key == "tl" || (0.0..=1.0).contains(&v), "{key} = {v}");
        }
        // CR is the paper's pooled ratio: all collisions over all actions.
        let (hits, actions) = out.records.iter().fold((0u64, 0u64), |(c, a), r| {
            (c + r.metrics.collisions as u64, a + r.metrics.steps as u64)
        });
        let pooled = hits as f64 / actions.max(1) as f64;
        assert!(
            (json["cr"].as_f64().unwrap() - pooled).abs() < 1e-9,
            "{name}: cr"
        );
        let csv = std::fs::read_to_string(dir.path().join(name).join("episodes.csv")).unwrap();
        assert_eq!(csv.lines().count(), eps.len() + 1);
        let trajs =
            std::fs::read_to_string(dir.path().join(name).join("trajectories.jsonl")).unwrap();
        assert_eq!(trajs.lines().count(), eps.len());
        assert!(dir.path().join(name).join("report.md").is_file());
        assert!(
            dir.path()
                .join(name)
                .join("plots")
                .read_dir()
                .unwrap()
                .count()
                >= 1
        );
    }
    // Random walks and walking straight rarely end within 3 m of a goal 4-14 m away.
    assert!(srs[0] <= 0.35, "random SR {}", srs[0]);
    assert!(srs[2] <= 0.35, "forward SR {}", srs[2]);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 2, 8, 5);
    let f = builtin("random", None, &EvalConfig::default()).unwrap();
    let mut one = request(dir.path(), "one", Setting::Lenient, ActionSpace::Discrete);
    one.threads = Some(1);
    let mut two = request(dir.path(), "two", Setting::Lenient, ActionSpace::Discrete);
    two.threads = Some(2);
    evaluate(&one, &*f).unwrap();
    evaluate(&two, &*f).unwrap();
    for file in ["summary.json", "episodes.csv", "trajectories.jsonl"] {
        assert_eq!(
            std::fs::read(dir.path().join("one").join(file)).unwrap(),
            std::fs::read(dir.path().join("two").join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn semantic_agent_finds_named_objects_without_the_goal() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_object_dataset(dir.path(), 2, 6, 3);
    assert!(!eps.is_empty());
    let cfg = EvalConfig {
        setting: Setting::Lenient,
        rig: eval_support::small_rig(dir.path()),
        plots: 1,
        ..Default::default()
    };
    let mut sr = Vec::new();
    for name in ["semantic", "random"] {
        let req = EvalRequest::new(
            dir.path().to_path_buf(),
            Task::Coarse,
            Split::Test,
            dir.path().join(name),
        )
        .threads(2)
        .config(cfg.clone());
        let out = evaluate(&req, &*builtin(name, None, &cfg).unwrap()).unwrap();
        let s = &out.summary.summary;
        eprintln!(
            "{name} coarse lenient: {} episodes SR {:.3} OSR {:.3} NE {:?} steps {:.1}",
            s.episodes, s.sr, s.osr, s.ne, s.steps
        );
        sr.push(s.sr);
    }
    assert!(
        sr[0] > sr[1],
        "semantic SR {} should beat random {}",
        sr[0],
        sr[1]
    );
}

#[test]
fn continuous_space_oracle_succeeds_with_velocity_commands_and_baselines_stay_legal() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 2, 6, 13);
    let cfg = EvalConfig::default();
    for (name, setting) in [
        ("oracle", Setting::Lenient),
        ("oracle", Setting::Strict),
        ("random", Setting::Lenient),
        ("forward", Setting::Lenient),
    ] {
        let f = builtin(name, None, &cfg).unwrap();
        let run = format!("{name}_{setting}_continuous");
        let req = request(dir.path(), &run, setting, ActionSpace::Continuous);
        // An action outside the space would stop the run with an error.
        let out = evaluate(&req, &*f).unwrap();
        let s = &out.summary.summary;
        eprintln!(
            "{name} {setting} continuous: SR {:.3} SPL {:.3} CR {:.4} steps {:.1}",
            s.sr, s.spl, s.cr, s.steps
        );
        assert_eq!(s.episodes, eps.len());
        for r in &out.records {
            let actions = r.trajectory.actions.as_ref().unwrap();
            assert!(
                actions.iter().all(|a| a == "velocity" || a == "stop"),
                "{name}: {actions:?}"
            );
        }
        if name == "oracle" {
            assert!(s.sr >= 0.99, "oracle SR {} in {setting}/continuous", s.sr);
            assert!(s.spl > 0.8, "oracle SPL {}", s.spl);
        }
    }
}
