//! Dialogue oracle throughput on a tiny-preset home: one "which way" question (one A* query).
//!
//! `cargo bench -p vlnverse-eval --bench oracle -- --warm-up-time 1 --measurement-time 3`

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec2;
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::SceneSource;
use vlnverse_eval::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
use vlnverse_procgen::{HomeGenerator, Preset};

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
    let (scene, graph, nav) = (
        Arc::new(scene.clone()),
        Arc::new(graph.clone()),
        Arc::new(maps.navigable.clone()),
    );
    c.bench_function("oracle which-way", |bch| {
        bch.iter(|| {
            let mut o = ShortestPathOracle::new(
                scene.clone(),
                graph.clone(),
                nav.clone(),
                [b.x, 0.0, b.y],
                None,
                OracleConfig::default(),
            )
            .expect("oracle");
            o.ask(&OracleQuery::WhichWay, [a.x, 0.0, a.y], 0.0)
                .expect("answer")
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
