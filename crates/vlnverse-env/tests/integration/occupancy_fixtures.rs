//! Hand-made scenes for the occupancy and geodesic tests (shared by the `occupancy_*` test modules).
#![allow(dead_code)]

use crate::common;

use glam::{Vec2, Vec3};
use vlnverse_env::{MeshData, Part, Pose, Scene, SceneObject, SemanticClass, Shape};

/// Wall height used by the fixtures.
pub const WALL_H: f32 = 2.5;
/// Wall thickness used by the fixtures.
pub const WALL_T: f32 = 0.1;

pub fn object(id: u32, class: SemanticClass, pose: Pose, shape: Shape) -> SceneObject {
    let part = Part {
        shape,
        transform: Pose::IDENTITY,
        color: [0.8, 0.8, 0.8],
    };
    common::object(id, class, pose, vec![part])
}

/// Axis-aligned box between two corners.
pub fn boxed(id: u32, class: SemanticClass, min: [f32; 3], max: [f32; 3]) -> SceneObject {
    SceneObject::cuboid(id, class, Vec3::from_array(min), Vec3::from_array(max))
}

/// A wall of thickness [`WALL_T`] centred on the axis-aligned segment `a`-`b` (x, z).
pub fn wall(id: u32, a: [f32; 2], b: [f32; 2]) -> SceneObject {
    let t = WALL_T / 2.0;
    let (x0, x1) = (a[0].min(b[0]), a[0].max(b[0]));
    let (z0, z1) = (a[1].min(b[1]), a[1].max(b[1]));
    // Extend past both ends too, so that the corners of a rectangle of walls are closed.
    boxed(
        id,
        SemanticClass::Wall,
        [x0 - t, 0.0, z0 - t],
        [x1 + t, WALL_H, z1 + t],
    )
}

/// Floor slab under `[x0, x1] x [z0, z1]`.
pub fn floor(id: u32, x0: f32, z0: f32, x1: f32, z1: f32) -> SceneObject {
    boxed(id, SemanticClass::Floor, [x0, -0.1, z0], [x1, 0.0, z1])
}

/// Four walls around the rectangle.
pub fn walls_rect(first_id: u32, x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<SceneObject> {
    vec![
        wall(first_id, [x0, z0], [x1, z0]),
        wall(first_id + 1, [x0, z1], [x1, z1]),
        wall(first_id + 2, [x0, z0], [x0, z1]),
        wall(first_id + 3, [x1, z0], [x1, z1]),
    ]
}

pub fn scene(id: &str, objects: Vec<SceneObject>) -> Scene {
    common::scene(id, Vec::new(), Vec::new(), objects)
}

/// Room A `[0,4]x[0,4]` and room B `[4,7]x[0,4]` joined by a gap of `door` metres centred at
/// z = 2 in the partition wall x = 4 (wall centre lines; walls are [`WALL_T`] thick).
pub fn two_rooms(door: f32) -> Scene {
    let mut o = vec![floor(1, -0.05, -0.05, 7.05, 4.05)];
    o.extend(walls_rect(2, 0.0, 0.0, 7.0, 4.0));
    // Partition: two pieces leaving exactly `door` clear between them.
    o.push(boxed(
        6,
        SemanticClass::Wall,
        [3.95, 0.0, 0.05],
        [4.05, WALL_H, 2.0 - door / 2.0],
    ));
    o.push(boxed(
        7,
        SemanticClass::Wall,
        [3.95, 0.0, 2.0 + door / 2.0],
        [4.05, WALL_H, 3.95],
    ));
    scene(&format!("two_rooms_{door}"), o)
}

/// Centre of room A / room B of [`two_rooms`].
pub const ROOM_A: Vec2 = Vec2::new(2.0, 2.0);
/// Centre of room B.
pub const ROOM_B: Vec2 = Vec2::new(5.5, 2.0);

/// A 6 x 5 m open room plus a closed 1.6 x 1.6 m room beside it (x in [7, 8.6]), each on its
/// own floor slab.
pub fn room_and_closed_room() -> Scene {
    let mut o = vec![
        floor(1, -0.05, -0.05, 6.05, 5.05),
        floor(10, 6.95, -0.05, 8.65, 1.65),
    ];
    o.extend(walls_rect(2, 0.0, 0.0, 6.0, 5.0));
    o.extend(walls_rect(6, 7.0, 0.0, 8.6, 1.6));
    scene("closed_room", o)
}

/// Centre of the closed room of [`room_and_closed_room`].
pub const CLOSED_ROOM: Vec2 = Vec2::new(7.8, 0.8);

/// An empty `size` x `size` room with walls.
pub fn open_room(size: f32) -> Scene {
    let mut o = vec![floor(1, -0.05, -0.05, size + 0.05, size + 0.05)];
    o.extend(walls_rect(2, 0.0, 0.0, size, size));
    scene("open_room", o)
}

/// A 10 x 10 m room with a wall along x = 5 from z = 0 up to z = 7 (3 m gap above it).
pub fn room_with_long_wall() -> Scene {
    let mut o = vec![floor(1, -0.05, -0.05, 10.05, 10.05)];
    o.extend(walls_rect(2, 0.0, 0.0, 10.0, 10.0));
    o.push(boxed(
        6,
        SemanticClass::Wall,
        [4.95, 0.0, 0.05],
        [5.05, WALL_H, 7.05],
    ));
    scene("long_wall", o)
}

/// A triangle-mesh object (positions in world space, identity pose).
pub fn mesh(
    id: u32,
    class: SemanticClass,
    positions: Vec<[f32; 3]>,
    indices: Vec<[u32; 3]>,
) -> SceneObject {
    object(
        id,
        class,
        Pose::IDENTITY,
        Shape::Mesh(MeshData {
            positions,
            indices,
            glb_mesh: None,
            ..Default::default()
        }),
    )
}
