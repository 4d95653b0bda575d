//! CPU rasteriser throughput: RGB-D frames (RGB 224x224 + semantic, depth 256x256, with the
//! images in CPU memory as every backend returns them) in a generated home (procgen `tiny`
//! preset) and in the demo home, one frame at a time and batched, on 1 and 2 threads; and
//! 12-view panoramas.
//!
//! `cargo bench -p vlnverse-sensors --bench raster -- --warm-up-time 1 --measurement-time 3`

mod support;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::sync::Arc;
use support::{floor_poses, panorama, pool, rgbd};
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{RasterRenderer, Renderer, SceneMesh, View};

fn bench(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("preset");
    let scenes = [
        ("procgen_tiny_0", homes.scene(0).expect("home")),
        ("demo", demo_scene(0)),
    ];
    let (one, two) = (pool(1), pool(2));
    for (name, scene) in &scenes {
        let mesh = Arc::new(SceneMesh::new(scene).expect("scene"));
        eprintln!("scene {name}: {} triangles", mesh.triangle_count());
        let mut r = RasterRenderer::new();
        r.set_scene(mesh).expect("scene");
        let ps = floor_poses(scene, 64, 1);

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
        let views = panorama(&ps[3]);
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
