//! Run folders under hostile use: the agent behind a resume, concurrent jobs, inputs that
//! cannot be evaluated, and what a failure leaves behind.

use std::path::Path;

use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, Agent, EpisodeInputs, EvalConfig, FnFactory, Setting, StepInput};
use vlnverse_score::{dataset, OutputLock, Split, Task};
use vlnverse_sim::Action;

use crate::eval_support;

struct Forward(u32);

impl Agent for Forward {
    fn reset(&mut self, _inputs: &EpisodeInputs) -> vlnverse_eval::Result<()> {
        Ok(())
    }
    fn act(&mut self, step: &mut StepInput) -> vlnverse_eval::Result<Action> {
        Ok(if step.step < self.0 {
            Action::MoveForward(0.25)
        } else {
            Action::Stop
        })
    }
}

fn blind_lenient() -> EvalConfig {
    EvalConfig {
        setting: Setting::Lenient,
        render: false,
        plots: 0,
        ..Default::default()
    }
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|r| {
            r.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn a_resume_with_another_agent_fingerprint_is_refused_and_fresh_starts_over() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 4);
    let cfg = blind_lenient();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
    let v1 = FnFactory::new("mine", false, || Box::new(Forward(2)) as Box<dyn Agent>)
        .with_fingerprint("checkpoint a1");
    let v2 = FnFactory::new("mine", false, || Box::new(Forward(5)) as Box<dyn Agent>)
        .with_fingerprint("checkpoint b2");
    let first = evaluate(&req, &v1).unwrap();
    assert_eq!(first.summary.method, "mine");

    let err = evaluate(&req, &v2).unwrap_err().to_string();
    assert!(
        err.contains("agent_fingerprint")
            && err.contains("checkpoint b2")
            && err.contains("checkpoint a1"),
        "{err}"
    );
    // The same fingerprint resumes (nothing to do).
    assert_eq!(evaluate(&req, &v1).unwrap().steps_run, 0);

    // --fresh: the other agent's results replace the first.
    let fresh = req.clone().fresh(true);
    let second = evaluate(&fresh, &v2).unwrap();
    assert_eq!(second.resumed, 0);
    assert!(second.records.iter().all(|r| r.trajectory.steps == 6));
    let run = std::fs::read_to_string(dir.path().join("run/run.json")).unwrap();
    assert!(run.contains("checkpoint b2"), "{run}");

    // Built-in agents carry a fingerprint too; an external agent hashes its script.
    let random = builtin("random", None, &cfg).unwrap();
    assert!(random.fingerprint().unwrap().contains("random"));
    let script = dir.path().join("agent.py");
    std::fs::write(&script, "print('a')\n").unwrap();
    let cmd = format!("python3 {}", script.display());
    let ext = |c: &str| builtin("external", Some(c), &cfg).unwrap().fingerprint();
    let before = ext(&cmd).unwrap();
    std::fs::write(&script, "print('b')\n").unwrap();
    assert_ne!(
        ext(&cmd).unwrap(),
        before,
        "an edited script is another agent"
    );
}

#[test]
fn an_absurd_thread_count_is_refused_before_any_thread_or_file() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 4);
    let cfg = blind_lenient();
    let random = builtin("random", None, &cfg).unwrap();
    for n in [0, vlnverse_eval::MAX_THREADS + 1, 100_000] {
        let req = eval_support::fine_test(dir.path(), "run", &cfg, None, n);
        let err = evaluate(&req, &*random).unwrap_err().to_string();
        assert!(
            err.contains("threads") && err.contains(&n.to_string()),
            "{err}"
        );
        assert!(!req.out.exists(), "{} was made", req.out.display());
    }
}

#[test]
fn a_second_job_on_a_locked_folder_is_refused_naming_the_first() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 4);
    let cfg = blind_lenient();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
    let held = OutputLock::acquire(&req.out, "evaluate").unwrap();
    let random = builtin("random", None, &cfg).unwrap();
    let err = evaluate(&req, &*random).unwrap_err().to_string();
    assert!(
        err.contains("another job") && err.contains(&format!("pid {}", std::process::id())),
        "{err}"
    );
    assert!(
        !req.out.join("run.json").exists(),
        "the refused job wrote nothing"
    );
    drop(held);
    evaluate(&req, &*random).unwrap();
}

