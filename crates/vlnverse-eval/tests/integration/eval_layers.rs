//! Swapping layers in an evaluation from outside the runner: a user's renderer and a user's
//! simulator run through `evaluate_with` under the same episode loop as the defaults.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use vlnverse_env::{Pose, Scene};
use vlnverse_eval::agents::builtin;
use vlnverse_eval::{
    configured_renderer, evaluate, evaluate_with, rapier_simulator, EvalConfig, Layers,
    RendererFactory, Setting, SimulatorFactory,
};
use vlnverse_score::Task;
use vlnverse_sensors::{Frame, Renderer, RigConfig, SceneMesh, View};
use vlnverse_sim::{Action, RapierSimulator, SimConfig, Simulator, StepOutcome};

use crate::eval_support;

/// Sees nothing: every pixel black, at the far plane, no object. Counts its frames.
struct Blind {
    frames: Arc<AtomicUsize>,
}

impl Renderer for Blind {
    fn name(&self) -> String {
        "blind".into()
    }
    fn set_scene(&mut self, _mesh: Arc<SceneMesh>) -> vlnverse_sensors::Result<()> {
        Ok(())
    }
    fn render(&mut self, views: &[View]) -> vlnverse_sensors::Result<Vec<Frame>> {
        self.frames.fetch_add(views.len(), Ordering::Relaxed);
        Ok(views
            .iter()
            .map(|v| {
                let (w, h) = (v.camera.width, v.camera.height);
                let n = (w * h) as usize;
                Frame {
                    width: w,
                    height: h,
                    rgb: if v.channels.rgb {
                        vec![0; 3 * n]
                    } else {
                        vec![]
                    },
                    depth: if v.channels.depth {
                        vec![v.camera.far; n]
                    } else {
                        vec![]
                    },
                    semantic: if v.channels.semantic {
                        vec![0; n]
                    } else {
                        vec![]
                    },
                    instance: if v.channels.instance {
                        vec![0; n]
                    } else {
                        vec![]
                    },
                }
            })
            .collect())
    }
}

/// A simulator around another that scales every forward move (actuation bias).
struct Perturbed<S> {
    inner: S,
    scale: f32,
}

impl<S: Simulator> Simulator for Perturbed<S> {
    fn name(&self) -> String {
        format!("perturbed({})", self.inner.name())
    }
    fn reset(&mut self, scene: &Scene, start: Pose) -> vlnverse_sim::Result<Pose> {
        self.inner.reset(scene, start)
    }
    fn step(&mut self, action: Action) -> vlnverse_sim::Result<StepOutcome> {
        let action = match action {
            Action::MoveForward(d) if self.scale != 1.0 => Action::MoveForward(d * self.scale),
            a => a,
        };
        self.inner.step(action)
    }
    fn pose(&self) -> Pose {
        self.inner.pose()
    }
    fn camera_pose(&self) -> Pose {
        self.inner.camera_pose()
    }
}

fn perturbed(
    scale: f32,
) -> impl Fn(&SimConfig) -> vlnverse_eval::Result<Perturbed<RapierSimulator>> {
    move |cfg| {
        Ok(Perturbed {
            inner: RapierSimulator::new(cfg.clone())?,
            scale,
        })
    }
}

/// The perturbed simulator and a renderer factory as evaluation layers.
fn wrapped<RF: RendererFactory>(
    scale: f32,
    renderers: RF,
) -> Layers<'static, impl SimulatorFactory<Sim = Perturbed<RapierSimulator>>, RF> {
    Layers::default()
        .simulators(perturbed(scale))
        .renderers(renderers)
}

const RUN_FILES: [&str; 3] = ["summary.json", "episodes.csv", "trajectories.jsonl"];

/// The lenient setting on the small ray-cast rig, no plots.
fn lenient_small(dir: &std::path::Path) -> EvalConfig {
    EvalConfig {
        setting: Setting::Lenient,
        rig: eval_support::small_rig(dir),
        plots: 0,
        ..Default::default()
    }
}

