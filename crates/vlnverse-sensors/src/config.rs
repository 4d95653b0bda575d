//! The sensor rig config (`configs/sensors/*.toml`): which sensors, where they sit, how often they
//! sample, their noise, and the rendering backend. Defaults follow the paper: RGB 224x224 and
//! depth 256x256, both with a 90 deg horizontal field of view, depth clipped at 10 m.

use crate::camera::{Camera, Mount};
use crate::error::{Result, SensorError};
use serde::{Deserialize, Serialize};
use std::path::Path;
use vlnverse_env::EnvError;
use vlnverse_env::Pose;

/// Which renderer makes the images.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Backend {
    /// wgpu on a hardware GPU when one exists, else the CPU rasteriser ([`Backend::Raster`]),
    /// which beats wgpu on a software driver (lavapipe) several times over.
    #[default]
    Auto,
    /// The wgpu rasteriser (a hardware GPU or lavapipe); fails when no adapter exists.
    Wgpu,
    /// The CPU ray caster.
    Raycast,
    /// The CPU software rasteriser ([`crate::RasterRenderer`]); needs no graphics stack.
    Raster,
}

impl std::str::FromStr for Backend {
    type Err = SensorError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "auto" => Ok(Backend::Auto),
            "wgpu" => Ok(Backend::Wgpu),
            "raycast" => Ok(Backend::Raycast),
            "raster" => Ok(Backend::Raster),
            _ => Err(SensorError::invalid(
                "backend",
                s,
                "one of auto, wgpu, raycast, raster",
            )),
        }
    }
}

/// How often a sensor samples: every `every_steps` simulator steps, or at `hz` of simulated
/// time when set (then `every_steps` is ignored).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Rate {
    /// Sample on steps that are multiples of this (1 = every step).
    pub every_steps: u32,
    /// Samples per second of simulated time.
    pub hz: Option<f32>,
}

impl Default for Rate {
    fn default() -> Self {
        Rate {
            every_steps: 1,
            hz: None,
        }
    }
}

/// A seeded noise model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum Noise {
    /// Exact values.
    #[default]
    None,
    /// Additive zero-mean Gaussian noise (RGB: in 0..255 units; depth: metres).
    Gaussian {
        /// Standard deviation.
        stddev: f32,
    },
    /// Distance-dependent depth noise of structured-light sensors (Kinect / Redwood-like):
    /// `sigma(d) = a + b * (d - c)^2` metres, and depth quantised to `quantum * d^2` steps
    /// (disparity quantisation). Depth only.
    Redwood {
        /// Constant term of sigma (m).
        a: f32,
        /// Quadratic term of sigma (1/m).
        b: f32,
        /// Distance where sigma is smallest (m).
        c: f32,
        /// Quantisation step at 1 m (m); 0 disables.
        quantum: f32,
    },
}

impl Noise {
    /// The Kinect v1 fit (Nguyen et al. 2012) with disparity quantisation.
    pub const KINECT: Noise = Noise::Redwood {
        a: 0.0012,
        b: 0.0019,
        c: 0.4,
        quantum: 0.0028,
    };

    fn validate(&self, field: &str) -> Result<()> {
        match *self {
            Noise::None => Ok(()),
            Noise::Gaussian { stddev } => in_range(field, "stddev", stddev, 0.0, 255.0),
            Noise::Redwood { a, b, c, quantum } => {
                in_range(field, "a", a, 0.0, 1.0)?;
                in_range(field, "b", b, 0.0, 1.0)?;
                in_range(field, "c", c, 0.0, 20.0)?;
                in_range(field, "quantum", quantum, 0.0, 0.1)
            }
        }
    }
}

