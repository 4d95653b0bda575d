//! An interrupted run resumes: finished episodes are kept, the rest run, outputs match a run
//! that was never interrupted.

use crate::eval_support;

use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, EvalConfig, Setting};
use vlnverse_score::Task;

#[test]
fn a_truncated_run_resumes_and_keeps_finished_episodes() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 2, 6, 9);
    let cfg = EvalConfig {
        setting: Setting::Lenient,
        render: false,
        plots: 0,
        ..Default::default()
    };
    let req = |out: &str, n: Option<usize>| eval_support::fine_test(dir.path(), out, &cfg, n, 2);
    let f = builtin("random", None, &cfg).unwrap();
    let full = evaluate(&req("full", None), &*f).unwrap();
    assert_eq!(full.resumed, 0);

    // "Kill" a run: keep 5 finished lines and half of the 6th.
    let partial = dir.path().join("partial");
    evaluate(&req("partial", None), &*f).unwrap();
    let log = std::fs::read_to_string(partial.join("progress.jsonl")).unwrap();
    let lines: Vec<&str> = log.lines().collect();
    assert_eq!(lines.len(), eps.len());
    let mut cut = lines[..5].join("\n");
    cut.push('\n');
    cut.push_str(&lines[5][..lines[5].len() / 2]);
    std::fs::write(partial.join("progress.jsonl"), cut).unwrap();
    for f in ["summary.json", "episodes.csv", "trajectories.jsonl"] {
        std::fs::remove_file(partial.join(f)).unwrap();
    }

    let resumed = evaluate(&req("partial", None), &*f).unwrap();
    assert_eq!(resumed.resumed, 5);
    assert_eq!(resumed.records.len(), eps.len());
    let log = std::fs::read_to_string(partial.join("progress.jsonl")).unwrap();
    assert_eq!(
        log.lines().count(),
        eps.len(),
        "the half line was cut, the rest appended"
    );
    for file in ["summary.json", "episodes.csv", "trajectories.jsonl"] {
        assert_eq!(
            std::fs::read(dir.path().join("full").join(file)).unwrap(),
            std::fs::read(partial.join(file)).unwrap(),
            "{file}"
        );
    }
    // Nothing left to do: a third call runs no step.
    let again = evaluate(&req("partial", None), &*f).unwrap();
    assert_eq!((again.resumed, again.steps_run), (eps.len(), 0));

    // Another agent in the same folder is refused.
    let stop = builtin("stop", None, &cfg).unwrap();
    let err = evaluate(&req("partial", None), &*stop)
        .unwrap_err()
        .to_string();
    assert!(err.contains("run.json") && err.contains("agent"), "{err}");
}

#[test]
fn protocol_files_load_and_bad_values_are_named() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/eval");
    for (name, setting) in [
        ("strict", Setting::Strict),
        ("telhop", Setting::Telhop),
        ("lenient", Setting::Lenient),
    ] {
        let cfg = EvalConfig::load(root.join(format!("{name}.toml"))).unwrap();
        assert_eq!(cfg.setting, setting);
        assert_eq!((cfg.max_steps, cfg.success_distance), (200, 3.0));
        let rig = cfg.rig_config().unwrap();
        assert_eq!(rig.sensors.len(), 2, "{name}: the paper's RGB-D rig");
        cfg.agent_config().unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "setting = \"strict\"\nmax_steps = 0\n").unwrap();
    let err = EvalConfig::load(&bad).unwrap_err().to_string();
    assert!(
        err.contains("bad.toml") && err.contains("max_steps") && err.contains('0'),
        "{err}"
    );
    std::fs::write(&bad, "setting = \"fast\"\n").unwrap();
    let err = EvalConfig::load(&bad).unwrap_err().to_string();
    assert!(
        err.contains("bad.toml") && err.contains("line 1") && err.contains("fast"),
        "{err}"
    );
}

