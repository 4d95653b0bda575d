//! The plain-data scene model shared by every layer.
//!
//! Conventions (docs/formats.md): metres, right-handed, **Y up**, the floor at `y = 0` for generated
//! homes; quaternions `[x, y, z, w]`. Everything in a home is a [`SceneObject`], walls and floor
//! included (their class says they are structure), so physics, rendering and occupancy walk one
//! list.

use crate::vocab::{RoomType, SemanticClass};
use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Current version of the `scene.json` format.
pub const SCENE_FORMAT_VERSION: u32 = 1;

/// Identifier of an object, unique within its scene (also its instance id in renders; 0 is
/// reserved for "nothing", so ids start at 1).
pub type ObjectId = u32;
/// Identifier of a room, unique within its scene.
pub type RoomId = u32;

/// Axis-aligned bounding box in world coordinates (metres).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Minimum corner.
    pub min: [f32; 3],
    /// Maximum corner.
    pub max: [f32; 3],
}

impl Aabb {
    /// The empty box (grows with [`Aabb::extend`]).
    pub const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    /// Box from two corners.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Aabb {
            min: min.to_array(),
            max: max.to_array(),
        }
    }

    /// Minimum corner as a vector.
    pub fn min_v(&self) -> Vec3 {
        Vec3::from_array(self.min)
    }

    /// Maximum corner as a vector.
    pub fn max_v(&self) -> Vec3 {
        Vec3::from_array(self.max)
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        (self.min_v() + self.max_v()) * 0.5
    }

    /// Full size along each axis.
    pub fn size(&self) -> Vec3 {
        self.max_v() - self.min_v()
    }

    /// Whether nothing was added yet.
    pub fn is_empty(&self) -> bool {
        self.min[0] > self.max[0]
    }

    /// Grow to contain a point.
    pub fn extend(&mut self, p: Vec3) {
        self.min = self.min_v().min(p).to_array();
        self.max = self.max_v().max(p).to_array();
    }

    /// Smallest box containing both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min_v().min(o.min_v()), self.max_v().max(o.max_v()))
    }

    /// Overlap volume test with a tolerance: boxes that only touch (or overlap by less than
    /// `eps` on some axis) do not intersect.
    pub fn intersects(&self, o: &Aabb, eps: f32) -> bool {
        (0..3).all(|i| self.min[i] + eps < o.max[i] && o.min[i] + eps < self.max[i])
    }

    /// Whether the XZ footprints overlap by more than `eps`.
    pub fn intersects_xz(&self, o: &Aabb, eps: f32) -> bool {
        [0, 2]
            .iter()
            .all(|&i| self.min[i] + eps < o.max[i] && o.min[i] + eps < self.max[i])
    }
}

/// A rigid transform: position and orientation (`[x, y, z, w]`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position in metres.
    pub position: [f32; 3],
    /// Unit quaternion `[x, y, z, w]`.
    pub rotation: [f32; 4],
}

impl Default for Pose {
    fn default() -> Self {
        Pose::IDENTITY
    }
}

impl Pose {
    /// No translation, no rotation.
    pub const IDENTITY: Pose = Pose {
        position: [0.0; 3],
        rotation: [0.0, 0.0, 0.0, 1.0],
    };

    /// Pose from a position and a yaw about +Y (counter-clockwise seen from above; yaw 0 looks
    /// along -Z).
    pub fn from_yaw(position: Vec3, yaw: f32) -> Self {
        Pose {
            position: position.to_array(),
            rotation: Quat::from_rotation_y(yaw).to_array(),
        }
    }

    /// Position as a vector.
    pub fn translation(&self) -> Vec3 {
        Vec3::from_array(self.position)
    }

    /// Rotation as a quaternion.
    pub fn quat(&self) -> Quat {
        Quat::from_array(self.rotation)
    }

    /// Yaw about +Y (radians), assuming the rotation is (close to) a pure yaw.
    pub fn yaw(&self) -> f32 {
        let fwd = self.quat() * Vec3::NEG_Z;
        (-fwd.x).atan2(-fwd.z)
    }

    /// Map a point from this pose's local frame to the parent frame.
    pub fn transform_point(&self, p: Vec3) -> Vec3 {
        self.quat() * p + self.translation()
    }

