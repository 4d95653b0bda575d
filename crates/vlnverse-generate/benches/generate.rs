//! Generation hot spots on one benchmark home (`vlnverse` preset, scene 0): target preparation,
//! a distance field towards a target, a fine A* path, one reference image, and the tiny preset
//! end to end. Run: `cargo bench -p vlnverse-generate --bench generate -- --warm-up-time 1
//! --measurement-time 3`.

use criterion::{criterion_group, criterion_main, Criterion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::SceneSource;
use vlnverse_generate::ReferenceRenderer;
use vlnverse_generate::{run, RunOptions};
use vlnverse_generate::{GeneratePreset, SceneSampler, StageTimes};
use vlnverse_instructions::TemplateGenerator;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::Task;

fn bench(c: &mut Criterion) {
    let cfg = GeneratePreset::Vlnverse.config().unwrap();
    let scene = HomeGenerator::from_preset(Preset::Vlnverse)
        .unwrap()
        .scene(0)
        .unwrap();
    let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
    let graph = SceneGraph::build(&scene);
    c.bench_function("sampler_new (targets, goal points)", |b| {
        b.iter(|| black_box(SceneSampler::new(&scene, &maps, &graph, &cfg.sampling, 1)))
    });
    let sampler = SceneSampler::new(&scene, &maps, &graph, &cfg.sampling, 1);
    let spot = sampler.targets()[0];
    c.bench_function("distance_field (one target)", |b| {
        b.iter(|| {
            black_box(
                vlnverse_env::geodesic::DistanceField::new(&maps.navigable, spot.goal).unwrap(),
            )
        })
    });
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    c.bench_function("fine_path (one sample, A*)", |b| {
        b.iter(|| black_box(sampler.fine_path(&mut rng, &cfg.tasks.fine).unwrap()))
    });
    let renderer = ReferenceRenderer::new(&scene, &cfg.image).unwrap();
    let centre = scene.object(spot.object).unwrap().bbox.center();
    c.bench_function("reference_image 224x224 (render + png)", |b| {
        b.iter(|| black_box(renderer.render_png(spot.goal, centre).unwrap()))
    });
    let mut g = c.benchmark_group("tiny_preset");
    g.sample_size(10);
    g.bench_function("generate all tasks", |b| {
        let tiny = GeneratePreset::Tiny.config().unwrap();
        let source = HomeGenerator::from_preset(Preset::Tiny).unwrap();
        b.iter(|| {
            let d = tempfile::tempdir().unwrap();
            let opts = RunOptions {
                out: d.path().to_path_buf(),
                tasks: Task::ALL.to_vec(),
                shard: (0, 1),
                occupancy: OccupancyConfig::default(),
            };
            run(
                &source,
                &tiny,
                &opts,
                &TemplateGenerator::default(),
                &StageTimes::default(),
                &|_| {},
            )
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