/// A pinhole camera sensor (RGB, depth, semantic or instance).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraSpec {
    /// Name in observations (defaults to the type, e.g. `rgb`).
    pub name: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Horizontal field of view in degrees (vertical follows from the aspect ratio).
    pub hfov_deg: f32,
    /// Placement on the agent.
    pub mount: Mount,
    /// Near clipping distance (m).
    pub near: f32,
    /// Far clipping distance (m); depth is clipped here.
    pub far: f32,
    /// Sampling rate.
    pub rate: Rate,
    /// Noise (RGB: Gaussian; depth: Gaussian or Redwood; ignored for ids).
    pub noise: Noise,
    /// Depth only: divide by `far` so values lie in `[0, 1]` (as VLN-CE).
    pub normalize: bool,
}

impl Default for CameraSpec {
    /// The paper's RGB camera: 224x224, HFOV 90.
    fn default() -> Self {
        CameraSpec {
            name: String::new(),
            width: 224,
            height: 224,
            hfov_deg: 90.0,
            mount: Mount::default(),
            near: 0.05,
            far: 10.0,
            rate: Rate::default(),
            noise: Noise::None,
            normalize: false,
        }
    }
}

impl CameraSpec {
    /// The paper's depth camera: 256x256, HFOV 90, clipped at 10 m and normalised to
    /// `[0, 1]` (the paper's appendix and VLN-CE).
    pub fn depth() -> Self {
        CameraSpec {
            width: 256,
            height: 256,
            normalize: true,
            ..CameraSpec::default()
        }
    }

    /// The camera for an agent whose base is at `base`.
    pub fn camera(&self, base: &Pose) -> Camera {
        Camera::new(
            &self.mount.world_pose(base),
            self.width,
            self.height,
            self.hfov_deg.to_radians(),
            self.near,
            self.far,
        )
    }

    fn validate(&self, f: &str) -> Result<()> {
        for (k, v) in [("width", self.width), ("height", self.height)] {
            if !(1..=MAX_SIDE).contains(&v) {
                return Err(SensorError::invalid(
                    format!("{f}.{k}"),
                    v,
                    format!("1..={MAX_SIDE} pixels"),
                ));
            }
        }
        let pixels = u64::from(self.width) * u64::from(self.height);
        if pixels > MAX_PIXELS {
            return Err(SensorError::invalid(
                format!("{f}.width"),
                format!(
                    "{} (x height {} = {pixels} pixels)",
                    self.width, self.height
                ),
                format!("at most {MAX_PIXELS} pixels an image (4096 x 4096)"),
            ));
        }
        if !(self.hfov_deg > 0.0 && self.hfov_deg < 180.0) {
            return Err(SensorError::invalid(
                format!("{f}.hfov_deg"),
                self.hfov_deg,
                "in (0, 180)",
            ));
        }
        in_range(f, "near", self.near, 0.001, 10.0)?;
        in_range(f, "far", self.far, 0.001, MAX_RANGE)?;
        if self.far <= self.near {
            return Err(SensorError::invalid(
                format!("{f}.far"),
                self.far,
                format!("must be > near ({})", self.near),
            ));
        }
        validate_mount(&self.mount, f)?;
        validate_rate(&self.rate, f)?;
        self.noise.validate(&format!("{f}.noise"))
    }
}

/// A LiDAR: `channels` rings of `beams` rays; one channel at elevation 0 is a 2-D scanner.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LidarSpec {
    /// Name in observations (defaults to `lidar`).
    pub name: String,
    /// Rays per ring.
    pub beams: u32,
    /// Number of rings (1 = 2-D).
    pub channels: u32,
    /// Horizontal field of view in degrees (360 = all around).
    pub hfov_deg: f32,
    /// Lowest and highest ring elevation in degrees (ignored with one channel, which is level).
    pub elevation_deg: [f32; 2],
    /// Minimum range (m); closer returns are dropped.
    pub range_min: f32,
    /// Maximum range (m).
    pub range_max: f32,
    /// Placement on the agent.
    pub mount: Mount,
    /// Sampling rate.
    pub rate: Rate,
    /// Gaussian range noise standard deviation (m).
    pub range_stddev: f32,
    /// Probability that a return is dropped (reported as NaN).
    pub dropout: f32,
}

