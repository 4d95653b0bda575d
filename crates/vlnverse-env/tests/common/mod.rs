//! Builders shared by the hand-made fixtures of the env tests (each fixture module includes
//! this file with `#[path]`); the fixtures override the fields their tests look at.
#![allow(dead_code)]

use vlnverse_env::{
    Aabb, Door, Motion, Part, Physics, Pose, Room, Scene, SceneObject, SemanticClass,
    SCENE_FORMAT_VERSION,
};

/// A static object named `<class>_<id>`, white plaster, 10 kg, friction 0.5, in no room, with
/// its bounding box computed from `parts`.
pub fn object(id: u32, class: SemanticClass, pose: Pose, parts: Vec<Part>) -> SceneObject {
    let mut o = SceneObject {
        id,
        name: format!("{}_{id}", class.name()),
        class,
        room: None,
        pose,
        bbox: Aabb::EMPTY,
        color: "white".into(),
        material: "plaster".into(),
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

/// A test scene (source `test`, no seed, floor at 0) with its objects sorted by id.
pub fn scene(id: &str, rooms: Vec<Room>, doors: Vec<Door>, mut objects: Vec<SceneObject>) -> Scene {
    objects.sort_by_key(|o| o.id);
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: id.into(),
        source: "test".into(),
        seed: None,
        floor_height: 0.0,
        rooms,
        doors,
        objects,
    }
}
