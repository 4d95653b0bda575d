//! Rendering throughput: RGB-D frames (one environment and batched), panoramas, LiDAR scans and
//! ray-cast rays, on the wgpu backend (when an adapter exists), the CPU rasteriser and the CPU
//! ray caster, in the demo home and in a generated home (procgen `tiny` preset, scene 0).
//!
//! `cargo bench -p vlnverse-sensors --bench render -- --warm-up-time 1 --measurement-time 3`
//! (append a filter such as `rgbd_frame` to run one group).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;
use vlnverse_env::{Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    lidar, CameraSpec, Channels, GpuRenderer, LidarSpec, RasterRenderer, RaycastRenderer, Renderer,
    SceneMesh, SceneRaycaster, View,
};

/// Seeded agent poses on the floor of a room, with the camera outside every object's box.
fn poses(scene: &Scene, n: usize) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let b = scene.bounds();
    let mut out = Vec::new();
    for _ in 0..100_000 {
        if out.len() == n {
            break;
        }
        let p = Vec3::new(
            rng.random_range(b.min[0]..b.max[0]),
            scene.floor_height,
            rng.random_range(b.min[2]..b.max[2]),
        );
        let cam = p + Vec3::Y * 1.25;
        let blocked = scene.objects.iter().any(|o| {
            let (lo, hi) = (o.bbox.min_v() - 0.15, o.bbox.max_v() + 0.15);
            cam.cmpge(lo).all() && cam.cmple(hi).all()
        });
        if !blocked && scene.room_at(p.x, p.z).is_some() {
            out.push(Pose::from_yaw(
                p,
                rng.random_range(0.0..std::f32::consts::TAU),
            ));
        }
    }
    assert_eq!(out.len(), n, "scene {} has no free floor", scene.id);
    out
}

/// RGB 224 (+ semantic) and depth 256 views of one frame.
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

fn backends() -> Vec<Box<dyn Renderer>> {
    let mut v: Vec<Box<dyn Renderer>> = Vec::new();
    match GpuRenderer::new() {
        Ok(g) => {
            eprintln!("wgpu adapter: {}", g.context().adapter_description());
            v.push(Box::new(g));
        }
        Err(e) => eprintln!("no wgpu bench: {e}"),
    }
    v.push(Box::new(RasterRenderer::new()));
    v.push(Box::new(RaycastRenderer::new()));
    v
}

fn bench(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset");
    let scenes = [demo_scene(0), homes.scene(0).expect("generated home")];
    let mut renderers = backends();
    for scene in &scenes {
        let mesh = Arc::new(SceneMesh::new(scene).expect("scene"));
        eprintln!("scene {}: {} triangles", scene.id, mesh.triangle_count());
        let ps = poses(scene, 64);
        for r in &mut renderers {
            r.set_scene(mesh.clone()).expect("scene");
        }
        let id = |r: &dyn Renderer| BenchmarkId::new(r.name(), &scene.id);

        let mut g = c.benchmark_group("rgbd_frame");
        g.throughput(Throughput::Elements(1));
        for r in &mut renderers {
            let mut i = 0;
            g.bench_function(id(r.as_ref()), |b| {
                b.iter(|| {
                    i = (i + 1) % ps.len();
                    r.render(&rgbd(&ps[i])).expect("render")
                })
            });
        }
        g.finish();

        let batch = 8;
        let mut g = c.benchmark_group("rgbd_batched_8");
        g.throughput(Throughput::Elements(batch as u64));
        let views: Vec<View> = ps[..batch].iter().flat_map(rgbd).collect();
        for r in &mut renderers {
            g.bench_function(id(r.as_ref()), |b| {
                b.iter(|| r.render(&views).expect("render"))
            });
        }
        g.finish();

        let mut g = c.benchmark_group("panorama_12x224_rgbd");
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
        for r in &mut renderers {
            g.bench_function(id(r.as_ref()), |b| {
                b.iter(|| r.render(&views).expect("render"))
            });
        }
        g.finish();

        let rc = SceneRaycaster::new(mesh.clone()).expect("bvh");
        let mut g = c.benchmark_group("lidar_scan");
        g.throughput(Throughput::Elements(1));
        let l2 = LidarSpec::default();
        let l3 = LidarSpec {
            beams: 1024,
            channels: 16,
            ..LidarSpec::default()
        };
        g.bench_function(BenchmarkId::new("2d_360_beams", &scene.id), |b| {
            b.iter(|| lidar::scan(&l2, &ps[5], &rc))
        });
        g.bench_function(BenchmarkId::new("3d_16x1024_beams", &scene.id), |b| {
            b.iter(|| lidar::scan(&l3, &ps[5], &rc))
        });
        g.finish();

        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .expect("pool");
        let mut g = c.benchmark_group("raycast_rays_2_threads");
        g.throughput(Throughput::Elements(256 * 256));
        let view = View {
            camera: CameraSpec::depth().camera(&ps[7]),
            channels: Channels::DEPTH,
        };
        g.bench_function(BenchmarkId::new("depth_256x256", &scene.id), |b| {
            b.iter(|| pool.install(|| rc.render_view(&view)))
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
