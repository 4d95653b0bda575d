//! [`RapierSimulator`]: the [`Simulator`] over rapier3d.
//!
//! Discrete moves and driven waypoints are kinematic: a short loop of shape casts that stops
//! at, or slides along, what it hits (a few microseconds); velocity commands run the full rigid-body
//! pipeline with the agent as a dynamic body, so it pushes light furniture and is stopped
//! by heavy furniture; Tel-Hop teleports and searches the nearest collision-free spot.

use crate::config::{CollisionSetting, SimConfig};
use crate::error::{Result, SimError};
use crate::physics_cache::PhysicsCache;
use crate::simulator::{Failure, Hop, Simulator, StepOutcome};
use crate::world::{
    agent_key, check_agent, content_key, PhysicsScene, World, AGENT_QUERY, STAND_QUERY,
};
use crate::{Action, WaypointMode};
use glam::{Quat, Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rapier3d::parry::query::ShapeCastOptions;
use rapier3d::prelude::*;
use std::collections::BTreeSet;
use std::f64::consts::{PI, TAU};
use std::hash::{Hash, Hasher};
use std::sync::Arc;
use vlnverse_env::ObjectId;

mod ground;

/// Gap kept between the agent and obstacles by discrete moves (m).
const SKIN: f32 = 0.005;
/// Distance at which a discrete move's shape cast reports a hit (m); less than `SKIN`.
const CAST_GAP: f32 = 0.5 * SKIN;
/// Most shape casts of one discrete move (free move: 1; slide along a wall: 2; corner: 3).
const MAX_SLIDES: usize = 4;
/// Motion below this is no motion (m).
const MIN_MOVE: f32 = 1e-6;
/// Push of a slide's remainder away from the surface it slides along (m).
const NUDGE: f32 = 1e-4;
/// Drive force limit as a multiple of `mass * max_linear_accel` (margin to track the ramp).
const DRIVE_MARGIN: f32 = 2.0;

/// Agent state outside the physics world. Yaw is kept in f64 so that turns compose exactly.
#[derive(Clone, Debug, PartialEq)]
struct AgentState {
    base: Vec3,
    yaw: f64,
    pitch: f32,
    speed: f32,
    omega: f32,
    over: Option<String>,
}

/// Full state of a [`RapierSimulator`] (physics world included) at one moment
/// ([`RapierSimulator::snapshot`]).
#[derive(Clone)]
pub struct RapierSnapshot {
    scene: Option<Arc<PhysicsScene>>,
    scene_key: Option<u64>,
    world: Option<World>,
    state: AgentState,
    rng: ChaCha8Rng,
}

impl std::fmt::Debug for RapierSnapshot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RapierSnapshot")
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

/// The rapier3d-based simulator. One instance is one environment; it is `Send`, and
/// [`crate::VecSimulator`] runs many of them in parallel.
///
/// The physics world of a scene (its static colliders) comes from a [`PhysicsCache`] keyed by
/// the scene's content, shared by every simulator made with the same cache (by default the
/// process-wide one): [`Simulator::reset`] in a scene seen before builds nothing.
pub struct RapierSimulator {
    cfg: SimConfig,
    cache: Arc<PhysicsCache>,
    /// [`agent_key`] of `cfg.agent`.
    agent_key: u64,
    /// [`content_key`] of the current scene.
    scene_key: Option<u64>,
    pipeline: PhysicsPipeline,
    params: IntegrationParameters,
    scene: Option<Arc<PhysicsScene>>,
    world: Option<World>,
    state: AgentState,
    rng: ChaCha8Rng,
    hop_offsets: Arc<Vec<Vec2>>,
}

impl std::fmt::Debug for RapierSimulator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RapierSimulator")
            .field("scene", &self.scene.as_ref().map(|s| s.scene_id()))
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

impl RapierSimulator {
    /// A simulator with these settings (validated here), sharing physics worlds through the
    /// process-wide [`PhysicsCache::global`]; call [`Simulator::reset`] next.
    pub fn new(cfg: SimConfig) -> Result<Self> {
        Self::with_cache(cfg, PhysicsCache::global())
    }

    /// [`Self::new`] sharing physics worlds through `cache` instead of the process-wide one.
    pub fn with_cache(cfg: SimConfig, cache: Arc<PhysicsCache>) -> Result<Self> {
        cfg.validate()?;
        let params = IntegrationParameters {
            dt: cfg.physics_dt,
            ..Default::default()
        };
        let hop_offsets = Arc::new(spiral(cfg.hop_radius, cfg.hop_resolution));
        Ok(RapierSimulator {
            rng: ChaCha8Rng::seed_from_u64(cfg.seed),
            agent_key: agent_key(&cfg.agent),
            cache,
            scene_key: None,
            cfg,
            pipeline: PhysicsPipeline::new(),
            params,
            scene: None,
            world: None,
            state: AgentState {
                base: Vec3::ZERO,
                yaw: 0.0,
                pitch: 0.0,
                speed: 0.0,
                omega: 0.0,
                over: None,
            },
            hop_offsets,
        })
    }

    /// The settings.
    pub fn config(&self) -> &SimConfig {
        &self.cfg
    }

    /// The cache this simulator takes its physics worlds from.
    pub fn physics_cache(&self) -> &Arc<PhysicsCache> {
        &self.cache
    }

    /// Capture the whole state (agent, moved furniture, noise generator).
    pub fn snapshot(&self) -> RapierSnapshot {
        RapierSnapshot {
            scene: self.scene.clone(),
            scene_key: self.scene_key,
            world: self.world.clone(),
            state: self.state.clone(),
            rng: self.rng.clone(),
        }
    }

    /// Return to a state captured by [`Self::snapshot`].
    pub fn restore(&mut self, snapshot: &RapierSnapshot) {
        self.scene = snapshot.scene.clone();
        self.scene_key = snapshot.scene_key;
        self.world = snapshot.world.clone();
        self.state = snapshot.state.clone();
        self.rng = snapshot.rng.clone();
    }

    /// The physics world of the current scene (share it with [`Self::reset_in`]).
    pub fn physics_scene(&self) -> Option<&Arc<PhysicsScene>> {
        self.scene.as_ref()
    }

    /// Start an episode in an already built physics world (shared between environments:
    /// its static colliders are not copied, only per-collider records).
    pub fn reset_in(
        &mut self,
        scene: Arc<PhysicsScene>,
        start: vlnverse_env::Pose,
    ) -> Result<vlnverse_env::Pose> {
        check_agent(&scene, &self.cfg.agent)?;
        let p = start.translation();
        let yaw = start.yaw();
        if !p.is_finite() || !yaw.is_finite() {
            return Err(SimError::InvalidScene {
                scene: scene.scene_id.clone(),
                message: format!("start pose is not finite: {start:?}"),
            });
        }
        self.world = Some(scene.world.clone());
        self.scene_key = None;
        self.state = AgentState {
            base: p,
            yaw: wrap(yaw as f64),
            pitch: 0.0,
            speed: 0.0,
            omega: 0.0,
            over: None,
        };
        // Noise depends on the seed and the episode, not on the order episodes run in.
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (self.cfg.seed, scene.fingerprint).hash(&mut h);
        start.position.map(f32::to_bits).hash(&mut h);
        start.rotation.map(f32::to_bits).hash(&mut h);
        self.rng = ChaCha8Rng::seed_from_u64(h.finish());
        self.scene = Some(scene);
        if self.follows_ground() {
            self.state.base.y = self.stand_height(p);
        }
        self.sync_body(Vec3::ZERO);
        let hits = self.overlaps(self.state.base);
        if !hits.is_empty() {
            tracing::warn!(?hits, "start pose overlaps objects");
        }
        Ok(self.pose())
    }

    /// Current pose of a dynamic object (furniture the agent can push), None for static
    /// objects or unknown ids.
    pub fn object_pose(&self, id: ObjectId) -> Option<vlnverse_env::Pose> {
        let (scene, world) = (self.scene.as_ref()?, self.world.as_ref()?);
        let (_, h) = scene.dynamic_objects.iter().find(|(i, _)| *i == id)?;
        let p = world.bodies.get(*h)?.position();
        Some(vlnverse_env::Pose {
            position: p.translation.to_array(),
            rotation: p.rotation.to_array(),
        })
    }

    /// Whether the agent shape at base position `(x, z)` (current yaw, current floor)
    /// overlaps nothing.
    pub fn is_free(&self, x: f32, z: f32) -> bool {
        let p = Vec3::new(x, self.state.base.y, z);
        self.overlaps(p).is_empty()
    }

    fn forward(&self) -> Vec3 {
        let (s, c) = self.state.yaw.sin_cos();
        Vec3::new(-s as f32, 0.0, -c as f32)
    }

    fn quat(&self) -> Quat {
        Quat::from_rotation_y(self.state.yaw as f32)
    }

    fn shape_pose(&self, base: Vec3, rot: Quat) -> Pose {
        let c = self.scene.as_ref().map_or(0.0, |s| s.agent_center);
        Pose::from_parts(base + Vec3::new(0.0, c, 0.0), rot)
    }

    /// Put the agent body where the state says, with this horizontal velocity.
    fn sync_body(&mut self, linvel: Vec3) {
        let pose = Pose::from_parts(self.state.base, self.quat());
        if let (Some(s), Some(w)) = (self.scene.as_ref(), self.world.as_mut()) {
            if let Some(b) = w.bodies.get_mut(s.agent_body) {
                b.set_position(pose, true);
                b.set_linvel(linvel, true);
                b.set_angvel(Vec3::ZERO, true);
            }
        }
    }

    fn ids(&self, handles: impl IntoIterator<Item = ColliderHandle>) -> Vec<ObjectId> {
        let Some(w) = self.world.as_ref() else {
            return vec![];
        };
        let set: BTreeSet<ObjectId> = handles
            .into_iter()
            .filter_map(|h| w.colliders.get(h))
            .map(|c| c.user_data as ObjectId)
            .filter(|id| *id != 0)
            .collect();
        set.into_iter().collect()
    }

    /// Objects the agent shape would overlap with its base at `p`.
    fn overlaps(&self, p: Vec3) -> Vec<ObjectId> {
        self.overlaps_rot(p, self.quat())
    }

    fn overlaps_rot(&self, p: Vec3, rot: Quat) -> Vec<ObjectId> {
        let (Some(s), Some(w)) = (self.scene.as_ref(), self.world.as_ref()) else {
            return vec![];
        };
        // Following the ground, a floor higher than the feet is in the way too.
        let groups = match s.follows_ground() {
            true => STAND_QUERY,
            false => AGENT_QUERY,
        };
        let qp = w.query(
            QueryFilter::default()
                .exclude_rigid_body(s.agent_body)
                .groups(groups),
        );
        let shape = s.agent_shape.as_ref();
        let handles: Vec<ColliderHandle> = qp
            .intersect_shape(self.shape_pose(p, rot), shape)
            .map(|(h, _)| h)
            .collect();
        self.ids(handles)
    }

    /// A floor (or anything) under the agent's feet at `p`.
    fn supported(&self, p: Vec3) -> bool {
        let (Some(s), Some(w)) = (self.scene.as_ref(), self.world.as_ref()) else {
            return false;
        };
        if !s.has_floor {
            return true;
        }
        let qp = w.query(QueryFilter::default().exclude_rigid_body(s.agent_body));
        let top = self.cfg.agent.ground_clearance + 0.01;
        let ray = Ray::new(p + Vec3::new(0.0, top, 0.0), Vec3::NEG_Y);
        qp.cast_ray(&ray, top + 0.1, true).is_some()
    }

    fn noise(&mut self, std: f32) -> f32 {
        if std <= 0.0 {
            return 0.0;
        }
        let u1: f64 = self.rng.random::<f64>().max(1e-12);
        let u2: f64 = self.rng.random::<f64>();
        ((-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()) as f32 * std
    }

    fn turn(&mut self, angle: f32, out: &mut StepOutcome) {
        let noisy = match self.cfg.noise {
            Some(n) => angle + self.noise(n.angle_std_deg.to_radians()),
            None => angle,
        };
        let new_yaw = wrap(self.state.yaw + noisy as f64);
        if !self.cfg.agent.shape.is_round() {
            let hit = self.overlaps_rot(self.state.base, Quat::from_rotation_y(new_yaw as f32));
            if !hit.is_empty() {
                out.collided = true;
                out.hit = hit;
                return;
            }
        }
        self.state.yaw = new_yaw;
        self.sync_body(Vec3::ZERO);
    }

    /// Move the agent shape by `desired` (horizontal) with a shape-cast slide loop; returns
    /// the achieved displacement and the objects hit.
    ///
    /// Each iteration casts the shape along the remaining motion, stops `SKIN` away from the
    /// first hit and, with sliding on, keeps only the part of the remainder along the hit
    /// surface's horizontal tangent. At most `MAX_SLIDES` casts. Replaces rapier's character
    /// controller, whose ground-contact tests (useless for a planar agent) made blocked moves
    /// 3-4 times slower.
    fn slide_move(&mut self, desired: Vec3) -> (Vec3, Vec<ObjectId>) {
        if self.follows_ground() {
            return self.climb_move(desired);
        }
        let (achieved, hits) = self.slide_cast(self.state.base, desired, AGENT_QUERY);
        let hits = self.ids(hits);
        self.state.base += achieved;
        self.state.speed = 0.0;
        self.state.omega = 0.0;
        self.sync_body(Vec3::ZERO);
        (achieved, hits)
    }

    /// The slide loop of [`Self::slide_move`] from base position `start` against the
    /// colliders of `groups`, changing nothing: the achieved horizontal displacement and the
    /// colliders hit.
    fn slide_cast(
        &self,
        start: Vec3,
        desired: Vec3,
        groups: InteractionGroups,
    ) -> (Vec3, Vec<ColliderHandle>) {
        let (Some(s), Some(w)) = (self.scene.as_ref(), self.world.as_ref()) else {
            return (Vec3::ZERO, vec![]);
        };
        let qp = w.query(
            QueryFilter::default()
                .exclude_rigid_body(s.agent_body)
                .groups(groups),
        );
        let rot = self.quat();
        let sliding = self.cfg.agent.allow_sliding;
        let mut achieved = Vec3::ZERO;
        let mut remaining = Vec3::new(desired.x, 0.0, desired.z);
        let mut hits = Vec::new();
        let mut normals: Vec<Vec3> = Vec::new();
        for _ in 0..MAX_SLIDES {
            let dist = remaining.length();
            if dist < MIN_MOVE {
                break;
            }
            let dir = remaining / dist;
            let cast = qp.cast_shape(
                &self.shape_pose(start + achieved, rot),
                dir,
                s.agent_shape.as_ref(),
                ShapeCastOptions {
                    target_distance: CAST_GAP,
                    stop_at_penetration: false,
                    max_time_of_impact: dist,
                    compute_impact_geometry_on_penetration: true,
                },
            );
            let Some((handle, hit)) = cast else {
                achieved += remaining;
                break;
            };
            hits.push(handle);
            let n = Vec3::new(hit.normal1.x, 0.0, hit.normal1.z).normalize_or_zero();
            // Stop `SKIN` from the surface: the next cast then starts clear of the `CAST_GAP`
            // shell (a cast starting inside it also runs a contact query, ~20% of the step).
            let into = -dir.dot(n);
            let back = if into > 1e-3 {
                (SKIN - CAST_GAP) / into
            } else {
                0.0
            };
            let toi = (hit.time_of_impact - back).clamp(0.0, dist);
            achieved += dir * toi;
            remaining -= dir * toi;
            if !sliding || n == Vec3::ZERO {
                break;
            }
            // Keep the horizontal tangent part of the remainder (drop what goes into the surface).
            remaining -= n * remaining.dot(n).min(0.0);
            // In a corner the slide along one surface runs into the other: stop there.
            if remaining.length() < MIN_MOVE
                || normals.iter().any(|m| remaining.dot(*m) < -MIN_MOVE)
            {
                break;
            }
            normals.push(n);
            // A hair away from the surface so the next cast does not start touching it.
            remaining += n * NUDGE;
        }
        (achieved, hits)
    }

    /// Teleport to `target` (base position) and resolve to the nearest free spot.
    fn hop(&mut self, target: Vec3, out: &mut StepOutcome) {
        if self.follows_ground() {
            return self.hop_on_ground(target, out);
        }
        let start = self.state.base;
        out.commanded = [target.x - start.x, target.z - start.z];
        let at_target = self.overlaps(target);
        out.collided = !at_target.is_empty();
        out.hit = at_target;
        let offsets = Arc::clone(&self.hop_offsets);
        // A teleport may not pass a closed door: spots behind one do not count.
        let door = |p: Vec3| {
            self.scene
                .as_ref()
                .and_then(|s| s.closed_door_between([start.x, start.z], [p.x, p.z]))
        };
        let mut behind = None;
        let landed = offsets
            .iter()
            .map(|o| target + Vec3::new(o.x, 0.0, o.y))
            .find(|p| {
                let free = (*p == target && out.hit.is_empty()
                    || *p != target && self.overlaps(*p).is_empty())
                    && self.supported(*p);
                if !free {
                    return false;
                }
                match door(*p) {
                    Some(d) => {
                        behind.get_or_insert(d);
                        false
                    }
                    None => true,
                }
            });
        let landed = landed.map(|p| (p, (p - target).length()));
        self.settle_hop(landed, behind, start, out);
    }

    /// End a hop from `start`: stand at the spot landed on (with its distance from the
    /// commanded one), or stay where the agent was because a closed door (`behind`) or no free
    /// spot stopped it; the agent ends at rest.
    fn settle_hop(
        &mut self,
        landed: Option<(Vec3, f32)>,
        behind: Option<u32>,
        start: Vec3,
        out: &mut StepOutcome,
    ) {
        match landed {
            Some((p, shift)) => {
                out.hop = Some(Hop::Landed { shift });
                self.state.base = p;
            }
            None if behind.is_some() => {
                out.collided = true;
                out.hop = behind.map(|door| Hop::ClosedDoor { door });
            }
            None => {
                out.collided = true;
                out.hop = Some(Hop::NoFreeSpot {
                    radius: self.cfg.hop_radius,
                });
            }
        }
        self.state.speed = 0.0;
        self.state.omega = 0.0;
        self.sync_body(Vec3::ZERO);
        out.achieved = [self.state.base.x - start.x, self.state.base.z - start.z];
    }

    /// Velocity control through the rigid-body pipeline (along the ground in a multi-level
    /// scene: [`Self::drive_on_ground`]).
    fn drive(&mut self, v: f32, omega: f32, duration: f32, out: &mut StepOutcome) {
        let a = &self.cfg.agent;
        let mut v = v.clamp(-a.max_linear_speed, a.max_linear_speed);
        let mut w_cmd = omega.clamp(-a.max_angular_speed(), a.max_angular_speed());
        if let Some(d) = &a.differential_drive {
            let wheel = v.abs() + w_cmd.abs() * 0.5 * d.wheel_base;
            if wheel > d.max_wheel_speed {
                let k = d.max_wheel_speed / wheel;
                v *= k;
                w_cmd *= k;
            }
        }
        let dt = self.params.dt;
        let steps = ((duration / dt).round() as u32).max(1);
        let cmd = ground::Drive {
            v,
            omega: w_cmd,
            ticks: steps,
            dt,
            lin_acc: a.max_linear_accel * dt,
            ang_acc: a.max_angular_accel() * dt,
        };
        if self.follows_ground() {
            return self.drive_on_ground(cmd, out);
        }
        let max_impulse = DRIVE_MARGIN * a.mass * a.max_linear_accel * dt;
        let mass = a.mass;
        let Some(scene) = self.scene.clone() else {
            return;
        };
        let start = self.state.base;
        let mut commanded = Vec3::ZERO;
        let mut touched = Vec::new();
        self.sync_body(self.forward() * self.state.speed);
        for _ in 0..steps {
            self.accelerate(&cmd);
            let desired = self.forward() * self.state.speed;
            commanded += desired * dt;
            let rot = self.quat();
            let Some(w) = self.world.as_mut() else {
                return;
            };
            if let Some(b) = w.bodies.get_mut(scene.agent_body) {
                let cur = b.linvel();
                let dv = desired - Vec3::new(cur.x, 0.0, cur.z);
                b.apply_impulse((dv * mass).clamp_length_max(max_impulse), true);
                b.set_rotation(rot, true);
                b.set_angvel(Vec3::ZERO, true);
            }
            self.pipeline.step(
                Vec3::new(0.0, -9.81, 0.0),
                &self.params,
                &mut w.islands,
                &mut w.broad_phase,
                &mut w.narrow_phase,
                &mut w.bodies,
                &mut w.colliders,
                &mut w.impulse_joints,
                &mut w.multibody_joints,
                &mut w.soft_bodies,
                &mut w.ccd_solver,
                &(),
                &(),
            );
            for pair in w.narrow_phase.contact_pairs_with(scene.agent_collider) {
                if pair.has_any_active_contact() {
                    let other = if pair.collider1 == scene.agent_collider {
                        pair.collider2
                    } else {
                        pair.collider1
                    };
                    touched.push(other);
                }
            }
        }
        if let Some(b) = self
            .world
            .as_ref()
            .and_then(|w| w.bodies.get(scene.agent_body))
        {
            let t = b.translation();
            self.state.base = Vec3::new(t.x, start.y, t.z);
        }
        out.commanded = [commanded.x, commanded.z];
        out.achieved = [self.state.base.x - start.x, self.state.base.z - start.z];
        out.hit = self.ids(touched);
        out.collided = !out.hit.is_empty();
    }

    fn check_in_bounds(&self, x: f32, z: f32) -> Result<()> {
        let b = self.scene.as_ref().and_then(|s| s.bounds);
        match b {
            Some([x0, z0, x1, z1]) if x >= x0 && x <= x1 && z >= z0 && z <= z1 => Ok(()),
            Some([x0, z0, x1, z1]) => Err(SimError::action(
                "Waypoint",
                format!("({x}, {z})"),
                format!("outside the scene (x in [{x0}, {x1}], z in [{z0}, {z1}])"),
            )),
            None => Err(SimError::action(
                "Waypoint",
                format!("({x}, {z})"),
                "the scene is empty",
            )),
        }
    }
}

impl Simulator for RapierSimulator {
    fn name(&self) -> String {
        "rapier".into()
    }

    fn reset(
        &mut self,
        scene: &vlnverse_env::Scene,
        start: vlnverse_env::Pose,
    ) -> Result<vlnverse_env::Pose> {
        let key = content_key(scene, self.agent_key);
        let physics = match &self.scene {
            Some(s) if self.scene_key == Some(key) => Arc::clone(s),
            _ => self.cache.get(scene, &self.cfg.agent, self.agent_key)?,
        };
        self.reset_in(physics, start)?;
        self.scene_key = Some(key);
        Ok(self.pose())
    }

    fn step(&mut self, action: Action) -> Result<StepOutcome> {
        action.validate()?;
        if self.scene.is_none() {
            return Err(SimError::NotReset);
        }
        if let Some(why) = &self.state.over {
            return Err(SimError::EpisodeOver(why.clone()));
        }
        if let Action::Waypoint { x, z, .. } = action {
            self.check_in_bounds(x, z)?;
        }
        let mut out = StepOutcome::default();
        let telhop = self.cfg.setting == CollisionSetting::TelHop;
        match action {
            Action::Stop => {
                out.done = true;
                self.state.over = Some("stopped".into());
            }
            Action::TurnLeft(a) => self.turn(a, &mut out),
            Action::TurnRight(a) => self.turn(-a, &mut out),
            Action::LookUp | Action::LookDown => {
                let step = self.cfg.agent.look_angle_deg.to_radians();
                let max = self.cfg.agent.max_pitch_deg.to_radians();
                let sign = if action == Action::LookUp { 1.0 } else { -1.0 };
                self.state.pitch = (self.state.pitch + sign * step).clamp(-max, max);
            }
            Action::MoveForward(d) => {
                let d = match self.cfg.noise {
                    Some(n) => (d + self.noise(n.distance_std)).max(0.0),
                    None => d,
                };
                let desired = self.forward() * d;
                if telhop {
                    self.hop(self.state.base + desired, &mut out);
                } else {
                    out.commanded = [desired.x, desired.z];
                    let (achieved, hit) = self.slide_move(desired);
                    out.achieved = [achieved.x, achieved.z];
                    out.collided = !hit.is_empty();
                    out.hit = hit;
                }
            }
            Action::Velocity { v, omega, duration } => self.drive(v, omega, duration, &mut out),
            Action::Waypoint { x, z, mode } => {
                let target = Vec3::new(x, self.state.base.y, z);
                let d = target - self.state.base;
                if d.length() > 1e-6 {
                    self.state.yaw = wrap((-d.x as f64).atan2(-d.z as f64));
                }
                if telhop || mode == WaypointMode::TelHop {
                    self.hop(target, &mut out);
                } else {
                    out.commanded = [d.x, d.z];
                    let (achieved, hit) = self.slide_move(d);
                    out.achieved = [achieved.x, achieved.z];
                    out.collided = !hit.is_empty();
                    out.hit = hit;
                }
            }
        }
        let miss = Vec2::from(out.commanded) - Vec2::from(out.achieved);
        out.noticeable = miss.length() > self.cfg.agent.collision_threshold
            || matches!(
                out.hop,
                Some(Hop::NoFreeSpot { .. } | Hop::ClosedDoor { .. })
            );
        if out.noticeable && self.cfg.setting == CollisionSetting::Strict {
            out.failure = Some(Failure::Collision {
                hit: out.hit.clone(),
            });
            out.done = true;
            self.state.over = Some(format!("noticeable collision with {:?}", out.hit));
        }
        out.pose = self.pose();
        Ok(out)
    }

    fn pose(&self) -> vlnverse_env::Pose {
        vlnverse_env::Pose {
            position: self.state.base.to_array(),
            rotation: self.quat().to_array(),
        }
    }

    fn camera_pose(&self) -> vlnverse_env::Pose {
        let up = Vec3::new(0.0, self.cfg.agent.sensor_height, 0.0);
        vlnverse_env::Pose {
            position: (self.state.base + up).to_array(),
            rotation: (self.quat() * Quat::from_rotation_x(self.state.pitch)).to_array(),
        }
    }
}

/// Wrap an angle to `(-pi, pi]`.
fn wrap(a: f64) -> f64 {
    let w = (a + PI).rem_euclid(TAU) - PI;
    if w <= -PI {
        w + TAU
    } else {
        w
    }
}

/// Candidate offsets of the Tel-Hop search: rings of growing radius, nearest first.
fn spiral(radius: f32, res: f32) -> Vec<Vec2> {
    let mut out = vec![Vec2::ZERO];
    let rings = (radius / res).floor() as u32;
    for k in 1..=rings {
        let r = k as f32 * res;
        let n = ((std::f32::consts::TAU * r / res).ceil() as u32).max(4);
        for j in 0..n {
            let a = std::f32::consts::TAU * j as f32 / n as f32;
            out.push(Vec2::new(r * a.cos(), r * a.sin()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_keeps_angles_in_range() {
        for a in [-10.0, -PI, -1.0, 0.0, 1.0, PI, 7.0] {
            let w = wrap(a);
            assert!(w > -PI - 1e-12 && w <= PI + 1e-12, "{a} -> {w}");
            assert!(((w - a) / TAU - ((w - a) / TAU).round()).abs() < 1e-12);
        }
    }

    #[test]
    fn spiral_is_sorted_by_distance() {
        let s = spiral(0.5, 0.05);
        assert_eq!(s[0], Vec2::ZERO);
        for w in s.windows(2) {
            assert!(w[0].length() <= w[1].length() + 1e-5);
        }
        assert!(s.iter().all(|p| p.length() <= 0.5 + 1e-5));
    }

    #[test]
    fn simulator_is_send() {
        fn send<T: Send>() {}
        send::<RapierSimulator>();
        send::<RapierSnapshot>();
    }
}