    /// Compose: `self * local` (apply `local` first, then `self`).
    pub fn mul(&self, local: &Pose) -> Pose {
        Pose {
            position: self.transform_point(local.translation()).to_array(),
            rotation: (self.quat() * local.quat()).normalize().to_array(),
        }
    }
}

/// Geometry of one part of an object, in the part's local frame (centred at its origin).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Shape {
    /// A box with the given half extents.
    Cuboid {
        /// Half sizes along x, y, z.
        half_extents: [f32; 3],
        /// Width in metres of the 45-degree chamfer on the four top edges (0: sharp edges).
        /// Only the drawn mesh is bevelled: physics and occupancy keep the full box, which contains it.
        #[serde(default, skip_serializing_if = "is_zero")]
        bevel: f32,
    },
    /// A cylinder around the local Y axis.
    Cylinder {
        /// Radius in metres.
        radius: f32,
        /// Half of the height.
        half_height: f32,
    },
    /// A sphere.
    Sphere {
        /// Radius in metres.
        radius: f32,
    },
    /// An arbitrary triangle mesh (imported scenes). In `scene.json` the vertex data is not
    /// written: it lives in `scene.glb` and is restored from there on load.
    Mesh(MeshData),
}

impl Shape {
    /// Nominal volume in cubic metres, used to rank an object's parts (its largest part gives
    /// the colour and shape words of instructions): boxes ignore their bevel, spheres use
    /// 4.19 for 4/3 pi (kept as it was: the ranking and so the released instructions depend on
    /// it), meshes count 0.
    pub fn nominal_volume(&self) -> f32 {
        match self {
            Shape::Cuboid {
                half_extents: h, ..
            } => 8.0 * h[0] * h[1] * h[2],
            Shape::Cylinder {
                radius,
                half_height,
            } => std::f32::consts::PI * radius * radius * 2.0 * half_height,
            Shape::Sphere { radius } => 4.19 * radius * radius * radius,
            Shape::Mesh(_) => 0.0,
        }
    }
}

/// Triangle mesh data.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshData {
    /// Vertex positions.
    #[serde(skip)]
    pub positions: Vec<[f32; 3]>,
    /// Triangles as vertex index triples.
    #[serde(skip)]
    pub indices: Vec<[u32; 3]>,
    /// Index of the glTF mesh in `scene.glb` holding the data.
    pub glb_mesh: Option<u32>,
    /// Base-colour texture coordinates per vertex (glTF convention: `(0, 0)` is the image's
    /// top-left corner, `v` runs down, repeating), empty when the part has no [`MeshTexture`].
    /// Not in `scene.json`: restored from `scene.glb` (`TEXCOORD_0`) like the positions.
    #[serde(skip)]
    pub uvs: Vec<[f32; 2]>,
    /// The part's own base-colour texture (imported homes), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<MeshTexture>,
}

/// A base-colour image texture of a mesh part, as imported from glTF. The part's
/// [`Part::color`] stays its flat colour (`factor` times the image's mean), which is what
/// consumers without textures (maps, language, flat shading) use.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshTexture {
    /// glTF `baseColorFactor` (linear RGB), multiplied with the image.
    pub factor: [f32; 3],
    /// Image width in texels (a power of two, at most [`MeshTexture::MAX_SIDE`]).
    pub width: u32,
    /// Image height in texels (a power of two, at most [`MeshTexture::MAX_SIDE`]).
    pub height: u32,
    /// `width * height` sRGB-encoded RGB texels, row-major, `v` down the rows. Not in
    /// `scene.json`: restored from the image in `scene.glb`. Shared between parts that use the
    /// same image.
    #[serde(skip)]
    pub texels: Arc<Vec<[u8; 3]>>,
}

impl MeshTexture {
    /// Largest side of an imported texture (larger images are resampled down).
    pub const MAX_SIDE: u32 = 1024;

    /// Whether the image has the sides and texel count the renderers rely on.
    pub fn is_valid(&self) -> bool {
        self.width.is_power_of_two()
            && self.height.is_power_of_two()
            && self.width <= Self::MAX_SIDE
            && self.height <= Self::MAX_SIDE
            && self.texels.len() == (self.width * self.height) as usize
    }

    /// Mean linear colour of the image (sRGB decoded; black for an empty image).
    pub fn mean_linear(&self) -> [f32; 3] {
        let lut: Vec<f64> = (0..256)
            .map(|i| srgb_to_linear(i as f32 / 255.0) as f64)
            .collect();
        let mut sum = [0.0f64; 3];
        for t in self.texels.iter() {
            for k in 0..3 {
                sum[k] += lut[t[k] as usize];
            }
        }
        let n = self.texels.len().max(1) as f64;
        sum.map(|s| (s / n) as f32)
    }
}

