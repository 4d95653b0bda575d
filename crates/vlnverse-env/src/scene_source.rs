//! The swap point for where scenes come from.

use crate::error::Result;
use crate::scene::Scene;

/// Anything that produces [`Scene`]s: the procedural home generator (`vlnverse-procgen`), the
/// glTF/OBJ importer (`vlnverse-import`), or a loader of scene folders on disk.
///
/// Implementations must be deterministic: the same index gives the same scene, whatever the
/// thread or the order of calls, so that generation can be parallel and sharded.
///
/// ```
/// use vlnverse_env::{Scene, SceneSource, Result};
///
/// /// A source with one fixed, empty scene.
/// struct Empty;
///
/// impl SceneSource for Empty {
///     fn len(&self) -> usize { 1 }
///     fn scene_id(&self, _index: usize) -> String { "empty".into() }
///     fn scene(&self, index: usize) -> Result<Scene> {
///         Ok(Scene {
///             format_version: vlnverse_env::SCENE_FORMAT_VERSION,
///             id: self.scene_id(index),
///             source: "example".into(),
///             seed: None,
///             floor_height: 0.0,
///             rooms: vec![],
///             doors: vec![],
///             objects: vec![],
///             storeys: Default::default(),
///         })
///     }
/// }
///
/// assert_eq!(Empty.scene(0).unwrap().id, "empty");
/// ```
pub trait SceneSource: Send + Sync {
    /// Number of scenes this source provides.
    fn len(&self) -> usize;

    /// Whether the source has no scenes.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Id (folder name) of the scene at `index`, without building it.
    fn scene_id(&self, index: usize) -> String;

    /// Build or load the scene at `index`.
    fn scene(&self, index: usize) -> Result<Scene>;
}
