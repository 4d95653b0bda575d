//! One home generated from its seed (vlnverse preset), and its light baked
//! (`vlnverse_env::light::bake_fresh`: occlusion, lamp and daylight shadow rays per vertex).
//!
//! `cargo bench -p vlnverse-procgen --bench generate -- --warm-up-time 1 --measurement-time 5`

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};

fn generate(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Vlnverse).expect("shipped preset is valid");
    let mut i = 0;
    c.bench_function("generate_one_vlnverse_home", |b| {
        b.iter(|| {
            i = (i + 1) % homes.len();
            black_box(homes.scene(black_box(i)).expect("scene generates"))
        })
    });
}

fn bake(c: &mut Criterion) {
    let homes = HomeGenerator::from_preset(Preset::Vlnverse).expect("shipped preset is valid");
    // The first 8 homes, baked in turn; `bake_fresh` bypasses the content cache.
    let scenes: Vec<_> = (0..8)
        .map(|i| homes.scene(i).expect("scene generates"))
        .collect();
    let mut i = 0;
    c.bench_function("bake_light_one_vlnverse_home", |b| {
        b.iter(|| {
            i = (i + 1) % scenes.len();
            black_box(vlnverse_env::light::bake_fresh(black_box(&scenes[i])))
        })
    });
}

criterion_group!(benches, generate, bake);
criterion_main!(benches);
