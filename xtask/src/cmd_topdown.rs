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

/// The warning when the picture is drawn at another scale than asked (the map area is limited
/// to `max_size` pixels, and to at least 1 pixel per metre); `None` when it is as asked.
pub fn clamp_warning(requested: f32, used: f32, max_size: u32) -> Option<String> {
    if (used - requested).abs() <= 1e-3 * requested.abs().max(1.0) {
        return None;
    }
    Some(if used < requested {
        format!(
            "--px-per-m {requested} is more than this scene allows (the map is at most \
             {max_size} pixels wide or high, so 1 to {used} px/m); drawn at {used} px/m"
        )
    } else {
        format!("--px-per-m {requested} is below the minimum of 1 px/m; drawn at {used} px/m")
    })
}

/// Render the picture of a scene folder as PNG bytes.
pub fn render_png(scene_dir: &Path, px_per_m: f32, labels: bool) -> anyhow::Result<Vec<u8>> {
    Ok(render_png_scaled(scene_dir, px_per_m, labels)?.0)
}

/// [`render_png`], also returning the pixels per metre used (see [`clamp_warning`]).
pub fn render_png_scaled(
    scene_dir: &Path,
    px_per_m: f32,
    labels: bool,
) -> anyhow::Result<(Vec<u8>, f32)> {
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
    if let Some(w) = clamp_warning(px_per_m, td.frame.px_per_m, opts.max_size) {
        tracing::warn!("{}: {w}", scene_dir.display());
    }
    let mut png = Vec::new();
    td.image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .context("PNG encoding failed")?;
    Ok((png, td.frame.px_per_m))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A scale the map cannot hold is lowered with a warning naming both values; a scale that
    /// fits says nothing.
    #[test]
    fn a_clamped_scale_is_reported_with_the_requested_and_used_value() {
        let dir = tempfile::tempdir().unwrap();
        let scene = vlnverse_sensors::demo::demo_scene(1);
        let folder = vlnverse_env::io::write_scene_dir(dir.path(), &scene, &[]).unwrap();
        let (_, used) = render_png_scaled(&folder, 100000.0, false).unwrap();
        assert!((1.0..100000.0).contains(&used), "{used}");
        let w = clamp_warning(100000.0, used, TopdownOptions::default().max_size).unwrap();
        assert!(
            w.contains("100000") && w.contains(&format!("{used}")),
            "{w}"
        );
        let (_, used) = render_png_scaled(&folder, 20.0, false).unwrap();
        assert_eq!(used, 20.0);
        assert_eq!(clamp_warning(20.0, used, 3000), None);
        // Below 1 px/m the picture is drawn at 1.
        let w = clamp_warning(0.01, 1.0, 3000).unwrap();
        assert!(w.contains("0.01") && w.contains("at 1 px/m"), "{w}");
    }
}
