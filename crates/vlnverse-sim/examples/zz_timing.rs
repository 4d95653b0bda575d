use std::sync::Arc;
use std::time::Instant;
use vlnverse_env::{Pose, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sim::*;
fn main() {
    let scene = HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(0)
        .unwrap();
    let cfg = SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    };
    let physics = Arc::new(PhysicsScene::build(&scene, &cfg.agent).unwrap());
    let mut s = RapierSimulator::new(cfg.clone()).unwrap();
    let b = scene.bounds();
    println!("bounds {:?}", b);
    s.reset_in(physics.clone(), Pose::IDENTITY).unwrap();
    let mut start = Pose::IDENTITY;
    'o: for i in 0..100 {
        for j in 0..100 {
            let x = b.min[0] + (b.max[0] - b.min[0]) * i as f32 / 100.0;
            let z = b.min[2] + (b.max[2] - b.min[2]) * j as f32 / 100.0;
            if scene.room_at(x, z).is_some() && s.is_free(x, z) {
                start = Pose::from_yaw(glam::Vec3::new(x, 0.0, z), 0.0);
                break 'o;
            }
        }
    }
    {
        s.reset_in(physics.clone(), start).unwrap();
        let t = Instant::now();
        let n = 10000;
        let mut col = 0;
        for i in 0..n {
            let a = if i % 3 == 2 {
                Action::TurnLeft(std::f32::consts::PI)
            } else {
                Action::MoveForward(0.25)
            };
            if s.step(a).unwrap().collided {
                col += 1;
            }
        }
        println!(
            "free fwd/back: {:.2} us/action (2/3 fwd), collided {col}",
            t.elapsed().as_secs_f64() * 1e6 / n as f64
        );
    }
    for (name, a) in [
        ("turn", Action::TurnLeft(0.26)),
        ("look", Action::LookUp),
        ("fwd", Action::MoveForward(0.25)),
        ("fwd0", Action::MoveForward(0.0)),
    ] {
        s.reset_in(physics.clone(), start).unwrap();
        let t = Instant::now();
        let n = 10000;
        let mut col = 0;
        for _ in 0..n {
            if s.step(a).unwrap().collided {
                col += 1;
            }
        }
        println!(
            "{name}: {:.2} us/action, collided {col}",
            t.elapsed().as_secs_f64() * 1e6 / n as f64
        );
    }
}
