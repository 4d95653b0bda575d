//! The simulator in a procedurally generated home (procgen `tiny` preset, scene 0).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sim::*;

fn home() -> Scene {
    HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(0)
        .unwrap()
}

fn free_start(scene: &Scene, sim: &mut RapierSimulator, seed: u64) -> Pose {
    sim.reset(scene, Pose::IDENTITY).unwrap();
    let b = scene.bounds();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    loop {
        let x = rng.random_range(b.min[0]..b.max[0]);
        let z = rng.random_range(b.min[2]..b.max[2]);
        if scene.room_at(x, z).is_some() && sim.is_free(x, z) {
            return Pose::from_yaw(glam::Vec3::new(x, scene.floor_height, z), 0.0);
        }
    }
}

fn walk(seed: u64) -> Vec<[u32; 3]> {
    let scene = home();
    let cfg = SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    };
    let mut sim = RapierSimulator::new(cfg.clone()).unwrap();
    let start = free_start(&scene, &mut sim, seed);
    sim.reset(&scene, start).unwrap();
    let b = scene.bounds();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut trace = vec![];
    for _ in 0..400 {
        let a = match rng.random_range(0..8) {
            0..=3 => Action::forward(&cfg.agent),
            4 => Action::left(&cfg.agent),
            5 => Action::right(&cfg.agent),
            6 => Action::Waypoint {
                x: rng.random_range(b.min[0]..b.max[0]),
                z: rng.random_range(b.min[2]..b.max[2]),
                mode: WaypointMode::Drive,
            },
            _ => Action::MoveForward(rng.random_range(0.0..3.0)),
        };
        let out = sim.step(a).unwrap();
        let p = out.pose.position;
        // Discrete moves never end inside anything.
        assert!(
            sim.is_free(p[0], p[2]),
            "inside an obstacle after {a:?}: {out:?}"
        );
        assert!(out.hit.iter().all(|id| scene.object(*id).is_some()));
        trace.push(p.map(f32::to_bits));
    }
    trace
}

#[test]
fn random_walk_in_a_generated_home_stays_free_and_is_deterministic() {
    assert_eq!(walk(5), walk(5));
}

#[test]
fn generated_home_builds_a_physics_world() {
    let scene = home();
    let physics = PhysicsScene::build(&scene, &AgentConfig::default()).unwrap();
    assert!(physics.collider_count() >= scene.objects.len() / 2);
    for id in physics.dynamic_object_ids() {
        let o = scene.object(id).unwrap();
        assert_eq!(o.physics.motion, vlnverse_env::Motion::Dynamic);
    }
}