#[test]
fn a_resume_with_another_identity_is_refused_naming_the_key_and_both_values() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 5);
    let strict = EvalConfig {
        setting: Setting::Strict,
        render: false,
        plots: 0,
        max_steps: 5,
        ..Default::default()
    };
    let req =
        |cfg: &EvalConfig, n: Option<usize>| eval_support::fine_test(dir.path(), "run", cfg, n, 1);
    let random = builtin("random", None, &strict).unwrap();
    evaluate(&req(&strict, Some(1)), &*random).unwrap();
    // More episodes with the same identity is a resume, not another run.
    evaluate(&req(&strict, None), &*random).unwrap();

    let refused = |cfg: &EvalConfig, f: &dyn vlnverse_eval::AgentFactory| {
        evaluate(&req(cfg, None), f).unwrap_err().to_string()
    };
    // Regression: a strict run resumed as telhop (whose file also changes the action space)
    // is refused on `setting`, the first key that differs.
    let telhop = EvalConfig {
        setting: Setting::Telhop,
        action_space: vlnverse_eval::ActionSpace::Waypoint,
        ..strict.clone()
    };
    let err = refused(&telhop, &*random);
    assert!(
        err.contains("run.json")
            && err.contains("`setting`")
            && err.contains("\"telhop\"")
            && err.contains("\"strict\"")
            && !err.contains("action_space"),
        "{err}"
    );
    // Keys that were missing from run.json before: render, backend, rig, observations.
    let rendered = EvalConfig {
        render: true,
        ..strict.clone()
    };
    let err = refused(&rendered, &*random);
    assert!(
        err.contains("`render`") && err.contains("true") && err.contains("false"),
        "{err}"
    );
    let raster = EvalConfig {
        backend: Some(vlnverse_sensors::Backend::Raster),
        ..strict.clone()
    };
    let err = refused(&raster, &*random);
    assert!(err.contains("`backend`") && err.contains("raster"), "{err}");
    let rig = EvalConfig {
        rig: eval_support::small_rig(dir.path()),
        ..strict.clone()
    };
    let err = refused(&rig, &*random);
    assert!(err.contains("`rig`"), "{err}");
    let b64 = EvalConfig {
        external_observations: vlnverse_eval::agents::ObsEncoding::Base64,
        ..strict.clone()
    };
    let err = refused(&b64, &*random);
    assert!(
        err.contains("`external_observations`") && err.contains("base64"),
        "{err}"
    );
}

#[test]
fn external_runs_with_another_command_are_different_runs() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 1, 5);
    let cfg = EvalConfig {
        render: false,
        plots: 0,
        max_steps: 3,
        ..Default::default()
    };
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
    // A shell agent that answers every step with STOP.
    let stop_cmd =
        "while read l; do case \"$l\" in *'\"step\"'*) echo '{\"action\":\"stop\"}';; esac; done";
    let a = builtin("external", Some(stop_cmd), &cfg).unwrap();
    let out = evaluate(&req, &*a).unwrap();
    assert_eq!(out.records.len(), 1);
    let other = format!("{stop_cmd} # v2");
    let b = builtin("external", Some(&other), &cfg).unwrap();
    let err = evaluate(&req, &*b).unwrap_err().to_string();
    assert!(err.contains("`agent_cmd`") && err.contains("v2"), "{err}");
}

#[test]
fn zero_episodes_and_blind_looking_agents_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 1, 5);
    let cfg = EvalConfig {
        render: false,
        plots: 0,
        ..Default::default()
    };
    let req = |n: Option<usize>, out: &str| eval_support::fine_test(dir.path(), out, &cfg, n, 1);
    let random = builtin("random", None, &cfg).unwrap();
    let err = evaluate(&req(Some(0), "zero"), &*random)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("episodes") && err.contains("at least 1"),
        "{err}"
    );
    // Regression: `--agent semantic --no-render` ran blind (SR 0) without a word.
    let semantic = builtin("semantic", None, &cfg).unwrap();
    let err = evaluate(&req(None, "blind"), &*semantic)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("render") && err.contains("semantic") && err.contains("blind"),
        "{err}"
    );
    // Nothing is written, so the same folder takes the run once rendering is on.
    assert!(!dir.path().join("blind/run.json").exists());
    assert!(!dir.path().join("blind/progress.jsonl").exists());
    // Blind agents still run without rendering.
    evaluate(&req(None, "random"), &*random).unwrap();
}

#[test]
fn config_parse_errors_name_the_file_and_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("neg.toml");
    std::fs::write(&bad, "setting = \"strict\"\nseed = 1\nmax_steps = -5\n").unwrap();
    let err = EvalConfig::load(&bad).unwrap_err().to_string();
    assert!(
        err.contains("neg.toml") && err.contains("line 3") && err.contains("`max_steps`"),
        "{err}"
    );
    std::fs::write(&bad, "max_stepz = 5\n").unwrap();
    let err = EvalConfig::load(&bad).unwrap_err().to_string();
    assert!(
        err.contains("neg.toml") && err.contains("max_stepz"),
        "{err}"
    );
}

#[test]
fn a_run_with_the_full_rig_resumes() {
    // Regression: f32 rig values (e.g. `b = 0.0019`) stored in run.json as f64 read back one
    // bit off without serde_json's float_roundtrip, so such runs could never be resumed.
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 5);
    let rig =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/sensors/full.toml");
    let cfg = EvalConfig {
        rig: rig.display().to_string(),
        render: false,
        plots: 0,
        max_steps: 5,
        ..Default::default()
    };
    let req = |n: Option<usize>| eval_support::fine_test(dir.path(), "run", &cfg, n, 1);
    let random = builtin("random", None, &cfg).unwrap();
    evaluate(&req(Some(1)), &*random).unwrap();
    let out = evaluate(&req(None), &*random).unwrap();
    assert_eq!(out.resumed, 1);
}
