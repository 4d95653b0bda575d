//! The real homes of `../shared/scenes/` (outside the repository, see its README) that tests
//! and benches of several crates load: the AWS RoboMaker small house with its shipped label
//! mapping (`configs/import/aws_small_house.toml`). Feature `import`.

use std::path::PathBuf;
use vlnverse_import::ImportOptions;

/// The AWS small house (GLB, Y up) and the import options with its mapping file; `None`, with a
/// message on stderr, when `../shared/scenes/` is absent (callers then skip it).
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
