//! Embodiment (`AgentConfig`, one TOML file per profile in `configs/agent/`) and simulator
//! settings (`SimConfig`: collision setting, physics step, Tel-Hop search, actuation noise).

use crate::error::{Result, SimError};
use serde::{Deserialize, Serialize};
use std::path::Path;
use vlnverse_env::EnvError;

/// Collision footprint of the agent. The shape stands on the floor (raised by
/// [`AgentConfig::ground_clearance`]) with its axis along +Y.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum AgentShape {
    /// Upright cylinder (the paper's default).
    Cylinder {
        /// Total height (m).
        height: f32,
        /// Radius (m).
        radius: f32,
    },
    /// Upright capsule; `height` includes the two half-spheres.
    Capsule {
        /// Total height (m), at least `2 * radius`.
        height: f32,
        /// Radius (m).
        radius: f32,
    },
    /// Upright box, `width` across (x at yaw 0) and `length` along the heading (z).
    Box {
        /// Total height (m).
        height: f32,
        /// Size across the heading (m).
        width: f32,
        /// Size along the heading (m).
        length: f32,
    },
}

impl AgentShape {
    /// Total height (m).
    pub fn height(&self) -> f32 {
        match *self {
            AgentShape::Cylinder { height, .. }
            | AgentShape::Capsule { height, .. }
            | AgentShape::Box { height, .. } => height,
        }
    }

    /// Radius of the smallest vertical cylinder around the shape (m): what an occupancy map
    /// must be dilated by.
    pub fn bounding_radius(&self) -> f32 {
        match *self {
            AgentShape::Cylinder { radius, .. } | AgentShape::Capsule { radius, .. } => radius,
            AgentShape::Box { width, length, .. } => 0.5 * width.hypot(length),
        }
    }

    /// Whether turning in place can never hit anything (round footprint).
    pub fn is_round(&self) -> bool {
        !matches!(self, AgentShape::Box { .. })
    }

    fn validate(&self) -> Result<()> {
        let h = self.height();
        check_range("shape.height", h, 0.05, 5.0)?;
        match *self {
            AgentShape::Cylinder { radius, .. } => check_range("shape.radius", radius, 0.01, 2.0),
            AgentShape::Capsule { radius, height } => {
                check_range("shape.radius", radius, 0.01, 2.0)?;
                if height < 2.0 * radius {
                    return Err(SimError::invalid(
                        "shape.height",
                        height,
                        format!(
                            "a capsule must be at least 2 * radius = {} high",
                            2.0 * radius
                        ),
                    ));
                }
                Ok(())
            }
            AgentShape::Box { width, length, .. } => {
                check_range("shape.width", width, 0.02, 4.0)?;
                check_range("shape.length", length, 0.02, 4.0)
            }
        }
    }
}

/// Differential-drive limits of a wheeled robot: a velocity command `(v, omega)` is scaled
/// down so that neither wheel exceeds `max_wheel_speed`
/// (`|v| + |omega| * wheel_base / 2 <= max_wheel_speed`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DifferentialDrive {
    /// Distance between the two drive wheels (m).
    pub wheel_base: f32,
    /// Top speed of one wheel's contact point (m/s).
    pub max_wheel_speed: f32,
}