#[test]
fn a_wrapped_simulator_and_a_blind_renderer_run_under_the_same_loop() {
    let dir = tempfile::tempdir().unwrap();
    eval_support::make_dataset(dir.path(), Task::Fine, 2, 4, 21);
    let cfg = lenient_small(dir.path());
    let oracle = builtin("oracle", None, &cfg).unwrap();
    let req = |out: &str| eval_support::fine_test(dir.path(), out, &cfg, None, 2);

    // The default path, and the same layers passed in explicitly.
    let default = evaluate(&req("default"), &*oracle).unwrap();
    evaluate_with(
        &req("explicit"),
        &*oracle,
        Layers::default()
            .simulators(rapier_simulator)
            .renderers(configured_renderer),
    )
    .unwrap();

    // The wrapper with no perturbation, rendering with the blind renderer.
    let frames = Arc::new(AtomicUsize::new(0));
    let blind = {
        let frames = frames.clone();
        move |_rig: &RigConfig| -> vlnverse_eval::Result<Box<dyn Renderer>> {
            Ok(Box::new(Blind {
                frames: frames.clone(),
            }))
        }
    };
    let same = evaluate_with(&req("wrapped"), &*oracle, wrapped(1.0, blind.clone())).unwrap();
    let steps: u64 = same.records.iter().map(|r| r.trajectory.steps as u64).sum();
    // One observation per agent decision: before each action.
    // One view per decision (rgb and depth share a camera, so one frame renders both).
    assert_eq!(frames.load(Ordering::Relaxed) as u64, steps);
    for out in ["explicit", "wrapped"] {
        for f in RUN_FILES {
            assert_eq!(
                std::fs::read(dir.path().join("default").join(f)).unwrap(),
                std::fs::read(dir.path().join(out).join(f)).unwrap(),
                "{out}/{f} differs from the default path"
            );
        }
    }

    // Half-length forward moves: the oracle needs more steps, and the results say so.
    let short = evaluate_with(&req("short"), &*oracle, wrapped(0.5, blind.clone())).unwrap();
    let total = |o: &vlnverse_eval::EvalOutcome| -> u64 {
        o.records.iter().map(|r| r.trajectory.steps as u64).sum()
    };
    assert!(
        total(&short) > total(&default),
        "{} steps with half moves vs {}",
        total(&short),
        total(&default)
    );
    // Every forward step moved at most half the step size.
    let step = cfg.agent_config().unwrap().step_size;
    for r in &short.records {
        let t = &r.trajectory;
        let acts = t.actions.as_ref().unwrap();
        for (i, a) in acts.iter().enumerate() {
            if a == "move_forward" && i + 1 < t.positions.len() {
                let (p, q) = (t.positions[i], t.positions[i + 1]);
                let d = ((q[0] - p[0]).powi(2) + (q[2] - p[2]).powi(2)).sqrt();
                assert!(
                    d <= 0.5 * step + 1e-3,
                    "episode {}: moved {d}",
                    t.episode_id
                );
            }
        }
    }
}

/// Draws nothing and writes down, for every frame, the home it shows.
struct Watching {
    scene: String,
    log: Arc<std::sync::Mutex<Vec<String>>>,
    blind: Blind,
}

impl Renderer for Watching {
    fn name(&self) -> String {
        "watching".into()
    }
    fn set_scene(&mut self, mesh: Arc<SceneMesh>) -> vlnverse_sensors::Result<()> {
        self.scene = mesh.scene_id.clone();
        Ok(())
    }
    fn render(&mut self, views: &[View]) -> vlnverse_sensors::Result<Vec<Frame>> {
        self.log.lock().unwrap().push(self.scene.clone());
        self.blind.render(views)
    }
}

/// Two workers run a split home by home: once a frame of the next home is drawn, no frame of
/// an earlier home is (so the run holds one home at a time), and every episode runs.
#[test]
fn two_workers_run_a_split_home_by_home() {
    let dir = tempfile::tempdir().unwrap();
    let episodes = eval_support::make_dataset(dir.path(), Task::Fine, 3, 16, 5);
    let homes: std::collections::BTreeSet<&str> =
        episodes.iter().map(|e| e.scene_id.as_str()).collect();
    assert_eq!(homes.len(), 3);
    let cfg = lenient_small(dir.path());
    let oracle = builtin("oracle", None, &cfg).unwrap();
    let log = Arc::new(std::sync::Mutex::new(Vec::new()));
    let watching = {
        let log = log.clone();
        move |_rig: &RigConfig| -> vlnverse_eval::Result<Box<dyn Renderer>> {
            Ok(Box::new(Watching {
                scene: String::new(),
                log: log.clone(),
                blind: Blind {
                    frames: Arc::new(AtomicUsize::new(0)),
                },
            }))
        }
    };
    let req = eval_support::fine_test(dir.path(), "run", &cfg, None, 2);
    let out = evaluate_with(&req, &*oracle, Layers::default().renderers(watching)).unwrap();
    assert_eq!(out.records.len(), episodes.len());
    let log = log.lock().unwrap();
    let mut shown: Vec<&str> = log.iter().map(String::as_str).collect();
    shown.dedup();
    assert_eq!(
        shown,
        homes.iter().copied().collect::<Vec<_>>(),
        "homes in the order their frames were drawn"
    );
}
