//! The physics world built from a [`Scene`]: static colliders for structure and static
//! furniture, dynamic bodies for movable furniture, and the agent body. Built once per
//! (scene, agent) and shared (`Arc`) by every environment in that scene; shapes are
//! reference-counted so an environment's copy costs only the per-collider records.

use crate::config::{AgentConfig, AgentShape};
use crate::error::{Result, SimError};
use rapier3d::prelude::*;
use std::hash::{Hash, Hasher};
use vlnverse_env::{Motion, ObjectId, Scene, SceneObject, SemanticClass, Shape};

/// Collision group of floors and objects lower than the agent's ground clearance.
const GROUND: InteractionGroups =
    InteractionGroups::new(Group::GROUP_2, Group::ALL, InteractionTestMode::And);
/// Collision group of everything else.
const SOLID: InteractionGroups =
    InteractionGroups::new(Group::GROUP_1, Group::ALL, InteractionTestMode::And);
/// Groups of the agent's collider, moves and overlap tests: everything but the ground.
pub(crate) const AGENT_QUERY: InteractionGroups =
    InteractionGroups::new(Group::GROUP_1, Group::GROUP_1, InteractionTestMode::And);
/// Collision group of floors in a multi-level scene: ground (never in [`AGENT_QUERY`]) that
/// the agent also stands on ([`STAND_QUERY`]). Single-level scenes keep [`GROUND`].
const FLOOR: InteractionGroups = InteractionGroups::new(
    Group::GROUP_2.union(Group::GROUP_3),
    Group::ALL,
    InteractionTestMode::And,
);
/// Collision group, in a multi-level scene, of solids the agent may stand on: flights of
/// stairs (class `stairs`) and objects lower than its `max_step_height` above their level's
/// floor (thresholds, kerbs, low platforms). Solid for every agent query ([`AGENT_QUERY`]);
/// the walls, furniture and other solids of [`SOLID`] are never stood on (a wall's top next
/// to a flight, a bed reached from a low stool).
const STEP: InteractionGroups = InteractionGroups::new(
    Group::GROUP_1.union(Group::GROUP_4),
    Group::ALL,
    InteractionTestMode::And,
);
/// Groups of the multi-level agent's moves, overlap tests and "what am I standing on" casts:
/// solids and floors, not the low objects it drives over (rugs).
pub(crate) const STAND_QUERY: InteractionGroups = InteractionGroups::new(
    Group::GROUP_1,
    Group::GROUP_1.union(Group::GROUP_3),
    InteractionTestMode::And,
);
/// Groups of what the multi-level agent may stand on: floors and [`STEP`] solids.
pub(crate) const STEP_QUERY: InteractionGroups = InteractionGroups::new(
    Group::GROUP_1,
    Group::GROUP_3.union(Group::GROUP_4),
    InteractionTestMode::And,
);

/// Whether a collider's groups make it something the agent may stand on (floor or step).
pub(crate) fn standable(groups: InteractionGroups) -> bool {
    groups
        .memberships
        .intersects(Group::GROUP_3.union(Group::GROUP_4))
}

/// The mutable part of a rapier world (what an environment owns and a snapshot copies).
#[derive(Clone)]
pub(crate) struct World {
    pub bodies: RigidBodySet,
    pub colliders: ColliderSet,
    pub broad_phase: BroadPhaseBvh,
    pub narrow_phase: NarrowPhase,
    pub islands: IslandManager,
    pub impulse_joints: ImpulseJointSet,
    pub multibody_joints: MultibodyJointSet,
    pub soft_bodies: SoftBodySet,
    pub ccd_solver: CCDSolver,
}

impl World {
    /// A query view of this world with `filter` (the pipeline is a borrowed view, not `Sync`:
    /// build one per query).
    pub(crate) fn query<'a>(&'a self, filter: QueryFilter<'a>) -> QueryPipeline<'a> {
        self.broad_phase.as_query_pipeline(
            self.narrow_phase.query_dispatcher(),
            &self.bodies,
            &self.colliders,
            filter,
        )
    }

    fn new() -> Self {
        World {
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            islands: IslandManager::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd_solver: CCDSolver::new(),
        }
    }
}