/// Embodiment of the agent: footprint, mass, kinematic limits, discrete action sizes,
/// collision rules and the sensor mount. `Default` is the paper's `vlnverse` profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AgentConfig {
    /// Profile name (informative).
    pub name: String,
    /// Collision footprint.
    pub shape: AgentShape,
    /// Mass in kilograms (continuous control: how hard the agent pushes).
    pub mass: f32,
    /// The collision shape starts this far above the floor, so rugs and door thresholds
    /// lower than this are driven over (same meaning as the occupancy map's
    /// `floor_clearance`).
    pub ground_clearance: f32,
    /// Height of the camera / sensor mount above the floor (m).
    pub sensor_height: f32,
    /// Distance of one `MoveForward` step of the discrete action space (m).
    pub step_size: f32,
    /// Angle of one turn of the discrete action space (degrees).
    pub turn_angle_deg: f32,
    /// Camera pitch change of one `LookUp` / `LookDown` (degrees).
    pub look_angle_deg: f32,
    /// Largest camera pitch, up or down (degrees).
    pub max_pitch_deg: f32,
    /// Whether a blocked discrete move slides along the obstacle (true) or stops at it.
    pub allow_sliding: bool,
    /// A collision is "noticeable" when the commanded and achieved horizontal displacements
    /// differ by more than this (m).
    pub collision_threshold: f32,
    /// Top linear speed (m/s).
    pub max_linear_speed: f32,
    /// Top turning speed (degrees/s).
    pub max_angular_speed_deg: f32,
    /// Linear acceleration limit (m/s^2); the drive force is capped at
    /// `2 * mass * max_linear_accel`.
    pub max_linear_accel: f32,
    /// Angular acceleration limit (degrees/s^2).
    pub max_angular_accel_deg: f32,
    /// Wheel limits of a differential-drive robot (None: no wheel constraint).
    pub differential_drive: Option<DifferentialDrive>,
    /// Highest step the agent climbs onto (or steps down from) while walking (m): a tread,
    /// a kerb, a threshold. Used in scenes with more than one level (`Scene::is_multi_level`),
    /// where the agent follows the ground; single-level scenes keep the planar agent.
    pub max_step_height: f32,
    /// Steepest surface the agent walks up (degrees from horizontal, measured on the
    /// surface's normal): ramps and sloped imported meshes; the flat treads of a flight of
    /// stairs are steps, whatever the flight's pitch. Multi-level scenes only.
    pub max_slope_deg: f32,
}

impl Default for AgentConfig {
    fn default() -> Self {
        AgentConfig {
            name: "vlnverse".into(),
            shape: AgentShape::Cylinder {
                height: 1.5,
                radius: 0.3,
            },
            mass: 40.0,
            ground_clearance: 0.05,
            sensor_height: 1.25,
            step_size: 0.25,
            turn_angle_deg: 15.0,
            look_angle_deg: 30.0,
            max_pitch_deg: 60.0,
            allow_sliding: true,
            collision_threshold: 0.10,
            max_linear_speed: 1.0,
            max_angular_speed_deg: 90.0,
            max_linear_accel: 1.5,
            max_angular_accel_deg: 360.0,
            differential_drive: None,
            max_step_height: DEFAULT_MAX_STEP_HEIGHT,
            max_slope_deg: DEFAULT_MAX_SLOPE_DEG,
        }
    }
}

/// Default [`AgentConfig::max_step_height`] (m): above the generated homes' risers (at most
/// 0.18 m, 0.175 m at the default storey height) and the usual building-code limit of 0.2 m.
pub const DEFAULT_MAX_STEP_HEIGHT: f32 = 0.2;
/// Default [`AgentConfig::max_slope_deg`]: above the generated flights' pitch (about 32
/// degrees), so a flight imported as one sloped mesh is walkable too.
pub const DEFAULT_MAX_SLOPE_DEG: f32 = 35.0;

/// The shipped profiles, embedded from `configs/agent/*.toml`.
pub const PROFILES: &[(&str, &str)] = &[
    ("vlnverse", include_str!("../configs/agent/vlnverse.toml")),
    ("vlnce", include_str!("../configs/agent/vlnce.toml")),
    ("rxr", include_str!("../configs/agent/rxr.toml")),
    ("locobot", include_str!("../configs/agent/locobot.toml")),
];

impl AgentConfig {
    /// One of the shipped profiles by name: `vlnverse`, `vlnce`, `rxr`, `locobot`.
    pub fn profile(name: &str) -> Result<AgentConfig> {
        let (_, text) =
            PROFILES
                .iter()
                .find(|(n, _)| *n == name)
                .ok_or_else(|| SimError::UnknownProfile {
                    name: name.into(),
                    known: PROFILES
                        .iter()
                        .map(|(n, _)| *n)
                        .collect::<Vec<_>>()
                        .join(", "),
                })?;
        Self::from_toml_str(text, Path::new(&format!("profile:{name}")))
    }

