//! RGB 224 + depth 256 observations per second of the default rig on the CPU rasteriser in a
//! generated tiny home (one observation at a time, all threads), and the cost of baking its
//! light. `cargo run --release -p vlnverse-sensors --example look_rate -- [N] [no-ceiling]`.

use glam::Vec3;
use std::time::Instant;
use vlnverse_env::{SceneSource, SemanticClass};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::{AgentState, Backend, RigConfig, SceneMesh, SensorRig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(400);
    let mut scene = HomeGenerator::from_preset(Preset::Tiny)?.scene(0)?;
    if args.iter().any(|a| a == "no-ceiling") {
        scene.objects.retain(|o| o.class != SemanticClass::Ceiling);
    }
    let mut rig = SensorRig::new(RigConfig {
        backend: Backend::Raster,
        ..Default::default()
    })?;
    let t = Instant::now();
    rig.set_scene(&scene)?;
    let prep = t.elapsed().as_secs_f64();
    // Room centres, turning on the spot.
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
    let states: Vec<AgentState> = (0..n)
        .map(|i| AgentState::at(centres[i % centres.len()], i as f32 * 0.37))
        .collect();
    for s in states.iter().take(20) {
        rig.observe(s)?;
    }
    let t = Instant::now();
    for s in &states {
        std::hint::black_box(rig.observe(s)?);
    }
    let secs = t.elapsed().as_secs_f64();
    println!(
        "{} triangles drawn, scene prepared (bake included) in {prep:.3} s; {n} observations: {:.0} frames/s",
        SceneMesh::new(&scene)?.triangle_count(),
        n as f64 / secs
    );
    Ok(())
}
