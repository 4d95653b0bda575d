//! Throughput of the simulator in a generated home (procgen `tiny` preset, scene 0), and
//! on the flight of stairs of a two-storey home (`configs/scenes/two_storey.toml`, scene 0).
//!
//! `cargo bench -p vlnverse-sim --bench sim -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::sync::Arc;
use vlnverse_env::{Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sim::*;

fn home() -> Scene {
    HomeGenerator::from_preset(Preset::Tiny)
        .and_then(|g| g.scene(0))
        .expect("procgen tiny scene 0")
}

/// The first home of `configs/scenes/two_storey.toml` (on two floors).
fn two_storey_home() -> Scene {
    let cfg = vlnverse_procgen::ProcgenConfig::from_toml_str(
        include_str!("../../vlnverse-procgen/configs/scenes/two_storey.toml"),
        None,
    )
    .expect("two_storey.toml");
    HomeGenerator::new(cfg)
        .and_then(|g| g.scene(0))
        .expect("two-storey scene 0")
}

/// At the foot of the home's first flight facing its head; moves from the foot to the head.
fn flight_start(scene: &Scene, step: f32) -> (Pose, usize) {
    let st = &scene.storeys.stairs[0];
    let (f, h) = (glam::Vec3::from(st.foot), glam::Vec3::from(st.head));
    let d = glam::Vec3::new(h.x - f.x, 0.0, h.z - f.z);
    let yaw = (-d.x).atan2(-d.z);
    (Pose::from_yaw(f, yaw), (d.length() / step).round() as usize)
}

/// `n` collision-free start poses, sampled deterministically inside the rooms.
fn starts(scene: &Scene, sim: &mut RapierSimulator, n: usize) -> Vec<Pose> {
    let b = scene.bounds();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    sim.reset(scene, Pose::IDENTITY).expect("reset");
    let mut out = Vec::new();
    while out.len() < n {
        let (x, z) = (
            rng.random_range(b.min[0]..b.max[0]),
            rng.random_range(b.min[2]..b.max[2]),
        );
        if scene.room_at(x, z).is_some() && sim.is_free(x, z) {
            let yaw = rng.random_range(-3.1..3.1);
            out.push(Pose::from_yaw(
                glam::Vec3::new(x, scene.floor_height, z),
                yaw,
            ));
        }
    }
    out
}

/// A random agent: half forward moves, a quarter left turns, a quarter right turns.
fn discrete_actions(n: usize, seed: u64, agent: &AgentConfig) -> Vec<Action> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| match rng.random_range(0..4) {
            0 | 1 => Action::forward(agent),
            2 => Action::left(agent),
            _ => Action::right(agent),
        })
        .collect()
}

fn lenient() -> SimConfig {
    SimConfig {
        setting: CollisionSetting::Lenient,
        ..Default::default()
    }
}

fn bench(c: &mut Criterion) {
    let scene = home();
    let cfg = lenient();
    let mut sim = RapierSimulator::new(cfg.clone()).expect("sim");
    let poses = starts(&scene, &mut sim, 64);
    let physics = Arc::new(PhysicsScene::build(&scene, &cfg.agent).expect("physics"));

    let mut g = c.benchmark_group("discrete");
    let n = 1000;
    let mixed = discrete_actions(n, 2, &cfg.agent);
    let forward = vec![Action::forward(&cfg.agent); n];
    for (name, actions) in [("mixed_1_env", &mixed), ("forward_1_env", &forward)] {
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(name, |b| {
            b.iter_batched_ref(
                || {
                    let mut s = RapierSimulator::new(cfg.clone()).expect("sim");
                    s.reset_in(Arc::clone(&physics), poses[0]).expect("reset");
                    s
                },
                |s| {
                    for a in actions.iter() {
                        black_box(s.step(*a).expect("step"));
                    }
                },
                BatchSize::LargeInput,
            )
        });
    }

    // Up the flight and back down (Strict: not one noticeable collision on the way).
    let stairs = two_storey_home();
    let strict = SimConfig::default();
    let (foot, n_up) = flight_start(&stairs, strict.agent.step_size);
    let upstairs = Arc::new(PhysicsScene::build(&stairs, &strict.agent).expect("physics"));
    let mut up_down = vec![Action::forward(&strict.agent); n_up];
    up_down.push(Action::TurnLeft(std::f32::consts::PI));
    up_down.extend(vec![Action::forward(&strict.agent); n_up]);
    g.throughput(Throughput::Elements(up_down.len() as u64));
    g.bench_function("flight_up_and_down_1_env", |b| {
        b.iter_batched_ref(
            || {
                let mut s = RapierSimulator::new(strict.clone()).expect("sim");
                s.reset_in(Arc::clone(&upstairs), foot).expect("reset");
                s
            },
            |s| {
                for a in up_down.iter() {
                    black_box(s.step(*a).expect("step"));
                }
            },
            BatchSize::SmallInput,
        )
    });

    let envs = 64;
    let rounds = 20;
    let per_env: Vec<Vec<Action>> = (0..envs)
        .map(|i| discrete_actions(rounds, 10 + i as u64, &cfg.agent))
        .collect();
    g.throughput(Throughput::Elements((envs * rounds) as u64));
    g.bench_function("mixed_64_envs_2_threads", |b| {
        b.iter_batched_ref(
            || {
                let mut v = VecSimulator::new(envs, cfg.clone(), Some(2)).expect("vec");
                for (e, p) in v.envs_mut().iter_mut().zip(&poses) {
                    e.reset_in(Arc::clone(&physics), *p).expect("reset");
                }
                v
            },
            |v| {
                for r in 0..rounds {
                    let acts: Vec<Action> = per_env.iter().map(|a| a[r]).collect();
                    black_box(v.step(&acts).expect("step"));
                }
            },
            BatchSize::LargeInput,
        )
    });
    g.finish();

    let mut g = c.benchmark_group("continuous");
    let steps = 30u64;
    g.throughput(Throughput::Elements(steps));
    g.bench_function("physics_steps", |b| {
        b.iter_batched_ref(
            || {
                let mut s = RapierSimulator::new(cfg.clone()).expect("sim");
                s.reset_in(Arc::clone(&physics), poses[1]).expect("reset");
                s
            },
            |s| {
                let a = Action::Velocity {
                    v: 0.8,
                    omega: 0.3,
                    duration: steps as f32 * cfg.physics_dt,
                };
                black_box(s.step(a).expect("step"))
            },
            BatchSize::SmallInput,
        )
    });
    g.finish();

    let mut g = c.benchmark_group("episode");
    g.bench_function("reset_shared_world", |b| {
        let mut s = RapierSimulator::new(cfg.clone()).expect("sim");
        b.iter(|| black_box(s.reset_in(Arc::clone(&physics), poses[2]).expect("reset")))
    });
    g.bench_function("build_physics_scene", |b| {
        b.iter(|| black_box(PhysicsScene::build(&scene, &cfg.agent).expect("build")))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
