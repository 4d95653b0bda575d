//! The scene layer alone: a synthetic home, its occupancy and navigable maps, a geodesic
//! shortest path between two rooms, and the scene folder on disk (`scene.glb`, maps, graph).
//!
//! `cargo run -p vlnverse-env --example scene_maps [OUT_DIR]`

use std::path::PathBuf;

use glam::Vec2;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::io::write_scene_bundle;
use vlnverse_env::occupancy::synthetic::grid_home;
use vlnverse_env::occupancy::OccupancyConfig;

/// Build, map and write a 2x2-room home; return the path length between opposite rooms (m).
pub fn run(arg: Option<PathBuf>) -> Result<f32, Box<dyn std::error::Error>> {
    let out = arg.unwrap_or_else(|| std::env::temp_dir().join("vlnverse-scene-maps"));
    let scene = grid_home(2, 2, 4.0, 7);
    println!(
        "scene {}: {} rooms, {} doors, {} objects",
        scene.id,
        scene.rooms.len(),
        scene.doors.len(),
        scene.objects.len()
    );
    let (bundle, dir) = write_scene_bundle(&out, scene, &OccupancyConfig::default())?;
    let nav = &bundle.maps.navigable;
    println!(
        "navigable map: {}x{} cells at {} m, {:.1} m2 free -> {}",
        nav.width,
        nav.height,
        nav.resolution,
        nav.free_area_m2(),
        dir.display()
    );
    // Opposite corners of the free space.
    let free: Vec<Vec2> = nav
        .free_cells()
        .map(|(c, r)| nav.cell_center(c, r))
        .collect();
    let a = *free
        .iter()
        .min_by(|p, q| (p.x + p.y).total_cmp(&(q.x + q.y)))
        .ok_or("no free cell")?;
    let b = *free
        .iter()
        .max_by(|p, q| (p.x + p.y).total_cmp(&(q.x + q.y)))
        .ok_or("no free cell")?;
    let path = shortest_path(nav, a, b)?.ok_or("the corners are not connected")?;
    println!(
        "shortest path {a} -> {b}: {:.2} m in {} points (straight line {:.2} m)",
        path.length,
        path.points.len(),
        a.distance(b)
    );
    Ok(path.length)
}

#[allow(dead_code)] // the tests call `run` through `#[path]`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(std::env::args().nth(1).map(PathBuf::from)).map(|_| ())
}
