//! Test homes: the tiny preset's homes with maps and graph, and random shortest paths between
//! navigable points.

use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::occupancy::{build_maps, GridMap, OccupancyConfig, OccupancyMaps};
use vlnverse_env::scene_graph::{yaw_from_direction, SceneGraph};
use vlnverse_env::{Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};

/// A scene with its maps and graph.
pub struct World {
    /// The home.
    pub scene: Scene,
    /// Its occupancy and navigable maps.
    pub maps: OccupancyMaps,
    /// Its scene graph.
    pub graph: SceneGraph,
}

/// A sampled path.
pub struct Sample {
    /// The path points `(x, y, z)`.
    pub path: Vec<[f32; 3]>,
    /// The heading at the start.
    pub start_yaw: f32,
}

/// The first `n` homes of the tiny preset.
pub fn worlds(n: usize) -> Vec<World> {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset");
    (0..n.min(homes.len()))
        .map(|i| {
            let scene = homes.scene(i).expect("tiny scene");
            let maps = build_maps(&scene, &OccupancyConfig::default()).expect("maps");
            let graph = SceneGraph::build(&scene);
            World { scene, maps, graph }
        })
        .collect()
}

/// A random free point of the map.
pub fn random_free(map: &GridMap, rng: &mut ChaCha8Rng) -> Vec2 {
    let free: Vec<(u32, u32)> = map.free_cells().collect();
    let (c, r) = free[rng.random_range(0..free.len())];
    map.cell_center(c, r)
}

/// `count` shortest paths between random navigable points at least 3 m apart; the start yaw is
/// random.
pub fn paths(w: &World, count: usize, seed: u64) -> Vec<Sample> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let map = &w.maps.navigable;
    let free: Vec<(u32, u32)> = map.free_cells().collect();
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < count && tries < count * 50 {
        tries += 1;
        let (c, r) = free[rng.random_range(0..free.len())];
        let a = map.cell_center(c, r);
        let (c, r) = free[rng.random_range(0..free.len())];
        let b = map.cell_center(c, r);
        if a.distance(b) < 3.0 {
            continue;
        }
        let Some(p) = shortest_path(map, a, b).expect("finite points") else {
            continue;
        };
        let start_yaw = rng.random_range(-std::f32::consts::PI..std::f32::consts::PI);
        out.push(Sample {
            path: p.points.iter().map(|q| [q.x, 0.0, q.y]).collect(),
            start_yaw,
        });
    }
    out
}

/// Yaw of the heading from `a` to `b`.
pub fn yaw_along(a: Vec2, b: Vec2) -> f32 {
    yaw_from_direction(b - a)
}
