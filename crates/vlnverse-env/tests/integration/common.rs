//! Builders shared by the hand-made fixtures of the env tests (each fixture module includes
//! this file with `#[path]`); the fixtures override the fields their tests look at.
#![allow(dead_code)]

use vlnverse_env::{
    Door, Part, Pose, Room, Scene, SceneObject, SemanticClass, SCENE_FORMAT_VERSION,
};

/// [`SceneObject::from_parts`]: white plaster, 10 kg, friction 0.5, static, in no room.
pub fn object(id: u32, class: SemanticClass, pose: Pose, parts: Vec<Part>) -> SceneObject {
    SceneObject::from_parts(id, class, pose, parts)
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
        storeys: Default::default(),
    }
}
