//! Hand-made scenes for the scene-graph tests: every box is written out so expected relations
//! can be read off the numbers.
#![allow(dead_code)]

use crate::common;

use glam::Vec3;
use vlnverse_env::{
    Aabb, Door, ObjectId, Part, Pose, Room, RoomId, RoomType, Scene, SceneObject, SemanticClass,
    Shape,
};

/// Living room (x 0..5, z 0..4).
pub const LIVING: RoomId = 1;
/// Bedroom (x 5..9, z 0..4), door 1 from the living room.
pub const BEDROOM: RoomId = 2;
/// Kitchen (x 0..5, z 4..8), open-plan opening 2 from the living room.
pub const KITCHEN: RoomId = 3;

pub const WALL: ObjectId = 1;
pub const TABLE: ObjectId = 10;
pub const RED_MUG: ObjectId = 11;
pub const BLUE_MUG: ObjectId = 12;
pub const RED_SOFA: ObjectId = 13;
pub const GREEN_SOFA: ObjectId = 14;
pub const LAMP: ObjectId = 15;
pub const CHAIR_BY_SOFA: ObjectId = 16;
pub const CHAIR_BY_TABLE: ObjectId = 17;
pub const RUG: ObjectId = 18;
pub const BED: ObjectId = 20;
pub const NIGHTSTAND: ObjectId = 21;
pub const NIGHTSTAND_MUG: ObjectId = 22;
pub const BEDROOM_BOOK: ObjectId = 23;
pub const COUNTER: ObjectId = 30;
pub const WHITE_MUG_A: ObjectId = 31;
pub const WHITE_MUG_B: ObjectId = 32;
pub const FRIDGE: ObjectId = 33;
pub const KITCHEN_BOOK: ObjectId = 34;

