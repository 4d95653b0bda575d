//! The sensor rig: the configured sensors on an agent, sampled at their rates, rendered in one
//! batch per step, with seeded noise.

use crate::camera::Camera;
use crate::config::{RigConfig, SensorSpec};
use crate::error::{Result, SensorError};
use crate::frame::{Channels, Frame, View};
use crate::lidar::{self, LidarScan};
use crate::noise;
use crate::raycast::SceneRaycaster;
use crate::renderer::{create_renderer, Renderer};
use crate::scene_mesh::SceneMesh;
use glam::Vec3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::sync::Arc;
use vlnverse_env::{Pose, Scene};

/// What the simulator reports about collisions in the last step (the collision sensor's input).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CollisionInfo {
    /// Whether the agent touched an obstacle during the step.
    pub collided: bool,
    /// How far obstacles displaced the agent from its commanded position (m).
    pub displacement: f32,
    /// Collisions since the episode start.
    pub count: u32,
}

/// The agent state the rig observes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AgentState {
    /// The agent base: position on the floor and orientation (yaw).
    pub base: Pose,
    /// Simulator step index (0 at reset).
    pub step: u64,
    /// Simulated time in seconds.
    pub time_s: f64,
    /// Collision report of the last step.
    pub collision: CollisionInfo,
}

impl AgentState {
    /// State at step 0 with no collision.
    pub fn at(position: Vec3, yaw: f32) -> Self {
        AgentState {
            base: Pose::from_yaw(position, yaw),
            step: 0,
            time_s: 0.0,
            collision: CollisionInfo::default(),
        }
    }
}

/// One sensor reading.
#[derive(Clone, Debug, PartialEq)]
pub enum Observation {
    /// Colour (`frame.rgb`).
    Rgb(Frame),
    /// Depth (`frame.depth`, metres or normalised to `[0, 1]` when configured).
    Depth(Frame),
    /// Class ids (`frame.semantic`).
    Semantic(Frame),
    /// Object ids (`frame.instance`).
    Instance(Frame),
    /// Views in yaw order.
    Panorama(Vec<Frame>),
    /// A LiDAR scan.
    Lidar(LidarScan),
    /// World pose of the agent base.
    Pose(Pose),
    /// Heading relative to the episode start, radians in (-pi, pi], counter-clockwise.
    Compass(f32),
    /// Position relative to the start, in the start frame (x right, y up, z back).
    Gps([f32; 3]),
    /// The simulator's collision report.
    Collision(CollisionInfo),
}

/// Readings of the sensors due at a step, by sensor name.
pub type Observations = BTreeMap<String, Observation>;

/// Sensors attached to an agent.
pub struct SensorRig {
    config: RigConfig,
    renderer: Box<dyn Renderer>,
    raycaster: Option<Arc<SceneRaycaster>>,
    mesh: Option<Arc<SceneMesh>>,
    scene_id: Option<String>,
    start: Pose,
    last_sample: BTreeMap<String, f64>,
}

impl SensorRig {
    /// A rig from a validated config; picks the renderer backend (see [`create_renderer`]).
    pub fn new(config: RigConfig) -> Result<Self> {
        config.validate()?;
        let renderer = create_renderer(config.backend)?;
        Ok(SensorRig::with_renderer(config, renderer))
    }

    /// A rig drawing with a given renderer (e.g. a user's own backend).
    pub fn with_renderer(config: RigConfig, renderer: Box<dyn Renderer>) -> Self {
        SensorRig {
            config,
            renderer,
            raycaster: None,
            mesh: None,
            scene_id: None,
            start: Pose::IDENTITY,
            last_sample: BTreeMap::new(),
        }
    }

    /// The config (with attached/detached sensors applied).
    pub fn config(&self) -> &RigConfig {
        &self.config
    }

    /// Name of the renderer backend in use.
    pub fn backend_name(&self) -> String {
        self.renderer.name()
    }

    /// Load a scene into the renderer (and the ray caster, when a LiDAR needs it).
    pub fn set_scene(&mut self, scene: &Scene) -> Result<()> {
        self.set_mesh(Arc::new(SceneMesh::new(scene)?))
    }