/// sRGB -> linear transfer function for one channel in `[0, 1]`.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// One primitive of an object: shape, placement relative to the object, colour.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Part {
    /// Geometry in the part frame.
    pub shape: Shape,
    /// Part frame relative to the object's pose.
    pub transform: Pose,
    /// Linear RGB base colour in `[0, 1]`.
    pub color: [f32; 3],
}

/// Whether the physics layer may move an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Motion {
    /// Never moves (walls, heavy furniture).
    Static,
    /// A dynamic rigid body the agent can push (chairs, stools, small objects).
    Dynamic,
}

/// Physical properties used by the simulator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Physics {
    /// Mass in kilograms.
    pub mass: f32,
    /// Coulomb friction coefficient.
    pub friction: f32,
    /// Static or dynamic.
    pub motion: Motion,
}

/// Anything in a scene: walls, floor, furniture and small objects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneObject {
    /// Unique id within the scene (>= 1).
    pub id: ObjectId,
    /// Human-readable unique name, e.g. `chair_12` (the glTF node name).
    pub name: String,
    /// Semantic class.
    pub class: SemanticClass,
    /// Room the object stands in (None for walls and anything outside rooms).
    pub room: Option<RoomId>,
    /// Object frame in world coordinates.
    pub pose: Pose,
    /// World-space bounding box of all parts.
    pub bbox: Aabb,
    /// Colour word used in language ("red", "wooden", "white").
    pub color: String,
    /// Material word ("wood", "metal", "fabric", ...).
    pub material: String,
    /// The shade of the colour word that the object's maker chose ("navy" for a blue sofa,
    /// "oak" for a wooden one), when it chose one; language reads its words from it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shade: Option<String>,
    /// Features of the object's model that tell it from others of its class, as the maker
    /// names them ("footboard", "armless"); language turns them into phrases.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub features: Vec<String>,
    /// Mass, friction, static/dynamic.
    pub physics: Physics,
    /// The object this one stands on (`X on Y`), if any.
    pub supported_by: Option<ObjectId>,
    /// Geometry, in the object frame.
    pub parts: Vec<Part>,
}

impl SceneObject {
    /// A static object named `<class>_<id>`, in no room, with its bounding box computed from
    /// `parts`; words `white` / `plaster`, 10 kg, friction 0.5. Hand-made scenes and fixtures
    /// set the fields they care about afterwards.
    pub fn from_parts(id: ObjectId, class: SemanticClass, pose: Pose, parts: Vec<Part>) -> Self {
        let mut o = SceneObject {
            id,
            name: format!("{}_{id}", class.name()),
            class,
            room: None,
            pose,
            bbox: Aabb::EMPTY,
            color: "white".into(),
            material: "plaster".into(),
            shade: None,
            features: Vec::new(),
            physics: Physics {
                mass: 10.0,
                friction: 0.5,
                motion: Motion::Static,
            },
            supported_by: None,
            parts,
        };
        o.bbox = o.compute_bbox();
        o
    }

    /// An axis-aligned box between the world corners `min` and `max` (one light grey cuboid
    /// part, the pose at its centre), otherwise as [`SceneObject::from_parts`].
    pub fn cuboid(id: ObjectId, class: SemanticClass, min: Vec3, max: Vec3) -> Self {
        let part = Part {
            shape: Shape::Cuboid {
                half_extents: ((max - min) * 0.5).to_array(),
                bevel: 0.0,
            },
            transform: Pose::IDENTITY,
            color: [0.8, 0.8, 0.8],
        };
        Self::from_parts(
            id,
            class,
            Pose::from_yaw((min + max) * 0.5, 0.0),
            vec![part],
        )
    }

    /// Whether the object is building structure.
    pub fn is_structure(&self) -> bool {
        self.class.is_structure()
    }

    /// Recompute `bbox` from the parts and the pose.
    pub fn compute_bbox(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for part in &self.parts {
            let t = self.pose.mul(&part.transform);
            for p in crate::geometry::shape_corners(&part.shape) {
                b.extend(t.transform_point(p));
            }
        }
        b
    }
}

