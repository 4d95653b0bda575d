//! Scoring throughput: 100k trajectories of 50 positions against 8-point reference paths, with
//! straight-line distances and with a geodesic distance field (rayon, all threads).
//!
//! `cargo bench -p vlnverse-task --bench metrics -- --warm-up-time 1 --measurement-time 3`

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::geodesic::DistanceField;
use vlnverse_env::occupancy::{CellState, GridMap};
use vlnverse_score::metrics::{score_all, GoalDistance, GoalDistances, MetricsConfig};
use vlnverse_score::{Episode, EpisodeInfo, Goal, Trajectory};

const N: usize = 100_000;

fn fixtures() -> (Vec<Episode>, Vec<Trajectory>) {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let goal = [8.0, 0.0, 8.0];
    let mut eps = Vec::with_capacity(N);
    let mut trajs = Vec::with_capacity(N);
    for i in 0..N as u64 {
        let start = [rng.random_range(1.0..3.0), 0.0, rng.random_range(1.0..3.0)];
        let reference: Vec<[f32; 3]> = (0..8)
            .map(|k| {
                let t = k as f32 / 7.0;
                [
                    start[0] + (goal[0] - start[0]) * t,
                    0.0,
                    start[2] + (goal[2] - start[2]) * t,
                ]
            })
            .collect();
        let mut p = start;
        let positions: Vec<[f32; 3]> = (0..50)
            .map(|_| {
                let out = p;
                p[0] = (p[0] + rng.random_range(-0.05..0.25)).clamp(0.5, 9.5);
                p[2] = (p[2] + rng.random_range(-0.05..0.25)).clamp(0.5, 9.5);
                out
            })
            .collect();
        let headings = Some((0..50).map(|_| rng.random_range(-3.1..3.1)).collect());
        eps.push(Episode {
            episode_id: i,
            trajectory_id: i,
            scene_id: "bench".into(),
            start_position: start,
            goals: vec![Goal {
                position: goal,
                radius: 3.0,
                object_id: None,
            }],
            reference_path: reference,
            info: EpisodeInfo {
                geodesic_distance: 8.5,
                ..Default::default()
            },
            ..Default::default()
        });
        let mut t = Trajectory::from_positions(i, positions, rng.random_bool(0.8));
        t.headings = headings;
        trajs.push(t);
    }
    (eps, trajs)
}

fn bench(c: &mut Criterion) {
    let (eps, trajs) = fixtures();
    let cfg = MetricsConfig::default();
    let mut map = GridMap::new(200, 200, 0.05, Vec2::ZERO, CellState::Free).unwrap();
    for row in 40..160 {
        map.set(100, row, CellState::Occupied);
    }
    let field: Arc<dyn GoalDistance> =
        Arc::new(DistanceField::new(&map, Vec2::new(8.0, 8.0)).unwrap());
    let geodesic = move |_: &Episode| GoalDistances {
        goal: field.clone(),
        sub_goals: vec![],
    };

    let mut g = c.benchmark_group("score_100k_trajectories_50_points");
    g.sample_size(10);
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("euclidean", |b| {
        b.iter(|| score_all(&eps, &trajs, &GoalDistances::euclidean, &cfg))
    });
    g.bench_function("distance_field", |b| {
        b.iter(|| score_all(&eps, &trajs, &geodesic, &cfg))
    });
    let raw = MetricsConfig {
        ndtw_spacing: None,
        ..Default::default()
    };
    g.bench_function("euclidean_raw_ndtw", |b| {
        b.iter(|| score_all(&eps, &trajs, &GoalDistances::euclidean, &raw))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
