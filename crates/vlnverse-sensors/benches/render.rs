//! Rendering throughput: RGB-D frames (one environment and batched), panoramas, LiDAR scans and
//! ray-cast rays, on the wgpu backend (when an adapter exists), the CPU rasteriser and the CPU
//! ray caster, in the demo home and in a generated home (procgen `tiny` preset, scene 0).
//!
//! `cargo bench -p vlnverse-sensors --bench render -- --warm-up-time 1 --measurement-time 3`
//! (append a filter such as `rgbd_frame` to run one group).

mod support;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::sync::Arc;
use support::{backends, floor_poses, panorama, pool, rgbd};
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    lidar, CameraSpec, Channels, LidarSpec, Renderer, SceneMesh, SceneRaycaster, View,
};

fn bench(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset");
    let scenes = [demo_scene(0), homes.scene(0).expect("generated home")];
    let mut renderers = backends();
    for scene in &scenes {
        let mesh = Arc::new(SceneMesh::new(scene).expect("scene"));
        eprintln!("scene {}: {} triangles", scene.id, mesh.triangle_count());
        let ps = floor_poses(scene, 64, 7);
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
        let views = panorama(&ps[3]);
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

        let pool = pool(2);
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
