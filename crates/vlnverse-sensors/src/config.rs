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
        let bad = |f: &str, v: f32| {
            SensorError::invalid(format!("{field}.{f}"), v, "must be finite and >= 0")
        };
        let ok = |v: f32| v.is_finite() && v >= 0.0;
        match *self {
            Noise::None => Ok(()),
            Noise::Gaussian { stddev } if !ok(stddev) => Err(bad("stddev", stddev)),
            Noise::Redwood { a, .. } if !ok(a) => Err(bad("a", a)),
            Noise::Redwood { b, .. } if !ok(b) => Err(bad("b", b)),
            Noise::Redwood { quantum, .. } if !ok(quantum) => Err(bad("quantum", quantum)),
            _ => Ok(()),
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
            if !(1..=8192).contains(&v) {
                return Err(SensorError::invalid(
                    format!("{f}.{k}"),
                    v,
                    "1..=8192 pixels",
                ));
            }
        }
        if !(self.hfov_deg > 0.0 && self.hfov_deg < 180.0) {
            return Err(SensorError::invalid(
                format!("{f}.hfov_deg"),
                self.hfov_deg,
                "in (0, 180)",
            ));
        }
        if !(self.near > 0.0 && self.near.is_finite()) {
            return Err(SensorError::invalid(format!("{f}.near"), self.near, "> 0"));
        }
        if !(self.far > self.near && self.far.is_finite()) {
            return Err(SensorError::invalid(
                format!("{f}.far"),
                self.far,
                "finite and > near",
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
        if !(self.range_min >= 0.0 && self.range_max > self.range_min && self.range_max.is_finite())
        {
            return Err(SensorError::invalid(
                format!("{f}.range_max"),
                self.range_max,
                "finite and > range_min >= 0",
            ));
        }
        if !(self.range_stddev >= 0.0 && self.range_stddev.is_finite()) {
            return Err(SensorError::invalid(
                format!("{f}.range_stddev"),
                self.range_stddev,
                ">= 0",
            ));
        }
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
                if !p.step_deg.is_finite() {
                    return Err(SensorError::invalid(
                        format!("{field}.step_deg"),
                        p.step_deg,
                        "finite",
                    ));
                }
                p.camera.validate(&format!("{field}.camera"))
            }
            SensorSpec::Pose(s)
            | SensorSpec::Compass(s)
            | SensorSpec::Gps(s)
            | SensorSpec::Collision(s) => validate_rate(&s.rate, field),
        }
    }
}

fn validate_mount(m: &Mount, f: &str) -> Result<()> {
    if !m.offset.iter().all(|v| v.is_finite()) {
        return Err(SensorError::invalid(
            format!("{f}.mount.offset"),
            format!("{:?}", m.offset),
            "finite",
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
        if !(hz > 0.0 && hz.is_finite()) {
            return Err(SensorError::invalid(
                format!("{f}.rate.hz"),
                hz,
                "finite and > 0",
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
