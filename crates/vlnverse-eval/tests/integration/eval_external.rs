//! The external-agent protocol end to end with examples/python/random_agent.py.

use crate::eval_support;

use vlnverse_eval::agents::builtin;
use vlnverse_eval::agents::ObsEncoding;
use vlnverse_eval::{evaluate, EvalConfig, EvalRequest, Setting};
use vlnverse_score::{Split, Task};

fn python() -> bool {
    std::process::Command::new("python3")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn python_random_agent_drives_episodes_through_the_protocol() {
    if !python() {
        eprintln!("skipped: python3 is not available");
        return;
    }
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/python/random_agent.py")
        .canonicalize()
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 4, 21);
    let cmd = format!("python3 {}", script.display());
    let mut results = Vec::new();
    for enc in [ObsEncoding::Files, ObsEncoding::Base64] {
        let cfg = EvalConfig {
            setting: Setting::Lenient,
            max_steps: 25,
            rig: eval_support::small_rig(dir.path()),
            external_observations: enc,
            plots: 0,
            ..Default::default()
        };
        let out_dir = dir.path().join(format!("{enc:?}"));
        let req = EvalRequest::new(
            dir.path().to_path_buf(),
            Task::Fine,
            Split::Test,
            out_dir.clone(),
        )
        .threads(2)
        .config(cfg.clone());
        let f = builtin("external", Some(&cmd), &cfg).unwrap();
        let out = evaluate(&req, &*f).unwrap();
        assert_eq!(out.records.len(), eps.len());
        for r in &out.records {
            let t = &r.trajectory;
            assert!(t.steps >= 1 && t.steps <= 25, "steps {}", t.steps);
            // The Python policy's actions reached the simulator.
            let acts = t.actions.as_ref().unwrap();
            assert!(acts.iter().any(|a| a != "stop"), "{acts:?}");
            assert!(
                acts.iter()
                    .all(|a| ["stop", "move_forward", "turn_left", "turn_right"]
                        .contains(&a.as_ref()))
            );
        }
        results.push(std::fs::read(out_dir.join("trajectories.jsonl")).unwrap());
    }
    // Seeded per episode: the same actions whichever way the images travel.
    assert_eq!(results[0], results[1]);

    // A broken agent gives an error naming the command and episode.
    let cfg = EvalConfig {
        plots: 0,
        render: false,
        ..Default::default()
    };
    let req = eval_support::fine_test(dir.path(), "broken", &cfg, Some(1), 1);
    let f = builtin("external", Some("echo not-json"), &cfg).unwrap();
    let err = evaluate(&req, &*f).unwrap_err().to_string();
    assert!(
        err.contains("echo not-json") && err.contains("episode"),
        "{err}"
    );
}

#[test]
fn an_agent_that_exits_early_reports_its_status_and_stderr() {
    // Regression: only "Broken pipe" was shown.
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 1, 21);
    let cfg = EvalConfig {
        plots: 0,
        render: false,
        ..Default::default()
    };
    let req = eval_support::fine_test(dir.path(), "dead", &cfg, None, 1);
    let cmd = "echo 'loading weights' >&2; echo 'CUDA out of memory' >&2; exit 3";
    let f = builtin("external", Some(cmd), &cfg).unwrap();
    let err = evaluate(&req, &*f).unwrap_err().to_string();
    assert!(
        err.contains("episode")
            && err.contains("exit status: 3")
            && err.contains("loading weights")
            && err.contains("CUDA out of memory"),
        "{err}"
    );
}

#[test]
fn an_agent_that_never_replies_is_stopped_after_the_timeout_naming_command_and_step() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 1, 21);
    let cfg = EvalConfig {
        plots: 0,
        render: false,
        external_timeout_s: 0.5,
        ..Default::default()
    };
    let req = eval_support::fine_test(dir.path(), "hung", &cfg, None, 1);
    // Reads every message and answers none.
    let cmd = "cat > /dev/null";
    let f = builtin("external", Some(cmd), &cfg).unwrap();
    let err = evaluate(&req, &*f).unwrap_err().to_string();
    assert!(
        err.contains(cmd)
            && err.contains("step 0")
            && err.contains("no reply within 0.5 s")
            && err.contains("external_timeout_s"),
        "{err}"
    );
    // Out of range is refused before anything runs.
    for bad in [0.0, -1.0, f64::NAN, 1e12] {
        let cfg = EvalConfig {
            external_timeout_s: bad,
            ..cfg.clone()
        };
        let err = cfg.validate().unwrap_err().to_string();
        assert!(err.contains("external_timeout_s"), "{err}");
    }
}

#[test]
fn an_agent_that_never_reads_its_input_is_stopped_after_the_timeout() {
    // Observations larger than the pipe buffer: the step message cannot be written to an
    // agent that does not read, and the write must not block the run.
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 1, 21);
    let rig = dir.path().join("big_rig.toml");
    std::fs::write(
        &rig,
        "backend = \"raycast\"\n[[sensors]]\ntype = \"rgb\"\nwidth = 192\nheight = 192\n",
    )
    .unwrap();
    let script = dir.path().join("deaf_agent.sh");
    std::fs::write(
        &script,
        "#!/bin/sh\n# Never reads its input.\nexec sleep 60\n",
    )
    .unwrap();
    let cfg = EvalConfig {
        plots: 0,
        rig: rig.display().to_string(),
        external_observations: ObsEncoding::Base64,
        external_timeout_s: 0.5,
        ..Default::default()
    };
    let req = eval_support::fine_test(dir.path(), "deaf", &cfg, None, 1);
    let cmd = format!("sh {}", script.display());
    let f = builtin("external", Some(&cmd), &cfg).unwrap();
    let err = evaluate(&req, &*f).unwrap_err().to_string();
    assert!(
        err.contains(&cmd)
            && err.contains("episode")
            && err.contains("step 0")
            && err.contains("did not read")
            && err.contains("external_timeout_s"),
        "{err}"
    );
}
