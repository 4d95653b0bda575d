//! The split a run is made of: every episode is checked in its scene before anything is
//! written, and a resume after the split file changed is refused by the key that changed.

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
fn a_resume_of_an_edited_split_is_refused_naming_the_split_fingerprint() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 21);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = |n| eval_support::fine_test(dir.path(), "run", &cfg, n, 1);
    evaluate(&req(Some(1)), &*agent).unwrap();
    let run = std::fs::read_to_string(dir.path().join("run/run.json")).unwrap();
    assert!(run.contains("\"split_fingerprint\""), "{run}");

    // The goals of the episodes not yet run move: resuming would mix two splits.
    let mut edited = eps.clone();
    edited[2].goals[0] = eps[1].goals[0].clone();
    write_split(dir.path(), Task::Fine, Split::Test, &edited).unwrap();
    let err = evaluate(&req(None), &*agent).unwrap_err().to_string();
    assert!(
        err.contains("`split_fingerprint`") && err.contains("--fresh"),
        "{err}"
    );
    let log = std::fs::read_to_string(dir.path().join("run/progress.jsonl")).unwrap();
    assert_eq!(log.lines().count(), 1, "the refused resume ran nothing");

    // The split as it was resumes, with more episodes than the first call ran.
    write_split(dir.path(), Task::Fine, Split::Test, &eps).unwrap();
    let rest = evaluate(&req(None), &*agent).unwrap();
    assert_eq!((rest.resumed, rest.records.len()), (1, 3));
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