pub fn rect(x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<[f32; 2]> {
    vec![[x0, z0], [x1, z0], [x1, z1], [x0, z1]]
}

pub fn room(id: RoomId, kind: RoomType, polygon: Vec<[f32; 2]>) -> Room {
    Room {
        id,
        kind,
        name: format!("{}_{id}", kind.name()),
        polygon,
    }
}

/// A one-box object spanning `min..max`.
pub fn obj(
    id: ObjectId,
    class: SemanticClass,
    color: &str,
    room: Option<RoomId>,
    min: [f32; 3],
    max: [f32; 3],
    supported_by: Option<ObjectId>,
) -> SceneObject {
    let (lo, hi) = (Vec3::from_array(min), Vec3::from_array(max));
    let part = Part {
        shape: Shape::Cuboid {
            half_extents: ((hi - lo) * 0.5).to_array(),
            bevel: 0.0,
        },
        transform: Pose::IDENTITY,
        color: [0.5, 0.5, 0.5],
    };
    let mut o = common::object(id, class, Pose::from_yaw((lo + hi) * 0.5, 0.0), vec![part]);
    o.room = room;
    o.bbox = Aabb::new(lo, hi);
    o.color = color.into();
    o.material = "wood".into();
    o.supported_by = supported_by;
    o
}

pub use common::scene;

pub fn home() -> Scene {
    use SemanticClass as C;
    let (l, b, k) = (Some(LIVING), Some(BEDROOM), Some(KITCHEN));
    let rooms = vec![
        room(LIVING, RoomType::LivingRoom, rect(0.0, 0.0, 5.0, 4.0)),
        room(BEDROOM, RoomType::Bedroom, rect(5.0, 0.0, 9.0, 4.0)),
        room(KITCHEN, RoomType::Kitchen, rect(0.0, 4.0, 5.0, 8.0)),
    ];
    let doors = vec![
        Door {
            id: 1,
            position: [5.0, 0.0, 2.0],
            width: 0.9,
            normal: [1.0, 0.0],
            rooms: [LIVING, BEDROOM],
            open_plan: false,
            state: None,
            leaf: None,
            second_leaf: None,
            kind: Default::default(),
        },
        Door {
            id: 2,
            position: [2.5, 0.0, 4.0],
            width: 2.0,
            normal: [0.0, 1.0],
            rooms: [KITCHEN, LIVING],
            open_plan: true,
            state: None,
            leaf: None,
            second_leaf: None,
            kind: Default::default(),
        },
    ];
    let objects = vec![
        // Structure right next to furniture: never a node.
        obj(
            WALL,
            C::Wall,
            "white",
            None,
            [4.95, 0.0, 0.0],
            [5.05, 2.5, 4.0],
            None,
        ),
        obj(
            TABLE,
            C::CoffeeTable,
            "brown",
            l,
            [1.0, 0.0, 1.0],
            [2.0, 0.5, 2.0],
            None,
        ),
        obj(
            RED_MUG,
            C::Mug,
            "red",
            l,
            [1.2, 0.5, 1.2],
            [1.3, 0.6, 1.3],
            Some(TABLE),
        ),
        // On the table by geometry only.
        obj(
            BLUE_MUG,
            C::Mug,
            "blue",
            l,
            [1.6, 0.5, 1.6],
            [1.7, 0.6, 1.7],
            None,
        ),
        obj(
            RED_SOFA,
            C::Sofa,
            "red",
            l,
            [3.0, 0.0, 0.2],
            [4.8, 0.9, 1.0],
            None,
        ),
        obj(
            GREEN_SOFA,
            C::Sofa,
            "green",
            l,
            [3.0, 0.0, 3.0],
            [4.8, 0.9, 3.8],
            None,
        ),
        // 0.1 m from the table (next to), 0.7 m from the red sofa (near only).
        obj(
            LAMP,
            C::FloorLamp,
            "black",
            l,
            [2.1, 0.0, 1.0],
            [2.3, 1.6, 1.2],
            None,
        ),
        // Two identical chairs: one 0.1 m from the green sofa, one 0.64 m from the table.
        obj(
            CHAIR_BY_SOFA,
            C::Chair,
            "black",
            l,
            [2.5, 0.0, 3.2],
            [2.9, 0.9, 3.6],
            None,
        ),
        obj(
            CHAIR_BY_TABLE,
            C::Chair,
            "black",
            l,
            [0.2, 0.0, 2.5],
            [0.6, 0.9, 2.9],
            None,
        ),
        // Under the green sofa: the sofa is not "on" a 1 cm rug.
        obj(
            RUG,
            C::Rug,
            "beige",
            l,
            [3.3, 0.0, 3.1],
            [4.6, 0.01, 3.7],
            None,
        ),
        // 0.6 m from the red sofa, but through the wall in another room.
        obj(
            BED,
            C::Bed,
            "white",
            b,
            [5.4, 0.0, 0.5],
            [7.4, 0.6, 2.5],
            None,
        ),
        obj(
            NIGHTSTAND,
            C::Nightstand,
            "white",
            b,
            [7.6, 0.0, 0.5],
            [8.1, 0.5, 1.0],
            None,
        ),
        obj(
            NIGHTSTAND_MUG,
            C::Mug,
            "red",
            b,
            [7.8, 0.5, 0.7],
            [7.9, 0.6, 0.8],
            Some(NIGHTSTAND),
        ),
        obj(
            BEDROOM_BOOK,
            C::Book,
            "green",
            b,
            [6.2, 0.0, 3.2],
            [6.4, 0.05, 3.4],
            None,
        ),
        obj(
            COUNTER,
            C::Counter,
            "white",
            k,
            [0.0, 0.0, 7.4],
            [3.0, 0.9, 8.0],
            None,
        ),
        obj(
            WHITE_MUG_A,
            C::Mug,
            "white",
            k,
            [1.0, 0.9, 7.6],
            [1.1, 1.0, 7.7],
            Some(COUNTER),
        ),
        obj(
            WHITE_MUG_B,
            C::Mug,
            "white",
            k,
            [2.0, 0.9, 7.6],
            [2.1, 1.0, 7.7],
            Some(COUNTER),
        ),
        // No room given: found from its position.
        obj(
            FRIDGE,
            C::Fridge,
            "silver",
            None,
            [4.0, 0.0, 7.2],
            [4.8, 1.8, 8.0],
            None,
        ),
        obj(
            KITCHEN_BOOK,
            C::Book,
            "green",
            k,
            [1.0, 0.0, 5.0],
            [1.2, 0.05, 5.2],
            None,
        ),
    ];
    scene("fixture_home", rooms, doors, objects)
}