    /// [`SensorRig::set_scene`] with the scene already prepared as a mesh (shared by
    /// environments that show the same home).
    pub fn set_mesh(&mut self, mesh: Arc<SceneMesh>) -> Result<()> {
        self.scene_id = None;
        self.renderer.set_scene(mesh.clone())?;
        self.raycaster = None;
        let id = mesh.scene_id.clone();
        self.mesh = Some(mesh);
        self.ensure_raycaster()?;
        self.scene_id = Some(id);
        Ok(())
    }

    /// What prepares a scene for this rig's renderer ahead of time, from any thread
    /// ([`Renderer::scene_preparer`]).
    pub fn scene_preparer(&self) -> Option<fn(Arc<SceneMesh>)> {
        self.renderer.scene_preparer()
    }

    /// Id of the scene loaded by the last successful [`SensorRig::set_scene`] (callers skip
    /// reloading the scene it already shows).
    pub fn scene_id(&self) -> Option<&str> {
        self.scene_id.as_deref()
    }

    fn ensure_raycaster(&mut self) -> Result<()> {
        let needs = self
            .config
            .sensors
            .iter()
            .any(|s| matches!(s, SensorSpec::Lidar(_)));
        if needs && self.raycaster.is_none() {
            if let Some(mesh) = &self.mesh {
                self.raycaster = Some(Arc::new(SceneRaycaster::new(mesh.clone())?));
            }
        }
        Ok(())
    }

    /// Start an episode: GPS and compass are relative to `start`; rate clocks restart.
    pub fn reset(&mut self, start: Pose) {
        self.start = start;
        self.last_sample.clear();
    }

    /// Attach a sensor (its name must be new).
    pub fn attach(&mut self, spec: SensorSpec) -> Result<()> {
        let field = format!("sensors[{}]", self.config.sensors.len());
        spec.validate(&field)?;
        if self.config.sensors.iter().any(|s| s.name() == spec.name()) {
            return Err(SensorError::invalid(
                format!("{field}.name"),
                spec.name(),
                "already attached",
            ));
        }
        self.config.sensors.push(spec);
        self.ensure_raycaster()
    }

    /// Detach the sensor with this name, returning it.
    pub fn detach(&mut self, name: &str) -> Option<SensorSpec> {
        let i = self.config.sensors.iter().position(|s| s.name() == name)?;
        self.last_sample.remove(name);
        Some(self.config.sensors.remove(i))
    }

    fn due(&mut self, spec: &SensorSpec, state: &AgentState) -> bool {
        let rate = spec.rate();
        match rate.hz {
            Some(hz) => {
                let due = self
                    .last_sample
                    .get(spec.name())
                    .is_none_or(|&t| state.time_s - t >= 1.0 / hz as f64 - 1e-9);
                if due {
                    self.last_sample
                        .insert(spec.name().to_string(), state.time_s);
                }
                due
            }
            None => state.step.is_multiple_of(rate.every_steps as u64),
        }
    }