impl Default for LidarSpec {
    /// A 2-D scanner: 360 beams over 360 deg, 0.1..20 m, 0.3 m above the floor.
    fn default() -> Self {
        LidarSpec {
            name: String::new(),
            beams: 360,
            channels: 1,
            hfov_deg: 360.0,
            elevation_deg: [-15.0, 15.0],
            range_min: 0.1,
            range_max: 20.0,
            mount: Mount {
                offset: [0.0, 0.3, 0.0],
                pitch_deg: 0.0,
            },
            rate: Rate::default(),
            range_stddev: 0.0,
            dropout: 0.0,
        }
    }
}

impl LidarSpec {
    fn validate(&self, f: &str) -> Result<()> {
        if self.beams == 0 || self.beams > 1 << 16 {
            return Err(SensorError::invalid(
                format!("{f}.beams"),
                self.beams,
                "1..=65536",
            ));
        }
        if self.channels == 0 || self.channels > 1024 {
            return Err(SensorError::invalid(
                format!("{f}.channels"),
                self.channels,
                "1..=1024",
            ));
        }
        let rays = u64::from(self.beams) * u64::from(self.channels);
        if rays > MAX_RAYS {
            return Err(SensorError::invalid(
                format!("{f}.beams"),
                format!(
                    "{} (x channels {} = {rays} rays)",
                    self.beams, self.channels
                ),
                format!("at most {MAX_RAYS} rays a scan"),
            ));
        }
        if !(self.hfov_deg > 0.0 && self.hfov_deg <= 360.0) {
            return Err(SensorError::invalid(
                format!("{f}.hfov_deg"),
                self.hfov_deg,
                "in (0, 360]",
            ));
        }
        let [lo, hi] = self.elevation_deg;
        if !(-90.0..=90.0).contains(&lo) || !(-90.0..=90.0).contains(&hi) || lo > hi {
            return Err(SensorError::invalid(
                format!("{f}.elevation_deg"),
                format!("[{lo}, {hi}]"),
                "-90 <= low <= high <= 90",
            ));
        }
        in_range(f, "range_min", self.range_min, 0.0, MAX_RANGE)?;
        in_range(f, "range_max", self.range_max, 0.001, MAX_RANGE)?;
        if self.range_max <= self.range_min {
            return Err(SensorError::invalid(
                format!("{f}.range_max"),
                self.range_max,
                format!("must be > range_min ({})", self.range_min),
            ));
        }
        in_range(f, "range_stddev", self.range_stddev, 0.0, 10.0)?;
        if !(0.0..=1.0).contains(&self.dropout) {
            return Err(SensorError::invalid(
                format!("{f}.dropout"),
                self.dropout,
                "in [0, 1]",
            ));
        }
        validate_mount(&self.mount, f)?;
        validate_rate(&self.rate, f)
    }
}

/// A panorama: `views` cameras turned by `step_deg` each (counter-clockwise seen from above, as
/// yaw), rendered in one batch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PanoramaSpec {
    /// The camera of view 0 (name defaults to `panorama`).
    pub camera: CameraSpec,
    /// Number of views.
    pub views: u32,
    /// Yaw step between views in degrees.
    pub step_deg: f32,
    /// Render colour.
    pub rgb: bool,
    /// Render depth.
    pub depth: bool,
    /// Render semantic ids.
    pub semantic: bool,
}

impl Default for PanoramaSpec {
    /// 12 RGB-D views at 30 deg steps.
    fn default() -> Self {
        PanoramaSpec {
            camera: CameraSpec::default(),
            views: 12,
            step_deg: 30.0,
            rgb: true,
            depth: true,
            semantic: false,
        }
    }
}

/// A sensor without geometry (pose, compass, GPS, collision).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StateSpec {
    /// Name in observations (defaults to the type).
    pub name: String,
    /// Sampling rate.
    pub rate: Rate,
}

