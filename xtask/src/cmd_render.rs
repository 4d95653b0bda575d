//! `cargo xtask render`: read every sensor of a rig on an agent standing in a scene, once, and
//! write one file per reading, named after the sensor (see docs/formats.md; the writing is
//! `vlnverse_sensors::output`):
//!
//! - RGB camera `NAME`: `NAME.png` (8-bit sRGB, noise applied as configured);
//! - depth camera: `NAME.png` (16-bit, millimetres along the optical axis; pixels that see
//!   nothing within `far` hold `far`; a `normalize`d depth sensor is written in metres too);
//! - semantic / instance camera: `NAME.png` (ids colourised with a fixed palette);
//! - panorama: `NAME_K_rgb.png`, `NAME_K_depth.png`, `NAME_K_semantic.png` for view `K` (yaw
//!   order, `K` from 0), the channels the panorama has;
//! - LiDAR: `NAME.npy` (little-endian float32, shape `[channels, beams]`, metres; `inf` = no
//!   return, `NaN` = dropped return) and `NAME.png` (the scan seen from above in the sensor frame,
//!   forward up, all rings, scaled to the farthest return);
//! - `camera.json` (when the rig has cameras): intrinsics and world pose of each camera (camera
//!   looks along -Z, Y up, quaternions `[x, y, z, w]`); panorama views are listed as `NAME_K`;
//! - `sensors.json`: agent pose, backend, and the readings of pose, compass, GPS and collision
//!   sensors, plus each LiDAR's beam layout.
//!
//! Without `--sensors` the rig is the paper's RGB and depth cameras plus semantic and instance
//! cameras matching the RGB one (`rgb.png`, `depth.png`, `semantic.png`, `instance.png`).
//!
//! `--top-down SIZE` instead writes `topdown_rgb.png`: the whole home seen from high above
//! (a narrow, nearly orthographic view, north = -Z up) on the CPU rasteriser, with the light
//! baked for the full home but the ceilings left out so the rooms show.

use anyhow::Context;
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};
use vlnverse_env::occupancy::{build_maps, CellState, GridMap, OccupancyConfig};
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::output::{write_rig, RigCapture};
use vlnverse_sensors::{AgentState, Backend, Camera, CameraSpec, RigConfig, SensorRig, SensorSpec};

/// Arguments of `cargo xtask render`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene folder (with scene.json and scene.glb).
    #[arg(long)]
    scene: PathBuf,
    /// Agent base position on the floor, `x,y,z` in metres.
    #[arg(long, allow_hyphen_values = true, required_unless_present = "top_down")]
    position: Option<String>,
    /// Render the whole home from above into `topdown_rgb.png`, SIZE pixels square (no agent).
    #[arg(long, value_name = "SIZE")]
    top_down: Option<u32>,
    /// Agent yaw in degrees (counter-clockwise from above; 0 looks along -Z).
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    yaw: f32,
    /// Sensor rig config (TOML); default: the paper's RGB 224x224 + depth 256x256, plus
    /// semantic and instance cameras like the RGB one.
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

/// The rig of `render` without `--sensors`: the paper's RGB and depth cameras, and semantic and
/// instance cameras identical to the RGB one.
pub fn default_render_rig() -> RigConfig {
    let mut config = RigConfig::default();
    config
        .sensors
        .push(SensorSpec::Semantic(CameraSpec::default()));
    config
        .sensors
        .push(SensorSpec::Instance(CameraSpec::default()));
    config
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut config = match &args.sensors {
        Some(p) => RigConfig::load(p)?,
        None => default_render_rig(),
    };
    if let Some(b) = &args.backend {
        config.backend = b.parse::<Backend>()?;
    }
    if let Some(size) = args.top_down {
        check_top_down_size(size)?;
        let scene = vlnverse_env::io::load_scene(&args.scene)
            .with_context(|| format!("loading scene {}", args.scene.display()))?;
        std::fs::create_dir_all(&args.out)
            .with_context(|| format!("creating {}", args.out.display()))?;
        let path = args.out.join("topdown_rgb.png");
        top_down(&scene, size)?
            .save(&path)
            .with_context(|| format!("writing {}", path.display()))?;
        tracing::info!("wrote {}", path.display());
        return Ok(());
    }
    let position = parse_position(args.position.as_deref().unwrap_or_default())?;
    anyhow::ensure!(args.yaw.is_finite(), "--yaw {}: not a number", args.yaw);
    let scene = vlnverse_env::io::load_scene(&args.scene)
        .with_context(|| format!("loading scene {}", args.scene.display()))?;
    if let Some(w) = check_position(&args.scene, &scene, position) {
        tracing::warn!("{}: {w}", args.scene.display());
    }
    let written = render_rig(&scene, config, position, args.yaw, &args.out)?;
    let names = if written.len() <= 8 {
        written.join(", ")
    } else {
        format!("{}, ... ({} files)", written[..6].join(", "), written.len())
    };
    tracing::info!("wrote {names} to {}", args.out.display());
    Ok(())
}

