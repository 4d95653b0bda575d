//! Debug: print the rooms, doors and furniture of one scene.
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
fn main() -> Result<(), vlnverse_env::EnvError> {
    let mut a = std::env::args().skip(1);
    let preset: Preset = a.next().unwrap_or_else(|| "tiny".into()).parse()?;
    let i: usize = a.next().and_then(|s| s.parse().ok()).unwrap_or(0);
    let s = HomeGenerator::from_preset(preset)?.scene(i)?;
    for r in &s.rooms {
        println!("{} {:?}", r.name, r.polygon);
        for o in s.items().filter(|o| o.room == Some(r.id) && o.supported_by.is_none()) {
            println!("   {} {:?} {:?}", o.name, o.bbox.min, o.bbox.max);
        }
    }
    for d in &s.doors {
        println!("door {} {:?} w {} n {:?} rooms {:?} open {}", d.id, d.position, d.width, d.normal, d.rooms, d.open_plan);
    }
    Ok(())
}