/// A room: type, floor polygon (x, z), name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Room {
    /// Unique id within the scene.
    pub id: RoomId,
    /// Room type.
    pub kind: RoomType,
    /// Unique name, e.g. `bedroom_2`.
    pub name: String,
    /// Floor polygon as `[x, z]` points, counter-clockwise seen from above.
    pub polygon: Vec<[f32; 2]>,
}

impl Room {
    /// Floor area of the polygon (m^2).
    pub fn area(&self) -> f32 {
        let n = self.polygon.len();
        let mut a = 0.0;
        for i in 0..n {
            let p = self.polygon[i];
            let q = self.polygon[(i + 1) % n];
            a += p[0] * q[1] - q[0] * p[1];
        }
        (a * 0.5).abs()
    }

    /// Whether the point `(x, z)` is inside the polygon.
    pub fn contains(&self, x: f32, z: f32) -> bool {
        let n = self.polygon.len();
        let mut inside = false;
        let mut j = n.wrapping_sub(1);
        for i in 0..n {
            let (pi, pj) = (self.polygon[i], self.polygon[j]);
            if (pi[1] > z) != (pj[1] > z)
                && x < (pj[0] - pi[0]) * (z - pi[1]) / (pj[1] - pi[1]) + pi[0]
            {
                inside = !inside;
            }
            j = i;
        }
        inside
    }

    /// Centroid of the polygon's vertices.
    pub fn center(&self) -> [f32; 2] {
        let n = self.polygon.len().max(1) as f32;
        let (sx, sz) = self
            .polygon
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p[0], b + p[1]));
        [sx / n, sz / n]
    }
}

/// A doorway (with a frame) or an open-plan opening between two rooms.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Door {
    /// Unique id within the scene.
    pub id: u32,
    /// Centre of the opening on the floor.
    pub position: [f32; 3],
    /// Clear width of the opening (m).
    pub width: f32,
    /// Unit normal of the wall the opening is cut in, `[x, z]`.
    pub normal: [f32; 2],
    /// The two rooms the opening connects.
    pub rooms: [RoomId; 2],
    /// True for a wide open-plan connection without a door frame.
    pub open_plan: bool,
    /// Whether the door leaf stands open or closed; `None` for open-plan openings and doorways
    /// without a leaf (scenes written before doors had leaves).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<DoorState>,
    /// The object (class `door`) that is the leaf, if the doorway has one (of a pair of french
    /// doors the first; see `second_leaf` and [`Door::leaves`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leaf: Option<ObjectId>,
    /// The other leaf of a pair of french doors (class `door`, in the same state); `None` for
    /// every other kind.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_leaf: Option<ObjectId>,
    /// What kind of doorway this is. `hinged` (the default) is not written, so open-plan
    /// openings, bare doorways, hinged doors and scenes written before doors had kinds carry no
    /// `kind` in `scene.json`.
    #[serde(default, skip_serializing_if = "DoorKind::is_hinged")]
    pub kind: DoorKind,
}

/// The kind of a doorway: how its leaf opens, or an arched doorway without one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DoorKind {
    /// One solid leaf on hinges that swings into a room when open.
    #[default]
    Hinged,
    /// A glass panel (class `door`, material `glass`) that slides along the wall: open, it lies
    /// flat against the wall beside the opening.
    Sliding,
    /// Two glass-paned leaves, each half the width, hinged at the two jambs (`leaf` and
    /// `second_leaf`); open, both swing into the same room.
    French,
    /// No leaf: the wall above the opening is shaped as a round arch, clear of the door head.
    Arched,
}

impl DoorKind {
    /// Every kind, in order.
    pub const ALL: [DoorKind; 4] = [
        DoorKind::Hinged,
        DoorKind::Sliding,
        DoorKind::French,
        DoorKind::Arched,
    ];

    /// The word used in files and text: `hinged`, `sliding`, `french` or `arched`.
    pub fn name(self) -> &'static str {
        match self {
            DoorKind::Hinged => "hinged",
            DoorKind::Sliding => "sliding",
            DoorKind::French => "french",
            DoorKind::Arched => "arched",
        }
    }

    /// Whether this is the default kind, `hinged` (not written to `scene.json`).
    pub fn is_hinged(&self) -> bool {
        *self == DoorKind::Hinged
    }

    /// Whether the leaves of this kind are glass panes in a frame (object material `glass`).
    pub fn is_glass(self) -> bool {
        matches!(self, DoorKind::Sliding | DoorKind::French)
    }
}