/// A scene turned into a physics world for one agent embodiment, ready to be copied into
/// environments (see [`crate::RapierSimulator::reset_in`]).
pub struct PhysicsScene {
    pub(crate) scene_id: String,
    pub(crate) fingerprint: u64,
    pub(crate) agent: AgentConfig,
    pub(crate) world: World,
    pub(crate) agent_body: RigidBodyHandle,
    pub(crate) agent_collider: ColliderHandle,
    pub(crate) agent_shape: SharedShape,
    /// Height of the agent shape's centre above its base (feet).
    pub(crate) agent_center: f32,
    /// Horizontal scene bounds `[min_x, min_z, max_x, max_z]` (None for an empty scene).
    pub(crate) bounds: Option<[f32; 4]>,
    pub(crate) has_floor: bool,
    /// Floor heights of the levels, lowest first, when the scene has more than one (the agent
    /// then follows the ground: steps, flights, falls); empty for a single-level scene.
    pub(crate) levels: Vec<f32>,
    /// Lowest y of the scene (the bottom of the deepest fall).
    pub(crate) min_y: f32,
    pub(crate) dynamic_objects: Vec<(ObjectId, RigidBodyHandle)>,
    /// Closed doors as `(door id, doorway segment [x, z] to [x, z])`: a Tel-Hop may not pass
    /// one (the leaf is a static collider, so moves in the other settings stop at it anyway).
    pub(crate) closed_doors: Vec<(u32, [[f32; 2]; 2])>,
    /// The level (index into `levels`) of each of `closed_doors`, 0 in a single-level scene.
    pub(crate) closed_door_levels: Vec<usize>,
}

impl std::fmt::Debug for PhysicsScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PhysicsScene")
            .field("scene_id", &self.scene_id)
            .field("colliders", &self.world.colliders.len())
            .field("dynamic_objects", &self.dynamic_objects.len())
            .finish()
    }
}

