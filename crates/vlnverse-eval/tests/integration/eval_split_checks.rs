//! The split a run is made of: every episode is checked in its scene before anything is
//! written, and a resume after a finished episode changed in the split file is refused.

use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, EvalConfig, Setting};
use vlnverse_score::dataset::{read_split, write_split};
use vlnverse_score::{Split, Task};

use crate::eval_support;

fn blind_lenient() -> EvalConfig {
    EvalConfig {
        setting: Setting::Lenient,
        render: false,
        plots: 0,
        ..Default::default()
    }
}

#[test]
fn a_resume_is_refused_only_when_a_finished_episode_changed_in_the_split() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 21);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = |n| eval_support::fine_test(dir.path(), "run", &cfg, n, 1);
    evaluate(&req(Some(1)), &*agent).unwrap();
    let log = std::fs::read_to_string(dir.path().join("run/progress.jsonl")).unwrap();
    assert!(log.contains("\"episode_fingerprint\""), "{log}");

    // An episode the run has not reached moves its goal: nothing of the run depends on it,
    // and the resume runs it as it is now.
    let mut edited = eps.clone();
    edited[2].goals[0] = eps[1].goals[0].clone();
    write_split(dir.path(), Task::Fine, Split::Test, &edited).unwrap();
    let out = evaluate(&req(Some(2)), &*agent).unwrap();
    assert_eq!((out.resumed, out.records.len()), (1, 2));

    // A finished one changes: its result would come from the old split.
    let mut changed = edited.clone();
    changed[0].goals[0] = eps[1].goals[0].clone();
    write_split(dir.path(), Task::Fine, Split::Test, &changed).unwrap();
    let err = evaluate(&req(None), &*agent).unwrap_err().to_string();
    let first = format!(
        "episode {} (episodes[0]).episode_fingerprint",
        eps[0].episode_id
    );
    assert!(err.contains(&first) && err.contains("--fresh"), "{err}");
    let log = std::fs::read_to_string(dir.path().join("run/progress.jsonl")).unwrap();
    assert_eq!(log.lines().count(), 2, "the refused resume ran nothing");

    // The split as the run saw it resumes to the end, even with a run.json of the time when
    // it held the whole split's hash.
    write_split(dir.path(), Task::Fine, Split::Test, &edited).unwrap();
    let run_json = dir.path().join("run/run.json");
    let mut run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&run_json).unwrap()).unwrap();
    assert!(run.get("split_fingerprint").is_none(), "{run}");
    run["split_fingerprint"] = "0123456789abcdef".into();
    std::fs::write(&run_json, run.to_string()).unwrap();
    let rest = evaluate(&req(None), &*agent).unwrap();
    assert_eq!((rest.resumed, rest.records.len()), (2, 3));
}

#[test]
fn an_impossible_episode_at_the_end_of_the_split_fails_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 2, 3, 22);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let last = eps.len() - 1;
    let spoil: [(&str, &str, Box<dyn Fn(&mut vlnverse_score::Episode)>); 3] = [
        (
            "start_position",
            "outside the scene's navigable map",
            Box::new(|e| e.start_position = [500.0, e.start_position[1], 500.0]),
        ),
        (
            "goals",
            "outside the scene's navigable map",
            Box::new(|e| e.goals[0].position = [-500.0, 0.0, 3.0]),
        ),
        (
            "target_object_id",
            "999999",
            Box::new(|e| e.target_object_id = Some(999_999)),
        ),
    ];
    for (field, why, spoil) in spoil {
        let mut bad = eps.clone();
        spoil(&mut bad[last]);
        write_split(dir.path(), Task::Fine, Split::Test, &bad).unwrap();
        assert_eq!(
            read_split(dir.path(), Task::Fine, Split::Test).unwrap(),
            bad
        );
        let out = dir.path().join("run");
        let err = evaluate(
            &eval_support::fine_test(dir.path(), "run", &cfg, None, 2),
            &*agent,
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains(&format!("(episodes[{last}]).{field}")) && err.contains(why),
            "{field}: {err}"
        );
        assert!(!out.exists(), "{field}: {out:?} was left behind");

        // An existing folder is left as it was (no run.json, progress.jsonl or .lock).
        std::fs::create_dir_all(&out).unwrap();
        evaluate(
            &eval_support::fine_test(dir.path(), "run", &cfg, None, 2),
            &*agent,
        )
        .unwrap_err();
        let left: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
        assert!(left.is_empty(), "{field}: {left:?}");
        std::fs::remove_dir(&out).unwrap();
    }
}