    /// Parse and validate TOML text; `origin` names the source in errors.
    pub fn from_toml_str(text: &str, origin: &Path) -> Result<AgentConfig> {
        let cfg: AgentConfig =
            toml::from_str(text).map_err(|e| EnvError::parse(origin, e.to_string()))?;
        cfg.validate().map_err(|e| e.in_file(origin))?;
        Ok(cfg)
    }

    /// Read, parse and validate a TOML file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<AgentConfig> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| EnvError::io(path, e))?;
        Self::from_toml_str(&text, path)
    }

    /// Check every value; the error names the field and the value.
    pub fn validate(&self) -> Result<()> {
        self.shape.validate()?;
        let h = self.shape.height();
        check_range("mass", self.mass, 0.1, 10_000.0)?;
        check_range("ground_clearance", self.ground_clearance, 0.0, 0.5 * h)?;
        check_range("sensor_height", self.sensor_height, 0.0, 5.0)?;
        check_range("step_size", self.step_size, 0.01, 5.0)?;
        check_range("turn_angle_deg", self.turn_angle_deg, 0.1, 180.0)?;
        check_range("look_angle_deg", self.look_angle_deg, 0.1, 90.0)?;
        check_range("max_pitch_deg", self.max_pitch_deg, 0.0, 90.0)?;
        check_range("collision_threshold", self.collision_threshold, 0.0, 1.0)?;
        check_range("max_linear_speed", self.max_linear_speed, 0.01, 20.0)?;
        check_range(
            "max_angular_speed_deg",
            self.max_angular_speed_deg,
            1.0,
            3600.0,
        )?;
        check_range("max_linear_accel", self.max_linear_accel, 0.01, 100.0)?;
        check_range(
            "max_angular_accel_deg",
            self.max_angular_accel_deg,
            1.0,
            36_000.0,
        )?;
        check_range("max_step_height", self.max_step_height, 0.0, 1.0)?;
        check_range("max_slope_deg", self.max_slope_deg, 0.0, 85.0)?;
        if let Some(d) = &self.differential_drive {
            check_range("differential_drive.wheel_base", d.wheel_base, 0.01, 5.0)?;
            check_range(
                "differential_drive.max_wheel_speed",
                d.max_wheel_speed,
                0.01,
                20.0,
            )?;
        }
        Ok(())
    }

    /// Discrete turn angle in radians.
    pub fn turn_angle(&self) -> f32 {
        self.turn_angle_deg.to_radians()
    }

    /// Top turning speed in rad/s.
    pub fn max_angular_speed(&self) -> f32 {
        self.max_angular_speed_deg.to_radians()
    }

    /// Angular acceleration limit in rad/s^2.
    pub fn max_angular_accel(&self) -> f32 {
        self.max_angular_accel_deg.to_radians()
    }
}

/// What a noticeable collision does to the episode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CollisionSetting {
    /// Full physics; the episode ends, failed, at the first noticeable collision.
    #[default]
    Strict,
    /// `MoveForward` and every waypoint teleport to the commanded spot and physics only
    /// resolves the destination (nearest free spot); collisions are counted, never fatal.
    TelHop,
    /// Full physics; collisions are only counted (as in VLN-CE).
    Lenient,
}

/// Seeded Gaussian actuation noise on discrete actions.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ActuationNoise {
    /// Standard deviation of the forward distance (m).
    pub distance_std: f32,
    /// Standard deviation of turn angles (degrees).
    pub angle_std_deg: f32,
}

impl Default for ActuationNoise {
    fn default() -> Self {
        ActuationNoise {
            distance_std: 0.025,
            angle_std_deg: 1.0,
        }
    }
}

