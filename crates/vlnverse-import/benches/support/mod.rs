//! Set-up shared by the benches that work on a real home: the AWS RoboMaker small house of
//! `../shared/scenes/` (see its README) with the shipped label mapping. Included with
//! `mod support;` by `benches/import.rs`, and by `vlnverse-sensors/benches/support/mod.rs`
//! through a `#[path]` (both crates sit at the same depth, so the paths below hold for both).

use std::path::PathBuf;
use vlnverse_import::ImportOptions;

/// The AWS small house (GLB, Y up) and the import options with its mapping file; None, with a
/// message, when `../shared/scenes/` is absent (the benches then skip it).
pub fn aws_small_house() -> Option<(PathBuf, ImportOptions)> {
    let file = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/scenes/aws_small_house/aws_small_house_yup.glb"
    ));
    if !file.exists() {
        eprintln!("skipped: {} is absent", file.display());
        return None;
    }
    let opts = ImportOptions {
        mapping: Some(PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../configs/import/aws_small_house.toml"
        ))),
        ..Default::default()
    };
    Some((file, opts))
}
