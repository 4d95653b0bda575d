//! An interrupted run resumes: finished episodes are kept, the rest run, outputs match a run
//! that was never interrupted.

use crate::eval_support;

use vlnverse_task::eval::agents::builtin;
use vlnverse_task::eval::{evaluate, EvalConfig, EvalRequest, Setting};
use vlnverse_task::{Split, Task};

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
    let req = |out: &str, n: Option<usize>| EvalRequest {
        dataset: dir.path().to_path_buf(),
        task: Task::Fine,
        split: Split::Test,
        episodes: n,
        threads: Some(2),
        out: dir.path().join(out),
        config: cfg.clone(),
    };
    let f = builtin("random", None, &cfg).unwrap();
    let full = evaluate(&req("full", None), &*f, &|| {}).unwrap();
    assert_eq!(full.resumed, 0);

    // "Kill" a run: keep 5 finished lines and half of the 6th.
    let partial = dir.path().join("partial");
    evaluate(&req("partial", None), &*f, &|| {}).unwrap();
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

    let resumed = evaluate(&req("partial", None), &*f, &|| {}).unwrap();
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
    let again = evaluate(&req("partial", None), &*f, &|| {}).unwrap();
    assert_eq!((again.resumed, again.steps_run), (eps.len(), 0));

    // Another agent in the same folder is refused.
    let stop = builtin("stop", None, &cfg).unwrap();
    let err = evaluate(&req("partial", None), &*stop, &|| {})
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
