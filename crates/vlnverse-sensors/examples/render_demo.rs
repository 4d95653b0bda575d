//! Render the demo home with the paper's rig and save the images as PNG files.
//!
//! `cargo run -p vlnverse-sensors --example render_demo -- [auto|wgpu|raycast] [OUT_DIR]`

use glam::Vec3;
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::frame::colorize_ids;
use vlnverse_sensors::{AgentState, Backend, Observation, RigConfig, SensorRig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let backend: Backend = args.next().as_deref().unwrap_or("auto").parse()?;
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "render_demo".into()));
    std::fs::create_dir_all(&out)?;
    let mut config: RigConfig = RigConfig::load(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/sensors/full.toml"),
    )?;
    config.backend = backend;
    let mut rig = SensorRig::new(config)?;
    rig.set_scene(&demo_scene(0))?;
    let obs = rig.observe(&AgentState::at(Vec3::new(3.8, 0.0, 4.2), 0.9))?;
    for (name, o) in &obs {
        match o {
            Observation::Rgb(f) => image::save_buffer(
                out.join(format!("{name}.png")),
                &f.rgb,
                f.width,
                f.height,
                image::ColorType::Rgb8,
            )?,
            Observation::Semantic(f) => {
                let c = colorize_ids(f.semantic.iter().map(|&c| c as u32));
                image::save_buffer(
                    out.join(format!("{name}.png")),
                    &c,
                    f.width,
                    f.height,
                    image::ColorType::Rgb8,
                )?
            }
            Observation::Depth(f) => {
                let g: Vec<u8> = f.depth.iter().map(|d| (d / 10.0 * 255.0) as u8).collect();
                image::save_buffer(
                    out.join(format!("{name}.png")),
                    &g,
                    f.width,
                    f.height,
                    image::ColorType::L8,
                )?
            }
            Observation::Lidar(s) => {
                let hits = s.ranges.iter().filter(|r| r.is_finite()).count();
                println!("{name}: {} x {} beams, {hits} returns", s.channels, s.beams);
            }
            Observation::Panorama(views) => println!("{name}: {} views", views.len()),
            Observation::Instance(f) => {
                let c = colorize_ids(f.instance.iter().copied());
                image::save_buffer(
                    out.join(format!("{name}.png")),
                    &c,
                    f.width,
                    f.height,
                    image::ColorType::Rgb8,
                )?
            }
            other => println!("{name}: {other:?}"),
        }
    }
    println!(
        "rendered with {}; images in {}",
        rig.backend_name(),
        out.display()
    );
    Ok(())
}
