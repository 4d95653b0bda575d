//! Statistics of a preset or a config file: rooms, areas, objects, triangles, time per scene,
//! homes on two floors.
//!
//! `cargo run --release -p vlnverse-procgen --example stats -- vlnverse` (or `tiny`, or a path
//! to a `.toml` config such as `configs/scenes/two_storey.toml`).
use std::time::Instant;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset, ProcgenConfig};

fn main() -> Result<(), vlnverse_env::EnvError> {
    let name = std::env::args().nth(1).unwrap_or_else(|| "vlnverse".into());
    let g = if name.ends_with(".toml") {
        HomeGenerator::new(ProcgenConfig::from_toml_file(&name)?)?
    } else {
        HomeGenerator::from_preset(name.parse::<Preset>()?)?
    };
    let mut two_storey = 0usize;
    let mut rooms = Vec::new();
    let mut areas = Vec::new();
    let mut items = Vec::new();
    let mut tris = Vec::new();
    let mut times = Vec::new();
    let mut classes = std::collections::BTreeMap::new();
    for i in 0..g.len() {
        let t = Instant::now();
        let s = match g.scene(i) {
            Ok(s) => s,
            Err(e) => {
                println!("scene {i}: {e}");
                continue;
            }
        };
        times.push(t.elapsed().as_secs_f64() * 1e3);
        rooms.push(s.rooms.len());
        two_storey += usize::from(s.is_multi_level());
        areas.push(s.rooms.iter().map(|r| r.area()).sum::<f32>());
        items.push(s.items().count());
        tris.push(s.triangle_count());
        for r in &s.rooms {
            use vlnverse_env::{RoomType as R, SemanticClass as C};
            let key = match r.kind {
                R::Bedroom => C::Bed,
                R::Bathroom => C::Toilet,
                R::Kitchen => C::Stove,
                R::LivingRoom => C::Sofa,
                R::DiningRoom => C::DiningTable,
                R::Office => C::Desk,
                R::LaundryRoom => C::WashingMachine,
                _ => continue,
            };
            if !s.items().any(|o| o.room == Some(r.id) && o.class == key) {
                println!("{} {} lacks {}", s.id, r.name, key);
            }
        }
        for o in s.items() {
            *classes.entry(o.class.name()).or_insert(0) += 1;
        }
    }
    let stat = |v: &[f64]| {
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        format!(
            "min {:.1} med {:.1} max {:.1}",
            v[0],
            v[v.len() / 2],
            v[v.len() - 1]
        )
    };
    let f = |v: &[usize]| v.iter().map(|&x| x as f64).collect::<Vec<_>>();
    println!("scenes {}", rooms.len());
    println!("two-storey {two_storey} of {}", rooms.len());
    println!("rooms {}", stat(&f(&rooms)));
    println!(
        "area {}",
        stat(&areas.iter().map(|&a| a as f64).collect::<Vec<_>>())
    );
    println!("items {}", stat(&f(&items)));
    println!("tris {}", stat(&f(&tris)));
    println!("ms {}", stat(&times));
    println!("{classes:?}");
    Ok(())
}