/// Settings of one simulator instance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimConfig {
    /// Embodiment.
    pub agent: AgentConfig,
    /// Strict, Tel-Hop or lenient collision handling.
    pub setting: CollisionSetting,
    /// Physics time step for continuous control (s).
    pub physics_dt: f32,
    /// Tel-Hop: how far from the commanded spot a free spot is searched (m).
    pub hop_radius: f32,
    /// Tel-Hop: spacing of the candidate spots of the search (m).
    pub hop_resolution: f32,
    /// Optional actuation noise (None: exact actions).
    pub noise: Option<ActuationNoise>,
    /// Seed of the actuation noise.
    pub seed: u64,
}

impl Default for SimConfig {
    fn default() -> Self {
        SimConfig {
            agent: AgentConfig::default(),
            setting: CollisionSetting::Strict,
            physics_dt: 1.0 / 60.0,
            hop_radius: 1.0,
            hop_resolution: 0.05,
            noise: None,
            seed: 0,
        }
    }
}

impl SimConfig {
    /// Check every value (the agent included).
    pub fn validate(&self) -> Result<()> {
        self.agent.validate()?;
        check_range("physics_dt", self.physics_dt, 1e-4, 0.1)?;
        check_range("hop_radius", self.hop_radius, 0.0, 10.0)?;
        check_range("hop_resolution", self.hop_resolution, 0.005, 1.0)?;
        if let Some(n) = &self.noise {
            check_range("noise.distance_std", n.distance_std, 0.0, 1.0)?;
            check_range("noise.angle_std_deg", n.angle_std_deg, 0.0, 45.0)?;
        }
        Ok(())
    }
}

