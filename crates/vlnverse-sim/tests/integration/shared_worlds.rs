//! Physics worlds are built once per scene content and shared by every simulator of a cache,
//! including simulators wrapped by a user who forwards nothing but the trait's methods.

use crate::common::*;
use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::{Motion, Pose, Scene, SemanticClass};
use vlnverse_sim::*;

/// A user's wrapper: forwards the trait, nothing else.
struct Noisy<S>(S);

impl<S: Simulator> Simulator for Noisy<S> {
    fn name(&self) -> String {
        format!("noisy({})", self.0.name())
    }
    fn reset(&mut self, scene: &Scene, start: Pose) -> Result<Pose> {
        self.0.reset(scene, start)
    }
    fn step(&mut self, action: Action) -> Result<StepOutcome> {
        self.0.step(action)
    }
    fn pose(&self) -> Pose {
        self.0.pose()
    }
    fn camera_pose(&self) -> Pose {
        self.0.camera_pose()
    }
}

fn chair_at(x: f32) -> Scene {
    room_with(vec![boxed(
        6,
        SemanticClass::Chair,
        Vec3::new(x, 0.4, -1.5),
        Vec3::new(0.25, 0.4, 0.25),
        Motion::Dynamic,
        8.0,
        0.4,
    )])
}

#[test]
fn colliders_are_built_once_per_scene_whoever_resets() {
    let cache = Arc::new(PhysicsCache::new(64 << 20));
    let cfg = SimConfig::default();
    let mut a = RapierSimulator::with_cache(cfg.clone(), cache.clone()).unwrap();
    let mut b = Noisy(RapierSimulator::with_cache(cfg.clone(), cache.clone()).unwrap());
    assert_eq!(b.name(), "noisy(rapier)");
    // Scenes loaded apart (equal content, other allocations) and episodes in turn.
    for episode in 0..5 {
        let start = at(0.1 * episode as f32, 0.0, 0.0);
        a.reset(&chair_at(0.0), start).unwrap();
        b.reset(&chair_at(0.0), start).unwrap();
        b.reset(&room(), start).unwrap();
        a.step(Action::MoveForward(0.25)).unwrap();
    }
    assert_eq!(cache.builds(), 2, "one world per distinct scene");
    b.reset(&chair_at(0.0), at(0.0, 0.0, 0.0)).unwrap();
    assert!(Arc::ptr_eq(
        a.physics_scene().unwrap(),
        b.0.physics_scene().unwrap()
    ));
    // Another content (the chair moved) is another world; another embodiment too.
    a.reset(&chair_at(1.0), at(0.0, 0.0, 0.0)).unwrap();
    assert_eq!(cache.builds(), 3);
    let mut wide = cfg.clone();
    if let AgentShape::Cylinder { radius, .. } = &mut wide.agent.shape {
        *radius *= 0.5;
    }
    let mut c = RapierSimulator::with_cache(wide, cache.clone()).unwrap();
    c.reset(&chair_at(0.0), at(0.0, 0.0, 0.0)).unwrap();
    assert_eq!(cache.builds(), 4);
}

#[test]
fn a_shared_world_gives_the_same_steps_as_a_fresh_one() {
    let actions = [
        Action::MoveForward(0.25),
        Action::TurnLeft(0.3),
        Action::MoveForward(0.25),
        Action::Velocity {
            v: 0.5,
            omega: 0.2,
            duration: 0.5,
        },
    ];
    let run = |sim: &mut RapierSimulator| -> Vec<StepOutcome> {
        sim.reset(&chair_at(0.0), at(0.0, 0.0, 0.0)).unwrap();
        actions.iter().map(|a| sim.step(*a).unwrap()).collect()
    };
    let cache = Arc::new(PhysicsCache::new(64 << 20));
    let mut shared = RapierSimulator::with_cache(SimConfig::default(), cache.clone()).unwrap();
    let first = run(&mut shared);
    // The world was pushed about by the first episode; the cached one is untouched.
    let second = run(&mut shared);
    let mut fresh =
        RapierSimulator::with_cache(SimConfig::default(), Arc::new(PhysicsCache::new(0))).unwrap();
    assert_eq!(first, second);
    assert_eq!(first, run(&mut fresh));
    assert_eq!(cache.builds(), 1);
}
