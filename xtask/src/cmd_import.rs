//! `cargo xtask import`: turn a glTF/GLB or OBJ home into a scene folder of our format
//! (`scene.glb`, `scene.json`, `scene_graph.json`, `occupancy.{pgm,yaml}`,
//! `navigable.{pgm,yaml}`, plus `import_report.json`) and print the import report.

use anyhow::Context;
use std::path::PathBuf;
use std::time::Instant;
use vlnverse_env::io::{scene_bundle, write_scene_dir};
use vlnverse_import::{import_scene, ImportOptions, Unit, UpAxis};

/// Arguments of `cargo xtask import`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Input file: `.glb`, `.gltf` (with its buffers beside it) or `.obj` (with its `.mtl`).
    #[arg(long)]
    pub input: PathBuf,
    /// Mapping file (TOML rules from names to classes), e.g. `configs/import/aws_small_house.toml`;
    /// default: the built-in generic English rules.
    #[arg(long)]
    pub mapping: Option<PathBuf>,
    /// Up axis of the source: `y` (glTF) or `z` (Blender, Habitat stages, CAD).
    #[arg(long, default_value = "y")]
    pub up: UpAxis,
    /// Length unit of the source: `m`, `cm` or `mm`.
    #[arg(long, default_value = "m")]
    pub unit: Unit,
    /// Room annotation file (TOML `[[room]]` with kind and polygon); default: segment rooms.
    #[arg(long)]
    pub rooms: Option<PathBuf>,
    /// Scene id (folder name); default: the input file stem.
    #[arg(long)]
    pub scene_id: Option<String>,
    /// Keep the source's heights instead of moving the detected floor to y = 0.
    #[arg(long)]
    pub keep_height: bool,
    /// Do not use the built-in rules when no mapping file is given.
    #[arg(long)]
    pub no_builtin_mapping: bool,
    /// Output folder; the scene goes to `<out>/<scene id>/`.
    #[arg(long)]
    pub out: PathBuf,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let opts = ImportOptions {
        up: args.up,
        unit: args.unit,
        mapping: args.mapping.clone(),
        builtin_mapping: !args.no_builtin_mapping,
        rooms: args.rooms.clone(),
        scene_id: args.scene_id.clone(),
        floor_to_zero: !args.keep_height,
        ..Default::default()
    };
    let (scene, report) = import_scene(&args.input, &opts)
        .with_context(|| format!("importing {}", args.input.display()))?;
    let bundle = scene_bundle(scene, &opts.occupancy)
        .with_context(|| format!("building maps and scene graph of {}", args.input.display()))?;
    let mut files = bundle.companion_files();
    let mut report_json = serde_json::to_vec_pretty(&report)?;
    report_json.push(b'\n');
    files.push(("import_report.json", report_json));
    let dir = write_scene_dir(&args.out, &bundle.scene, &files)
        .with_context(|| format!("writing the scene folder under {}", args.out.display()))?;
    print!("{report}");
    println!(
        "  navigable area {:.1} m^2; wrote {} in {:.2} s",
        bundle.maps.navigable.free_area_m2(),
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