/// State of a door leaf. A closed leaf fills its doorway: it blocks the agent in every setting,
/// the maps mark it occupied and routes go round it (agents cannot open doors yet).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DoorState {
    /// Swung open into one of the rooms, clear of the doorway.
    Open,
    /// Shut in the doorway.
    Closed,
}

impl DoorState {
    /// The word used in files and text: `open` or `closed`.
    pub fn name(self) -> &'static str {
        match self {
            DoorState::Open => "open",
            DoorState::Closed => "closed",
        }
    }
}

impl Door {
    /// Whether a closed leaf blocks the doorway.
    pub fn is_closed(&self) -> bool {
        self.state == Some(DoorState::Closed)
    }

    /// The doorway's leaf objects: none, one, or two for french doors.
    pub fn leaves(&self) -> impl Iterator<Item = ObjectId> + '_ {
        self.leaf.into_iter().chain(self.second_leaf)
    }

    /// The doorway as a floor segment `[x, z]` to `[x, z]` across its clear width, in the
    /// plane of the wall.
    pub fn segment(&self) -> [[f32; 2]; 2] {
        let [x, _, z] = self.position;
        // Along the wall: the normal turned by 90 degrees.
        let (ax, az) = (-self.normal[1], self.normal[0]);
        let h = self.width * 0.5;
        [[x - ax * h, z - az * h], [x + ax * h, z + az * h]]
    }

    /// Whether the floor segment from `a` to `b` (`[x, z]`) passes through the doorway.
    pub fn crossed_by(&self, a: [f32; 2], b: [f32; 2]) -> bool {
        let [p, q] = self.segment();
        segments_cross(a, b, p, q)
    }
}

/// Whether two floor segments `a`-`b` and `c`-`d` (`[x, z]`) intersect; touching counts.
pub fn segments_cross(a: [f32; 2], b: [f32; 2], c: [f32; 2], d: [f32; 2]) -> bool {
    let cross = |o: [f32; 2], p: [f32; 2], q: [f32; 2]| {
        (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
    };
    let (d1, d2) = (cross(c, d, a), cross(c, d, b));
    let (d3, d4) = (cross(a, b, c), cross(a, b, d));
    let opposite = |u: f32, v: f32| (u <= 0.0 && v >= 0.0) || (u >= 0.0 && v <= 0.0);
    opposite(d1, d2) && opposite(d3, d4) && !(d1 == 0.0 && d2 == 0.0)
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// `scene.json` format version.
    pub format_version: u32,
    /// Scene id (also the folder name).
    pub id: String,
    /// Where it came from: `procgen` or `import:<file>`.
    pub source: String,
    /// Seed that generated it, for procedural scenes.
    pub seed: Option<u64>,
    /// Height of the walkable floor (y).
    pub floor_height: f32,
    /// Rooms.
    pub rooms: Vec<Room>,
    /// Doors and openings.
    pub doors: Vec<Door>,
    /// All objects, structure included, sorted by id.
    pub objects: Vec<SceneObject>,
    /// Levels (storeys) and stairs of a home on more than one floor; empty for a single-storey
    /// scene (every scene written before storeys existed), which has one implicit level at
    /// `floor_height` holding every room. In `scene.json` its fields are top-level keys
    /// (`levels`, `stairs`), each left out when empty.
    #[serde(flatten)]
    pub storeys: Storeys,
}

/// Identifier of a level (storey) within its scene: its index in [`Storeys::levels`], the
/// ground floor first.
pub type LevelId = u32;

/// The levels and stairs of a scene (see [`Scene::storeys`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Storeys {
    /// Levels from the lowest up; empty: one implicit level at [`Scene::floor_height`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub levels: Vec<Level>,
    /// Flights of stairs between levels.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stairs: Vec<Stairs>,
}

impl Storeys {
    /// Whether the scene is single-storey (no levels listed).
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty() && self.stairs.is_empty()
    }
}

/// One storey of a home: the height of its walkable floor and the rooms on it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Level {
    /// Index of the level, from 0 (the lowest) up.
    pub id: LevelId,
    /// Words for the level: `ground floor`, `upper floor`.
    pub name: String,
    /// y of the level's walkable floor (m).
    pub floor_height: f32,
    /// The rooms on this level.
    pub rooms: Vec<RoomId>,
}

