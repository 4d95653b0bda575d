//! Import of the AWS RoboMaker small house (148k triangles, 87 nodes) from
//! `../shared/scenes/`: the import alone (labels, floor, room segmentation), and the import plus
//! the occupancy maps and the scene graph (`vlnverse_env::io::scene_bundle`), i.e. everything
//! `cargo xtask import` computes before writing files.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use vlnverse_env::io::scene_bundle;
use vlnverse_import::import_scene;
use vlnverse_testkit::real_scenes::aws_small_house;

fn bench(c: &mut Criterion) {
    let Some((file, opts)) = aws_small_house() else {
        return;
    };
    let mut g = c.benchmark_group("aws_small_house");
    g.sample_size(10);
    g.bench_function("import", |b| {
        b.iter(|| black_box(import_scene(&file, &opts).expect("imports")))
    });
    g.bench_function("import_maps_scene_graph", |b| {
        b.iter(|| {
            let (scene, _) = import_scene(&file, &opts).expect("imports");
            black_box(scene_bundle(scene, &opts.occupancy).expect("bundle"))
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
