//! Hand-made scene fixtures: a 10 m x 10 m walled room with a floor, plus furniture helpers.
#![allow(dead_code)]

use glam::Vec3;
use vlnverse_env::{Aabb, Motion, Part, Physics, Pose, Scene, SceneObject, SemanticClass, Shape};

/// A box object standing with its centre at `center` (world), half sizes `half`.
pub fn boxed(
    id: u32,
    class: SemanticClass,
    center: Vec3,
    half: Vec3,
    motion: Motion,
    mass: f32,
    friction: f32,
) -> SceneObject {
    SceneObject {
        id,
        name: format!("{}_{id}", class.name()),
        class,
        room: None,
        pose: Pose::from_yaw(center, 0.0),
        bbox: Aabb::new(center - half, center + half),
        color: "white".into(),
        material: "wood".into(),
        shade: None,
        features: Vec::new(),
        physics: Physics {
            mass,
            friction,
            motion,
        },
        supported_by: None,
        parts: vec![Part {
            shape: Shape::Cuboid {
                half_extents: half.to_array(),
                bevel: 0.0,
            },
            transform: Pose::IDENTITY,
            color: [0.8; 3],
        }],
    }
}

/// Static wall.
pub fn wall(id: u32, center: Vec3, half: Vec3) -> SceneObject {
    boxed(
        id,
        SemanticClass::Wall,
        center,
        half,
        Motion::Static,
        1000.0,
        0.5,
    )
}

/// A 10 m x 10 m room centred at the origin: floor (id 1) and four 0.2 m walls (ids 2-5)
/// whose inner faces are at x, z = +-5.
pub fn room() -> Scene {
    let objects = vec![
        boxed(
            1,
            SemanticClass::Floor,
            Vec3::new(0.0, -0.05, 0.0),
            Vec3::new(5.2, 0.05, 5.2),
            Motion::Static,
            1000.0,
            0.6,
        ),
        wall(2, Vec3::new(0.0, 1.25, -5.1), Vec3::new(5.2, 1.25, 0.1)),
        wall(3, Vec3::new(0.0, 1.25, 5.1), Vec3::new(5.2, 1.25, 0.1)),
        wall(4, Vec3::new(-5.1, 1.25, 0.0), Vec3::new(0.1, 1.25, 5.2)),
        wall(5, Vec3::new(5.1, 1.25, 0.0), Vec3::new(0.1, 1.25, 5.2)),
    ];
    Scene {
        format_version: vlnverse_env::SCENE_FORMAT_VERSION,
        id: "test_room".into(),
        source: "test".into(),
        seed: None,
        floor_height: 0.0,
        rooms: vec![],
        doors: vec![],
        objects,
        storeys: Default::default(),
    }
}

/// The room plus extra objects (ids must continue from 6).
pub fn room_with(extra: Vec<SceneObject>) -> Scene {
    let mut s = room();
    s.objects.extend(extra);
    s
}

/// Start pose at floor point `(x, z)` with yaw (radians).
pub fn at(x: f32, z: f32, yaw: f32) -> Pose {
    Pose::from_yaw(Vec3::new(x, 0.0, z), yaw)
}