/// A straight flight of stairs between two levels. The agent walks onto it at `foot` (on the
/// lower level, in front of the first step) and leaves it at `head` (on the upper level, past
/// the last step); the flight rises `steps` times by `rise` over `steps - 1` treads of `run`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Stairs {
    /// Unique id within the scene.
    pub id: u32,
    /// The lower and the upper level it joins.
    pub levels: [LevelId; 2],
    /// The object (class `stairs`) that is the flight, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object: Option<ObjectId>,
    /// The flight's floor outline as `[x, z]` points, counter-clockwise seen from above.
    pub footprint: Vec<[f32; 2]>,
    /// Where a walk up begins: a point on the lower level's floor in front of the first step.
    pub foot: [f32; 3],
    /// Where a walk up ends: a point on the upper level's floor past the last step.
    pub head: [f32; 3],
    /// Number of risers (the last one reaches the upper floor).
    pub steps: u32,
    /// Height of one riser (m).
    pub rise: f32,
    /// Depth of one tread (m).
    pub run: f32,
    /// Clear width of the flight (m).
    pub width: f32,
}

impl Stairs {
    /// Length of the walk from `foot` to `head` along the flight: the flat legs to and from the
    /// steps and the sloped flight between them (m).
    pub fn walk_length(&self) -> f32 {
        let flight = (self.steps.saturating_sub(1)) as f32 * self.run;
        let dx = self.head[0] - self.foot[0];
        let dz = self.head[2] - self.foot[2];
        let flat = ((dx * dx + dz * dz).sqrt() - flight).max(0.0);
        let rise = self.head[1] - self.foot[1];
        flat + (flight * flight + rise * rise).sqrt()
    }

    /// Pitch of the flight: the angle of the line over the step nosings (radians).
    pub fn pitch(&self) -> f32 {
        self.rise.atan2(self.run)
    }
}

impl Scene {
    /// Bounding box of every object.
    pub fn bounds(&self) -> Aabb {
        self.objects
            .iter()
            .fold(Aabb::EMPTY, |acc, o| acc.union(&o.bbox))
    }

    /// Object by id.
    pub fn object(&self, id: ObjectId) -> Option<&SceneObject> {
        self.objects
            .binary_search_by_key(&id, |o| o.id)
            .ok()
            .map(|i| &self.objects[i])
            .or_else(|| self.objects.iter().find(|o| o.id == id))
    }

    /// Room by id.
    pub fn room(&self, id: RoomId) -> Option<&Room> {
        self.rooms.iter().find(|r| r.id == id)
    }

    /// The room containing the floor point `(x, z)`, if any.
    pub fn room_at(&self, x: f32, z: f32) -> Option<&Room> {
        self.rooms.iter().find(|r| r.contains(x, z))
    }

    /// Objects that are not structure (furniture, small objects, unknown).
    pub fn items(&self) -> impl Iterator<Item = &SceneObject> {
        self.objects.iter().filter(|o| !o.is_structure())
    }

