//! `cargo xtask topdown`: a top-down PNG of a scene folder (rooms, navigable area, walls,
//! doors, objects coloured by class with labels, legend and scale bar); one per floor for a
//! home on several floors.

use anyhow::Context;
use std::path::{Path, PathBuf};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{render_topdown, render_topdown_level, TopdownOptions};

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
    /// Only this floor (0 = ground floor) of a home on several floors. Without it, a home on
    /// several floors gives one picture per floor: floor 0 in `--out`, floor k beside it as
    /// `<name>_level<k>.png`.
    #[arg(long)]
    pub level: Option<u32>,
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

/// The pictures of one floor of a scene folder, or of every floor (`level` `None`), as
/// `(level, PNG bytes)`; floor `k > 0` is drawn with its own navigable map
/// (`navigable_level<k>.yaml`). An error names the scene and its floors for a floor it lacks.
pub fn render_levels(
    scene_dir: &Path,
    px_per_m: f32,
    labels: bool,
    level: Option<u32>,
) -> anyhow::Result<Vec<(u32, Vec<u8>)>> {
    let scene = vlnverse_env::io::load_scene(scene_dir)?;
    let levels = scene.level_count() as u32;
    if let Some(k) = level.filter(|&k| k >= levels) {
        anyhow::bail!(
            "--level {k}: scene `{}` ({}) has {levels} floor{} (0 to {})",
            scene.id,
            scene_dir.display(),
            if levels == 1 { "" } else { "s" },
            levels - 1
        );
    }
    if levels == 1 {
        return Ok(vec![(0, render_png(scene_dir, px_per_m, labels)?)]);
    }
    let wanted: Vec<u32> = level.map_or_else(|| (0..levels).collect(), |k| vec![k]);
    let mut out = Vec::new();
    for k in wanted {
        let nav = navigable_map(scene_dir, k)?;
        let opts = options(&scene, px_per_m, labels);
        let td = render_topdown_level(&scene, k, nav.as_ref(), &opts)
            .with_context(|| format!("scene `{}` has no floor {k}", scene.id))?;
        out.push((k, png_bytes(&td)?));
    }
    Ok(out)
}

/// Where the picture of floor `k` goes: `out` for floor 0 or a single floor asked for,
/// `<stem>_level<k>.png` beside it for the other floors of an all-floors run.
fn level_path(out: &Path, k: u32, single: bool) -> PathBuf {
    if single || k == 0 {
        return out.to_path_buf();
    }
    let stem = out
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("topdown");
    out.with_file_name(format!("{stem}_level{k}.png"))
}

/// [`render_png`], also returning the pixels per metre used (see [`clamp_warning`]).
pub fn render_png_scaled(
    scene_dir: &Path,
    px_per_m: f32,
    labels: bool,
) -> anyhow::Result<(Vec<u8>, f32)> {
    let scene = vlnverse_env::io::load_scene(scene_dir)?;
    let nav = navigable_map(scene_dir, 0)?;
    let opts = options(&scene, px_per_m, labels);
    let td = render_topdown(&scene, nav.as_ref(), &opts);
    if let Some(w) = clamp_warning(px_per_m, td.frame.px_per_m, opts.max_size) {
        tracing::warn!("{}: {w}", scene_dir.display());
    }
    Ok((png_bytes(&td)?, td.frame.px_per_m))
}

/// The navigable map of floor `level` in a scene folder (`navigable.yaml`, or
/// `navigable_level<k>.yaml` above the ground floor), if the folder has one.
pub fn navigable_map(scene_dir: &Path, level: u32) -> anyhow::Result<Option<GridMap>> {
    let yaml = scene_dir.join(vlnverse_env::occupancy::level_map_file(
        "navigable",
        level,
        "yaml",
    ));
    Ok(if yaml.is_file() {
        Some(GridMap::load_ros(&yaml)?)
    } else {
        None
    })
}

/// The picture options of the command for `scene`.
fn options(scene: &vlnverse_env::Scene, px_per_m: f32, labels: bool) -> TopdownOptions {
    TopdownOptions {
        px_per_m,
        labels,
        title: scene.id.clone(),
        ..TopdownOptions::default()
    }
}

/// The picture as PNG bytes.
fn png_bytes(td: &vlnverse_env::topdown::Topdown) -> anyhow::Result<Vec<u8>> {
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
    let pictures = render_levels(&args.scene, args.px_per_m, !args.no_labels, args.level)?;
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", dir.display()))?;
    }
    let single = pictures.len() == 1;
    for (k, png) in pictures {
        let path = level_path(&args.out, k, single);
        vlnverse_env::io::write_atomic(&path, &png)?;
        println!("topdown: {}", path.display());
    }
    Ok(())
}

/// A scene folder of the first home of `configs/scenes/two_storey.toml` (two floors, with each
/// floor's maps) written under `dir`, for the tests of the commands that read floors.
#[cfg(test)]
pub fn two_storey_folder(dir: &Path) -> PathBuf {
    let mut cfg = vlnverse_procgen::ProcgenConfig::from_toml_str(
        include_str!("../../configs/scenes/two_storey.toml"),
        None,
    )
    .unwrap();
    cfg.scenes.count = 1;
    let generator = vlnverse_procgen::HomeGenerator::new(cfg).unwrap();
    let scene = vlnverse_env::SceneSource::scene(&generator, 0).unwrap();
    let occupancy = vlnverse_env::occupancy::OccupancyConfig::default();
    vlnverse_env::io::write_scene_bundle(dir, scene, &occupancy)
        .unwrap()
        .1
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

    /// A home on two floors gives a picture per floor, each of its own rooms; a floor it lacks
    /// is refused naming the scene and its floors; a one-floor home gives one picture.
    #[test]
    fn a_two_storey_home_gives_a_picture_per_floor() {
        let dir = tempfile::tempdir().unwrap();
        let folder = two_storey_folder(dir.path());
        let all = render_levels(&folder, 20.0, false, None).unwrap();
        assert_eq!(all.iter().map(|p| p.0).collect::<Vec<_>>(), vec![0, 1]);
        assert_ne!(all[0].1, all[1].1, "the two floors drew the same picture");
        let upper = render_levels(&folder, 20.0, false, Some(1)).unwrap();
        assert_eq!(upper, vec![all[1].clone()]);
        let err = render_levels(&folder, 20.0, false, Some(2))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("--level 2") && err.contains("2 floors"),
            "{err}"
        );
        let out = Path::new("/x/home.png");
        assert_eq!(level_path(out, 1, false), Path::new("/x/home_level1.png"));
        assert_eq!(level_path(out, 1, true), out);

        let flat = vlnverse_sensors::demo::demo_scene(1);
        let flat = vlnverse_env::io::write_scene_dir(dir.path(), &flat, &[]).unwrap();
        assert_eq!(render_levels(&flat, 20.0, false, None).unwrap().len(), 1);
        let err = render_levels(&flat, 20.0, false, Some(1))
            .unwrap_err()
            .to_string();
        assert!(err.contains("1 floor (0 to 0)"), "{err}");
    }
}
