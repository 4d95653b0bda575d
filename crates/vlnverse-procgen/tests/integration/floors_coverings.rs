//! Floor coverings: carpet in many bedrooms and some studies, home theaters and libraries,
//! stone tiles in some halls, concrete in garages, wood by default; each drawn the way it is
//! named (a carpet looks like carpet, wood like boards).

use rayon::prelude::*;
use std::collections::BTreeMap;
use vlnverse_env::material::{surface_of, Surface};
use vlnverse_env::{RoomType, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset};

#[test]
fn floors_are_covered_as_their_rooms_are_and_look_like_their_material() {
    let v = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    let floors: Vec<(RoomType, String, Surface)> = (0..v.len())
        .into_par_iter()
        .flat_map_iter(|i| {
            let s = v.scene(i).unwrap();
            let area = |o: &vlnverse_env::SceneObject| o.bbox.size().x * o.bbox.size().z;
            s.rooms
                .iter()
                .filter_map(|r| {
                    // The room's slab: its largest floor object (skirting boards are floors too).
                    let slab = s
                        .objects
                        .iter()
                        .filter(|o| o.class == C::Floor && o.room == Some(r.id))
                        .max_by(|a, b| area(a).total_cmp(&area(b)))?;
                    Some((r.kind, slab.material.clone(), surface_of(&s, slab)))
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut by: BTreeMap<(RoomType, &str), usize> = BTreeMap::new();
    for (kind, material, surface) in &floors {
        *by.entry((*kind, material.as_str())).or_default() += 1;
        let want = match material.as_str() {
            "carpet" => Surface::Carpet,
            "wood" => Surface::WoodFloor,
            "tile" | "stone" => Surface::Tiles,
            "concrete" => Surface::Plaster,
            other => panic!("a floor of {other}"),
        };
        assert_eq!(*surface, want, "{kind:?} floor of {material}");
        match kind {
            RoomType::Garage | RoomType::Workshop => assert_eq!(material, "concrete"),
            RoomType::Kitchen | RoomType::Bathroom | RoomType::Spa | RoomType::MudRoom => {
                assert_eq!(material, "tile")
            }
            RoomType::WineCellar => assert_eq!(material, "stone"),
            _ => {}
        }
        if material == "carpet" {
            assert!(matches!(
                kind,
                RoomType::Bedroom
                    | RoomType::Office
                    | RoomType::HomeTheater
                    | RoomType::Library
                    | RoomType::Playroom
            ));
        }
    }
    let count = |k: RoomType, m: &str| by.get(&(k, m)).copied().unwrap_or(0);
    eprintln!("floors by room and material: {by:?}");
    let bedrooms = count(RoomType::Bedroom, "carpet") + count(RoomType::Bedroom, "wood");
    let share = count(RoomType::Bedroom, "carpet") as f32 / bedrooms.max(1) as f32;
    assert!(
        (0.35..0.75).contains(&share),
        "{share} of bedrooms carpeted"
    );
    assert!(count(RoomType::Office, "carpet") >= 10);
    assert!(count(RoomType::Hallway, "stone") >= 10);
    // Wood stays the most common floor.
    let total = |m: &str| floors.iter().filter(|f| f.1 == m).count();
    assert!(total("wood") > total("carpet") && total("wood") > total("tile"));
}