    /// The doors (with a leaf or not, open plan included) that the floor polyline `path`
    /// (`[x, z]` points) passes through, in the order it meets them; a door met twice is listed
    /// twice. With the door's `leaf` and `state` this tells which door leaves a route passes.
    pub fn doors_on_path(&self, path: &[[f32; 2]]) -> Vec<&Door> {
        let mut out = Vec::new();
        for w in path.windows(2) {
            let mut hits: Vec<(f32, &Door)> = self
                .doors
                .iter()
                .filter(|d| d.crossed_by(w[0], w[1]))
                .map(|d| {
                    let dx = d.position[0] - w[0][0];
                    let dz = d.position[2] - w[0][1];
                    (dx * dx + dz * dz, d)
                })
                .collect();
            hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.id.cmp(&b.1.id)));
            for (_, d) in hits {
                // A path vertex exactly in a doorway touches it from both segments.
                if out.last().is_some_and(|l: &&Door| l.id == d.id) && on_segment(w[0], d) {
                    continue;
                }
                out.push(d);
            }
        }
        out
    }

    /// Number of levels (1 for a single-storey scene).
    pub fn level_count(&self) -> usize {
        self.storeys.levels.len().max(1)
    }

    /// Whether the scene has more than one level.
    pub fn is_multi_level(&self) -> bool {
        self.storeys.levels.len() > 1
    }

    /// Floor height of a level (`floor_height` for level 0 of a single-storey scene); None for a
    /// level the scene does not have.
    pub fn level_height(&self, level: LevelId) -> Option<f32> {
        if self.storeys.levels.is_empty() {
            return (level == 0).then_some(self.floor_height);
        }
        self.storeys
            .levels
            .get(level as usize)
            .map(|l| l.floor_height)
    }

    /// The level a room is on (0 for every room of a single-storey scene); None when a
    /// multi-level scene lists the room on no level.
    pub fn room_level(&self, room: RoomId) -> Option<LevelId> {
        if self.storeys.levels.is_empty() {
            return Some(0);
        }
        self.storeys
            .levels
            .iter()
            .find(|l| l.rooms.contains(&room))
            .map(|l| l.id)
    }

    /// The level whose floor is the highest at or below `y` (plus a 0.25 m tolerance for a
    /// point on a step or a sensor slightly below the floor); level 0 below every floor.
    pub fn level_at_height(&self, y: f32) -> LevelId {
        let mut out = 0;
        for l in &self.storeys.levels {
            if l.floor_height <= y + 0.25 {
                out = l.id;
            }
        }
        out
    }

    /// The room on `level` containing the floor point `(x, z)`, if any (rooms of different
    /// levels overlap in plan).
    pub fn room_at_level(&self, level: LevelId, x: f32, z: f32) -> Option<&Room> {
        self.rooms
            .iter()
            .find(|r| self.room_level(r.id) == Some(level) && r.contains(x, z))
    }

    /// The part of the scene on one level, as a single-storey scene with that level's floor
    /// height: its rooms, the doors between them, the objects in them, the objects in no room
    /// (walls, frames) whose bottom lies between this level's floor and the next one's, and the
    /// flights of stairs that reach it. A single-storey scene's level 0 is the scene itself;
    /// None for a level the scene does not have.
    pub fn level_view(&self, level: LevelId) -> Option<Scene> {
        let floor = self.level_height(level)?;
        if !self.is_multi_level() {
            return Some(self.clone());
        }
        let next = self.level_height(level + 1).unwrap_or(f32::INFINITY);
        let on = |r: RoomId| self.room_level(r) == Some(level);
        let flights: Vec<ObjectId> = self
            .storeys
            .stairs
            .iter()
            .filter(|s| s.levels.contains(&level))
            .filter_map(|s| s.object)
            .collect();
        let keep = |o: &SceneObject| match o.room {
            _ if flights.contains(&o.id) => true,
            Some(r) => on(r),
            None => o.bbox.min[1] >= floor - 0.1 && o.bbox.min[1] < next - 0.1,
        };
        Some(Scene {
            format_version: self.format_version,
            id: self.id.clone(),
            source: self.source.clone(),
            seed: self.seed,
            floor_height: floor,
            rooms: self.rooms.iter().filter(|r| on(r.id)).cloned().collect(),
            doors: self
                .doors
                .iter()
                .filter(|d| d.rooms.iter().all(|&r| on(r)))
                .cloned()
                .collect(),
            objects: self.objects.iter().filter(|o| keep(o)).cloned().collect(),
            storeys: Storeys::default(),
        })
    }

    /// Check the levels and stairs: levels numbered from 0 in rising floor height, level 0 at
    /// `floor_height`, every room on exactly one level, every stair between two existing levels
    /// (lower first) with positive steps, rise, run and width and finite points. Single-storey
    /// scenes always pass. The error names the field and the value.
    pub fn validate_storeys(&self) -> crate::Result<()> {
        use crate::EnvError;
        let st = &self.storeys;
        if st.levels.is_empty() {
            if let Some(s) = st.stairs.first() {
                return Err(EnvError::invalid(
                    format!("stairs[{}]", s.id),
                    "(no levels)",
                    "stairs need the scene's `levels`",
                ));
            }
            return Ok(());
        }
        for (i, l) in st.levels.iter().enumerate() {
            let field = |f: &str| format!("levels[{i}].{f}");
            if l.id as usize != i {
                return Err(EnvError::invalid(field("id"), l.id, format!("must be {i}")));
            }
            if !l.floor_height.is_finite() {
                return Err(EnvError::invalid(
                    field("floor_height"),
                    l.floor_height,
                    "must be finite",
                ));
            }
            if i == 0 && l.floor_height != self.floor_height {
                return Err(EnvError::invalid(
                    field("floor_height"),
                    l.floor_height,
                    format!(
                        "must equal the scene's floor_height = {}",
                        self.floor_height
                    ),
                ));
            }
            if i > 0 && l.floor_height <= st.levels[i - 1].floor_height {
                return Err(EnvError::invalid(
                    field("floor_height"),
                    l.floor_height,
                    "must be above the level below",
                ));
            }
        }
        for r in &self.rooms {
            let on = st.levels.iter().filter(|l| l.rooms.contains(&r.id)).count();
            if on != 1 {
                return Err(EnvError::invalid(
                    format!("room {}", r.id),
                    &r.name,
                    format!("is listed on {on} levels; every room must be on exactly one"),
                ));
            }
        }
        for s in &st.stairs {
            let field = |f: &str| format!("stairs[{}].{f}", s.id);
            let [lo, hi] = s.levels;
            if lo >= hi || hi as usize >= st.levels.len() {
                return Err(EnvError::invalid(
                    field("levels"),
                    format!("{:?}", s.levels),
                    format!(
                        "must name two of the {} levels, the lower first",
                        st.levels.len()
                    ),
                ));
            }
            let positive = [
                ("rise", s.rise),
                ("run", s.run),
                ("width", s.width),
                ("steps", s.steps as f32),
            ];
            for (f, v) in positive {
                if !(v.is_finite() && v > 0.0) {
                    return Err(EnvError::invalid(field(f), v, "must be a positive number"));
                }
            }
            let finite = s.foot.iter().chain(&s.head).all(|v| v.is_finite())
                && s.footprint.len() >= 3
                && s.footprint.iter().flatten().all(|v| v.is_finite());
            if !finite {
                return Err(EnvError::invalid(
                    field("foot/head/footprint"),
                    format!("{:?} {:?}", s.foot, s.head),
                    "needs finite points and a footprint of at least 3",
                ));
            }
        }
        Ok(())
    }

    /// Total number of triangles when every part is triangulated.
    pub fn triangle_count(&self) -> usize {
        self.objects
            .iter()
            .flat_map(|o| &o.parts)
            .map(|p| crate::geometry::triangle_count(&p.shape))
            .sum()
    }
}

