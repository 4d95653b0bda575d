//! One `vlnverse` home through the whole per-scene pipeline: generation, occupancy maps, scene
//! graph, then the file encoders, each stage on its own and all together (one thread).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use vlnverse_env::io::{glb::write_glb, json::scene_to_json, scene_bundle};
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};

fn bench(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Vlnverse).expect("shipped preset is valid");
    let occ = OccupancyConfig::default();
    let scenes: Vec<_> = (0..16).map(|i| homes.scene(i).expect("scene")).collect();
    let dir = tempfile::tempdir().expect("temp dir");
    let mut i = 0;
    let mut next = || {
        i = (i + 1) % scenes.len();
        i
    };
    c.bench_function("scene_full_pipeline_with_files", |b| {
        b.iter(|| {
            let k = next();
            let scene = homes.scene(k).expect("scene");
            let bundle = scene_bundle(scene, &occ).expect("bundle");
            black_box(bundle.write(dir.path()).expect("write"))
        })
    });
    c.bench_function("stage_generate", |b| {
        b.iter(|| black_box(homes.scene(next()).expect("scene")))
    });
    c.bench_function("stage_maps", |b| {
        b.iter(|| black_box(build_maps(&scenes[next()], &occ).expect("maps")))
    });
    c.bench_function("stage_graph", |b| {
        b.iter(|| black_box(SceneGraph::build(&scenes[next()])))
    });
    c.bench_function("stage_encode_glb", |b| {
        b.iter(|| black_box(write_glb(&scenes[next()])))
    });
    c.bench_function("stage_encode_json", |b| {
        b.iter(|| black_box(scene_to_json(&scenes[next()])))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
