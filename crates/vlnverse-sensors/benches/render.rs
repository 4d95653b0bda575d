//! Rendering throughput: RGB-D frames (one environment and batched), panoramas, LiDAR scans and
//! ray-cast rays, on the wgpu backend (when an adapter exists) and the CPU ray caster.
//!
//! `cargo bench -p vlnverse-sensors --bench render -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::Pose;
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    lidar, CameraSpec, Channels, GpuRenderer, LidarSpec, RaycastRenderer, Renderer, SceneMesh,
    SceneRaycaster, View,
};

fn poses(n: usize) -> Vec<Pose> {
    (0..n)
        .map(|i| {
            let t = i as f32 / n as f32;
            Pose::from_yaw(
                Vec3::new(1.0 + 3.0 * t, 0.0, 1.5 + 3.0 * t),
                t * std::f32::consts::TAU,
            )
        })
        .collect()
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

fn backends(mesh: &Arc<SceneMesh>) -> Vec<Box<dyn Renderer>> {
    let mut v: Vec<Box<dyn Renderer>> = Vec::new();
    match GpuRenderer::new() {
        Ok(g) => {
            eprintln!("wgpu adapter: {}", g.context().adapter_description());
            v.push(Box::new(g));
        }
        Err(e) => eprintln!("no wgpu bench: {e}"),
    }
    v.push(Box::new(RaycastRenderer::new()));
    for r in &mut v {
        r.set_scene(mesh.clone()).expect("scene");
    }
    v
}

fn bench(c: &mut Criterion) {
    let scene = demo_scene(0);
    let mesh = Arc::new(SceneMesh::new(&scene).expect("scene"));
    eprintln!("scene {}: {} triangles", scene.id, mesh.triangle_count());
    let ps = poses(64);
    let mut renderers = backends(&mesh);
    let mut g = c.benchmark_group("rgbd_frame");
    g.throughput(Throughput::Elements(1));
    for r in &mut renderers {
        let mut i = 0;
        g.bench_function(r.name(), |b| {
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
    for r in &mut renderers {
        let views: Vec<View> = ps[..batch].iter().flat_map(rgbd).collect();
        g.bench_function(r.name(), |b| b.iter(|| r.render(&views).expect("render")));
    }
    g.finish();
    let mut g = c.benchmark_group("panorama_12x224_rgbd");
    g.throughput(Throughput::Elements(1));
    for r in &mut renderers {
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
        g.bench_function(r.name(), |b| b.iter(|| r.render(&views).expect("render")));
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
    g.bench_function("2d_360_beams", |b| b.iter(|| lidar::scan(&l2, &ps[5], &rc)));
    g.bench_function("3d_16x1024_beams", |b| {
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
    g.bench_function("depth_256x256", |b| {
        b.iter(|| pool.install(|| rc.render_view(&view)))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
