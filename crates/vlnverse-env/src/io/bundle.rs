//! The per-scene pipeline shared by `cargo xtask scenes`, dataset generation and the importer:
//! scene -> occupancy maps -> scene graph -> a complete scene folder.

use super::scene_dir::write_scene_dir;
use crate::error::Result;
use crate::occupancy::{build_maps, OccupancyConfig, OccupancyMaps};
use crate::scene::Scene;
use crate::scene_graph::SceneGraph;
use std::path::{Path, PathBuf};

/// A scene with everything derived from it.
#[derive(Clone, Debug)]
pub struct SceneBundle {
    /// The scene.
    pub scene: Scene,
    /// Raw and agent-dilated occupancy maps.
    pub maps: OccupancyMaps,
    /// The scene graph.
    pub graph: SceneGraph,
}

impl SceneBundle {
    /// The companion files of the scene folder (everything but `scene.glb` and `scene.json`):
    /// `scene_graph.json`, `occupancy.{pgm,yaml}`, `navigable.{pgm,yaml}`.
    pub fn companion_files(&self) -> Vec<(&'static str, Vec<u8>)> {
        let mut graph = self.graph.to_json_string().into_bytes();
        graph.push(b'\n');
        vec![
            ("scene_graph.json", graph),
            ("occupancy.pgm", self.maps.occupancy.to_pgm_bytes()),
            (
                "occupancy.yaml",
                self.maps.occupancy.to_yaml("occupancy.pgm").into_bytes(),
            ),
            ("navigable.pgm", self.maps.navigable.to_pgm_bytes()),
            (
                "navigable.yaml",
                self.maps.navigable.to_yaml("navigable.pgm").into_bytes(),
            ),
        ]
    }

    /// Write `<out_dir>/<scene id>/` atomically with every file of
    /// [`super::BUNDLE_FILES`]; returns the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf> {
        write_scene_dir(out_dir, &self.scene, &self.companion_files())
    }
}

/// Build the maps and the scene graph of a scene.
pub fn scene_bundle(scene: Scene, occupancy: &OccupancyConfig) -> Result<SceneBundle> {
    let maps = build_maps(&scene, occupancy)?;
    let graph = SceneGraph::build(&scene);
    Ok(SceneBundle { scene, maps, graph })
}

/// Build maps and graph, then write the complete scene folder; returns the bundle and the
/// folder.
pub fn write_scene_bundle(
    out_dir: impl AsRef<Path>,
    scene: Scene,
    occupancy: &OccupancyConfig,
) -> Result<(SceneBundle, PathBuf)> {
    let bundle = scene_bundle(scene, occupancy)?;
    let dir = if bundle.scene.is_multi_level() {
        // The upper floors' ROS maps join the folder in the same atomic write.
        let upper = crate::occupancy::upper_level_files(&bundle.scene, occupancy)?;
        let mut files: Vec<(&str, Vec<u8>)> = bundle.companion_files();
        files.extend(upper.iter().map(|(n, b)| (n.as_str(), b.clone())));
        write_scene_dir(out_dir, &bundle.scene, &files)?
    } else {
        bundle.write(out_dir)?
    };
    Ok((bundle, dir))
}

/// What [`write_source_bundles`] did with one scene.
#[derive(Clone, Debug, PartialEq)]
pub enum BundleOutcome {
    /// The folder was (re)written.
    Written {
        /// Scene id.
        id: String,
        /// Navigable floor area (m^2).
        navigable_m2: f32,
        /// Number of rooms.
        rooms: usize,
        /// Number of non-structure objects.
        objects: usize,
    },
    /// The folder was already complete and was left alone.
    Skipped {
        /// Scene id.
        id: String,
    },
}

/// Write the scene folders of `indices` of `source` into `out_dir` in parallel (on the current
/// rayon pool), skipping folders that are already complete unless `force`. `on_done` is called
/// once per scene (from worker threads, e.g. to advance a progress bar). Outcomes come back in
/// the order of `indices`; the first failing index (in that order) gives the error. Output
/// files do not depend on the number of threads.
pub fn write_source_bundles(
    source: &dyn crate::SceneSource,
    indices: &[usize],
    out_dir: &Path,
    occupancy: &OccupancyConfig,
    force: bool,
    on_done: &(dyn Fn(&BundleOutcome) + Sync),
) -> Result<Vec<BundleOutcome>> {
    use rayon::prelude::*;
    let results: Vec<Result<BundleOutcome>> = indices
        .par_iter()
        .map(|&i| {
            let id = source.scene_id(i);
            let outcome = if !force && super::is_complete_scene_dir(out_dir.join(&id)) {
                tracing::debug!(scene = %id, "complete, skipped");
                BundleOutcome::Skipped { id }
            } else {
                let scene = source.scene(i)?;
                let (b, _) = write_scene_bundle(out_dir, scene, occupancy)?;
                BundleOutcome::Written {
                    id,
                    navigable_m2: b.maps.navigable.free_area_m2(),
                    rooms: b.scene.rooms.len(),
                    objects: b.scene.items().count(),
                }
            };
            on_done(&outcome);
            Ok(outcome)
        })
        .collect();
    results.into_iter().collect()
}
