//! The layers behind a run folder: `run.json` records the simulator, the renderer and the rig,
//! a resume with other ones is refused like a resume with another agent, and the default
//! simulator builds each scene's colliders once for the whole evaluation.

use std::sync::Arc;

use vlnverse_env::{Pose, Scene};
use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, evaluate_with, EvalConfig, Layers, Setting};
use vlnverse_score::Task;
use vlnverse_sensors::{Frame, Renderer, RigConfig, SceneMesh, View};
use vlnverse_sim::{Action, PhysicsCache, RapierSimulator, SimConfig, Simulator, StepOutcome};

use crate::eval_support;

/// A user's wrapper that forwards everything (results are the default's).
struct Logged<S>(S);

impl<S: Simulator> Simulator for Logged<S> {
    fn name(&self) -> String {
        format!("logged({})", self.0.name())
    }
    fn reset(&mut self, scene: &Scene, start: Pose) -> vlnverse_sim::Result<Pose> {
        self.0.reset(scene, start)
    }
    fn step(&mut self, action: Action) -> vlnverse_sim::Result<StepOutcome> {
        self.0.step(action)
    }
    fn pose(&self) -> Pose {
        self.0.pose()
    }
    fn camera_pose(&self) -> Pose {
        self.0.camera_pose()
    }
}

fn logged(cfg: &SimConfig) -> vlnverse_eval::Result<Logged<RapierSimulator>> {
    Ok(Logged(RapierSimulator::new(cfg.clone())?))
}

/// Renders nothing (black, far, no object).
struct Blind;

impl Renderer for Blind {
    fn name(&self) -> String {
        "blind".into()
    }
    fn set_scene(&mut self, _mesh: Arc<SceneMesh>) -> vlnverse_sensors::Result<()> {
        Ok(())
    }
    fn render(&mut self, views: &[View]) -> vlnverse_sensors::Result<Vec<Frame>> {
        Ok(views
            .iter()
            .map(|v| {
                let (w, h) = (v.camera.width, v.camera.height);
                let n = (w * h) as usize;
                let c = v.channels;
                Frame {
                    width: w,
                    height: h,
                    rgb: vec![0; if c.rgb { 3 * n } else { 0 }],
                    depth: vec![v.camera.far; if c.depth { n } else { 0 }],
                    semantic: vec![0; if c.semantic { n } else { 0 }],
                    instance: vec![0; if c.instance { n } else { 0 }],
                }
            })
            .collect())
    }
}

fn blind(_rig: &RigConfig) -> vlnverse_eval::Result<Box<dyn Renderer>> {
    Ok(Box::new(Blind))
}

fn blind_lenient() -> EvalConfig {
    EvalConfig {
        setting: Setting::Lenient,
        render: false,
        plots: 0,
        ..Default::default()
    }
}

fn assert_refused_on(err: &str, key: &str, now: &str, before: &str) {
    assert!(
        err.contains(&format!("`{key}`"))
            && err.contains(now)
            && err.contains(before)
            && err.contains("--fresh"),
        "{err}"
    );
}

#[test]
fn a_run_of_a_wrapped_simulator_is_not_resumed_by_the_default_one_nor_the_reverse() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 3, 5);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = |out: &str| eval_support::fine_test(dir.path(), out, &cfg, None, 1);

    // Made through evaluate_with with a wrapper; the default may not resume it.
    let wrapped = evaluate_with(
        &req("wrapped"),
        &*agent,
        Layers::default().simulators(logged),
    )
    .unwrap();
    let run = std::fs::read_to_string(dir.path().join("wrapped/run.json")).unwrap();
    assert!(run.contains("\"simulator\": \"logged(rapier)\""), "{run}");
    let err = evaluate(&req("wrapped"), &*agent).unwrap_err().to_string();
    assert_refused_on(&err, "simulator", "\"rapier\"", "\"logged(rapier)\"");

    // The reverse: a default run is not resumed through the wrapper.
    let plain = evaluate(&req("plain"), &*agent).unwrap();
    let run = std::fs::read_to_string(dir.path().join("plain/run.json")).unwrap();
    assert!(run.contains("\"simulator\": \"rapier\""), "{run}");
    let err = evaluate_with(&req("plain"), &*agent, Layers::default().simulators(logged))
        .unwrap_err()
        .to_string();
    assert_refused_on(&err, "simulator", "\"logged(rapier)\"", "\"rapier\"");

    // The refused resumes changed nothing; identical resumes run nothing and agree.
    let again = evaluate_with(
        &req("wrapped"),
        &*agent,
        Layers::default().simulators(logged),
    )
    .unwrap();
    assert_eq!((again.steps_run, again.resumed), (0, 3));
    assert_eq!(again.records, wrapped.records);
    let again = evaluate(&req("plain"), &*agent).unwrap();
    assert_eq!((again.steps_run, again.resumed), (0, 3));
    // A forwarding wrapper scores exactly as the default.
    assert_eq!(plain.records, wrapped.records);
    // --fresh starts over with the other simulator.
    let fresh = evaluate(&req("wrapped").fresh(true), &*agent).unwrap();
    assert_eq!(fresh.resumed, 0);
}

