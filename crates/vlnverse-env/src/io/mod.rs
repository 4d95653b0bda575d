//! Scene files: `scene.glb` ([`glb`]), `scene.json` ([`json`]), scene folders written
//! atomically and loaded back ([`scene_dir`]), and the per-scene pipeline that turns a scene into
//! its whole folder ([`bundle`]).

pub mod bundle;
pub mod glb;
mod glb_light;
pub mod json;
pub mod scene_dir;

pub use bundle::{
    scene_bundle, write_scene_bundle, write_source_bundles, BundleOutcome, SceneBundle,
};
pub use scene_dir::{
    is_complete_scene_dir, is_complete_scene_dir_with, is_temp_leftover, list_scene_dirs,
    load_scene, load_scene_and_light, remove_temp_leftovers, write_scene_dir, BUNDLE_FILES,
    SCENE_GLB, SCENE_JSON,
};

use crate::error::{EnvError, Result};
use std::io::Write;
use std::path::Path;

/// Write `bytes` to `path` atomically: a temporary file in the same folder, flushed, then
/// renamed over `path`, so readers never see a half-written file.
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| EnvError::parse(path, "not a file path"))?
        .to_string_lossy();
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let res = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    res.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        EnvError::io(path, e)
    })
}
