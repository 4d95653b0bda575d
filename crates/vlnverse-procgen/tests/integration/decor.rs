//! Windows, skirting boards and pictures: where they stand, and that they change nothing else
//! (object ids, occupancy, the navigable map) while windows brighten the baked light.

use vlnverse_env::occupancy::{build_level_maps, build_maps, OccupancyConfig};
use vlnverse_env::{light, Scene, SceneObject, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset, ProcgenConfig};

fn generator(decor: bool) -> HomeGenerator {
    let mut cfg: ProcgenConfig = Preset::Tiny.config().unwrap();
    cfg.walls.decor = decor;
    cfg.walls.pictures = decor;
    HomeGenerator::new(cfg).unwrap()
}

fn pair(i: usize) -> (Scene, Scene) {
    (
        generator(true).scene(i).unwrap(),
        generator(false).scene(i).unwrap(),
    )
}

fn panes(s: &Scene) -> Vec<&SceneObject> {
    s.objects.iter().filter(|o| light::is_pane(o)).collect()
}

/// The objects with the ceilings' light panels (parts after the slab) taken off.
fn without_panels(objects: &[SceneObject]) -> Vec<SceneObject> {
    objects
        .iter()
        .map(|o| {
            let mut o = o.clone();
            if o.class == C::Ceiling {
                o.parts.truncate(1);
                o.bbox = o.compute_bbox();
            }
            o
        })
        .collect()
}

#[test]
fn decor_comes_after_every_other_object_and_changes_no_map() {
    let vln = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    let mut cfg = vln.config().clone();
    cfg.walls.decor = false;
    let bare_vln = HomeGenerator::new(cfg).unwrap();
    let tiny = (0..generator(true).len()).map(pair);
    let big = (0..6).map(|k| (vln.scene(k * 40).unwrap(), bare_vln.scene(k * 40).unwrap()));
    let occ = OccupancyConfig::default();
    let mut windows = 0;
    let mut two = 0;
    for (with, without) in tiny.chain(big) {
        let occ_maps = |s: &Scene| build_level_maps(s, &occ).unwrap();
        if with.is_multi_level() {
            // Each floor's decoration follows that floor's objects, so ids move; what is
            // checked is that the rooms and every floor's maps are the same.
            two += 1;
            assert_eq!(with.rooms, without.rooms);
            assert!(with.objects.len() > without.objects.len());
            assert_eq!(occ_maps(&with), occ_maps(&without), "{}", with.id);
            continue;
        }
        let n = without.objects.len();
        assert!(with.objects.len() > n, "{}: no decoration", with.id);
        assert_eq!(
            without_panels(&with.objects[..n]),
            without.objects[..],
            "{}",
            with.id
        );
        assert_eq!(with.rooms, without.rooms);
        assert_eq!(with.doors, without.doors);
        for o in &with.objects[n..] {
            assert!(
                matches!(o.class, C::Window | C::Curtain | C::Floor | C::PictureFrame),
                "{}: {:?}",
                with.id,
                o.class
            );
        }
        windows += panes(&with).len();
        let (a, b) = (
            build_maps(&with, &occ).unwrap(),
            build_maps(&without, &occ).unwrap(),
        );
        assert_eq!(a.occupancy, b.occupancy, "{}: occupancy changed", with.id);
        assert_eq!(
            a.navigable, b.navigable,
            "{}: navigable map changed",
            with.id
        );
    }
    assert!(windows >= 10, "{windows} windows");
    assert!(two > 0, "no two-storey home in the sample");
}

#[test]
fn windows_hang_on_exterior_walls_at_window_height_clear_of_doors() {
    let g = generator(true);
    let mut count = 0;
    for i in 0..g.len() {
        let s = g.scene(i).unwrap();
        let (lo, hi) = (s.bounds().min, s.bounds().max);
        for o in s.objects.iter().filter(|o| o.class == C::Window) {
            count += 1;
            let b = o.bbox;
            assert!(b.min[1] >= 0.75 && b.max[1] <= 2.45, "{}: {b:?}", s.id);
            // Against an exterior wall: within 0.25 m of the home's outer bounds along the
            // thin axis.
            let thin = if b.max[0] - b.min[0] < b.max[2] - b.min[2] {
                0
            } else {
                2
            };
            let near_edge =
                (b.min[thin] - lo[thin]).abs() < 0.25 || (hi[thin] - b.max[thin]).abs() < 0.25;
            assert!(
                near_edge,
                "{}: window {} not on an exterior wall",
                s.id, o.id
            );
            for d in &s.doors {
                let c = vlnverse_procgen::door_clearance(d, 0.3, 2.0);
                let overlap = (0..3).all(|k| b.min[k] < c.max[k] && b.max[k] > c.min[k]);
                assert!(!overlap, "{}: window {} overlaps door {}", s.id, o.id, d.id);
            }
        }
        // The pane glows: baked at full light.
        let baked = light::bake_fresh(&s);
        let mut k = 0;
        for o in &s.objects {
            for _ in &o.parts {
                if light::is_pane(o) {
                    assert!(baked.parts[k].iter().all(|c| c[1] == 255));
                }
                k += 1;
            }
        }
    }
    assert!(count > 0);
}