fn check_range(field: &str, v: f32, lo: f32, hi: f32) -> Result<()> {
    if !v.is_finite() || v < lo || v > hi {
        return Err(SimError::invalid(
            field,
            v,
            format!("must be in [{lo}, {hi}]"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_the_vlnverse_profile() {
        assert_eq!(
            AgentConfig::profile("vlnverse").unwrap(),
            AgentConfig::default()
        );
    }

    #[test]
    fn every_profile_parses_and_validates() {
        for (name, _) in PROFILES {
            let cfg = AgentConfig::profile(name).unwrap();
            assert_eq!(cfg.name, *name);
        }
        let vlnce = AgentConfig::profile("vlnce").unwrap();
        assert_eq!(vlnce.shape.bounding_radius(), 0.1);
        let rxr = AgentConfig::profile("rxr").unwrap();
        assert!(!rxr.allow_sliding);
        assert_eq!(rxr.turn_angle_deg, 30.0);
        assert!(AgentConfig::profile("locobot")
            .unwrap()
            .differential_drive
            .is_some());
    }

    #[test]
    fn unknown_profile_lists_the_known_ones() {
        let e = AgentConfig::profile("nope").unwrap_err().to_string();
        assert!(e.contains("vlnce") && e.contains("nope"), "{e}");
    }

    #[test]
    fn bad_value_error_names_file_field_and_value() {
        let text = "[shape]\nkind = \"cylinder\"\nheight = 1.5\nradius = -0.3\n";
        let e = AgentConfig::from_toml_str(text, Path::new("bad.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bad.toml") && e.contains("shape.radius") && e.contains("-0.3"),
            "{e}"
        );

        let e = AgentConfig::from_toml_str("step_size = nan\n", Path::new("nan.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("nan.toml") && e.contains("step_size") && e.contains("NaN"),
            "{e}"
        );

        // Malformed values are parse errors that quote the field and the value.
        let e = AgentConfig::from_toml_str("step_size = \"long\"\n", Path::new("str.toml"))
            .unwrap_err();
        assert!(matches!(e, SimError::Env(EnvError::Parse { .. })), "{e:?}");
        let e = e.to_string();
        assert!(
            e.contains("str.toml") && e.contains("step_size") && e.contains("long"),
            "{e}"
        );

        let e = AgentConfig::from_toml_str("stepsize = 0.3\n", Path::new("typo.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("typo.toml") && e.contains("stepsize"), "{e}");
    }

    #[test]
    fn every_numeric_agent_field_has_a_range_named_in_its_error() {
        // Each line is appended to the vlnverse profile's text; the error names the file, the
        // field and the value.
        let base = PROFILES[0].1;
        for (line, field, value) in [
            ("mass = 1e9", "mass", "1000000000"),
            ("ground_clearance = -0.1", "ground_clearance", "-0.1"),
            ("sensor_height = nan", "sensor_height", "NaN"),
            ("step_size = 0.0", "step_size", "0"),
            ("step_size = 1e6", "step_size", "1000000"),
            ("turn_angle_deg = 0.0", "turn_angle_deg", "0"),
            ("turn_angle_deg = 720.0", "turn_angle_deg", "720"),
            ("look_angle_deg = inf", "look_angle_deg", "inf"),
            ("max_pitch_deg = 91.0", "max_pitch_deg", "91"),
            ("collision_threshold = -1.0", "collision_threshold", "-1"),
            ("max_linear_speed = 1e6", "max_linear_speed", "1000000"),
            ("max_angular_speed_deg = 0.0", "max_angular_speed_deg", "0"),
            ("max_linear_accel = nan", "max_linear_accel", "NaN"),
            (
                "max_angular_accel_deg = 1e9",
                "max_angular_accel_deg",
                "1000000000",
            ),
            ("max_step_height = -0.2", "max_step_height", "-0.2"),
            ("max_step_height = 1.5", "max_step_height", "1.5"),
            ("max_slope_deg = nan", "max_slope_deg", "NaN"),
            ("max_slope_deg = 90.0", "max_slope_deg", "90"),
        ] {
            // Replace the profile's own line for the field, if any, so the TOML stays valid.
            let key = line.split(' ').next().unwrap();
            let mut text: String = base
                .lines()
                .filter(|l| l.split([' ', '=']).next() != Some(key))
                .map(|l| format!("{l}\n"))
                .collect();
            // Top-level keys go before the first table.
            let at = text.find("\n[").map_or(0, |i| i + 1);
            text.insert_str(at, &format!("{line}\n"));
            let e = AgentConfig::from_toml_str(&text, Path::new("agent.toml"))
                .expect_err(line)
                .to_string();
            assert!(
                e.contains("agent.toml") && e.contains(field) && e.contains(value),
                "{line}: {e}"
            );
        }
        for (shape, field) in [
            (
                "kind = \"cylinder\"\nheight = 1e6\nradius = 0.3",
                "shape.height",
            ),
            (
                "kind = \"cylinder\"\nheight = 1.5\nradius = 0.0",
                "shape.radius",
            ),
            (
                "kind = \"box\"\nheight = 1.0\nwidth = nan\nlength = 0.5",
                "shape.width",
            ),
            (
                "kind = \"box\"\nheight = 1.0\nwidth = 0.5\nlength = 100.0",
                "shape.length",
            ),
        ] {
            let e = AgentConfig::from_toml_str(&format!("[shape]\n{shape}\n"), Path::new("a.toml"))
                .expect_err(shape)
                .to_string();
            assert!(e.contains("a.toml") && e.contains(field), "{shape}: {e}");
        }
        let dd = "[differential_drive]\nwheel_base = 0.0\nmax_wheel_speed = 1.0\n";
        let e = AgentConfig::from_toml_str(dd, Path::new("a.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("differential_drive.wheel_base"), "{e}");
    }

    #[test]
    fn missing_file_names_the_path() {
        let e = AgentConfig::from_toml_file("/nonexistent/agent.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("/nonexistent/agent.toml"), "{e}");
    }

    #[test]
    fn capsule_shorter_than_its_diameter_is_rejected() {
        let cfg = AgentConfig {
            shape: AgentShape::Capsule {
                height: 0.4,
                radius: 0.3,
            },
            ..Default::default()
        };
        let e = cfg.validate().unwrap_err().to_string();
        assert!(e.contains("shape.height"), "{e}");
    }

    #[test]
    fn sim_config_checks_its_fields() {
        let cfg = SimConfig {
            physics_dt: 0.0,
            ..Default::default()
        };
        assert!(cfg
            .validate()
            .unwrap_err()
            .to_string()
            .contains("physics_dt"));
        assert!(SimConfig::default().validate().is_ok());
    }
}
