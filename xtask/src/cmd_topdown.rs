//! `cargo xtask topdown`: a top-down PNG of a scene folder (rooms, navigable area, walls,
//! doors, objects coloured by class with labels, legend and scale bar).

use anyhow::Context;
use std::path::{Path, PathBuf};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{render_topdown, TopdownOptions};

/// Arguments of `cargo xtask topdown`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Scene folder (with `scene.json`, `scene.glb`, optionally `navigable.yaml`).
    #[arg(long)]
    pub scene: PathBuf,
    /// Output PNG file.
    #[arg(long)]
    pub out: PathBuf,
    /// Pixels per metre.
    #[arg(long, default_value_t = 50.0)]
    pub px_per_m: f32,
    /// Leave out the class labels on furniture.
    #[arg(long)]
    pub no_labels: bool,
}

/// Render the picture of a scene folder as PNG bytes.
pub fn render_png(scene_dir: &Path, px_per_m: f32, labels: bool) -> anyhow::Result<Vec<u8>> {
    let scene = vlnverse_env::io::load_scene(scene_dir)?;
    let nav_yaml = scene_dir.join("navigable.yaml");
    let nav = if nav_yaml.is_file() {
        Some(GridMap::load_ros(&nav_yaml)?)
    } else {
        None
    };
    let opts = TopdownOptions {
        px_per_m,
        labels,
        title: scene.id.clone(),
        ..TopdownOptions::default()
    };
    let td = render_topdown(&scene, nav.as_ref(), &opts);
    let mut png = Vec::new();
    td.image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .context("PNG encoding failed")?;
    Ok(png)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.px_per_m > 0.0 && args.px_per_m.is_finite()) {
        anyhow::bail!("invalid `--px-per-m` = {}: must be > 0", args.px_per_m);
    }
    let png = render_png(&args.scene, args.px_per_m, !args.no_labels)?;
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", dir.display()))?;
    }
    vlnverse_env::io::write_atomic(&args.out, &png)?;
    println!("topdown: {}", args.out.display());
    Ok(())
}
