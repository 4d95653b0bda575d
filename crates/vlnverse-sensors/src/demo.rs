//! A small furnished two-room home built by hand, for examples, tests and benchmarks that must
//! run without the procedural generator. Deterministic from its seed.

use glam::{Quat, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{
    Motion, Part, Physics, Pose, Room, RoomType, Scene, SceneObject, SemanticClass, Shape,
    SCENE_FORMAT_VERSION,
};

/// Width (x) of the home in metres; it spans `x in [0, WIDTH]`.
pub const WIDTH: f32 = 8.0;
/// Depth (z) of the home in metres; it spans `z in [0, DEPTH]`.
pub const DEPTH: f32 = 6.0;
/// Ceiling height in metres.
pub const HEIGHT: f32 = 2.7;

fn cuboid(center: Vec3, half: Vec3, color: [f32; 3]) -> Part {
    Part {
        shape: Shape::Cuboid {
            half_extents: half.to_array(),
            bevel: 0.0,
        },
        transform: Pose {
            position: center.to_array(),
            rotation: [0.0, 0.0, 0.0, 1.0],
        },
        color,
    }
}

/// A two-room home (living room and bedroom joined by a doorway) with furniture placed from
/// `seed`: boxes, cylinders and spheres, so every primitive of the triangulation is present.
pub fn demo_scene(seed: u64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut objects: Vec<SceneObject> = Vec::new();
    let mut add = |class: SemanticClass, pose: Pose, parts: Vec<Part>, motion: Motion| {
        let id = objects.len() as u32 + 1;
        let mut o = SceneObject {
            id,
            name: format!("{}_{id}", class.name()),
            class,
            room: None,
            pose,
            bbox: vlnverse_env::Aabb::EMPTY,
            color: "grey".into(),
            material: "wood".into(),
            shade: None,
            features: Vec::new(),
            physics: Physics {
                mass: 10.0,
                friction: 0.6,
                motion,
            },
            supported_by: None,
            parts,
        };
        o.bbox = o.compute_bbox();
        objects.push(o);
    };
    let s = Motion::Static;
    let (w, d, h, t) = (WIDTH, DEPTH, HEIGHT, 0.1);
    add(
        SemanticClass::Floor,
        Pose::IDENTITY,
        vec![cuboid(
            Vec3::new(w / 2.0, -t / 2.0, d / 2.0),
            Vec3::new(w / 2.0, t / 2.0, d / 2.0),
            [0.55, 0.42, 0.3],
        )],
        s,
    );
    add(
        SemanticClass::Ceiling,
        Pose::IDENTITY,
        vec![cuboid(
            Vec3::new(w / 2.0, h + t / 2.0, d / 2.0),
            Vec3::new(w / 2.0, t / 2.0, d / 2.0),
            [0.9, 0.9, 0.88],
        )],
        s,
    );
    let wall = [0.8, 0.78, 0.7];
    for (c, half) in [
        (
            Vec3::new(w / 2.0, h / 2.0, -t / 2.0),
            Vec3::new(w / 2.0 + t, h / 2.0, t / 2.0),
        ),
        (
            Vec3::new(w / 2.0, h / 2.0, d + t / 2.0),
            Vec3::new(w / 2.0 + t, h / 2.0, t / 2.0),
        ),
        (
            Vec3::new(-t / 2.0, h / 2.0, d / 2.0),
            Vec3::new(t / 2.0, h / 2.0, d / 2.0),
        ),
        (
            Vec3::new(w + t / 2.0, h / 2.0, d / 2.0),
            Vec3::new(t / 2.0, h / 2.0, d / 2.0),
        ),
    ] {
        add(
            SemanticClass::Wall,
            Pose::IDENTITY,
            vec![cuboid(c, half, wall)],
            s,
        );
    }
    // Inner wall at x = 5 with a 1 m doorway at z in [2.5, 3.5].
    add(
        SemanticClass::Wall,
        Pose::IDENTITY,
        vec![cuboid(
            Vec3::new(5.0, h / 2.0, 1.25),
            Vec3::new(0.05, h / 2.0, 1.25),
            [0.7, 0.8, 0.75],
        )],
        s,
    );
    add(
        SemanticClass::Wall,
        Pose::IDENTITY,
        vec![cuboid(
            Vec3::new(5.0, h / 2.0, 4.75),
            Vec3::new(0.05, h / 2.0, 1.25),
            [0.7, 0.8, 0.75],
        )],
        s,
    );
    add(
        SemanticClass::DoorFrame,
        Pose::IDENTITY,
        vec![cuboid(
            Vec3::new(5.0, 2.3, 3.0),
            Vec3::new(0.06, 0.05, 0.5),
            [0.4, 0.25, 0.15],
        )],
        s,
    );

    let jitter = |rng: &mut ChaCha8Rng, c: Vec3| {
        c + Vec3::new(
            rng.random_range(-0.3..0.3),
            0.0,
            rng.random_range(-0.3..0.3),
        )
    };
    // Living room (x < 5): sofa, table with cylinder legs, chairs, vase (sphere), plant.
    let p = jitter(&mut rng, Vec3::new(1.5, 0.0, 5.0));
    add(
        SemanticClass::Sofa,
        Pose::from_yaw(p, rng.random_range(-0.3..0.3)),
        vec![
            cuboid(
                Vec3::new(0.0, 0.25, 0.0),
                Vec3::new(1.0, 0.25, 0.45),
                [0.2, 0.3, 0.6],
            ),
            cuboid(
                Vec3::new(0.0, 0.6, 0.35),
                Vec3::new(1.0, 0.35, 0.1),
                [0.2, 0.3, 0.6],
            ),
        ],
        s,
    );
    let table = jitter(&mut rng, Vec3::new(2.5, 0.0, 2.5));
    let mut parts = vec![cuboid(
        Vec3::new(0.0, 0.74, 0.0),
        Vec3::new(0.7, 0.03, 0.45),
        [0.6, 0.4, 0.2],
    )];
    for (x, z) in [(-0.6, -0.35), (0.6, -0.35), (-0.6, 0.35), (0.6, 0.35)] {
        parts.push(Part {
            shape: Shape::Cylinder {
                radius: 0.04,
                half_height: 0.355,
            },
            transform: Pose {
                position: [x, 0.355, z],
                rotation: [0.0, 0.0, 0.0, 1.0],
            },
            color: [0.3, 0.2, 0.1],
        });
    }
    add(
        SemanticClass::DiningTable,
        Pose::from_yaw(table, 0.0),
        parts,
        s,
    );
    for dz in [-0.8f32, 0.8] {
        let c = table + Vec3::new(rng.random_range(-0.3..0.3), 0.0, dz);
        add(
            SemanticClass::Chair,
            Pose::from_yaw(c, rng.random_range(-0.5..0.5)),
            vec![
                cuboid(
                    Vec3::new(0.0, 0.45, 0.0),
                    Vec3::new(0.22, 0.03, 0.22),
                    [0.8, 0.2, 0.2],
                ),
                cuboid(
                    Vec3::new(0.0, 0.21, 0.0),
                    Vec3::new(0.03, 0.21, 0.03),
                    [0.2, 0.2, 0.2],
                ),
                cuboid(
                    Vec3::new(0.0, 0.75, 0.2),
                    Vec3::new(0.22, 0.27, 0.02),
                    [0.8, 0.2, 0.2],
                ),
            ],
            Motion::Dynamic,
        );
    }
    add(
        SemanticClass::Vase,
        Pose::from_yaw(table + Vec3::new(0.2, 0.87, 0.0), 0.0),
        vec![Part {
            shape: Shape::Sphere { radius: 0.1 },
            transform: Pose::IDENTITY,
            color: [0.2, 0.7, 0.7],
        }],
        Motion::Dynamic,
    );
    add(
        SemanticClass::PottedPlant,
        Pose::from_yaw(Vec3::new(0.4, 0.0, 0.4), 0.0),
        vec![
            Part {
                shape: Shape::Cylinder {
                    radius: 0.2,
                    half_height: 0.2,
                },
                transform: Pose {
                    position: [0.0, 0.2, 0.0],
                    rotation: [0.0, 0.0, 0.0, 1.0],
                },
                color: [0.6, 0.3, 0.2],
            },
            Part {
                shape: Shape::Sphere { radius: 0.35 },
                transform: Pose {
                    position: [0.0, 0.75, 0.0],
                    rotation: [0.0, 0.0, 0.0, 1.0],
                },
                color: [0.1, 0.6, 0.15],
            },
        ],
        s,
    );
    add(
        SemanticClass::Bookshelf,
        Pose::from_yaw(Vec3::new(4.6, 0.0, 0.5), 0.0),
        vec![cuboid(
            Vec3::new(0.0, 0.9, 0.0),
            Vec3::new(0.3, 0.9, 0.2),
            [0.45, 0.3, 0.2],
        )],
        s,
    );
    // Bedroom (x > 5): bed, nightstand, wardrobe (rotated box), lamp.
    let bed = jitter(&mut rng, Vec3::new(6.8, 0.0, 4.6));
    add(
        SemanticClass::Bed,
        Pose::from_yaw(bed, 0.0),
        vec![
            cuboid(
                Vec3::new(0.0, 0.25, 0.0),
                Vec3::new(0.8, 0.25, 1.0),
                [0.9, 0.9, 0.95],
            ),
            cuboid(
                Vec3::new(0.0, 0.6, 1.0),
                Vec3::new(0.8, 0.6, 0.05),
                [0.35, 0.2, 0.1],
            ),
        ],
        s,
    );
    add(
        SemanticClass::Nightstand,
        Pose::from_yaw(Vec3::new(7.6, 0.0, 5.6), 0.0),
        vec![cuboid(
            Vec3::new(0.0, 0.3, 0.0),
            Vec3::new(0.2, 0.3, 0.2),
            [0.6, 0.5, 0.3],
        )],
        s,
    );
    add(
        SemanticClass::Wardrobe,
        Pose {
            position: [7.3, 0.0, 1.0],
            rotation: Quat::from_rotation_y(rng.random_range(0.2..0.6)).to_array(),
        },
        vec![cuboid(
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.5, 1.0, 0.3),
            [0.3, 0.2, 0.15],
        )],
        s,
    );
    add(
        SemanticClass::FloorLamp,
        Pose::from_yaw(Vec3::new(5.5, 0.0, 5.5), 0.0),
        vec![
            Part {
                shape: Shape::Cylinder {
                    radius: 0.03,
                    half_height: 0.8,
                },
                transform: Pose {
                    position: [0.0, 0.8, 0.0],
                    rotation: [0.0, 0.0, 0.0, 1.0],
                },
                color: [0.1, 0.1, 0.1],
            },
            Part {
                shape: Shape::Sphere { radius: 0.18 },
                transform: Pose {
                    position: [0.0, 1.7, 0.0],
                    rotation: [0.0, 0.0, 0.0, 1.0],
                },
                color: [1.0, 0.95, 0.7],
            },
        ],
        s,
    );
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: format!("demo_{seed:04}"),
        source: "demo".into(),
        seed: Some(seed),
        floor_height: 0.0,
        rooms: vec![
            Room {
                id: 0,
                kind: RoomType::LivingRoom,
                name: "living_room_0".into(),
                polygon: vec![[0.0, 0.0], [5.0, 0.0], [5.0, d], [0.0, d]],
            },
            Room {
                id: 1,
                kind: RoomType::Bedroom,
                name: "bedroom_1".into(),
                polygon: vec![[5.0, 0.0], [w, 0.0], [w, d], [5.0, d]],
            },
        ],
        doors: vec![],
        objects,
        storeys: Default::default(),
    }
}
