//! Render the demo home with the `full` rig (every sensor type) and write the readings as
//! files with [`vlnverse_sensors::output::write_rig`]: PNG images (depth as 16-bit
//! millimetres), LiDAR `.npy` scans, `camera.json` and `sensors.json`.
//!
//! `cargo run -p vlnverse-sensors --example render_demo -- [auto|wgpu|raster|raycast] [OUT_DIR]`

use glam::Vec3;
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::output::{write_rig, RigCapture};
use vlnverse_sensors::{AgentState, Backend, RigConfig, SensorRig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let backend: Backend = args.next().as_deref().unwrap_or("auto").parse()?;
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "render_demo".into()));
    // `configs/sensors/full.toml`, embedded in the crate.
    let mut config = RigConfig::shipped("full")?;
    config.backend = backend;
    let mut rig = SensorRig::new(config)?;
    rig.set_scene(&demo_scene(0))?;
    let (position, yaw) = (Vec3::new(3.8, 0.0, 4.2), 0.9f32);
    let observations = rig.observe(&AgentState::at(position, yaw))?;
    let files = write_rig(
        &out,
        &RigCapture {
            config: rig.config(),
            observations: &observations,
            position,
            yaw_deg: yaw.to_degrees(),
            backend: &rig.backend_name(),
        },
    )?;
    println!(
        "rendered {} sensors with {}; {} files in {}",
        observations.len(),
        rig.backend_name(),
        files.len(),
        out.display()
    );
    Ok(())
}
