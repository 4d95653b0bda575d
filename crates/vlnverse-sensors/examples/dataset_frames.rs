//! RGB 224 + depth 256 observations of the default rig on the CPU rasteriser in the homes of a
//! generated dataset, loaded as an environment loads them (the scene folder, its mesh, the
//! prepared scene from `raster.bin`): the load per home, then `P` seeded poses on the ground
//! floor's free cells twice (the first pass draws each face for the first time, the second
//! finds them drawn), frames per second of each pass; the bytes the prepared scene holds as
//! loaded, after the poses, and once every face texture is unpacked.
//!
//! `cargo run --release -p vlnverse-sensors --example dataset_frames -- DATASET [HOMES] [P]`

use glam::Vec3;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use vlnverse_env::occupancy::GridMap;
use vlnverse_sensors::{AgentState, Backend, RasterScene, RigConfig, SceneMesh, SensorRig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dataset = PathBuf::from(
        args.first()
            .ok_or("usage: dataset_frames DATASET [HOMES] [P]")?,
    );
    let homes: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(8);
    let poses: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(100);
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(dataset.join("scenes"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("scene.json").is_file())
        .collect();
    dirs.sort();
    dirs.truncate(homes);
    let mut rig = SensorRig::new(RigConfig {
        backend: Backend::Raster,
        ..Default::default()
    })?;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let (mut load, mut first, mut second) = (0.0, 0.0, 0.0);
    let (mut loaded, mut seen, mut most) = (0, 0, 0);
    for d in &dirs {
        let nav = GridMap::load_ros(d.join("navigable.yaml"))?;
        let free: Vec<_> = nav.free_cells().collect();
        let t = Instant::now();
        let scene = vlnverse_env::io::load_scene(d)?;
        let mut mesh = SceneMesh::new(&scene)?;
        mesh.prepared_file = Some(d.join(vlnverse_sensors::raster::PREPARED_FILE));
        let mesh = Arc::new(mesh);
        rig.set_mesh(mesh.clone())?;
        load += t.elapsed().as_secs_f64();
        // The scene the rig draws (the shared cache's).
        let prepared = RasterScene::shared(mesh);
        loaded += prepared.bytes();
        let states: Vec<AgentState> = (0..poses)
            .map(|_| {
                let (c, r) = free[rng.random_range(0..free.len())];
                let p = nav.cell_center(c, r);
                let yaw = rng.random_range(0.0..std::f32::consts::TAU);
                AgentState::at(Vec3::new(p.x, scene.floor_height, p.y), yaw)
            })
            .collect();
        for pass in [&mut first, &mut second] {
            let t = Instant::now();
            for s in &states {
                std::hint::black_box(rig.observe(s)?);
            }
            *pass += t.elapsed().as_secs_f64();
        }
        seen += prepared.bytes();
        most += prepared.bytes_at_most();
    }
    let (n, frames) = (dirs.len(), (dirs.len() * poses) as f64);
    println!(
        "{n} homes: load {:.1} ms/home; {poses} poses each: first pass {:.0} frames/s, second \
         pass {:.0} frames/s",
        1e3 * load / n as f64,
        frames / first,
        frames / second
    );
    let mb = |b: usize| b as f64 / n as f64 / 1e6;
    println!(
        "prepared scene: {:.2} MB/home as loaded, {:.2} MB/home after the poses, {:.2} MB/home \
         with every face texture unpacked",
        mb(loaded),
        mb(seen),
        mb(most)
    );
    Ok(())
}
