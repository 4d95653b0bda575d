//! RGB 224 + depth 256 observations per second of the default rig on the CPU rasteriser (one
//! observation at a time, all threads) and the cost of preparing the scene (baking its light):
//! in a generated tiny home (room centres, turning on the spot), or with `aws` in the AWS
//! RoboMaker small house of `../shared/scenes/` (148k triangles, seeded navigable poses).
//!
//! `cargo run --release -p vlnverse-sensors --example look_rate -- [N] [no-ceiling] [aws]`

use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use std::path::PathBuf;
use std::time::Instant;
use vlnverse_env::{Scene, SceneSource, SemanticClass};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::{AgentState, Backend, RasterScene, RigConfig, SceneMesh, SensorRig};

/// The AWS small house, imported with its label mapping, and `n` seeded navigable states.
fn aws(n: usize) -> Result<(Scene, Vec<AgentState>), Box<dyn std::error::Error>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let file = root.join("../shared/scenes/aws_small_house/aws_small_house_yup.glb");
    let opts = vlnverse_import::ImportOptions {
        mapping: Some(root.join("configs/import/aws_small_house.toml")),
        ..Default::default()
    };
    let (scene, _) = vlnverse_import::import_scene(&file, &opts)?;
    let bundle = vlnverse_env::io::scene_bundle(scene, &opts.occupancy)?;
    let nav = &bundle.maps.navigable;
    let (lo, hi) = nav.bounds();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let mut states = Vec::with_capacity(n);
    while states.len() < n {
        let p = Vec2::new(rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y));
        if nav.is_free_at(p) {
            let yaw = rng.random_range(0.0..std::f32::consts::TAU);
            let floor = bundle.scene.floor_height;
            states.push(AgentState::at(Vec3::new(p.x, floor, p.y), yaw));
        }
    }
    Ok((bundle.scene, states))
}

/// Generated tiny home 0 and `n` states at its room centres, turning on the spot.
fn tiny(n: usize, ceiling: bool) -> Result<(Scene, Vec<AgentState>), Box<dyn std::error::Error>> {
    let mut scene = HomeGenerator::from_preset(Preset::Tiny)?.scene(0)?;
    if !ceiling {
        scene.objects.retain(|o| o.class != SemanticClass::Ceiling);
    }
    let centres: Vec<Vec3> = scene
        .rooms
        .iter()
        .map(|r| {
            let k = r.polygon.len() as f32;
            let (x, z) = r
                .polygon
                .iter()
                .fold((0.0, 0.0), |a, p| (a.0 + p[0] / k, a.1 + p[1] / k));
            Vec3::new(x, 0.0, z)
        })
        .collect();
    let states = (0..n)
        .map(|i| AgentState::at(centres[i % centres.len()], i as f32 * 0.37))
        .collect();
    Ok((scene, states))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(400);
    let (scene, states) = if args.iter().any(|a| a == "aws") {
        aws(n)?
    } else {
        tiny(n, !args.iter().any(|a| a == "no-ceiling"))?
    };
    let mut rig = SensorRig::new(RigConfig {
        backend: Backend::Raster,
        ..Default::default()
    })?;
    let t = Instant::now();
    rig.set_scene(&scene)?;
    let prep = t.elapsed().as_secs_f64();
    for s in states.iter().take(20) {
        rig.observe(s)?;
    }
    let t = Instant::now();
    for s in &states {
        std::hint::black_box(rig.observe(s)?);
    }
    let secs = t.elapsed().as_secs_f64();
    let mesh = std::sync::Arc::new(SceneMesh::new(&scene)?);
    let raster = RasterScene::new(mesh.clone());
    println!(
        "{}: {} triangles ({} drawn, {:.1} MB of face textures), scene prepared (bake included) in {prep:.3} s; {n} observations: {:.0} frames/s",
        scene.id,
        mesh.triangle_count(),
        raster.drawn_triangles(),
        raster.face_texture_bytes() as f64 / 1e6,
        n as f64 / secs
    );
    Ok(())
}