/// One sensor of the rig.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum SensorSpec {
    /// Lit colour image.
    Rgb(CameraSpec),
    /// Depth image (metres along the optical axis).
    Depth(CameraSpec),
    /// Class id image.
    Semantic(CameraSpec),
    /// Object id image.
    Instance(CameraSpec),
    /// 2-D or 3-D LiDAR.
    Lidar(LidarSpec),
    /// Several camera views around the agent.
    Panorama(PanoramaSpec),
    /// World pose of the agent base.
    Pose(StateSpec),
    /// Heading relative to the episode start (radians, counter-clockwise).
    Compass(StateSpec),
    /// Position relative to the episode start, in the start frame.
    Gps(StateSpec),
    /// Collision report from the simulator.
    Collision(StateSpec),
}

impl SensorSpec {
    /// The type as written in TOML (`rgb`, `depth`, ...).
    pub fn kind(&self) -> &'static str {
        match self {
            SensorSpec::Rgb(_) => "rgb",
            SensorSpec::Depth(_) => "depth",
            SensorSpec::Semantic(_) => "semantic",
            SensorSpec::Instance(_) => "instance",
            SensorSpec::Lidar(_) => "lidar",
            SensorSpec::Panorama(_) => "panorama",
            SensorSpec::Pose(_) => "pose",
            SensorSpec::Compass(_) => "compass",
            SensorSpec::Gps(_) => "gps",
            SensorSpec::Collision(_) => "collision",
        }
    }

    /// The name in observations: the configured one, or the type when empty.
    pub fn name(&self) -> &str {
        let n = match self {
            SensorSpec::Rgb(c)
            | SensorSpec::Depth(c)
            | SensorSpec::Semantic(c)
            | SensorSpec::Instance(c) => &c.name,
            SensorSpec::Lidar(l) => &l.name,
            SensorSpec::Panorama(p) => &p.camera.name,
            SensorSpec::Pose(s)
            | SensorSpec::Compass(s)
            | SensorSpec::Gps(s)
            | SensorSpec::Collision(s) => &s.name,
        };
        if n.is_empty() {
            self.kind()
        } else {
            n
        }
    }

    /// The sampling rate.
    pub fn rate(&self) -> Rate {
        match self {
            SensorSpec::Rgb(c)
            | SensorSpec::Depth(c)
            | SensorSpec::Semantic(c)
            | SensorSpec::Instance(c) => c.rate,
            SensorSpec::Lidar(l) => l.rate,
            SensorSpec::Panorama(p) => p.camera.rate,
            SensorSpec::Pose(s)
            | SensorSpec::Compass(s)
            | SensorSpec::Gps(s)
            | SensorSpec::Collision(s) => s.rate,
        }
    }

    /// Check ranges; `field` prefixes error field names (e.g. `sensors[2]`).
    pub fn validate(&self, field: &str) -> Result<()> {
        match self {
            SensorSpec::Rgb(c)
            | SensorSpec::Depth(c)
            | SensorSpec::Semantic(c)
            | SensorSpec::Instance(c) => c.validate(field),
            SensorSpec::Lidar(l) => l.validate(field),
            SensorSpec::Panorama(p) => {
                if p.views == 0 || p.views > 360 {
                    return Err(SensorError::invalid(
                        format!("{field}.views"),
                        p.views,
                        "1..=360",
                    ));
                }
                in_range(field, "step_deg", p.step_deg, -360.0, 360.0)?;
                p.camera.validate(&format!("{field}.camera"))?;
                let pixels =
                    u64::from(p.views) * u64::from(p.camera.width) * u64::from(p.camera.height);
                if pixels > MAX_PANORAMA_PIXELS {
                    return Err(SensorError::invalid(
                        format!("{field}.views"),
                        format!(
                            "{} (x {} x {} = {pixels} pixels)",
                            p.views, p.camera.width, p.camera.height
                        ),
                        format!("at most {MAX_PANORAMA_PIXELS} pixels over all views"),
                    ));
                }
                Ok(())
            }
            SensorSpec::Pose(s)
            | SensorSpec::Compass(s)
            | SensorSpec::Gps(s)
            | SensorSpec::Collision(s) => validate_rate(&s.rate, field),
        }
    }
}