/// Whether the point lies on the doorway's segment (within a millimetre).
fn on_segment(p: [f32; 2], d: &Door) -> bool {
    let [a, b] = d.segment();
    let (ux, uz) = (b[0] - a[0], b[1] - a[1]);
    let len2 = (ux * ux + uz * uz).max(1e-12);
    let t = (((p[0] - a[0]) * ux + (p[1] - a[1]) * uz) / len2).clamp(0.0, 1.0);
    let (cx, cz) = (a[0] + ux * t - p[0], a[1] + uz * t - p[1]);
    cx * cx + cz * cz < 1e-6
}

/// Serde helper: a bevel of 0 is left out of `scene.json`, which keeps sharp-edged scenes
/// byte-identical to files written before bevels existed.
fn is_zero(v: &f32) -> bool {
    *v == 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_round_trips() {
        for yaw in [-3.0f32, -1.0, 0.0, 0.5, 1.5, 3.0] {
            let p = Pose::from_yaw(Vec3::ZERO, yaw);
            assert!((p.yaw() - yaw).abs() < 1e-5, "{yaw} -> {}", p.yaw());
        }
        // yaw 0 looks along -Z; +90 deg (counter-clockwise from above) looks along -X.
        let p = Pose::from_yaw(Vec3::ZERO, std::f32::consts::FRAC_PI_2);
        let fwd = p.quat() * Vec3::NEG_Z;
        assert!((fwd - Vec3::NEG_X).length() < 1e-5);
    }

    #[test]
    fn room_area_and_contains() {
        let r = Room {
            id: 0,
            kind: RoomType::Bedroom,
            name: "bedroom_0".into(),
            polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]],
        };
        assert!((r.area() - 12.0).abs() < 1e-6);
        assert!(r.contains(1.0, 1.0));
        assert!(!r.contains(5.0, 1.0));
    }

    #[test]
    fn aabb_touching_boxes_do_not_intersect() {
        let a = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let b = Aabb::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0));
        assert!(!a.intersects(&b, 1e-4));
        let c = Aabb::new(Vec3::splat(0.5), Vec3::splat(1.5));
        assert!(a.intersects(&c, 1e-4));
    }
}