#[test]
fn a_run_with_another_renderer_or_rig_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 8);
    let cfg = EvalConfig {
        setting: Setting::Lenient,
        rig: eval_support::small_rig(dir.path()),
        plots: 0,
        ..Default::default()
    };
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 1);
    evaluate(&req, &*agent).unwrap();
    let run = std::fs::read_to_string(dir.path().join("run/run.json")).unwrap();
    assert!(
        run.contains("\"renderer\"") && run.contains("\"rig_fingerprint\""),
        "{run}"
    );
    let err = evaluate_with(&req, &*agent, Layers::default().renderers(blind))
        .unwrap_err()
        .to_string();
    assert_refused_on(&err, "renderer", "\"blind\"", "in the folder's run");
    // The same layers resume.
    assert_eq!(evaluate(&req, &*agent).unwrap().steps_run, 0);
}

#[test]
fn an_older_run_json_without_the_layers_still_resumes() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 3);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, Some(1), 1);
    evaluate(&req, &*agent).unwrap();
    let path = dir.path().join("run/run.json");
    let mut run: serde_json::Map<String, serde_json::Value> =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    for key in vlnverse_eval::LATER_KEYS {
        assert!(run.remove(key).is_some(), "{key} not recorded");
    }
    std::fs::write(&path, serde_json::to_vec_pretty(&run).unwrap()).unwrap();
    let rest = evaluate(
        &eval_support::fine_test(dir.path(), "run", &cfg, None, 1),
        &*agent,
    )
    .unwrap();
    assert_eq!(rest.resumed, 1);
}

#[test]
fn colliders_are_built_once_per_scene_for_a_whole_evaluation() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 2, 6, 13);
    let cfg = blind_lenient();
    let agent = builtin("random", None, &cfg).unwrap();
    let cache = Arc::new(PhysicsCache::new(256 << 20));
    let sims = {
        let cache = cache.clone();
        move |c: &SimConfig| -> vlnverse_eval::Result<Logged<RapierSimulator>> {
            Ok(Logged(RapierSimulator::with_cache(
                c.clone(),
                cache.clone(),
            )?))
        }
    };
    let out = evaluate_with(
        &eval_support::fine_test(dir.path(), "run", &cfg, None, 2),
        &*agent,
        Layers::default().simulators(sims),
    )
    .unwrap();
    let scenes: std::collections::BTreeSet<_> =
        vlnverse_score::dataset::read_split(dir.path(), Task::Fine, vlnverse_score::Split::Test)
            .unwrap()
            .into_iter()
            .map(|e| e.scene_id)
            .collect();
    assert!(scenes.len() >= 2, "{scenes:?}");
    assert_eq!(
        cache.builds(),
        scenes.len() as u64,
        "one build per scene for {} episodes on 2 threads",
        out.records.len()
    );
}

#[test]
fn a_run_of_another_benchmark_version_is_not_resumed() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 1, 2, 3);
    let cfg = blind_lenient();
    let agent = builtin("forward", None, &cfg).unwrap();
    let req = eval_support::fine_test(dir.path(), "run", &cfg, Some(1), 1);
    let first = evaluate(&req, &*agent).unwrap();
    assert_eq!(
        first.summary.benchmark_version.as_deref(),
        Some(vlnverse_score::BENCHMARK_VERSION)
    );
    let path = dir.path().join("run/run.json");
    let mut run: serde_json::Map<String, serde_json::Value> =
        serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(
        run.insert("benchmark_version".into(), "0.9".into()),
        Some(vlnverse_score::BENCHMARK_VERSION.into())
    );
    std::fs::write(&path, serde_json::to_vec_pretty(&run).unwrap()).unwrap();
    let err = evaluate(
        &eval_support::fine_test(dir.path(), "run", &cfg, None, 1),
        &*agent,
    )
    .unwrap_err()
    .to_string();
    let now = format!("\"{}\"", vlnverse_score::BENCHMARK_VERSION);
    assert_refused_on(&err, "benchmark_version", &now, "\"0.9\"");
}