impl PhysicsScene {
    /// Build the physics world of `scene` for an agent with embodiment `agent`.
    pub fn build(scene: &Scene, agent: &AgentConfig) -> Result<PhysicsScene> {
        agent.validate()?;
        let mut w = World::new();
        let mut dynamic_objects = Vec::new();
        let levels: Vec<f32> = if scene.is_multi_level() {
            scene
                .storeys
                .levels
                .iter()
                .map(|l| l.floor_height)
                .collect()
        } else {
            vec![]
        };
        for o in &scene.objects {
            let dynamic = o.physics.motion == Motion::Dynamic
                && o.physics.mass.is_finite()
                && o.physics.mass > 0.0;
            let friction = if o.physics.friction.is_finite() && o.physics.friction >= 0.0 {
                o.physics.friction
            } else {
                0.5
            };
            let (mut convex, meshes) = object_shapes(o, dynamic);
            let pose = to_iso(&o.pose);
            let user = o.id as u128;
            // Floors and anything the agent drives over never block a horizontal move; keeping
            // them out of the agent's queries keeps every shape cast and overlap test short.
            // In a multi-level scene "low" is measured from the floor of the object's own level.
            let floor = match levels.is_empty() {
                true => scene.floor_height,
                false => levels[level_below(&levels, o.bbox.min[1])],
            };
            let is_floor = o.class == SemanticClass::Floor;
            let ground = is_floor || o.bbox.max[1] < floor + agent.ground_clearance;
            let groups = if levels.is_empty() {
                if ground {
                    GROUND
                } else {
                    SOLID
                }
            } else if is_floor {
                FLOOR
            } else if ground {
                GROUND
            } else if o.class == SemanticClass::Stairs
                || o.bbox.max[1] < floor + agent.max_step_height
            {
                STEP
            } else {
                SOLID
            };
            if dynamic {
                if convex.is_empty() {
                    continue;
                }
                let body = w
                    .bodies
                    .insert(RigidBodyBuilder::dynamic().pose(pose).user_data(user));
                let col = ColliderBuilder::compound(convex)
                    .mass(o.physics.mass)
                    .friction(friction)
                    .collision_groups(groups)
                    .user_data(user);
                w.colliders.insert_with_parent(col, body, &mut w.bodies);
                dynamic_objects.push((o.id, body));
            } else {
                let single = match convex.len() {
                    0 => None,
                    1 => convex.pop(),
                    _ => Some((Pose::IDENTITY, SharedShape::compound(convex))),
                };
                let shapes = single.into_iter().chain(meshes);
                insert_shapes(&mut w, shapes, pose, friction, groups, user);
            }
        }

        let (agent_shape, agent_center) = agent_shape(agent);
        let agent_body = w.bodies.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, -1000.0, 0.0))
                .enabled_translations(true, false, true)
                .lock_rotations()
                .gravity_scale(0.0)
                .ccd_enabled(true)
                .can_sleep(false),
        );
        let agent_collider = w.colliders.insert_with_parent(
            ColliderBuilder::new(agent_shape.clone())
                .translation(Vector::new(0.0, agent_center, 0.0))
                .mass(agent.mass)
                .friction(if agent.allow_sliding { 0.0 } else { 1.0 })
                .friction_combine_rule(CoefficientCombineRule::Min)
                // The agent's height is locked, so it never rests on the ground; contacts with
                // the floor or a rug under its clearance would only stall it at their edges.
                .collision_groups(AGENT_QUERY)
                .user_data(0),
            agent_body,
            &mut w.bodies,
        );

        // Fill the broad phase (scene queries) without advancing time.
        let mut collisions = CollisionPipeline::new();
        collisions.step(
            IntegrationParameters::default().prediction_distance(),
            &mut w.islands,
            &mut w.broad_phase,
            &mut w.narrow_phase,
            &mut w.bodies,
            &mut w.colliders,
            &(),
            &(),
        );
        // The collision pipeline consumed the "modified" marks without registering the
        // dynamic bodies in the island manager; mark them again for the physics pipeline.
        let movable: Vec<RigidBodyHandle> = dynamic_objects.iter().map(|(_, h)| *h).collect();
        for h in movable.into_iter().chain([agent_body]) {
            if let Some(b) = w.bodies.get_mut(h) {
                b.wake_up(true);
            }
        }

        let b = scene.bounds();
        let bounds = (!b.is_empty()).then(|| [b.min[0], b.min[2], b.max[0], b.max[2]]);
        let closed: Vec<&vlnverse_env::Door> =
            scene.doors.iter().filter(|d| d.is_closed()).collect();
        let closed_door_levels = closed
            .iter()
            .map(|d| {
                let level = scene.room_level(d.rooms[0]).unwrap_or(0) as usize;
                if level < levels.len() {
                    level
                } else {
                    0
                }
            })
            .collect();
        Ok(PhysicsScene {
            scene_id: scene.id.clone(),
            fingerprint: fingerprint(scene),
            agent: agent.clone(),
            world: w,
            agent_body,
            agent_collider,
            agent_shape,
            agent_center,
            bounds,
            has_floor: scene
                .objects
                .iter()
                .any(|o| o.class == SemanticClass::Floor),
            min_y: if b.is_empty() { 0.0 } else { b.min[1] },
            levels,
            dynamic_objects,
            closed_doors: closed.iter().map(|d| (d.id, d.segment())).collect(),
            closed_door_levels,
        })
    }

    /// Whether the agent follows the ground in this world (a scene of more than one level):
    /// it climbs steps up to its `max_step_height`, walks slopes up to its `max_slope_deg`
    /// and falls where nothing is under it. Single-level scenes keep the planar agent.
    pub fn follows_ground(&self) -> bool {
        !self.levels.is_empty()
    }

    /// The level whose floor is the highest at or below the feet height `y` (a small
    /// tolerance for a point a hair below its floor); 0 in a single-level scene.
    pub fn level_at(&self, y: f32) -> usize {
        level_below(&self.levels, y)
    }

    /// [`Self::closed_door_between`] for the doors on the given levels only.
    pub(crate) fn closed_door_between_on(
        &self,
        a: [f32; 2],
        b: [f32; 2],
        on: &[usize],
    ) -> Option<u32> {
        self.closed_doors
            .iter()
            .zip(&self.closed_door_levels)
            .find(|((_, s), l)| on.contains(l) && vlnverse_env::segments_cross(a, b, s[0], s[1]))
            .map(|((id, _), _)| *id)
    }

    /// The first closed door (by id) whose doorway the floor segment from `a` to `b` crosses.
    pub fn closed_door_between(&self, a: [f32; 2], b: [f32; 2]) -> Option<u32> {
        self.closed_doors
            .iter()
            .find(|(_, s)| vlnverse_env::segments_cross(a, b, s[0], s[1]))
            .map(|(id, _)| *id)
    }

    /// Id of the scene this world was built from.
    pub fn scene_id(&self) -> &str {
        &self.scene_id
    }

    /// Bytes the world of `scene` is expected to hold once built: what [`crate::PhysicsCache`]
    /// counts against its budget (an estimate fitted on measured worlds, see `approx_bytes`).
    pub fn estimated_bytes(scene: &Scene) -> usize {
        approx_bytes(scene)
    }

    /// Number of colliders (agent included).
    pub fn collider_count(&self) -> usize {
        self.world.colliders.len()
    }

    /// Ids of the objects simulated as dynamic bodies.
    pub fn dynamic_object_ids(&self) -> Vec<ObjectId> {
        self.dynamic_objects.iter().map(|(id, _)| *id).collect()
    }
}

