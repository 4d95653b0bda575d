//! A deterministic synthetic home (a grid of rooms joined by doors, with furniture), for
//! benchmarks and tests that need a realistic map before any generator exists.

use crate::scene::{Part, Pose, Scene, SceneObject, Shape, SCENE_FORMAT_VERSION};
use crate::vocab::SemanticClass;
use glam::Vec3;

struct SplitMix(u64);

impl SplitMix {
    fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Wooden, 20 kg, friction 0.6, brown parts (what the benchmarks have always measured).
fn wooden(mut o: SceneObject) -> SceneObject {
    for p in &mut o.parts {
        p.color = [0.7, 0.6, 0.5];
    }
    o.material = "wood".into();
    o.physics.mass = 20.0;
    o.physics.friction = 0.6;
    o
}

fn object(id: u32, class: SemanticClass, pose: Pose, shape: Shape) -> SceneObject {
    let part = Part {
        shape,
        transform: Pose::IDENTITY,
        color: [0.7, 0.6, 0.5],
    };
    wooden(SceneObject::from_parts(id, class, pose, vec![part]))
}

fn block(id: u32, class: SemanticClass, min: Vec3, max: Vec3) -> SceneObject {
    wooden(SceneObject::cuboid(id, class, min, max))
}

/// A home of `rooms_x` x `rooms_z` square rooms of side `room_size` metres (walls 0.1 m thick,
/// 2.5 m high, a 1 m door in every wall between two rooms), each with a few yawed boxes and a
/// round pillar placed from `seed`. Floor at y = 0, one floor slab, ceiling included.
pub fn grid_home(rooms_x: u32, rooms_z: u32, room_size: f32, seed: u64) -> Scene {
    let mut rng = SplitMix(seed);
    let mut objs = Vec::new();
    let mut id = 1;
    let mut next_id = || {
        id += 1;
        id - 1
    };
    let (w, d) = (rooms_x as f32 * room_size, rooms_z as f32 * room_size);
    let (t, h) = (0.05, 2.5);
    objs.push(block(
        next_id(),
        SemanticClass::Floor,
        Vec3::new(-t, -0.1, -t),
        Vec3::new(w + t, 0.0, d + t),
    ));
    objs.push(block(
        next_id(),
        SemanticClass::Ceiling,
        Vec3::new(-t, h, -t),
        Vec3::new(w + t, h + 0.1, d + t),
    ));
    // Walls along x (constant z), split around doors; then along z.
    let door = 1.0;
    for k in 0..=rooms_z {
        let z = k as f32 * room_size;
        for i in 0..rooms_x {
            let (x0, x1) = (i as f32 * room_size, (i + 1) as f32 * room_size);
            let inner = k > 0 && k < rooms_z;
            let pieces = if inner {
                let c = (x0 + x1) * 0.5;
                vec![(x0, c - door / 2.0), (c + door / 2.0, x1)]
            } else {
                vec![(x0, x1)]
            };
            for (a, b) in pieces {
                objs.push(block(
                    next_id(),
                    SemanticClass::Wall,
                    Vec3::new(a - t, 0.0, z - t),
                    Vec3::new(b + t, h, z + t),
                ));
            }
        }
    }
    for k in 0..=rooms_x {
        let x = k as f32 * room_size;
        for j in 0..rooms_z {
            let (z0, z1) = (j as f32 * room_size, (j + 1) as f32 * room_size);
            let inner = k > 0 && k < rooms_x;
            let pieces = if inner {
                let c = (z0 + z1) * 0.5;
                vec![(z0, c - door / 2.0), (c + door / 2.0, z1)]
            } else {
                vec![(z0, z1)]
            };
            for (a, b) in pieces {
                objs.push(block(
                    next_id(),
                    SemanticClass::Wall,
                    Vec3::new(x - t, 0.0, a - t),
                    Vec3::new(x + t, h, b + t),
                ));
            }
        }
    }
    // Furniture kept away from the doors (which sit at the middle of each wall).
    let classes = [
        SemanticClass::Sofa,
        SemanticClass::Bed,
        SemanticClass::DiningTable,
        SemanticClass::Bookshelf,
    ];
    for i in 0..rooms_x {
        for j in 0..rooms_z {
            let (x0, z0) = (i as f32 * room_size, j as f32 * room_size);
            for (q, class) in classes.iter().enumerate() {
                // One piece per quadrant, centred in it.
                let qx = if q % 2 == 0 { 0.25 } else { 0.75 };
                let qz = if q < 2 { 0.25 } else { 0.75 };
                let c = Vec3::new(
                    x0 + room_size * qx + (rng.next_f32() - 0.5) * 0.3,
                    0.4,
                    z0 + room_size * qz + (rng.next_f32() - 0.5) * 0.3,
                );
                let half = [0.3 + rng.next_f32() * 0.4, 0.4, 0.2 + rng.next_f32() * 0.3];
                objs.push(object(
                    next_id(),
                    *class,
                    Pose::from_yaw(c, rng.next_f32() * std::f32::consts::PI),
                    Shape::Cuboid {
                        half_extents: half,
                        bevel: 0.0,
                    },
                ));
            }
            objs.push(object(
                next_id(),
                SemanticClass::PottedPlant,
                Pose::from_yaw(
                    Vec3::new(x0 + room_size * 0.5, 0.5, z0 + room_size * 0.5),
                    0.0,
                ),
                Shape::Cylinder {
                    radius: 0.25,
                    half_height: 0.5,
                },
            ));
        }
    }
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: format!("grid_home_{rooms_x}x{rooms_z}_{seed}"),
        source: "synthetic".into(),
        seed: Some(seed),
        floor_height: 0.0,
        rooms: Vec::new(),
        doors: Vec::new(),
        objects: objs,
        storeys: Default::default(),
    }
}