    /// Read every sensor due at this state. Cameras (panoramas included) render in one batch;
    /// sensors with identical cameras share one view.
    pub fn observe(&mut self, state: &AgentState) -> Result<Observations> {
        let specs: Vec<SensorSpec> = self.config.sensors.clone();
        let due: Vec<bool> = specs.iter().map(|s| self.due(s, state)).collect();
        // Collect views, merging identical cameras.
        let mut views: Vec<View> = Vec::new();
        let mut slots: Vec<Vec<usize>> = vec![Vec::new(); specs.len()];
        let mut add = |cam: Camera, ch: Channels| -> usize {
            if let Some(i) = views.iter().position(|v| v.camera == cam) {
                views[i].channels = views[i].channels.union(ch);
                i
            } else {
                views.push(View {
                    camera: cam,
                    channels: ch,
                });
                views.len() - 1
            }
        };
        for (si, s) in specs.iter().enumerate() {
            if !due[si] {
                continue;
            }
            let one = |c: &crate::config::CameraSpec| c.camera(&state.base);
            match s {
                SensorSpec::Rgb(c) => slots[si].push(add(one(c), Channels::RGB)),
                SensorSpec::Depth(c) => slots[si].push(add(one(c), Channels::DEPTH)),
                SensorSpec::Semantic(c) => slots[si].push(add(
                    one(c),
                    Channels {
                        semantic: true,
                        ..Default::default()
                    },
                )),
                SensorSpec::Instance(c) => slots[si].push(add(
                    one(c),
                    Channels {
                        instance: true,
                        ..Default::default()
                    },
                )),
                SensorSpec::Panorama(p) => {
                    let ch = Channels {
                        rgb: p.rgb,
                        depth: p.depth,
                        semantic: p.semantic,
                        instance: false,
                    };
                    let cam = one(&p.camera);
                    for k in 0..p.views {
                        slots[si].push(add(cam.yawed((k as f32 * p.step_deg).to_radians()), ch));
                    }
                }
                _ => {}
            }
        }
        let mut frames = if views.is_empty() {
            Vec::new()
        } else {
            self.renderer.render(&views)?
        };
        // How many sensors read each view: the last one takes the frame instead of a copy.
        let mut uses = vec![0usize; frames.len()];
        for v in slots.iter().flatten() {
            if let Some(u) = uses.get_mut(*v) {
                *u += 1;
            }
        }
        let mut out = Observations::new();
        for (si, s) in specs.iter().enumerate() {
            if !due[si] {
                continue;
            }
            let mut rng = ChaCha8Rng::seed_from_u64(self.config.seed);
            rng.set_stream(state.step.wrapping_mul(1024).wrapping_add(si as u64));
            let mut frame = |k: usize| take_frame(&mut frames, &mut uses, slots[si][k]);
            let obs = match s {
                SensorSpec::Rgb(c) => {
                    let f = frame(0);
                    let mut f = Frame {
                        depth: vec![],
                        semantic: vec![],
                        instance: vec![],
                        ..f
                    };
                    noise::apply_rgb(&c.noise, &mut f.rgb, &mut rng);
                    Observation::Rgb(f)
                }
                SensorSpec::Depth(c) => {
                    let f = frame(0);
                    let mut f = Frame {
                        rgb: vec![],
                        semantic: vec![],
                        instance: vec![],
                        ..f
                    };
                    noise::apply_depth(&c.noise, &mut f.depth, c.far, &mut rng);
                    if c.normalize {
                        f.depth.iter_mut().for_each(|d| *d /= c.far);
                    }
                    Observation::Depth(f)
                }
                SensorSpec::Semantic(_) => {
                    let f = frame(0);
                    Observation::Semantic(Frame {
                        rgb: vec![],
                        depth: vec![],
                        instance: vec![],
                        ..f
                    })
                }
                SensorSpec::Instance(_) => {
                    let f = frame(0);
                    Observation::Instance(Frame {
                        rgb: vec![],
                        depth: vec![],
                        semantic: vec![],
                        ..f
                    })
                }
                SensorSpec::Panorama(p) => Observation::Panorama(
                    (0..slots[si].len())
                        .map(|k| {
                            let mut f = frame(k);
                            if !p.rgb {
                                f.rgb.clear();
                            }
                            if !p.depth {
                                f.depth.clear();
                            }
                            if !p.semantic {
                                f.semantic.clear();
                            }
                            f.instance.clear();
                            f
                        })
                        .collect(),
                ),
                SensorSpec::Lidar(l) => {
                    let rc = self.raycaster.as_ref().ok_or(SensorError::NoScene)?;
                    let mut scan = lidar::scan(l, &state.base, rc);
                    lidar::apply_noise(l, &mut scan, &mut rng);
                    Observation::Lidar(scan)
                }
                SensorSpec::Pose(_) => Observation::Pose(state.base),
                SensorSpec::Compass(_) => {
                    let mut h = state.base.yaw() - self.start.yaw();
                    while h > std::f32::consts::PI {
                        h -= std::f32::consts::TAU;
                    }
                    while h <= -std::f32::consts::PI {
                        h += std::f32::consts::TAU;
                    }
                    Observation::Compass(h)
                }
                SensorSpec::Gps(_) => {
                    let rel = self.start.quat().inverse()
                        * (state.base.translation() - self.start.translation());
                    Observation::Gps(rel.to_array())
                }
                SensorSpec::Collision(_) => Observation::Collision(state.collision),
            };
            out.insert(s.name().to_string(), obs);
        }
        Ok(out)
    }
}

/// View `v`'s frame for one reader: moved out by its last reader, copied for the others.
fn take_frame(frames: &mut [Frame], uses: &mut [usize], v: usize) -> Frame {
    uses[v] = uses[v].saturating_sub(1);
    if uses[v] == 0 {
        std::mem::take(&mut frames[v])
    } else {
        frames[v].clone()
    }
}