/// Index of the highest of `levels` (floor heights, ascending) at or below `y` (with 1 cm of
/// tolerance); 0 when `y` is below them all or there are none.
fn level_below(levels: &[f32], y: f32) -> usize {
    levels.iter().rposition(|&f| f <= y + 0.01).unwrap_or(0)
}

/// One static collider per shape, at `pose * local`, tagged with the object's `user` data.
fn insert_shapes(
    w: &mut World,
    shapes: impl IntoIterator<Item = (Pose, SharedShape)>,
    pose: Pose,
    friction: f32,
    groups: InteractionGroups,
    user: u128,
) {
    for (local, s) in shapes {
        w.colliders.insert(
            ColliderBuilder::new(s)
                .position(pose * local)
                .friction(friction)
                .collision_groups(groups)
                .user_data(user),
        );
    }
}

/// Convex parts (for a compound) and triangle-mesh parts (static objects only; dynamic
/// objects get the convex hull of a mesh instead).
fn object_shapes(
    o: &SceneObject,
    dynamic: bool,
) -> (Vec<(Pose, SharedShape)>, Vec<(Pose, SharedShape)>) {
    let mut convex = Vec::new();
    let mut meshes = Vec::new();
    for (i, part) in o.parts.iter().enumerate() {
        let local = to_iso(&part.transform);
        let ok = |v: f32| v.is_finite() && v > 0.0;
        let shape = match &part.shape {
            Shape::Cuboid {
                half_extents: h, ..
            } if h.iter().all(|v| ok(*v)) => Some(SharedShape::cuboid(h[0], h[1], h[2])),
            Shape::Cylinder {
                radius,
                half_height,
            } if ok(*radius) && ok(*half_height) => {
                Some(SharedShape::cylinder(*half_height, *radius))
            }
            Shape::Sphere { radius } if ok(*radius) => Some(SharedShape::ball(*radius)),
            Shape::Mesh(m) if !m.positions.is_empty() && !m.indices.is_empty() => {
                let pts: Vec<Vector> = m.positions.iter().map(|p| Vector::from_array(*p)).collect();
                if dynamic {
                    SharedShape::convex_hull(&pts)
                } else {
                    match SharedShape::trimesh(pts, m.indices.clone()) {
                        Ok(s) => {
                            meshes.push((local, s));
                            continue;
                        }
                        Err(e) => {
                            tracing::warn!(object = o.id, part = i, "mesh part skipped: {e}");
                            None
                        }
                    }
                }
            }
            _ => None,
        };
        match shape {
            Some(s) => convex.push((local, s)),
            None => tracing::warn!(
                object = o.id,
                part = i,
                "degenerate part skipped by physics"
            ),
        }
    }
    (convex, meshes)
}

/// The agent's collision shape and the height of its centre above the feet.
pub(crate) fn agent_shape(agent: &AgentConfig) -> (SharedShape, f32) {
    let h = agent.shape.height();
    let center = agent.ground_clearance + 0.5 * (h - agent.ground_clearance);
    let half = 0.5 * (h - agent.ground_clearance);
    let s = match agent.shape {
        AgentShape::Cylinder { radius, .. } => SharedShape::cylinder(half, radius),
        AgentShape::Capsule { radius, .. } => {
            SharedShape::capsule_y((half - radius).max(0.0), radius.min(half))
        }
        AgentShape::Box { width, length, .. } => {
            SharedShape::cuboid(0.5 * width, half, 0.5 * length)
        }
    };
    (s, center)
}

/// Scene pose to rapier pose.
pub(crate) fn to_iso(p: &vlnverse_env::Pose) -> Pose {
    Pose::from_parts(p.translation(), p.quat().normalize())
}

