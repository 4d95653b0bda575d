//! Dialogue oracle throughput on a tiny-preset home: one "which way" question (one A* query)
//! between the ends of a sampled path.
//!
//! `cargo bench -p vlnverse-eval --bench oracle -- --warm-up-time 1 --measurement-time 3`

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec2;
use vlnverse_eval::oracle::{Oracle, OracleConfig, OracleQuery, ShortestPathOracle};
use vlnverse_testkit::homes::{paths, worlds};

fn bench(c: &mut Criterion) {
    let w = worlds(1).pop().expect("a tiny home");
    let path = paths(&w, 1, 0).remove(0).path;
    let (a, b) = (path[0], path[path.len() - 1]);
    let (a, b) = (Vec2::new(a[0], a[2]), Vec2::new(b[0], b[2]));
    let (scene, graph, nav) = (
        Arc::new(w.scene),
        Arc::new(w.graph),
        Arc::new(w.maps.navigable),
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
