//! `cargo xtask render`: render the cameras of an agent standing in a scene to PNG files.
//!
//! Writes `rgb.png`, `depth.png` (16-bit, millimetres along the optical axis; pixels that see
//! nothing within `far` hold `far`), `semantic.png` and `instance.png` (ids colourised with a fixed
//! palette) and `camera.json` (intrinsics and world pose of each camera; camera looks along -Z,
//! Y up, quaternions `[x, y, z, w]`).

use anyhow::Context;
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vlnverse_env::Pose;
use vlnverse_sensors::frame::colorize_ids;
use vlnverse_sensors::{
    create_renderer, Backend, Camera, CameraSpec, Channels, Intrinsics, RigConfig, SceneMesh,
    SensorSpec, View,
};

/// Arguments of `cargo xtask render`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene folder (with scene.json and scene.glb).
    #[arg(long)]
    scene: PathBuf,
    /// Agent base position on the floor, `x,y,z` in metres.
    #[arg(long, allow_hyphen_values = true)]
    position: String,
    /// Agent yaw in degrees (counter-clockwise from above; 0 looks along -Z).
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    yaw: f32,
    /// Sensor rig config (TOML); default: the paper's RGB 224x224 + depth 256x256.
    #[arg(long)]
    sensors: Option<PathBuf>,
    /// Rendering backend, overriding the config's.
    #[arg(long)]
    backend: Option<String>,
    /// Output folder.
    #[arg(long)]
    out: PathBuf,
}

fn parse_position(s: &str) -> anyhow::Result<Vec3> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .with_context(|| format!("--position `{s}`: expected x,y,z in metres"))?;
    anyhow::ensure!(
        v.len() == 3 && v.iter().all(|x| x.is_finite()),
        "--position `{s}`: expected three finite numbers x,y,z"
    );
    Ok(Vec3::new(v[0], v[1], v[2]))
}

fn camera_json(name: &str, c: &Camera) -> serde_json::Value {
    let i = Intrinsics::from(c);
    serde_json::json!({
        "sensor": name,
        "width": i.width, "height": i.height,
        "fx": i.fx, "fy": i.fy, "cx": i.cx, "cy": i.cy,
        "hfov_deg": c.hfov.to_degrees(), "near": c.near, "far": c.far,
        "position": c.position.to_array(),
        "rotation": c.rotation.to_array(),
    })
}

fn save(path: &Path, r: image::ImageResult<()>) -> anyhow::Result<()> {
    r.with_context(|| format!("writing {}", path.display()))
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut config = match &args.sensors {
        Some(p) => RigConfig::load(p)?,
        None => RigConfig::default(),
    };
    if let Some(b) = &args.backend {
        config.backend = b.parse::<Backend>()?;
    }
    let position = parse_position(&args.position)?;
    anyhow::ensure!(args.yaw.is_finite(), "--yaw {}: not a number", args.yaw);
    let scene = vlnverse_env::io::load_scene(&args.scene)
        .with_context(|| format!("loading scene {}", args.scene.display()))?;
    let base = Pose::from_yaw(position, args.yaw.to_radians());

    let find = |kind: &str| {
        config.sensors.iter().find_map(|s| match s {
            SensorSpec::Rgb(c) if kind == "rgb" => Some(c.clone()),
            SensorSpec::Depth(c) if kind == "depth" => Some(c.clone()),
            SensorSpec::Semantic(c) if kind == "semantic" => Some(c.clone()),
            SensorSpec::Instance(c) if kind == "instance" => Some(c.clone()),
            _ => None,
        })
    };
    let rgb = find("rgb").unwrap_or_default();
    let depth = find("depth").unwrap_or_else(CameraSpec::depth);
    let sem = find("semantic").unwrap_or_else(|| rgb.clone());
    let inst = find("instance").unwrap_or_else(|| sem.clone());
    let cams = [
        ("rgb", rgb.camera(&base), Channels::RGB),
        ("depth", depth.camera(&base), Channels::DEPTH),
        (
            "semantic",
            sem.camera(&base),
            Channels {
                semantic: true,
                ..Default::default()
            },
        ),
        (
            "instance",
            inst.camera(&base),
            Channels {
                instance: true,
                ..Default::default()
            },
        ),
    ];
    let views: Vec<View> = cams
        .iter()
        .map(|(_, c, ch)| View {
            camera: *c,
            channels: *ch,
        })
        .collect();

    let mut renderer = create_renderer(config.backend)?;
    renderer.set_scene(Arc::new(SceneMesh::new(&scene)?))?;
    let frames = renderer.render(&views)?;

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let out = |f: &str| args.out.join(f);
    let f = &frames[0];
    let p = out("rgb.png");
    save(
        &p,
        image::save_buffer(&p, &f.rgb, f.width, f.height, image::ColorType::Rgb8),
    )?;
    let f = &frames[1];
    let mm: Vec<u16> = f
        .depth
        .iter()
        .map(|d| (d * 1000.0).round().clamp(0.0, 65535.0) as u16)
        .collect();
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(f.width, f.height, mm)
        .context("depth image size")?;
    let p = out("depth.png");
    save(&p, img.save(&p))?;
    let f = &frames[2];
    let p = out("semantic.png");
    let c = colorize_ids(f.semantic.iter().map(|&c| c as u32));
    save(
        &p,
        image::save_buffer(&p, &c, f.width, f.height, image::ColorType::Rgb8),
    )?;
    let f = &frames[3];
    let p = out("instance.png");
    let c = colorize_ids(f.instance.iter().copied());
    save(
        &p,
        image::save_buffer(&p, &c, f.width, f.height, image::ColorType::Rgb8),
    )?;

    let rgb_cam = &cams[0].1;
    let mut json = camera_json("rgb", rgb_cam);
    json["convention"] = serde_json::json!("camera looks along -Z, +Y up, +X right; rotation is the camera-to-world quaternion [x, y, z, w]; pixel (u, v) centre at (u + 0.5, v + 0.5), v = 0 top row");
    json["depth_png"] =
        serde_json::json!("uint16 millimetres along the optical axis, clipped at far");
    json["agent_position"] = serde_json::json!(position.to_array());
    json["agent_yaw_deg"] = serde_json::json!(args.yaw);
    json["backend"] = serde_json::json!(renderer.name());
    json["cameras"] = cams.iter().map(|(n, c, _)| camera_json(n, c)).collect();
    let p = out("camera.json");
    std::fs::write(&p, serde_json::to_string_pretty(&json)? + "\n")
        .with_context(|| format!("writing {}", p.display()))?;
    tracing::info!(
        "wrote rgb.png, depth.png, semantic.png, instance.png, camera.json to {}",
        args.out.display()
    );
    Ok(())
}