#[test]
fn skirting_boards_run_along_the_walls() {
    let s = generator(true).scene(0).unwrap();
    let boards: Vec<_> = s
        .objects
        .iter()
        .filter(|o| o.class == C::Floor && o.bbox.max[1] > 0.06)
        .collect();
    // At least a board per room, each a thin strip along one wall face.
    assert!(boards.len() >= s.rooms.len() * 3, "{} boards", boards.len());
    for o in &boards {
        let b = o.bbox;
        assert!(
            (b.max[0] - b.min[0]).min(b.max[2] - b.min[2]) < 0.02,
            "{b:?}"
        );
    }
}

#[test]
fn paintings_hang_at_eye_height_and_are_landmarks() {
    let g = generator(true);
    let mut count = 0;
    for i in 0..g.len() {
        let s = g.scene(i).unwrap();
        for o in s
            .objects
            .iter()
            .filter(|o| o.class == C::PictureFrame && o.material == "canvas")
        {
            count += 1;
            assert!(
                o.bbox.min[1] > 1.1 && o.bbox.max[1] < 2.0,
                "{}: {:?}",
                s.id,
                o.bbox
            );
            assert!(vlnverse_env::scene_graph::is_landmark(o), "{}", o.name);
            assert!(o.supported_by.is_none());
            let room = s.room(o.room.unwrap()).unwrap();
            assert!(matches!(
                room.kind,
                vlnverse_env::RoomType::LivingRoom
                    | vlnverse_env::RoomType::Bedroom
                    | vlnverse_env::RoomType::Hallway
                    | vlnverse_env::RoomType::DiningRoom
                    | vlnverse_env::RoomType::Office
                    | vlnverse_env::RoomType::EntranceHall
                    | vlnverse_env::RoomType::Library
                    | vlnverse_env::RoomType::HomeTheater
                    | vlnverse_env::RoomType::Playroom
                    | vlnverse_env::RoomType::Spa
            ));
        }
    }
    assert!(count >= 3, "{count} pictures");
}

#[test]
fn window_daylight_brightens_the_floor_in_front_of_it() {
    // The window whose floor in front is brightened most, over the tiny homes: furniture and
    // clutter by a window (a radiator under it) shade the floor in front of some windows.
    let g = generator(true);
    let mut best = (0i32, 1);
    for i in 0..g.len() {
        let s = g.scene(i).unwrap();
        let mut dark = s.clone();
        // Same geometry, panes no longer lights (material word changed).
        for o in dark.objects.iter_mut().filter(|o| light::is_pane(o)) {
            o.material = "plastic".into();
        }
        let (lit, unlit) = (light::bake_fresh(&s), light::bake_fresh(&dark));
        let meshes = light::bake_meshes(&s);
        for pane in panes(&s) {
            let centre = pane.bbox.center();
            // Floor vertices within 1.2 m of the window's foot.
            let (mut gain, mut n) = (0i32, 0);
            let mut k = 0;
            for o in &s.objects {
                for _ in &o.parts {
                    if o.class == C::Floor {
                        for (i, p) in meshes[k].positions.iter().enumerate() {
                            let d = glam::Vec2::new(p[0] - centre.x, p[2] - centre.z).length();
                            if p[1] > -0.01 && d < 1.2 {
                                gain +=
                                    i32::from(lit.parts[k][i][1]) - i32::from(unlit.parts[k][i][1]);
                                n += 1;
                            }
                        }
                    }
                    k += 1;
                }
            }
            if n > 0 && gain as f32 / n as f32 > best.0 as f32 / best.1 as f32 {
                best = (gain, n);
            }
        }
    }
    let (gain, n) = best;
    assert!(gain as f32 / n as f32 > 8.0, "mean gain {gain}/{n}");
}

#[test]
fn decor_is_deterministic() {
    let a = generator(true).scene(1).unwrap();
    let b = generator(true).scene(1).unwrap();
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
}

#[test]
fn a_light_panel_hangs_over_every_lamp_and_glows() {
    for i in 0..generator(true).len() {
        let s = generator(true).scene(i).unwrap();
        let lamps = light::lamps(&s);
        assert!(!lamps.is_empty(), "{}: no lamps", s.id);
        let baked = light::bake_fresh(&s);
        let meshes = light::bake_meshes(&s);
        // Part index of each (object, part), in the bake's order.
        let mut k = 0;
        let mut panels = Vec::new();
        for o in &s.objects {
            for (j, _) in o.parts.iter().enumerate() {
                if o.class == C::Ceiling && j > 0 {
                    panels.push(k);
                }
                k += 1;
            }
        }
        assert_eq!(panels.len(), lamps.len(), "{}: panels per lamp", s.id);
        for lamp in &lamps {
            // The panel right above the lamp, flush under its ceiling slab.
            let above = panels.iter().find(|&&k| {
                let m = &meshes[k];
                let (lo, hi) = m.positions.iter().fold(
                    ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
                    |(lo, hi), p| {
                        (
                            [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                            [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                        )
                    },
                );
                (lo[0]..hi[0]).contains(&lamp.x)
                    && (lo[2]..hi[2]).contains(&lamp.z)
                    && lo[1] > lamp.y
            });
            let Some(&k) = above else {
                panic!("{}: no panel over the lamp at {lamp}", s.id)
            };
            // Its underside, facing the lamp a few decimetres below, is lit to the full.
            let m = &meshes[k];
            let under: Vec<u8> = m
                .normals
                .iter()
                .zip(&baked.parts[k])
                .filter(|(n, _)| n[1] < -0.999)
                .map(|(_, l)| l[1])
                .collect();
            assert!(!under.is_empty());
            assert!(
                under.iter().all(|&g| g >= 250),
                "{}: panel underside light {under:?}",
                s.id
            );
        }
    }
}
