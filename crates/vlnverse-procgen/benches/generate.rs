//! One home generated from its seed (vlnverse preset; and a home on two floors from
//! `configs/scenes/two_storey.toml` with its per-level maps and a geodesic query across the
//! floors), and its light baked (`vlnverse_env::light::bake_fresh`: occlusion, lamp and
//! daylight shadow rays per vertex).
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

fn two_storey(c: &mut Criterion) {
    use vlnverse_env::geodesic::{LevelPoint, MultiLevelMap};
    let cfg = vlnverse_procgen::ProcgenConfig::from_toml_str(
        include_str!("../configs/scenes/two_storey.toml"),
        None,
    )
    .expect("two_storey.toml is valid");
    let homes = HomeGenerator::new(cfg).expect("valid config");
    let mut i = 0;
    c.bench_function("generate_one_two_storey_home", |b| {
        b.iter(|| {
            i = (i + 1) % homes.len();
            black_box(homes.scene(black_box(i)).expect("scene generates"))
        })
    });
    let scene = homes.scene(0).expect("scene generates");
    let occ = vlnverse_env::occupancy::OccupancyConfig::default();
    c.bench_function("level_maps_two_storey_home", |b| {
        b.iter(|| black_box(MultiLevelMap::from_scene(black_box(&scene), &occ).expect("maps")))
    });
    let map = MultiLevelMap::from_scene(&scene, &occ).expect("maps");
    // From a navigable cell of the first ground-floor room to one of the last upstairs room:
    // two A* legs and the flight.
    let cell_in = |room: u32| {
        let level = scene.room_level(room).expect("room on a level");
        let nav = map.level(level).expect("level map");
        let r = scene.room(room).expect("room");
        nav.free_cells()
            .map(|(c, w)| nav.cell_center(c, w))
            .find(|p| r.contains(p.x, p.y))
            .map(|p| LevelPoint::new(level, p.x, p.y))
            .expect("navigable room")
    };
    let a = cell_in(scene.rooms[0].id);
    let z = cell_in(scene.rooms[scene.rooms.len() - 2].id);
    c.bench_function("geodesic_across_floors_cold", |b| {
        b.iter(|| {
            black_box(
                map.geodesic_distance(black_box(a), black_box(z))
                    .expect("finite"),
            )
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

criterion_group!(benches, generate, two_storey, bake);
criterion_main!(benches);
