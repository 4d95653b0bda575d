//! Reachability on the real navigable map (vlnverse-env occupancy): every room has navigable
//! cells and every doorway, with its approach points on both sides, lies on the one navigable
//! island (the map keeps only the largest island), so every room is reachable from every other,
//! round closed doors where there are any.

use crate::support;
use glam::Vec2;
use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};

#[test]
fn every_room_and_doorway_is_on_the_navigable_island() {
    let tiny = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let vln = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    let scenes = (0..tiny.len())
        .map(|i| tiny.scene(i).unwrap())
        .chain((0..30).map(|k| vln.scene(k * 263 / 30).unwrap()));
    let cfg = OccupancyConfig::default();
    // Each floor on its own map (the stairs join them: see storeys.rs).
    let floors = scenes.flat_map(|s| {
        let maps = build_level_maps(&s, &cfg).unwrap();
        support::floors(&s)
            .into_iter()
            .zip(maps)
            .collect::<Vec<_>>()
    });
    for (s, maps) in floors {
        let nav = &maps.navigable;
        let cell_area = nav.resolution * nav.resolution;
        for r in &s.rooms {
            let free = nav
                .free_cells()
                .filter(|&(c, w)| {
                    let p = nav.cell_center(c, w);
                    r.contains(p.x, p.y)
                })
                .count() as f32
                * cell_area;
            assert!(
                free >= 0.15 * r.area(),
                "{}: {} has {free:.2} m^2 navigable of {:.1}",
                s.id,
                r.name,
                r.area()
            );
        }
        for d in &s.doors {
            let c = Vec2::new(d.position[0], d.position[2]);
            let n = Vec2::from_array(d.normal);
            // A closed door blocks its doorway; both of its sides stay reachable.
            assert_eq!(nav.is_free_at(c), !d.is_closed(), "{}: door {}", s.id, d.id);
            for p in [c + n * 0.5, c - n * 0.5] {
                assert!(
                    nav.is_free_at(p),
                    "{}: door {} point {p} not navigable",
                    s.id,
                    d.id
                );
            }
        }
    }
}