/// The top-down picture's size, checked before anything is loaded or written.
fn check_top_down_size(size: u32) -> anyhow::Result<()> {
    anyhow::ensure!(
        (16..=4096).contains(&size),
        "--top-down {size}: must be 16 to 4096 pixels"
    );
    Ok(())
}

/// The home seen from 40 m above its centre, looking straight down, without its ceilings.
pub fn top_down(scene: &Scene, size: u32) -> anyhow::Result<image::RgbImage> {
    use std::sync::Arc;
    use vlnverse_sensors::{Channels, RasterRenderer, Renderer, SceneMesh, View};
    check_top_down_size(size)?;
    let full = SceneMesh::new(scene)?;
    let ceiling = vlnverse_env::SemanticClass::Ceiling.id();
    let mut mesh = SceneMesh {
        objects: Vec::new(),
        positions: Vec::new(),
        object: Vec::new(),
        color: Vec::new(),
        look: Vec::new(),
        ..full.clone()
    };
    for r in full.objects.iter().filter(|r| full.class(r.id) != ceiling) {
        let (a, b) = (r.first as usize, (r.first + r.count) as usize);
        mesh.objects
            .push(vlnverse_sensors::scene_mesh::ObjectRange {
                first: mesh.object.len() as u32,
                ..*r
            });
        mesh.positions
            .extend_from_slice(&full.positions[3 * a..3 * b]);
        mesh.object.extend_from_slice(&full.object[a..b]);
        mesh.color.extend_from_slice(&full.color[a..b]);
        mesh.look.extend_from_slice(&full.look[a..b]);
    }
    let b = scene.bounds();
    let (lo, hi) = (b.min_v(), b.max_v());
    let centre = (lo + hi) * 0.5;
    let half = ((hi.x - lo.x).max(hi.z - lo.z) * 0.5 + 0.3).max(1.0);
    let height = 40.0;
    let pose = Pose {
        position: [centre.x, hi.y.max(3.0) + height, centre.z],
        rotation: glam::Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2).to_array(),
    };
    let hfov = 2.0 * (half / (height + hi.y.max(3.0))).atan();
    let camera = Camera::new(&pose, size, size, hfov, 1.0, height + 20.0);
    let mut r = RasterRenderer::new();
    r.set_scene(Arc::new(mesh))?;
    let frame = r
        .render(&[View {
            camera,
            channels: Channels::RGB,
        }])?
        .remove(0);
    image::RgbImage::from_raw(size, size, frame.rgb).context("top-down frame has the wrong size")
}

/// The scene's maps: `occupancy.yaml` and `navigable.yaml` of its folder, else built from the
/// scene.
fn scene_maps(dir: &Path, scene: &Scene) -> Option<(GridMap, Option<GridMap>)> {
    let occ = dir.join("occupancy.yaml");
    if occ.is_file() {
        let occupancy = GridMap::load_ros(&occ).ok()?;
        let nav = dir.join("navigable.yaml");
        let navigable = nav
            .is_file()
            .then(|| GridMap::load_ros(&nav).ok())
            .flatten();
        return Some((occupancy, navigable));
    }
    let maps = build_maps(scene, &OccupancyConfig::default()).ok()?;
    Some((maps.occupancy, Some(maps.navigable)))
}

/// Why an agent at `position` would see something other than the inside of the home: off the
/// map, outside the floor, inside a wall or object, or where the agent cannot stand. `None` for a
/// navigable position (or when the scene has no maps to check against).
pub fn check_position(dir: &Path, scene: &Scene, position: Vec3) -> Option<String> {
    let (occupancy, navigable) = scene_maps(dir, scene)?;
    position_warning(&occupancy, navigable.as_ref(), position)
}