#[test]
fn impossible_episodes_are_refused_naming_file_episode_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 6);
    let cfg = blind_lenient();
    let random = builtin("random", None, &cfg).unwrap();
    type Edit = fn(&mut vlnverse_score::Episode);
    let cases: [(&str, Edit, &str); 4] = [
        (
            "off the map",
            |e| e.start_position[0] = 1e6,
            "start_position",
        ),
        (
            "far above the floor",
            |e| e.start_position[1] += 50.0,
            "start_position",
        ),
        (
            "goal off the map",
            |e| e.goals[0].position[2] = -1e5,
            "goals",
        ),
        (
            "unknown scene",
            |e| e.scene_id = "nowhere".into(),
            "scene_id",
        ),
    ];
    for (what, edit, field) in cases {
        let mut bad = eps.clone();
        edit(&mut bad[1]);
        dataset::write_split(dir.path(), Task::Fine, Split::Test, &bad).unwrap();
        let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
        let err = evaluate(&req, &*random).unwrap_err().to_string();
        let id = bad[1].episode_id;
        assert!(
            err.contains("test.json.gz")
                && err.contains(&format!("episode {id} (episodes[1])"))
                && err.contains(field),
            "{what}: {err}"
        );
        // Every episode is checked before anything is written: no run folder at all.
        assert!(!req.out.exists(), "{what}: {:?}", files_in(&req.out));
    }
}

#[test]
fn duplicate_ids_and_empty_splits_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mut eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 6);
    let cfg = blind_lenient();
    let random = builtin("random", None, &cfg).unwrap();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);

    eps[2].episode_id = eps[0].episode_id;
    dataset::write_split(dir.path(), Task::Fine, Split::Test, &eps).unwrap();
    let err = evaluate(&req, &*random).unwrap_err().to_string();
    assert!(
        err.contains("episodes[2].episode_id")
            && err.contains("used twice")
            && err.contains("episodes[0]"),
        "{err}"
    );
    dataset::write_split(dir.path(), Task::Fine, Split::Test, &[]).unwrap();
    let err = evaluate(&req, &*random).unwrap_err().to_string();
    assert!(
        err.contains("no episodes") && err.contains("test.json.gz"),
        "{err}"
    );
    assert!(!req.out.exists(), "a refused run leaves no folder");
}

#[test]
fn a_failure_before_the_first_episode_leaves_the_folder_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 6);
    let random = builtin("random", None, &blind_lenient()).unwrap();
    // A bad profile: nothing is created.
    let bad_profile = EvalConfig {
        agent_profile: "no_such_robot".into(),
        ..blind_lenient()
    };
    let req = eval_support::fine_test(dir.path(), "run", &bad_profile, None, 1);
    let err = evaluate(&req, &*random).unwrap_err().to_string();
    assert!(err.contains("no_such_robot"), "{err}");
    assert!(!req.out.exists());
    // A scene that does not load: the folder it made is removed again.
    std::fs::write(dir.path().join("scenes/tiny_000/scene.json"), "{").unwrap();
    let req = eval_support::fine_test(dir.path(), "run", &blind_lenient(), None, 1);
    let err = evaluate(&req, &*random).unwrap_err().to_string();
    assert!(err.contains("scene"), "{err}");
    assert!(!req.out.exists(), "left behind: {:?}", files_in(&req.out));
}

#[test]
fn fewer_episodes_on_a_finished_run_do_not_overwrite_its_summary() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 4, 6);
    let cfg = blind_lenient();
    let random = builtin("random", None, &cfg).unwrap();
    evaluate(
        &eval_support::fine_test(dir.path(), "run", &cfg, None, 1),
        &*random,
    )
    .unwrap();
    let summary = std::fs::read(dir.path().join("run/summary.json")).unwrap();
    let err = evaluate(
        &eval_support::fine_test(dir.path(), "run", &cfg, Some(2), 1),
        &*random,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("already holds 4 finished episodes"), "{err}");
    assert_eq!(
        std::fs::read(dir.path().join("run/summary.json")).unwrap(),
        summary
    );
}

