//! Import a file and print the report (development aid): `cargo run -p vlnverse-import
//! --example inspect -- FILE [MAPPING] [z]`.
use std::path::PathBuf;
use vlnverse_import::{import_scene, ImportOptions, UpAxis};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut opts = ImportOptions {
        mapping: args.get(2).filter(|s| !s.is_empty()).map(PathBuf::from),
        ..Default::default()
    };
    if args.get(3).map(|s| s == "z").unwrap_or(false) {
        opts.up = UpAxis::Z;
    }
    let t = std::time::Instant::now();
    match import_scene(&PathBuf::from(&args[1]), &opts) {
        Ok((scene, report)) => {
            println!("{report}");
            println!("took {:?}", t.elapsed());
            for r in &scene.rooms {
                println!("room {} {} area {:.1} verts {}", r.id, r.name, r.area(), r.polygon.len());
            }
            for d in &scene.doors {
                println!("door {:?} w {:.2} rooms {:?} open {}", d.position, d.width, d.rooms, d.open_plan);
            }
            if let Some(png) = args.get(4) {
                let b = scene.bounds();
                let res = 0.05;
                let (w, h) = (((b.max[0] - b.min[0]) / res) as u32 + 1, ((b.max[2] - b.min[2]) / res) as u32 + 1);
                let occ = vlnverse_env::occupancy::build_maps(&scene, &Default::default()).unwrap().occupancy;
                let img = image::RgbImage::from_fn(w, h, |x, y| {
                    let p = glam::Vec2::new(b.min[0] + (x as f32 + 0.5) * res, b.min[2] + (y as f32 + 0.5) * res);
                    let base = match scene.room_at(p.x, p.y) {
                        Some(r) => { let k = (r.id as u32 + 1).wrapping_mul(2654435761); [(k >> 8) as u8 | 64, (k >> 16) as u8 | 64, (k >> 24) as u8 | 64] }
                        None => [40, 40, 40],
                    };
                    if !occ.is_free_at(p) { image::Rgb(base.map(|c| c / 3)) } else { image::Rgb(base) }
                });
                img.save(png).unwrap();
            }
            if let Some(yaml) = args.get(5) {
                use vlnverse_env::occupancy::{CellState, GridMap};
                let slam = GridMap::load_ros(yaml).unwrap();
                let occ = vlnverse_env::occupancy::build_maps(&scene, &Default::default()).unwrap().occupancy;
                let img = image::RgbImage::from_fn(slam.width, slam.height, |x, y| {
                    let p = slam.cell_center(x, y);
                    let s = slam.state(x, y);
                    let o = occ.world_to_cell(p).map(|(c, r)| occ.state(c, r));
                    let mut px = match s { CellState::Occupied => [0, 0, 255], CellState::Free => [230, 230, 230], CellState::Unknown => [120, 120, 120] };
                    if o == Some(CellState::Occupied) { px[0] = 255; if s != CellState::Occupied { px[1] = 0; px[2] = 0; } }
                    image::Rgb(px)
                });
                img.save("/tmp/slam_overlay.png").unwrap();
            }
            for o in &scene.objects {
                println!("  {:3} {:28} {:16} room {:?} bbox {:?}..{:?}", o.id, o.name, o.class.name(), o.room,
                    o.bbox.min.map(|v| (v * 100.0).round() / 100.0), o.bbox.max.map(|v| (v * 100.0).round() / 100.0));
            }
        }
        Err(e) => println!("error: {e}"),
    }
}
