//! `cargo xtask scene-info`: statistics of one scene folder or a folder of scenes (navigable
//! area, rooms by type, objects by class, triangle counts).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vlnverse_env::occupancy::GridMap;

/// Arguments of `cargo xtask scene-info`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// A scene folder, or a folder of scene folders.
    pub dir: PathBuf,
}

/// The scene folders under `dir` (itself if it holds a `scene.json`), sorted by name.
pub fn scene_dirs(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    if dir.join("scene.json").is_file() {
        return Ok(vec![dir.to_path_buf()]);
    }
    let rd = std::fs::read_dir(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    let mut v: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("scene.json").is_file())
        .collect();
    v.sort();
    if v.is_empty() {
        anyhow::bail!(
            "{}: no scene folder (nothing with a scene.json)",
            dir.display()
        );
    }
    Ok(v)
}

/// The statistics report as text.
pub fn report(dir: &Path) -> anyhow::Result<String> {
    let dirs = scene_dirs(dir)?;
    let mut out = String::new();
    let mut by_room: BTreeMap<String, usize> = BTreeMap::new();
    let mut by_class: BTreeMap<String, usize> = BTreeMap::new();
    let (mut tot_nav, mut tot_tris, mut tot_objs, mut tot_rooms) = (0.0f64, 0usize, 0usize, 0usize);
    let mut navs = Vec::new();
    writeln!(
        out,
        "{:<24} {:>5} {:>7} {:>9} {:>11} {:>11}",
        "scene", "rooms", "objects", "triangles", "floor m2", "navigable m2"
    )?;
    for d in &dirs {
        let scene = vlnverse_env::io::load_scene(d)?;
        let nav_yaml = d.join("navigable.yaml");
        let nav = if nav_yaml.is_file() {
            Some(GridMap::load_ros(&nav_yaml)?.free_area_m2() as f64)
        } else {
            None
        };
        let floor: f32 = scene.rooms.iter().map(|r| r.area()).sum();
        let items = scene.items().count();
        let tris = scene.triangle_count();
        for r in &scene.rooms {
            *by_room.entry(r.kind.name().to_string()).or_default() += 1;
        }
        for o in scene.items() {
            *by_class.entry(o.class.name().to_string()).or_default() += 1;
        }
        writeln!(
            out,
            "{:<24} {:>5} {:>7} {:>9} {:>11.1} {:>11}",
            scene.id,
            scene.rooms.len(),
            items,
            tris,
            floor,
            nav.map_or("-".to_string(), |a| format!("{a:.1}"))
        )?;
        tot_rooms += scene.rooms.len();
        tot_objs += items;
        tot_tris += tris;
        if let Some(a) = nav {
            tot_nav += a;
            navs.push(a);
        }
    }
    let n = dirs.len();
    writeln!(out)?;
    write!(
        out,
        "{n} scenes, {tot_rooms} rooms, {tot_objs} objects, {tot_tris} triangles"
    )?;
    if !navs.is_empty() {
        let lo = navs.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = navs.iter().cloned().fold(0.0, f64::max);
        write!(
            out,
            "; navigable {:.1} m2 in all, per scene mean {:.1}, min {lo:.1}, max {hi:.1}",
            tot_nav,
            tot_nav / navs.len() as f64
        )?;
    }
    writeln!(out)?;
    let mut table = |title: &str, m: &BTreeMap<String, usize>| -> std::fmt::Result {
        let mut v: Vec<(&String, &usize)> = m.iter().collect();
        v.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        writeln!(out, "\n{:<20} {:>7} {:>9}", title, "count", "per scene")?;
        for (k, c) in v {
            writeln!(out, "{:<20} {:>7} {:>9.2}", k, c, *c as f64 / n as f64)?;
        }
        Ok(())
    };
    table("room type", &by_room)?;
    table("object class", &by_class)?;
    Ok(out)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    print!("{}", report(&args.dir)?);
    Ok(())
}
