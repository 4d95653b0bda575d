//! Write the rasteriser's prepared scene ([`vlnverse_sensors::raster::PREPARED_FILE`]) of
//! every scene folder of a dataset again, as generation writes it: for a dataset generated
//! before [`vlnverse_sensors::raster::PREPARED_VERSION`] rose (its files are refused and its
//! homes prepared on every load otherwise).
//!
//! `cargo run --release -p vlnverse-sensors --example prepare_scenes -- DATASET`

use std::path::PathBuf;
use std::time::Instant;
use vlnverse_sensors::RasterScene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dataset = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .ok_or("usage: prepare_scenes DATASET")?;
    let scenes = dataset.join("scenes");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&scenes)
        .map_err(|e| format!("{}: {e}", scenes.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("scene.json").is_file())
        .collect();
    dirs.sort();
    let t0 = Instant::now();
    let bytes: Result<Vec<u64>, String> = {
        use rayon::prelude::*;
        dirs.par_iter()
            .map(|d| {
                let scene = vlnverse_env::io::load_scene(d).map_err(|e| e.to_string())?;
                let file =
                    RasterScene::write_prepared_scene(&scene, d).map_err(|e| e.to_string())?;
                Ok(std::fs::metadata(&file).map_err(|e| e.to_string())?.len())
            })
            .collect()
    };
    let bytes = bytes?;
    println!(
        "{} scenes prepared in {:.1} s, {:.2} MB a file on average",
        dirs.len(),
        t0.elapsed().as_secs_f64(),
        bytes.iter().sum::<u64>() as f64 / dirs.len().max(1) as f64 / 1e6
    );
    Ok(())
}
