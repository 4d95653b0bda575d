//! RGB-D frames inside a real home: the AWS RoboMaker small house (148k triangles) imported from
//! `../shared/scenes/` with the shipped mapping; RGB 224 (+ semantic) and depth 256 per frame,
//! at seeded navigable poses spread over its rooms, on every backend that starts here (wgpu on
//! whatever adapter exists, e.g. lavapipe; the CPU rasteriser; the CPU ray caster).
//!
//! `cargo bench -p vlnverse-sensors --bench real_scene -- --warm-up-time 1 --measurement-time 3`

mod support;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::sync::Arc;
use support::{backends, rgbd};
use vlnverse_env::io::scene_bundle;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::{Pose, Scene};
use vlnverse_import::import_scene;
use vlnverse_sensors::SceneMesh;
use vlnverse_testkit::real_scenes::aws_small_house;

/// Up to `per_room` seeded navigable poses in every room, random headings.
fn room_poses(scene: &Scene, nav: &GridMap, per_room: usize) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (lo, hi) = nav.bounds();
    let mut by_room: BTreeMap<String, Vec<Pose>> = BTreeMap::new();
    for _ in 0..200_000 {
        let p = Vec2::new(rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y));
        let yaw = rng.random_range(0.0..std::f32::consts::TAU);
        if !nav.is_free_at(p) {
            continue;
        }
        let Some(room) = scene.room_at(p.x, p.y) else {
            continue;
        };
        let v = by_room.entry(room.name.clone()).or_default();
        if v.len() < per_room {
            v.push(Pose::from_yaw(Vec3::new(p.x, scene.floor_height, p.y), yaw));
        }
    }
    eprintln!(
        "poses per room: {:?}",
        by_room
            .iter()
            .map(|(k, v)| (k, v.len()))
            .collect::<Vec<_>>()
    );
    // Interleave rooms so consecutive frames are in different rooms.
    let mut out = Vec::new();
    for i in 0..per_room {
        out.extend(by_room.values().filter_map(|v| v.get(i).cloned()));
    }
    out
}

fn bench(c: &mut Criterion) {
    let Some((file, opts)) = aws_small_house() else {
        return;
    };
    let (scene, _) = import_scene(&file, &opts).expect("imports");
    let bundle = scene_bundle(scene, &opts.occupancy).expect("maps");
    let scene = bundle.scene;
    let poses = room_poses(&scene, &bundle.maps.navigable, 4);
    assert!(poses.len() >= 8, "only {} navigable poses", poses.len());
    let mesh = Arc::new(SceneMesh::new(&scene).expect("mesh"));
    eprintln!("scene {}: {} triangles", scene.id, mesh.triangle_count());

    let mut renderers = backends();
    let mut g = c.benchmark_group("real_scene_rgbd_frame");
    g.throughput(Throughput::Elements(1));
    for r in &mut renderers {
        r.set_scene(mesh.clone()).expect("scene");
        let mut i = 0;
        g.bench_function(BenchmarkId::new(r.name(), &scene.id), |b| {
            b.iter(|| {
                i = (i + 1) % poses.len();
                r.render(&rgbd(&poses[i])).expect("render")
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
