//! One home generated from its seed (vlnverse preset).

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

criterion_group!(benches, generate);
criterion_main!(benches);
