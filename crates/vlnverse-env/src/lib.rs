#![doc = include_str!("../README.md")]

pub mod bvh;
pub mod cache;
pub mod error;
pub mod geodesic;
pub mod geometry;
pub mod io;
pub mod light;
pub mod material;
pub mod occupancy;
pub mod scene;
pub mod scene_graph;
pub mod scene_source;
pub mod topdown;
pub mod vocab;

pub use error::{EnvError, Result};
pub use scene::{
    segments_cross, Aabb, Door, DoorKind, DoorState, Level, LevelId, MeshData, Motion, ObjectId,
    Part, Physics, Pose, Room, RoomId, Scene, SceneObject, Shape, Stairs, Storeys,
    SCENE_FORMAT_VERSION,
};
pub use scene_source::SceneSource;
pub use vocab::{ClassKind, RoomType, SemanticClass};
