//! Import of the AWS RoboMaker small house (148k triangles, 87 nodes) from
//! `../shared/scenes/`: the import alone (labels, floor, room segmentation), and the import plus
//! the occupancy maps and the scene graph (`vlnverse_env::io::scene_bundle`), i.e. everything
//! `cargo xtask import` computes before writing files.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::PathBuf;
use vlnverse_env::io::scene_bundle;
use vlnverse_import::{import_scene, ImportOptions};

fn bench(c: &mut Criterion) {
    let file = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/scenes/aws_small_house/aws_small_house_yup.glb"
    ));
    if !file.exists() {
        eprintln!("skipped: {} is absent", file.display());
        return;
    }
    let opts = ImportOptions {
        mapping: Some(PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../configs/import/aws_small_house.toml"
        ))),
        ..Default::default()
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
