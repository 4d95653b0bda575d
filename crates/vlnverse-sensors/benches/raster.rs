//! CPU rasteriser throughput: RGB-D frames (RGB 224x224 + semantic, depth 256x256, with the
//! images in CPU memory as every backend returns them) in a generated home (procgen `tiny`
//! preset) and in the demo home, one frame at a time and batched, on 1 and 2 threads; and
//! 12-view panoramas.
//!
//! The `raster_rgbd_clutter` group looks at the small objects of a generated home (cups,
//! bottles, vases, fruit, plants, books: boxes under 40 cm) from 1 to 3 m, the views where the
//! many small triangles of round shapes cost the most (back faces of round shapes culled, empty
//! small triangles left out before the fill, occlusion culling before set-up). The
//! `raster_single_rgb_view` group renders the RGB view alone (a batch of one view, whose fill
//! runs on one thread).
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

        let near = clutter_poses(scene, &ps);
        if !near.is_empty() {
            let mut g = c.benchmark_group(format!("raster_rgbd_clutter/{name}"));
            g.throughput(Throughput::Elements(1));
            for (threads, pool) in [(1, &one), (2, &two)] {
                let mut i = 0;
                g.bench_function(format!("{threads}_threads"), |b| {
                    b.iter(|| {
                        i = (i + 1) % near.len();
                        pool.install(|| r.render(&rgbd(&near[i])).expect("render"))
                    })
                });
            }
            g.finish();
        }

        // One view alone (a batch of one): its fill runs on one thread, only its resolve is
        // split into bands of rows.
        let mut g = c.benchmark_group(format!("raster_single_rgb_view/{name}"));
        g.throughput(Throughput::Elements(1));
        for (threads, pool) in [(1, &one), (2, &two)] {
            let mut i = 0;
            g.bench_function(format!("{threads}_threads"), |b| {
                b.iter(|| {
                    i = (i + 1) % ps.len();
                    let views = rgbd(&ps[i]);
                    pool.install(|| r.render(&views[..1]).expect("render"))
                })
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

/// Of the poses `ps`, those with a small object (box under 40 cm on every side) 1 to 3 m away,
/// turned to face the nearest such object.
fn clutter_poses(
    scene: &vlnverse_env::Scene,
    ps: &[vlnverse_env::Pose],
) -> Vec<vlnverse_env::Pose> {
    let small: Vec<glam::Vec3> = scene
        .objects
        .iter()
        .filter(|o| (o.bbox.max_v() - o.bbox.min_v()).max_element() < 0.4)
        .map(|o| (o.bbox.min_v() + o.bbox.max_v()) * 0.5)
        .collect();
    ps.iter()
        .filter_map(|p| {
            let at = p.translation();
            let flat = |q: glam::Vec3| glam::Vec2::new(q.x - at.x, q.z - at.z);
            let d = small
                .iter()
                .map(|q| flat(*q))
                .filter(|d| (1.0..3.0).contains(&d.length()))
                .min_by(|a, b| a.length().total_cmp(&b.length()))?;
            Some(vlnverse_env::Pose::from_yaw(at, (-d.x).atan2(-d.y)))
        })
        .collect()
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
