//! Instruction generation throughput on a tiny-preset home: one fine instruction and the three
//! coarse styles of one target.
//!
//! `cargo bench -p vlnverse-instructions --bench instructions -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec2;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::SceneSource;
use vlnverse_instructions::{InstructionGenerator, PathContext, TemplateGenerator};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::Style;

fn bench(c: &mut Criterion) {
    let scene = HomeGenerator::from_preset(Preset::Tiny)
        .and_then(|h| h.scene(0))
        .expect("tiny scene");
    let maps = build_maps(&scene, &OccupancyConfig::default()).expect("maps");
    let graph = SceneGraph::build(&scene);
    let free: Vec<Vec2> = maps
        .navigable
        .free_cells()
        .map(|(c, r)| maps.navigable.cell_center(c, r))
        .collect();
    let (a, b) = (free[0], free[free.len() - 1]);
    let p = shortest_path(&maps.navigable, a, b)
        .expect("finite")
        .expect("one island");
    let path: Vec<[f32; 3]> = p.points.iter().map(|q| [q.x, 0.0, q.y]).collect();
    let ctx = PathContext {
        scene: &scene,
        graph: &graph,
        navigable: &maps.navigable,
        path: &path,
        start_yaw: 0.0,
        whole_home: None,
    };
    let target = scene
        .objects
        .iter()
        .find(|o| graph.referring_expression(&scene, o.id).is_some())
        .expect("a describable object")
        .id;
    let g = TemplateGenerator::default();
    let mut seed = 0u64;
    c.bench_function("fine instruction", |bch| {
        bch.iter(|| {
            seed += 1;
            g.fine(&ctx, seed).expect("fine")
        })
    });
    c.bench_function("coarse instruction, 3 styles", |bch| {
        bch.iter(|| {
            seed += 1;
            Style::ALL.map(|s| g.coarse(&ctx, target, s, seed).expect("coarse"))
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