#[test]
fn the_scene_cache_stays_bounded_and_reloads_what_it_evicted() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 3, 1, 8);
    let cache = vlnverse_eval::SceneCache::new(dir.path(), 2);
    let ids = ["tiny_000", "tiny_001", "tiny_002"];
    let first = cache.get(ids[0]).unwrap();
    for id in ids {
        let ctx = cache.get(id).unwrap();
        assert_eq!(ctx.scene.id, id);
        assert!(cache.len() <= 2);
    }
    assert_eq!((cache.len(), cache.loads()), (2, 3), "tiny_000 was evicted");
    // Still alive where it is used; loaded again when asked for.
    assert_eq!(first.scene.id, "tiny_000");
    cache.get(ids[0]).unwrap();
    assert_eq!(cache.loads(), 4);
    cache.get(ids[0]).unwrap();
    assert_eq!(cache.loads(), 4, "a hit does not reload");
    let err = cache.get("nowhere").err().unwrap().to_string();
    assert!(err.contains("nowhere") && err.contains("scenes"), "{err}");
}

#[test]
fn a_seeded_sample_spreads_over_scenes_and_is_part_of_the_run() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 3, 4, 9);
    let cfg = blind_lenient();
    let factory = FnFactory::new("fwd", false, || Box::new(Forward(1)) as Box<dyn Agent>);
    let sampled = |out: &str, count: usize, seed: u64| {
        eval_support::fine_test(dir.path(), out, &cfg, None, 1)
            .sample(vlnverse_score::sample::Sample { count, seed })
    };
    let a = evaluate(&sampled("a", 5, 7), &factory).unwrap();
    assert_eq!(a.records.len(), 5);
    let all = dataset::read_split(dir.path(), Task::Fine, Split::Test).unwrap();
    let scene_of = |id: u64| &all.iter().find(|e| e.episode_id == id).unwrap().scene_id;
    let mut scenes: Vec<&String> = a.records.iter().map(|r| scene_of(r.episode_id)).collect();
    scenes.sort();
    scenes.dedup();
    assert_eq!(
        scenes.len(),
        3,
        "five episodes over three scenes: every scene is in"
    );
    // The same seed draws the same episodes; another seed others.
    let ids =
        |o: &vlnverse_eval::EvalOutcome| o.records.iter().map(|r| r.episode_id).collect::<Vec<_>>();
    let again = evaluate(&sampled("b", 5, 7), &factory).unwrap();
    assert_eq!(ids(&a), ids(&again));
    let other = evaluate(&sampled("c", 5, 8), &factory).unwrap();
    assert_ne!(ids(&a), ids(&other));
    // The sample belongs to the run: resuming with another one is refused.
    let err = evaluate(&sampled("a", 5, 8), &factory).unwrap_err();
    assert!(err.to_string().contains("sample"), "{err}");
    // With --episodes it is refused, naming both.
    let both = sampled("d", 5, 7).episodes(2);
    let err = evaluate(&both, &factory).unwrap_err();
    assert!(err.to_string().contains("--sample"), "{err}");
    assert!(!dir.path().join("d").exists());
}

/// Turns on the spot and never stops.
struct Spinner;

impl Agent for Spinner {
    fn reset(&mut self, _inputs: &EpisodeInputs) -> vlnverse_eval::Result<()> {
        Ok(())
    }
    fn act(&mut self, _step: &mut StepInput) -> vlnverse_eval::Result<Action> {
        Ok(Action::TurnLeft(15f32.to_radians()))
    }
}

#[test]
fn a_long_horizon_episode_gets_the_step_limit_once_for_each_sub_goal() {
    let dir = tempfile::tempdir().unwrap();
    let mut eps = eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 9);
    // The second episode chains three sub-tasks (the same goal thrice: a spinner never gets
    // there, so only the limit ends it).
    let goal = eps[1].goals[0].clone();
    eps[1].sub_goals = vec![goal.clone(), goal.clone(), goal];
    dataset::write_split(dir.path(), Task::Fine, Split::Test, &eps).unwrap();
    let cfg = EvalConfig {
        max_steps: 4,
        ..blind_lenient()
    };
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
    let spinner = FnFactory::new("spinner", false, || Box::new(Spinner) as Box<dyn Agent>);
    let out = evaluate(&req, &spinner).unwrap();
    let steps: Vec<(u64, u32)> = out
        .records
        .iter()
        .map(|r| (r.trajectory.episode_id, r.trajectory.steps))
        .collect();
    assert_eq!(steps, vec![(eps[0].episode_id, 4), (eps[1].episode_id, 12)]);
}