/// Longest side of a camera image (pixels).
pub const MAX_SIDE: u32 = 8192;
/// Most pixels of one camera image (4096 x 4096).
pub const MAX_PIXELS: u64 = 4096 * 4096;
/// Most pixels of one panorama, all views together.
pub const MAX_PANORAMA_PIXELS: u64 = 1 << 26;
/// Most rays of one LiDAR scan (beams x channels).
pub const MAX_RAYS: u64 = 1 << 20;
/// Farthest clipping distance or LiDAR range (m).
pub const MAX_RANGE: f32 = 1000.0;

/// `prefix.name` must be a finite number in `[lo, hi]` (NaN and infinities are refused).
fn in_range(prefix: &str, name: &str, v: f32, lo: f32, hi: f32) -> Result<()> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        return Ok(());
    }
    Err(SensorError::invalid(
        format!("{prefix}.{name}"),
        v,
        format!("must be in [{lo}, {hi}]"),
    ))
}

fn validate_mount(m: &Mount, f: &str) -> Result<()> {
    if !m.offset.iter().all(|v| v.is_finite() && v.abs() <= 10.0) {
        return Err(SensorError::invalid(
            format!("{f}.mount.offset"),
            format!("{:?}", m.offset),
            "each coordinate must be in [-10, 10] m",
        ));
    }
    if !(-90.0..=90.0).contains(&m.pitch_deg) {
        return Err(SensorError::invalid(
            format!("{f}.mount.pitch_deg"),
            m.pitch_deg,
            "in [-90, 90]",
        ));
    }
    Ok(())
}

fn validate_rate(r: &Rate, f: &str) -> Result<()> {
    if r.every_steps == 0 {
        return Err(SensorError::invalid(
            format!("{f}.rate.every_steps"),
            0,
            ">= 1",
        ));
    }
    if let Some(hz) = r.hz {
        if !(hz > 0.0 && hz <= 1000.0) {
            return Err(SensorError::invalid(
                format!("{f}.rate.hz"),
                hz,
                "must be in (0, 1000]",
            ));
        }
    }
    Ok(())
}

/// The whole rig: backend, noise seed and sensors.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RigConfig {
    /// Rendering backend.
    pub backend: Backend,
    /// Seed of every noise model.
    pub seed: u64,
    /// The sensors, in observation order.
    pub sensors: Vec<SensorSpec>,
}

impl Default for RigConfig {
    /// The paper's rig: RGB 224x224 and depth 256x256, HFOV 90, depth clipped at 10 m.
    fn default() -> Self {
        RigConfig {
            backend: Backend::Auto,
            seed: 0,
            sensors: vec![
                SensorSpec::Rgb(CameraSpec::default()),
                SensorSpec::Depth(CameraSpec::depth()),
            ],
        }
    }
}

/// The rig configs shipped with the crate, by name: `configs/sensors/NAME.toml` of the crate
/// (the repository's `configs/sensors/` links there), embedded so they load anywhere.
pub const SHIPPED_RIGS: [(&str, &str); 4] = [
    ("default", include_str!("../configs/sensors/default.toml")),
    ("full", include_str!("../configs/sensors/full.toml")),
    ("lidar", include_str!("../configs/sensors/lidar.toml")),
    ("vlnce", include_str!("../configs/sensors/vlnce.toml")),
];

