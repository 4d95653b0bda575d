//! Hand-made scene fixture shared by the io tests (included with `mod`).

use crate::common;

use glam::Vec3;
use vlnverse_env::*;

fn obj(id: u32, class: SemanticClass, pose: Pose, parts: Vec<Part>, motion: Motion) -> SceneObject {
    let mut o = common::object(id, class, pose, parts);
    o.room = if class.is_structure() { None } else { Some(1) };
    o.color = "red".into();
    o.material = if id.is_multiple_of(2) {
        "metal"
    } else {
        "wood"
    }
    .into();
    o.physics = Physics {
        mass: 1.5 * id as f32,
        friction: 0.6,
        motion,
    };
    o
}

fn part(shape: Shape, at: Vec3, color: [f32; 3]) -> Part {
    Part {
        shape,
        transform: Pose::from_yaw(at, 0.3),
        color,
    }
}

/// A small scene with cuboids, cylinders, spheres and one mesh part.
pub fn fixture_scene() -> Scene {
    let wall = obj(
        1,
        SemanticClass::Wall,
        Pose::IDENTITY,
        vec![part(
            Shape::Cuboid {
                half_extents: [2.0, 1.25, 0.05],
                bevel: 0.0,
            },
            Vec3::new(0.0, 1.25, -2.0),
            [0.8, 0.8, 0.78],
        )],
        Motion::Static,
    );
    // Walls are axis-aligned, as in generated homes.
    let mut wall = wall;
    wall.parts[0].transform = Pose::from_yaw(Vec3::new(0.0, 1.25, -2.0), 0.0);
    wall.bbox = wall.compute_bbox();
    let table = obj(
        2,
        SemanticClass::DiningTable,
        Pose::from_yaw(Vec3::new(0.5, 0.0, 0.25), 0.7),
        vec![
            part(
                Shape::Cuboid {
                    half_extents: [0.6, 0.02, 0.4],
                    bevel: 0.0,
                },
                Vec3::new(0.0, 0.74, 0.0),
                [0.4, 0.2, 0.1],
            ),
            part(
                Shape::Cylinder {
                    radius: 0.03,
                    half_height: 0.36,
                },
                Vec3::new(0.5, 0.36, 0.3),
                [0.1, 0.1, 0.1],
            ),
            part(
                Shape::Cylinder {
                    radius: 0.03,
                    half_height: 0.36,
                },
                Vec3::new(-0.5, 0.36, 0.3),
                [0.1, 0.1, 0.1],
            ),
        ],
        Motion::Static,
    );
    let mut ball = obj(
        3,
        SemanticClass::Vase,
        Pose::from_yaw(Vec3::new(0.5, 0.76, 0.25), 0.0),
        vec![part(
            Shape::Sphere { radius: 0.1 },
            Vec3::new(0.0, 0.1, 0.0),
            [0.9, 0.1, 0.1],
        )],
        Motion::Dynamic,
    );
    ball.supported_by = Some(2);
    let mesh = MeshData {
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.123_456_79, -0.5, 1e-7],
        ],
        indices: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [4, 1, 0]],
        glb_mesh: Some(0),
        ..Default::default()
    };
    let statue = obj(
        4,
        SemanticClass::Unknown,
        Pose::from_yaw(Vec3::new(-1.0, 0.0, 1.0), -1.2),
        vec![
            part(Shape::Mesh(mesh), Vec3::new(0.0, 0.2, 0.0), [0.3, 0.6, 0.2]),
            part(
                Shape::Cuboid {
                    half_extents: [0.2, 0.1, 0.2],
                    bevel: 0.0,
                },
                Vec3::new(0.0, 0.1, 0.0),
                [0.3, 0.6, 0.2],
            ),
        ],
        Motion::Static,
    );
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: "fixture_0001".into(),
        source: "test".into(),
        seed: Some(7),
        floor_height: 0.0,
        rooms: vec![Room {
            id: 1,
            kind: RoomType::DiningRoom,
            name: "dining_room_1".into(),
            polygon: vec![[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]],
        }],
        doors: vec![Door {
            id: 1,
            position: [2.0, 0.0, 0.0],
            width: 0.9,
            normal: [1.0, 0.0],
            rooms: [1, 1],
            open_plan: false,
            state: None,
            leaf: None,
            second_leaf: None,
            kind: Default::default(),
        }],
        objects: vec![wall, table, ball, statue],
        storeys: Default::default(),
    }
}
