//! CPU rasteriser throughput: RGB-D frames (RGB 224x224 + semantic, depth 256x256, with the
//! images in CPU memory as every backend returns them) in a generated home (procgen `tiny`
//! preset) and in the demo home, one frame at a time and batched, on 1 and 2 threads; and
//! 12-view panoramas.
//!
//! `cargo bench -p vlnverse-sensors --bench raster -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;
use vlnverse_env::{Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{CameraSpec, Channels, RasterRenderer, Renderer, SceneMesh, View};

/// Agent poses inside rooms, with the camera clear of every object's box.
fn poses(scene: &Scene, n: usize, seed: u64) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let b = scene.bounds();
    let mut out = Vec::new();
    while out.len() < n {
        let p = Vec3::new(
            rng.random_range(b.min[0]..b.max[0]),
            scene.floor_height,
            rng.random_range(b.min[2]..b.max[2]),
        );
        let cam = p + Vec3::Y * 1.25;
        let clear = scene.objects.iter().all(|o| {
            let (lo, hi) = (o.bbox.min_v() - 0.15, o.bbox.max_v() + 0.15);
            !(cam.cmpge(lo).all() && cam.cmple(hi).all())
        });
        if clear && scene.room_at(p.x, p.z).is_some() {
            out.push(Pose::from_yaw(
                p,
                rng.random_range(0.0..std::f32::consts::TAU),
            ));
        }
    }
    out
}

/// The paper's observation: RGB 224 (+ semantic) and depth 256.
fn rgbd(base: &Pose) -> [View; 2] {
    [
        View {
            camera: CameraSpec::default().camera(base),
            channels: Channels {
                rgb: true,
                semantic: true,
                ..Default::default()
            },
        },
        View {
            camera: CameraSpec::depth().camera(base),
            channels: Channels::DEPTH,
        },
    ]
}

fn bench(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("preset");
    let scenes = [
        ("procgen_tiny_0", homes.scene(0).expect("home")),
        ("demo", demo_scene(0)),
    ];
    let pool = |n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("pool")
    };
    let (one, two) = (pool(1), pool(2));
    for (name, scene) in &scenes {
        let mesh = Arc::new(SceneMesh::new(scene).expect("scene"));
        eprintln!("scene {name}: {} triangles", mesh.triangle_count());
        let mut r = RasterRenderer::new();
        r.set_scene(mesh).expect("scene");
        let ps = poses(scene, 64, 1);

        let mut g = c.benchmark_group(format!("raster_rgbd_frame/{name}"));
        g.throughput(Throughput::Elements(1));
        for (threads, pool) in [(1, &one), (2, &two)] {
            let mut i = 0;
            g.bench_function(format!("{threads}_threads"), |b| {
                b.iter(|| {
                    i = (i + 1) % ps.len();
                    pool.install(|| r.render(&rgbd(&ps[i])).expect("render"))
                })
            });
        }
        g.finish();

        let batch = 8;
        let mut g = c.benchmark_group(format!("raster_rgbd_batched_{batch}/{name}"));
        g.throughput(Throughput::Elements(batch as u64));
        let views: Vec<View> = ps[..batch].iter().flat_map(rgbd).collect();
        for (threads, pool) in [(1, &one), (2, &two)] {
            g.bench_function(format!("{threads}_threads"), |b| {
                b.iter(|| pool.install(|| r.render(&views).expect("render")))
            });
        }
        g.finish();

        let mut g = c.benchmark_group(format!("raster_panorama_12x224_rgbd/{name}"));
        g.throughput(Throughput::Elements(1));
        let cam = CameraSpec::default().camera(&ps[3]);
        let views: Vec<View> = (0..12)
            .map(|k| View {
                camera: cam.yawed((30.0 * k as f32).to_radians()),
                channels: Channels {
                    rgb: true,
                    depth: true,
                    ..Default::default()
                },
            })
            .collect();
        g.bench_function("2_threads", |b| {
            b.iter(|| two.install(|| r.render(&views).expect("render")))
        });
        g.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