impl RigConfig {
    /// A shipped rig config by name (see [`SHIPPED_RIGS`]): `default` (the paper's RGB-D rig),
    /// `full` (every sensor type), `lidar`, `vlnce`. Errors list the names.
    pub fn shipped(name: &str) -> Result<Self> {
        let Some((_, text)) = SHIPPED_RIGS.iter().find(|(n, _)| *n == name) else {
            let names: Vec<&str> = SHIPPED_RIGS.iter().map(|(n, _)| *n).collect();
            return Err(SensorError::invalid(
                "rig",
                name,
                format!("not a shipped rig (one of {})", names.join(", ")),
            ));
        };
        let file = format!("configs/sensors/{name}.toml");
        let c: RigConfig =
            toml::from_str(text).map_err(|e| EnvError::parse(&file, e.to_string()))?;
        c.validate().map_err(|e| e.in_file(&file))?;
        Ok(c)
    }

    /// Parse TOML and validate.
    pub fn from_toml_str(text: &str) -> Result<Self> {
        let c: RigConfig =
            toml::from_str(text).map_err(|e| EnvError::parse("<string>", e.to_string()))?;
        c.validate()?;
        Ok(c)
    }

    /// Read, parse and validate a TOML file.
    pub fn load(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| EnvError::io(path, source))?;
        let c: RigConfig =
            toml::from_str(&text).map_err(|e| EnvError::parse(path, e.to_string()))?;
        c.validate().map_err(|e| e.in_file(path))?;
        Ok(c)
    }

    /// Check every sensor and that names are unique plain names (they become file names).
    pub fn validate(&self) -> Result<()> {
        let mut names = std::collections::BTreeSet::new();
        for (i, s) in self.sensors.iter().enumerate() {
            let f = format!("sensors[{i}]");
            s.validate(&f)?;
            let plain = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
            if !s.name().chars().all(plain) || s.name().len() > 64 {
                return Err(SensorError::invalid(
                    format!("{f}.name"),
                    format!("{:?}", s.name()),
                    "letters, digits, `_` and `-` only, at most 64 (it names files)",
                ));
            }
            if !names.insert(s.name()) {
                return Err(SensorError::invalid(
                    format!("{f}.name"),
                    s.name(),
                    "names must be unique (set `name` when two sensors share a type)",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sensor_names_that_would_leave_the_output_folder_are_refused() {
        for bad in ["../x", "/tmp/x", "a/b", "rgb.png"] {
            let text = format!(
                "[[sensors]]\ntype = \"rgb\"\nname = {bad:?}\nwidth = 8\nheight = 8\nhfov_deg = 90.0\n"
            );
            let c: RigConfig = toml::from_str(&text).unwrap();
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains("sensors[0].name") && e.contains(bad), "{e}");
        }
    }

    #[test]
    fn default_is_the_papers_rig_and_round_trips() {
        let c = RigConfig::default();
        let text = toml::to_string(&c).unwrap();
        let back = RigConfig::from_toml_str(&text).unwrap();
        assert_eq!(c, back);
        match &c.sensors[1] {
            SensorSpec::Depth(d) => assert_eq!((d.width, d.height, d.far), (256, 256, 10.0)),
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn shipped_rigs_load_and_unknown_names_are_listed() {
        for (name, _) in SHIPPED_RIGS {
            let c = RigConfig::shipped(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!c.sensors.is_empty(), "{name}");
        }
        assert_eq!(
            RigConfig::shipped("default").unwrap().sensors,
            RigConfig::default().sensors
        );
        let e = RigConfig::shipped("nope").unwrap_err().to_string();
        assert!(e.contains("nope") && e.contains("full"), "{e}");
    }

    #[test]
    fn every_numeric_field_out_of_range_is_refused_by_name_before_any_image_exists() {
        // (sensor table body, field the error names, value it quotes)
        let cases = [
            ("type = \"rgb\"\nwidth = 1000000", "sensors[0].width", "1000000"),
            ("type = \"rgb\"\nheight = 0", "sensors[0].height", "0"),
            ("type = \"rgb\"\nwidth = 8192\nheight = 8192", "sensors[0].width", "8192"),
            ("type = \"rgb\"\nhfov_deg = 0.0", "sensors[0].hfov_deg", "0"),
            ("type = \"rgb\"\nhfov_deg = nan", "sensors[0].hfov_deg", "NaN"),
            ("type = \"depth\"\nnear = 0.0", "sensors[0].near", "0"),
            ("type = \"depth\"\nfar = inf", "sensors[0].far", "inf"),
            ("type = \"depth\"\nfar = 1e9", "sensors[0].far", "1000000000"),
            ("type = \"depth\"\nnear = 5.0\nfar = 2.0", "sensors[0].far", "2"),
            (
                "type = \"rgb\"\nnoise = { model = \"gaussian\", stddev = 1e6 }",
                "sensors[0].noise.stddev",
                "1000000",
            ),
            (
                "type = \"depth\"\nnoise = { model = \"redwood\", a = 0.001, b = 0.002, c = nan, quantum = 0.003 }",
                "sensors[0].noise.c",
                "NaN",
            ),
            ("type = \"rgb\"\nmount = { offset = [0.0, 1e6, 0.0] }", "sensors[0].mount.offset", "1000000"),
            ("type = \"rgb\"\nmount = { pitch_deg = nan }", "sensors[0].mount.pitch_deg", "NaN"),
            ("type = \"rgb\"\nrate = { hz = 1e9 }", "sensors[0].rate.hz", "1000000000"),
            ("type = \"rgb\"\nrate = { every_steps = 0 }", "sensors[0].rate.every_steps", "0"),
            ("type = \"lidar\"\nbeams = 0", "sensors[0].beams", "0"),
            ("type = \"lidar\"\nbeams = 65536\nchannels = 1024", "sensors[0].beams", "65536"),
            ("type = \"lidar\"\nrange_min = nan", "sensors[0].range_min", "NaN"),
            ("type = \"lidar\"\nrange_max = 1e7", "sensors[0].range_max", "10000000"),
            ("type = \"lidar\"\nrange_stddev = -1.0", "sensors[0].range_stddev", "-1"),
            ("type = \"lidar\"\ndropout = nan", "sensors[0].dropout", "NaN"),
            ("type = \"lidar\"\nelevation_deg = [-100.0, 0.0]", "sensors[0].elevation_deg", "-100"),
            ("type = \"panorama\"\nviews = 0", "sensors[0].views", "0"),
            ("type = \"panorama\"\nstep_deg = 1e30", "sensors[0].step_deg", "1000000000000000000000000000000"),
            (
                "type = \"panorama\"\nviews = 360\ncamera = { width = 1024, height = 1024 }",
                "sensors[0].views",
                "360",
            ),
            ("type = \"panorama\"\ncamera = { width = 0 }", "sensors[0].camera.width", "0"),
        ];
        let dir = std::env::temp_dir().join(format!("vlnverse-rig-ranges-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("rig.toml");
        for (body, field, value) in cases {
            std::fs::write(&file, format!("[[sensors]]\n{body}\n")).unwrap();
            let e = RigConfig::load(&file).expect_err(body).to_string();
            assert!(
                e.contains("rig.toml") && e.contains(field) && e.contains(value),
                "{body}: {e}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn errors_name_the_field_and_value() {
        let e = RigConfig::from_toml_str("[[sensors]]\ntype = \"rgb\"\nhfov_deg = 200.0\n")
            .unwrap_err();
        let s = e.to_string();
        assert!(
            s.contains("sensors[0].hfov_deg") && s.contains("200"),
            "{s}"
        );
        let e =
            RigConfig::from_toml_str("[[sensors]]\ntype = \"rgb\"\n[[sensors]]\ntype = \"rgb\"\n")
                .unwrap_err();
        assert!(e.to_string().contains("sensors[1].name"), "{e}");
        let e = RigConfig::from_toml_str("[[sensors]]\ntype = \"sonar\"\n").unwrap_err();
        assert!(e.to_string().contains("sonar"), "{e}");
    }
}