/// A cheap content hash deciding whether a cached physics world still matches a scene.
pub(crate) fn fingerprint(scene: &Scene) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    scene.id.hash(&mut h);
    scene.objects.len().hash(&mut h);
    for o in &scene.objects {
        o.id.hash(&mut h);
        for v in o.pose.position.iter().chain(&o.pose.rotation) {
            v.to_bits().hash(&mut h);
        }
        for v in o.bbox.min.iter().chain(&o.bbox.max) {
            v.to_bits().hash(&mut h);
        }
        o.physics.mass.to_bits().hash(&mut h);
        o.physics.friction.to_bits().hash(&mut h);
        (o.physics.motion == Motion::Dynamic).hash(&mut h);
        o.parts.len().hash(&mut h);
    }
    h.finish()
}

/// Check that an agent of this embodiment can be placed in the world (used by tests).
pub(crate) fn check_agent(t: &PhysicsScene, agent: &AgentConfig) -> Result<()> {
    if &t.agent != agent {
        return Err(SimError::InvalidScene {
            scene: t.scene_id.clone(),
            message: format!(
                "physics world was built for agent `{}`, not `{}`",
                t.agent.name, agent.name
            ),
        });
    }
    Ok(())
}

/// Vertices of a mesh part sampled into [`content_key`] (its sizes always are).
const MESH_SAMPLES: usize = 64;

/// What a physics world is built from, as a key for the shared cache
/// ([`crate::PhysicsCache`]): [`fingerprint`] plus the floor height, object classes, every
/// part's transform and shape (a mesh by its sizes and up to [`MESH_SAMPLES`] vertices, so a
/// reset stays cheap for imported homes of millions of vertices) and the embodiment.
///
/// Kept apart from [`fingerprint`], which seeds the actuation noise: changing that would
/// change the metrics of noisy runs.
pub(crate) fn content_key(scene: &Scene, agent_key: u64) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (fingerprint(scene), agent_key).hash(&mut h);
    scene.floor_height.to_bits().hash(&mut h);
    // The levels decide whether the agent follows the ground (none: nothing hashed, as before).
    for l in &scene.storeys.levels {
        l.floor_height.to_bits().hash(&mut h);
    }
    // Closed doors also bound Tel-Hops.
    for d in scene.doors.iter().filter(|d| d.is_closed()) {
        d.id.hash(&mut h);
        d.segment().map(|p| p.map(f32::to_bits)).hash(&mut h);
    }
    for o in &scene.objects {
        std::mem::discriminant(&o.class).hash(&mut h);
        for part in &o.parts {
            for v in part
                .transform
                .position
                .iter()
                .chain(&part.transform.rotation)
            {
                v.to_bits().hash(&mut h);
            }
            std::mem::discriminant(&part.shape).hash(&mut h);
            let floats: &[f32] = match &part.shape {
                Shape::Cuboid { half_extents, .. } => half_extents,
                Shape::Cylinder {
                    radius,
                    half_height,
                } => &[*radius, *half_height],
                Shape::Sphere { radius } => &[*radius],
                Shape::Mesh(m) => {
                    (m.positions.len(), m.indices.len()).hash(&mut h);
                    let stride = (m.positions.len() / MESH_SAMPLES).max(1);
                    for p in m.positions.iter().step_by(stride) {
                        p.map(f32::to_bits).hash(&mut h);
                    }
                    let stride = (m.indices.len() / MESH_SAMPLES).max(1);
                    for t in m.indices.iter().step_by(stride) {
                        t.hash(&mut h);
                    }
                    &[]
                }
            };
            for v in floats {
                v.to_bits().hash(&mut h);
            }
        }
    }
    h.finish()
}

/// A key of an embodiment (every field, floats by their exact text).
pub(crate) fn agent_key(agent: &AgentConfig) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    format!("{agent:?}").hash(&mut h);
    h.finish()
}

/// Bytes the physics world of `scene` will hold, estimated before it is built (the cache's
/// budget counts these): a fixed part, each shape part, and a triangle mesh's vertices,
/// triangles and BVH. The fixed and per-part figures are fitted on what the built worlds
/// allocate (`examples/memory.rs` prints both): 19 homes of the `tiny` and `vlnverse` presets,
/// 250-1,300 parts and 0.24-1.24 MB each, came within -19% to +24% of the estimate.
pub(crate) fn approx_bytes(scene: &Scene) -> usize {
    let mut bytes = 57 * 1024;
    for o in &scene.objects {
        for part in &o.parts {
            bytes += 880;
            if let Shape::Mesh(m) = &part.shape {
                bytes += m.positions.len() * 12 + m.indices.len() * (12 + 64);
            }
        }
    }
    bytes
}
