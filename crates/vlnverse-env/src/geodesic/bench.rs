//! Query-rate measurement that `cargo xtask bench` (or anyone) can call on a map.

use super::{shortest_path, GeodesicCache};
use crate::occupancy::GridMap;
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Figures from [`benchmark`] (single thread).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeodesicBenchReport {
    /// Free cells of the map.
    pub free_cells: usize,
    /// Cold A* (Lazy Theta*) queries run.
    pub cold_queries: usize,
    /// Cold A* queries per second (each query a full search, no cache).
    pub cold_qps: f64,
    /// Distinct goals in the cached run (one distance field each).
    pub goals: usize,
    /// Mean time to build one distance field (ms).
    pub field_build_ms: f64,
    /// Cached queries run.
    pub cached_queries: usize,
    /// Queries per second once every field is built (O(1) look-ups).
    pub cached_qps: f64,
    /// Queries per second including the field builds (`goals` fields amortised over
    /// `cached_queries`).
    pub amortised_qps: f64,
}

/// Deterministic points sampled uniformly from the free cells (splitmix64 on `seed`).
pub fn sample_free_points(map: &GridMap, count: usize, seed: u64) -> Vec<Vec2> {
    let free: Vec<(u32, u32)> = map.free_cells().collect();
    if free.is_empty() {
        return Vec::new();
    }
    let mut state = seed;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    (0..count)
        .map(|_| {
            let (c, r) = free[(next() % free.len() as u64) as usize];
            map.cell_center(c, r)
        })
        .collect()
}

/// Time `cold_queries` independent A* queries between random free points, then
/// `cached_queries` queries from random starts to `goals` random goals through a
/// [`GeodesicCache`]. Single-threaded; results depend only on the map and `seed` (timings aside).
pub fn benchmark(
    map: &GridMap,
    cold_queries: usize,
    goals: usize,
    cached_queries: usize,
    seed: u64,
) -> GeodesicBenchReport {
    let pts = sample_free_points(map, 2 * cold_queries.max(1), seed);
    let t = Instant::now();
    let mut reachable = 0usize;
    for pair in pts.chunks_exact(2).take(cold_queries) {
        if let Ok(Some(_)) = shortest_path(map, pair[0], pair[1]) {
            reachable += 1;
        }
    }
    let cold_s = t.elapsed().as_secs_f64();
    tracing::debug!(reachable, cold_queries, "cold geodesic queries");
    let goal_pts = sample_free_points(map, goals.max(1), seed ^ 0x5555);
    let starts = sample_free_points(map, cached_queries.max(1), seed ^ 0xAAAA);
    let mut cache = GeodesicCache::new(map.clone(), goal_pts.len());
    let t = Instant::now();
    for g in &goal_pts {
        let _ = cache.field(*g);
    }
    let build_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut sum = 0.0f64;
    for (i, s) in starts.iter().enumerate().take(cached_queries) {
        if let Ok(d) = cache.distance(*s, goal_pts[i % goal_pts.len()]) {
            sum += d.meters().unwrap_or(0.0) as f64;
        }
    }
    let cached_s = t.elapsed().as_secs_f64().max(1e-12);
    std::hint::black_box(sum);
    GeodesicBenchReport {
        free_cells: map.free_count(),
        cold_queries,
        cold_qps: cold_queries as f64 / cold_s.max(1e-12),
        goals: goal_pts.len(),
        field_build_ms: build_s * 1e3 / goal_pts.len() as f64,
        cached_queries,
        cached_qps: cached_queries as f64 / cached_s,
        amortised_qps: cached_queries as f64 / (cached_s + build_s).max(1e-12),
    }
}
