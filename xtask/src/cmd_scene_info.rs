//! `cargo xtask scene-info`: statistics of one scene folder or a folder of scenes (floors,
//! navigable area, rooms by type, objects by class, triangle counts). `objects` counts every
//! object, structure included (as the importer's report); `items` the non-structure objects,
//! and `outside` those of them that lie in no room. The navigable area of a home on several
//! floors is that of all its floors.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `cargo xtask scene-info`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// A scene folder, or a folder of scene folders.
    pub dir: PathBuf,
}

/// The scene folders under `dir` (itself if it holds a `scene.json`), sorted by name; entries
/// whose name starts with `.` (an interrupted writer's temporary folders) are not scenes.
pub fn scene_dirs(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    if dir.join("scene.json").is_file() {
        return Ok(vec![dir.to_path_buf()]);
    }
    let v = vlnverse_env::io::list_scene_dirs(dir)?;
    if v.is_empty() {
        anyhow::bail!(
            "{}: no scene folder (nothing with a scene.json)",
            dir.display()
        );
    }
    Ok(v)
}

/// The statistics report as text. Columns: `objects` counts every object (structure included,
/// as the importer's report does), `items` the non-structure ones (furniture, small objects,
/// unknown), `outside` the items that lie in no room.
pub fn report(dir: &Path) -> anyhow::Result<String> {
    let dirs = scene_dirs(dir)?;
    let mut out = String::new();
    let mut by_room: BTreeMap<String, usize> = BTreeMap::new();
    let mut by_class: BTreeMap<String, usize> = BTreeMap::new();
    let (mut tot_nav, mut tot_tris, mut tot_items, mut tot_rooms) =
        (0.0f64, 0usize, 0usize, 0usize);
    let (mut tot_objs, mut tot_outside) = (0usize, 0usize);
    let mut navs = Vec::new();
    let mut rows: Vec<[String; 9]> = Vec::new();
    for d in &dirs {
        let scene = vlnverse_env::io::load_scene(d)?;
        let floors = scene.level_count();
        let nav = navigable_area(d, floors)?;
        let floor: f32 = scene.rooms.iter().map(|r| r.area()).sum();
        let items = scene.items().count();
        let outside = scene.items().filter(|o| o.room.is_none()).count();
        let tris = scene.triangle_count();
        for r in &scene.rooms {
            *by_room.entry(r.kind.name().to_string()).or_default() += 1;
        }
        for o in scene.items() {
            *by_class.entry(o.class.name().to_string()).or_default() += 1;
        }
        rows.push([
            scene.id.clone(),
            floors.to_string(),
            scene.rooms.len().to_string(),
            scene.objects.len().to_string(),
            items.to_string(),
            outside.to_string(),
            tris.to_string(),
            format!("{floor:.1}"),
            nav.map_or("-".to_string(), |a| format!("{a:.1}")),
        ]);
        tot_rooms += scene.rooms.len();
        tot_objs += scene.objects.len();
        tot_items += items;
        tot_outside += outside;
        tot_tris += tris;
        if let Some(a) = nav {
            tot_nav += a;
            navs.push(a);
        }
    }
    let header = [
        "scene",
        "floors",
        "rooms",
        "objects",
        "items",
        "outside",
        "triangles",
        "floor m2",
        "navigable m2",
    ];
    // Each column as wide as its widest cell, so long scene names keep the table aligned.
    let widths: Vec<usize> = (0..header.len())
        .map(|c| {
            rows.iter()
                .map(|r| r[c].len())
                .chain([header[c].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: [&str; 9]| -> String {
        let mut l = format!("{:<w$}", cells[0], w = widths[0]);
        for (c, w) in cells.iter().zip(&widths).skip(1) {
            l += &format!(" {:>w$}", c, w = *w);
        }
        l
    };
    writeln!(out, "{}", line(header))?;
    for r in &rows {
        writeln!(out, "{}", line(r.each_ref().map(|s| s.as_str())))?;
    }
    let n = dirs.len();
    writeln!(out)?;
    write!(
        out,
        "{n} scenes, {tot_rooms} rooms, {tot_objs} objects ({tot_items} non-structure, \
         {tot_outside} of them outside rooms), {tot_tris} triangles"
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

/// The navigable area (m^2) of a scene folder's `floors` floors: `navigable.yaml` and, above
/// the ground floor, `navigable_level<k>.yaml`; `None` when the ground floor's map is missing.
fn navigable_area(dir: &Path, floors: usize) -> anyhow::Result<Option<f64>> {
    let mut total = None;
    for k in 0..floors as u32 {
        match crate::cmd_topdown::navigable_map(dir, k)? {
            Some(map) => total = Some(total.unwrap_or(0.0) + map.free_area_m2() as f64),
            None if k == 0 => return Ok(None),
            None => {}
        }
    }
    Ok(total)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    print!("{}", report(&args.dir)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Long scene names keep the table aligned; `objects` counts structure too, and items
    /// outside every room are counted.
    #[test]
    fn counts_every_object_and_keeps_columns_aligned() {
        let dir = tempfile::tempdir().unwrap();
        let in_rooms = |seed: u64, id: &str| {
            let mut s = vlnverse_sensors::demo::demo_scene(seed);
            s.id = id.into();
            let room = s.rooms[0].id;
            for o in s.objects.iter_mut().filter(|o| !o.is_structure()) {
                o.room = Some(room);
            }
            s
        };
        let mut a = in_rooms(1, "a_scene_with_a_name_much_longer_than_twenty_four");
        let first_item = a.objects.iter().position(|o| !o.is_structure()).unwrap();
        a.objects[first_item].room = None;
        let b = in_rooms(2, "b");
        for s in [&a, &b] {
            vlnverse_env::io::write_scene_dir(dir.path(), s, &[]).unwrap();
        }
        let text = report(dir.path()).unwrap();
        let lines: Vec<&str> = text.lines().take(3).collect();
        // Right-aligned columns end at the same character in every row.
        assert!(lines.iter().all(|l| l.len() == lines[0].len()), "{text}");
        let cells: Vec<Vec<&str>> = lines
            .iter()
            .map(|l| l.split_whitespace().collect())
            .collect();
        assert_eq!(
            cells[0][1..6],
            ["floors", "rooms", "objects", "items", "outside"]
        );
        let row = &cells[1];
        assert_eq!(row[0], a.id);
        assert_eq!(row[1], "1");
        assert_eq!(row[3], a.objects.len().to_string());
        assert_eq!(row[4], a.items().count().to_string());
        assert_eq!(row[5], "1");
        assert!(a.objects.len() > a.items().count());
        assert_eq!(cells[2][5], "0");
    }

    /// A home on two floors counts its floors and the navigable area of both.
    #[test]
    fn a_two_storey_home_counts_both_floors() {
        let dir = tempfile::tempdir().unwrap();
        let folder = crate::cmd_topdown::two_storey_folder(dir.path());
        let ground = vlnverse_env::occupancy::GridMap::load_ros(folder.join("navigable.yaml"))
            .unwrap()
            .free_area_m2() as f64;
        let both = navigable_area(&folder, 2).unwrap().unwrap();
        assert!(
            both > ground + 5.0,
            "upper floor adds no area: {ground} {both}"
        );
        let text = report(&folder).unwrap();
        let row: Vec<&str> = text.lines().nth(1).unwrap().split_whitespace().collect();
        assert_eq!(row[1], "2", "{text}");
        assert_eq!(row[8], format!("{both:.1}"), "{text}");
    }
}
