//! What a home switch costs the renderer: a generated `vlnverse` home read from its folder
//! (`scene.json`, and the light `scene.glb` holds), its triangles and looks (`SceneMesh`), and
//! the rasteriser's prepared scene (`RasterScene`: merged faces and their face textures), read
//! back from the `raster.bin` generation writes or prepared afresh; for comparison, the light
//! bake a load no longer runs. Prints the bytes each part holds.
//!
//! `cargo bench -p vlnverse-sensors --bench home_load -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::PathBuf;
use std::sync::Arc;
use vlnverse_env::io::{load_scene, write_scene_dir};
use vlnverse_env::{light, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::raster::PREPARED_FILE;
use vlnverse_sensors::{RasterScene, SceneMesh};

/// Homes written to a temporary folder (removed when dropped).
struct Homes {
    root: PathBuf,
    dirs: Vec<PathBuf>,
}

impl Drop for Homes {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

fn homes(n: usize) -> Homes {
    let root = std::env::temp_dir().join(format!("vlnverse-home-load-{}", std::process::id()));
    let generator = HomeGenerator::from_preset(Preset::Vlnverse).expect("preset");
    let dirs = (0..n)
        .map(|i| {
            let scene = generator.scene(i).expect("home");
            let dir = write_scene_dir(&root, &scene, &[]).expect("written");
            RasterScene::write_prepared_scene(&scene, &dir).expect("prepared");
            dir
        })
        .collect();
    Homes { root, dirs }
}

fn bench(c: &mut Criterion) {
    let homes = homes(4);
    let scenes: Vec<_> = homes.dirs.iter().map(|d| load_scene(d).unwrap()).collect();
    let meshes: Vec<Arc<SceneMesh>> = scenes
        .iter()
        .map(|s| Arc::new(SceneMesh::new(s).expect("mesh")))
        .collect();
    for (s, m) in scenes.iter().zip(&meshes) {
        let r = RasterScene::new(m.clone());
        eprintln!(
            "{}: {} triangles ({} drawn); mesh {:.2} MB, prepared scene {:.2} MB ({:.2} MB face textures), light {:.3} MB",
            s.id,
            m.triangle_count(),
            r.drawn_triangles(),
            m.bytes() as f64 / 1e6,
            r.bytes() as f64 / 1e6,
            r.face_texture_bytes() as f64 / 1e6,
            light::bake(s).bytes() as f64 / 1e6,
        );
    }
    let mut g = c.benchmark_group("home_load");
    let mut i = 0;
    g.bench_function("load_scene_folder", |b| {
        b.iter(|| {
            i = (i + 1) % homes.dirs.len();
            black_box(load_scene(&homes.dirs[i]).unwrap())
        })
    });
    g.bench_function("bake_light_fresh", |b| {
        b.iter(|| {
            i = (i + 1) % scenes.len();
            black_box(light::bake_fresh(&scenes[i]))
        })
    });
    g.bench_function("scene_mesh", |b| {
        b.iter(|| {
            i = (i + 1) % scenes.len();
            black_box(SceneMesh::new(&scenes[i]).unwrap())
        })
    });
    g.bench_function("raster_scene", |b| {
        b.iter(|| {
            i = (i + 1) % meshes.len();
            black_box(RasterScene::new(meshes[i].clone()))
        })
    });
    let files: Vec<PathBuf> = homes.dirs.iter().map(|d| d.join(PREPARED_FILE)).collect();
    g.bench_function("raster_scene_from_file", |b| {
        b.iter(|| {
            i = (i + 1) % meshes.len();
            black_box(RasterScene::load_prepared(meshes[i].clone(), &files[i]).unwrap())
        })
    });
    // The whole switch without the prepared-scene cache: read the folder, triangulate, read
    // the prepared scene back.
    g.bench_function("switch_from_file", |b| {
        b.iter(|| {
            i = (i + 1) % homes.dirs.len();
            let s = load_scene(&homes.dirs[i]).unwrap();
            let mesh = Arc::new(SceneMesh::new(&s).unwrap());
            black_box(RasterScene::load_prepared(mesh, &files[i]).unwrap())
        })
    });
    // The same, preparing the scene afresh.
    g.bench_function("switch_uncached", |b| {
        b.iter(|| {
            i = (i + 1) % homes.dirs.len();
            let s = load_scene(&homes.dirs[i]).unwrap();
            black_box(RasterScene::new(Arc::new(SceneMesh::new(&s).unwrap())))
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
