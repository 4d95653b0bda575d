//! The import layer alone: read a glTF/GLB home into a VLNVerse scene and report what was
//! recognised. Without an argument it imports a home it first exports itself (a synthetic
//! `grid_home` written as `scene.glb`), so it runs anywhere.
//!
//! `cargo run -p vlnverse-import --example import_glb [FILE.glb|FILE.gltf]`

use std::path::PathBuf;

use vlnverse_env::io::write_scene_bundle;
use vlnverse_env::occupancy::synthetic::grid_home;
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_import::{import_scene, ImportOptions};

/// Import the file (or the round-tripped synthetic home); return its object count.
pub fn run(arg: Option<PathBuf>) -> Result<usize, Box<dyn std::error::Error>> {
    let file = match arg {
        Some(f) => f,
        None => {
            let out = std::env::temp_dir().join("vlnverse-import-example");
            let (_, dir) =
                write_scene_bundle(&out, grid_home(2, 1, 4.0, 3), &OccupancyConfig::default())?;
            dir.join("scene.glb")
        }
    };
    let (scene, report) = import_scene(&file, &ImportOptions::default())?;
    println!(
        "{} ({}): scene {}, {} objects, {} triangles, {} rooms",
        report.file.display(),
        report.format,
        scene.id,
        report.objects,
        report.triangles,
        scene.rooms.len()
    );
    for (class, n) in &report.objects_by_class {
        println!("  {class:<16} {n}");
    }
    Ok(report.objects)
}

#[allow(dead_code)] // the tests call `run` through `#[path]`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(std::env::args().nth(1).map(PathBuf::from)).map(|_| ())
}
