//! Geodesic query rates on a 20 x 20 m synthetic home at 5 cm: cold A* (Lazy Theta*) queries,
//! distance-field builds, and cached O(1) queries through `GeodesicCache`.

use criterion::{criterion_group, Criterion};
use std::hint::black_box;
use vlnverse_env::geodesic::bench::{benchmark, sample_free_points};
use vlnverse_env::geodesic::{shortest_path, DistanceField, GeodesicCache};
use vlnverse_env::occupancy::{build_maps, synthetic::grid_home, GridMap, OccupancyConfig};

fn navigable() -> GridMap {
    build_maps(&grid_home(4, 4, 5.0, 7), &OccupancyConfig::default())
        .expect("maps")
        .navigable
}

fn bench(c: &mut Criterion) {
    let map = navigable();
    let pts = sample_free_points(&map, 512, 1);
    let mut i = 0;
    c.bench_function("geodesic/cold_astar_query", |b| {
        b.iter(|| {
            i = (i + 2) % pts.len();
            black_box(shortest_path(&map, pts[i], pts[(i + 1) % pts.len()]).expect("query"))
        })
    });
    let mut k = 0;
    c.bench_function("geodesic/distance_field_build", |b| {
        b.iter(|| {
            k = (k + 1) % pts.len();
            black_box(DistanceField::new(&map, pts[k]).expect("field"))
        })
    });
    let goals = &pts[..8];
    let mut cache = GeodesicCache::new(map.clone(), goals.len());
    for g in goals {
        cache.field(*g).expect("field");
    }
    let mut j = 0;
    c.bench_function("geodesic/cached_query", |b| {
        b.iter(|| {
            j = (j + 1) % pts.len();
            black_box(
                cache
                    .distance(pts[j], goals[j % goals.len()])
                    .expect("query"),
            )
        })
    });
}

criterion_group!(benches, bench);

fn main() {
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
    // One honest single-thread summary in queries per second.
    let map = navigable();
    let r = benchmark(&map, 200, 16, 200_000, 3);
    eprintln!(
        "geodesic summary (1 thread, {} free cells): cold A* {:.0} q/s; field build {:.1} ms; \
         cached {:.0} q/s; amortised over {} queries to {} goals {:.0} q/s",
        r.free_cells,
        r.cold_qps,
        r.field_build_ms,
        r.cached_qps,
        r.cached_queries,
        r.goals,
        r.amortised_qps
    );
}
