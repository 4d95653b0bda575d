//! What a room looks like, read from its structure objects: how many windows it has and what
//! its floor is made of ("The room has two windows.", "It has a tiled floor.", "The floor is
//! carpeted.").

use vlnverse_env::{RoomId, Scene, SemanticClass as C};

/// What a room's floor is, as people name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FloorKind {
    /// Boards ("a wooden floor").
    Wood,
    /// Tiles ("a tiled floor").
    Tile,
    /// Carpet ("a carpeted floor").
    Carpet,
    /// Stone tiles ("a stone floor").
    Stone,
    /// Bare concrete ("a concrete floor").
    Concrete,
}

impl FloorKind {
    /// The floor's material as one word ("the floor changes from tile to carpet").
    pub(crate) fn material(self) -> &'static str {
        match self {
            FloorKind::Wood => "wood",
            FloorKind::Tile => "tile",
            FloorKind::Carpet => "carpet",
            FloorKind::Stone => "stone",
            FloorKind::Concrete => "concrete",
        }
    }
}

/// The windows of `room`: one per glass pane (a window is a pane and its frame, both of class
/// window; the frame is not counted again).
pub(crate) fn window_count(scene: &Scene, room: RoomId) -> usize {
    scene
        .objects
        .iter()
        .filter(|o| o.class == C::Window && o.room == Some(room) && o.material == "glass")
        .count()
}

/// The floor of `room`: the material of its largest floor object (the slab; skirting boards
/// are floor objects too, but thin). `None` for a material people would not name this way.
pub(crate) fn floor_kind(scene: &Scene, room: RoomId) -> Option<FloorKind> {
    let area = |o: &&vlnverse_env::SceneObject| {
        let s = o.bbox.size();
        s.x * s.z
    };
    let slab = scene
        .objects
        .iter()
        .filter(|o| o.class == C::Floor && o.room == Some(room))
        .max_by(|a, b| area(a).total_cmp(&area(b)))?;
    match slab.material.as_str() {
        "wood" => Some(FloorKind::Wood),
        "tile" => Some(FloorKind::Tile),
        "carpet" => Some(FloorKind::Carpet),
        "stone" => Some(FloorKind::Stone),
        "concrete" => Some(FloorKind::Concrete),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vlnverse_env::{Aabb, Pose, SceneObject};

    fn object(id: u32, class: C, material: &str, lo: [f32; 3], hi: [f32; 3]) -> SceneObject {
        let mut o = SceneObject::from_parts(id, class, Pose::IDENTITY, Vec::new());
        o.bbox = Aabb { min: lo, max: hi };
        o.room = Some(0);
        o.material = material.into();
        o
    }

    fn scene(objects: Vec<SceneObject>) -> Scene {
        serde_json::from_value(serde_json::json!({
            "format_version": 1, "id": "t", "source": "test", "seed": null,
            "floor_height": 0.0, "rooms": [{"id": 0, "kind": "bedroom", "name": "bedroom_0",
            "polygon": [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]}], "doors": [],
            "objects": objects,
        }))
        .unwrap()
    }

    #[test]
    fn two_windows_with_frames_count_as_two_and_other_rooms_not_at_all() {
        let mut elsewhere = object(5, C::Window, "glass", [4.0, 1.0, 1.0], [4.0, 2.0, 2.0]);
        elsewhere.room = Some(1);
        let s = scene(vec![
            object(1, C::Window, "glass", [0.0, 1.0, 1.0], [0.0, 2.0, 2.0]),
            object(2, C::Window, "plastic", [0.0, 0.9, 0.9], [0.0, 2.1, 2.1]),
            object(3, C::Window, "glass", [1.0, 1.0, 4.0], [2.0, 2.0, 4.0]),
            object(4, C::Window, "wood", [0.9, 0.9, 4.0], [2.1, 2.1, 4.0]),
            elsewhere,
        ]);
        assert_eq!(window_count(&s, 0), 2);
        assert_eq!(window_count(&s, 1), 1);
        assert_eq!(window_count(&s, 2), 0);
    }

    #[test]
    fn the_floor_is_the_slab_not_the_skirting() {
        let slab = |m: &str| object(1, C::Floor, m, [0.0, -0.1, 0.0], [4.0, 0.0, 4.0]);
        let skirting = object(2, C::Floor, "wood", [0.0, 0.0, 0.0], [4.0, 0.1, 0.02]);
        assert_eq!(
            floor_kind(&scene(vec![skirting.clone(), slab("tile")]), 0),
            Some(FloorKind::Tile)
        );
        assert_eq!(
            floor_kind(&scene(vec![slab("wood"), skirting.clone()]), 0),
            Some(FloorKind::Wood)
        );
        for (m, k) in [
            ("carpet", FloorKind::Carpet),
            ("stone", FloorKind::Stone),
            ("concrete", FloorKind::Concrete),
        ] {
            assert_eq!(floor_kind(&scene(vec![slab(m)]), 0), Some(k));
        }
        assert_eq!(floor_kind(&scene(vec![slab("plaster")]), 0), None);
        assert_eq!(floor_kind(&scene(vec![skirting]), 1), None);
    }
}