/// [`check_position`] against given maps.
pub fn position_warning(
    occupancy: &GridMap,
    navigable: Option<&GridMap>,
    position: Vec3,
) -> Option<String> {
    let p = Vec2::new(position.x, position.z);
    let at = format!("--position {},{},{}", position.x, position.y, position.z);
    let (lo, hi) = occupancy.bounds();
    let Some((c, r)) = occupancy.world_to_cell(p) else {
        return Some(format!(
            "{at} is off the map (it covers x {:.2} to {:.2}, z {:.2} to {:.2}); the \
             renders show the home from outside",
            lo.x, hi.x, lo.y, hi.y
        ));
    };
    match occupancy.state(c, r) {
        CellState::Occupied => {
            return Some(format!(
                "{at} is inside a wall or object; the renders show its inside"
            ))
        }
        CellState::Unknown => {
            return Some(format!(
                "{at} is outside the floor of the home (unknown on the occupancy map)"
            ))
        }
        CellState::Free => {}
    }
    if navigable.is_some_and(|n| !n.is_free_at(p)) {
        return Some(format!(
            "{at} is not navigable: too close to a wall or object for the agent to stand there"
        ));
    }
    None
}

/// Read every sensor of `config` once, for an agent at `position` looking `yaw_deg` degrees
/// (counter-clockwise from -Z), and write the files to `out`
/// ([`vlnverse_sensors::output::write_rig`]). Returns the file names written.
pub fn render_rig(
    scene: &Scene,
    config: RigConfig,
    position: Vec3,
    yaw_deg: f32,
    out: &Path,
) -> anyhow::Result<Vec<String>> {
    let base = Pose::from_yaw(position, yaw_deg.to_radians());
    let mut rig = SensorRig::new(config)?;
    rig.set_scene(scene)?;
    rig.reset(base);
    let observations = rig.observe(&AgentState::at(position, yaw_deg.to_radians()))?;
    let written = write_rig(
        out,
        &RigCapture {
            config: rig.config(),
            observations: &observations,
            position,
            yaw_deg,
            backend: &rig.backend_name(),
        },
    )?;
    Ok(written
        .iter()
        .filter_map(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_top_down_size_is_refused_before_the_folder_is_made() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("top");
        for size in [0, 15, 4097] {
            let err = run(Args {
                scene: dir.path().join("no_scene"),
                position: None,
                top_down: Some(size),
                yaw: 0.0,
                sensors: None,
                backend: None,
                out: out.clone(),
            })
            .unwrap_err()
            .to_string();
            assert!(err.contains(&format!("--top-down {size}")), "{err}");
            assert!(!out.exists(), "{size}: {out:?} was made");
        }
    }

    /// Off the map, in a wall and beside a wall are each named with the position; the centre
    /// of the home is not.
    #[test]
    fn an_off_map_or_in_wall_position_is_warned_about() {
        let (scene, at) = demo();
        let dir = tempfile::tempdir().unwrap();
        let maps = build_maps(&scene, &OccupancyConfig::default()).unwrap();
        assert_eq!(
            position_warning(&maps.occupancy, Some(&maps.navigable), at),
            None
        );
        let off = Vec3::new(1000.0, 0.0, 0.0);
        let w = check_position(dir.path(), &scene, off).unwrap();
        assert!(w.contains("1000,0,0") && w.contains("off the map"), "{w}");
        let (c, r) = (0..maps.occupancy.cells().len())
            .map(|i| maps.occupancy.cell_of_index(i))
            .find(|&(c, r)| maps.occupancy.state(c, r) == CellState::Occupied)
            .unwrap();
        let wall = maps.occupancy.cell_center(c, r);
        let w = position_warning(
            &maps.occupancy,
            Some(&maps.navigable),
            Vec3::new(wall.x, 0.0, wall.y),
        )
        .unwrap();
        assert!(w.contains("inside a wall"), "{w}");
        assert!(w.contains(&format!("{},0,{}", wall.x, wall.y)), "{w}");
    }

    fn demo() -> (Scene, Vec3) {
        let scene = vlnverse_sensors::demo::demo_scene(1);
        let c = scene.bounds().center();
        let at = Vec3::new(c.x, scene.floor_height, c.z);
        (scene, at)
    }

    /// A shipped rig (`configs/sensors/NAME.toml`) on `backend`.
    fn config(name: &str, backend: Backend) -> RigConfig {
        let mut c = RigConfig::shipped(name).unwrap();
        c.backend = backend;
        c
    }

    fn sorted(mut v: Vec<String>) -> Vec<String> {
        v.sort();
        v
    }

    #[test]
    fn default_rig_writes_the_four_camera_images() {
        let (scene, at) = demo();
        let dir = tempfile::tempdir().unwrap();
        let mut c = default_render_rig();
        c.backend = Backend::Raster;
        let files = render_rig(&scene, c, at, 30.0, dir.path()).unwrap();
        assert_eq!(
            sorted(files),
            [
                "camera.json",
                "depth.png",
                "instance.png",
                "rgb.png",
                "semantic.png",
                "sensors.json"
            ]
        );
        let depth = image::open(dir.path().join("depth.png")).unwrap();
        assert_eq!((depth.width(), depth.height()), (256, 256));
        assert!(matches!(depth, image::DynamicImage::ImageLuma16(_)));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("camera.json")).unwrap())
                .unwrap();
        assert_eq!(json["sensor"], "rgb");
        assert_eq!(json["width"], 224);
        let names: Vec<&str> = json["cameras"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["sensor"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["rgb", "depth", "semantic", "instance"]);
    }

    /// The LiDAR-only rig renders no camera image and writes each scan.
    #[test]
    fn lidar_rig_writes_scans_and_no_images() {
        let (scene, at) = demo();
        let dir = tempfile::tempdir().unwrap();
        let files = render_rig(
            &scene,
            config("lidar", Backend::Raycast),
            at,
            0.0,
            dir.path(),
        )
        .unwrap();
        assert_eq!(
            sorted(files),
            [
                "lidar2d.npy",
                "lidar2d.png",
                "lidar3d.npy",
                "lidar3d.png",
                "sensors.json"
            ]
        );
        let npy = std::fs::read(dir.path().join("lidar2d.npy")).unwrap();
        assert_eq!(&npy[..6], b"\x93NUMPY");
        let header_len = u16::from_le_bytes([npy[8], npy[9]]) as usize;
        assert_eq!((10 + header_len) % 64, 0);
        let header = std::str::from_utf8(&npy[10..10 + header_len]).unwrap();
        assert!(header.contains("'shape': (1, 720,)"), "{header}");
        assert_eq!(npy.len(), 10 + header_len + 4 * 720);
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("sensors.json")).unwrap(),
        )
        .unwrap();
        // Inside a closed home every level beam hits a wall.
        assert!(json["readings"]["lidar2d"]["returns"].as_u64().unwrap() > 600);
        assert_eq!(json["readings"]["lidar3d"]["shape"][0], 16);
    }

    /// Every sensor of the full rig gets its files: panorama views, scans and state readings.
    #[test]
    fn full_rig_writes_one_file_per_reading() {
        let (scene, at) = demo();
        let dir = tempfile::tempdir().unwrap();
        let files =
            render_rig(&scene, config("full", Backend::Raster), at, 0.0, dir.path()).unwrap();
        for f in [
            "rgb.png",
            "depth.png",
            "semantic.png",
            "instance.png",
            "panorama_0_rgb.png",
            "panorama_11_depth.png",
            "panorama_11_semantic.png",
            "lidar2d.npy",
            "lidar3d.npy",
            "camera.json",
            "sensors.json",
        ] {
            assert!(files.iter().any(|x| x == f), "{f} missing from {files:?}");
            assert!(dir.path().join(f).exists());
        }
        assert!(!files.iter().any(|x| x == "panorama_12_rgb.png"));
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("sensors.json")).unwrap(),
        )
        .unwrap();
        let r = &json["readings"];
        assert_eq!(r["compass"]["heading_rad"], 0.0);
        assert_eq!(r["gps"]["position"], serde_json::json!([0.0, 0.0, 0.0]));
        assert_eq!(r["collision"]["collided"], false);
        let cams: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("camera.json")).unwrap())
                .unwrap();
        assert_eq!(cams["cameras"].as_array().unwrap().len(), 4 + 12);
        // The RGB noise of the config is applied: the image differs from a noiseless render.
        let mut quiet = config("full", Backend::Raster);
        quiet.sensors.retain(|s| s.kind() == "rgb");
        if let SensorSpec::Rgb(c) = &mut quiet.sensors[0] {
            c.noise = vlnverse_sensors::Noise::None;
        }
        let dir2 = tempfile::tempdir().unwrap();
        render_rig(&scene, quiet, at, 0.0, dir2.path()).unwrap();
        let a = std::fs::read(dir.path().join("rgb.png")).unwrap();
        let b = std::fs::read(dir2.path().join("rgb.png")).unwrap();
        assert_ne!(a, b);
    }
}
