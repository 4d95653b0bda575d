//! Properties of generated homes: room counts, no overlaps, free doorways, connectivity,
//! support relations, determinism, preset statistics and config errors.

use crate::support;
use rayon::prelude::*;
use std::collections::BTreeSet;
use vlnverse_env::{
    Aabb, ClassKind, EnvError, Motion, Scene, SceneObject, SceneSource, SemanticClass as C,
};
use vlnverse_procgen::{door_clearance, HomeGenerator, Preset, ProcgenConfig};

/// Tolerance for touching boxes (m).
const EPS: f32 = 1e-3;

fn tiny() -> HomeGenerator {
    HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset")
}

fn vlnverse() -> HomeGenerator {
    HomeGenerator::from_preset(Preset::Vlnverse).expect("vlnverse preset")
}

/// Every tiny home and 30 homes spread over the vlnverse preset.
fn sample() -> Vec<Scene> {
    let t = tiny();
    let v = vlnverse();
    let mut out: Vec<Scene> = (0..t.len())
        .map(|i| t.scene(i).expect("tiny scene"))
        .collect();
    out.extend((0..30).map(|k| v.scene(k * 263 / 30).expect("vlnverse scene")));
    out
}

fn is_rug(o: &SceneObject) -> bool {
    o.class == C::Rug
}

/// Whether `a` legitimately rests on `b` (or the reverse): the support relation.
fn supported(a: &SceneObject, b: &SceneObject) -> bool {
    a.supported_by == Some(b.id) || b.supported_by == Some(a.id)
}

#[test]
fn room_counts_are_in_range() {
    let t = tiny();
    for i in 0..t.len() {
        let s = t.scene(i).unwrap();
        assert!(
            (3..=5).contains(&s.rooms.len()),
            "{}: {} rooms",
            s.id,
            s.rooms.len()
        );
    }
    for s in sample() {
        // The floorplan's range holds for the ground floor; a second floor adds the stair hall
        // below and a landing with bedrooms, a bathroom and sometimes an office above.
        let ground = support::ground_plan_rooms(&s).len();
        assert!((3..=10).contains(&ground), "{}: {ground} rooms", s.id);
        let upper = s.rooms.len() - ground;
        if s.is_multi_level() {
            assert!((3..=9).contains(&upper), "{}: {upper} more rooms", s.id);
        } else {
            assert_eq!(upper, 0, "{}", s.id);
        }
    }
}

#[test]
fn no_object_intersects_another_object_or_a_wall() {
    for s in sample() {
        let objs: Vec<&SceneObject> = s.objects.iter().filter(|o| o.class != C::Floor).collect();
        for (i, a) in objs.iter().enumerate() {
            for b in &objs[i + 1..] {
                if a.is_structure() && b.is_structure() {
                    continue; // walls meet walls and door frames at corners
                }
                // A rug may lie under furniture, never in a wall or on another rug.
                let rug_under = (is_rug(a) && !b.is_structure() && !is_rug(b))
                    || (is_rug(b) && !a.is_structure() && !is_rug(a));
                // Curtains hang in front of their window's frame.
                let curtain = |x: &SceneObject, y: &SceneObject| {
                    x.class == C::Curtain && y.class == C::Window
                };
                if rug_under || supported(a, b) || curtain(a, b) || curtain(b, a) {
                    continue;
                }
                // A closed leaf stands inside its frame: they may not overlap part by part.
                if a.class == C::Door && b.class == C::DoorFrame
                    || b.class == C::Door && a.class == C::DoorFrame
                {
                    for pa in &a.parts {
                        for pb in &b.parts {
                            let piece = |o: &SceneObject, p: &vlnverse_env::Part| {
                                SceneObject {
                                    parts: vec![p.clone()],
                                    ..o.clone()
                                }
                                .compute_bbox()
                            };
                            assert!(
                                !piece(a, pa).intersects(&piece(b, pb), EPS),
                                "{}: a part of {} intersects a part of {}",
                                s.id,
                                a.name,
                                b.name
                            );
                        }
                    }
                    continue;
                }
                assert!(
                    !a.bbox.intersects(&b.bbox, EPS),
                    "{}: {} {:?} intersects {} {:?}",
                    s.id,
                    a.name,
                    a.bbox,
                    b.name,
                    b.bbox
                );
            }
        }
    }
}

#[test]
fn supported_objects_stand_on_their_support_top() {
    let mut count = 0;
    for s in sample() {
        for o in s.objects.iter().filter(|o| o.supported_by.is_some()) {
            let sup = s.object(o.supported_by.unwrap()).expect("support exists");
            assert!(!sup.is_structure(), "{}: {} on structure", s.id, o.name);
            assert!(
                (o.bbox.min[1] - sup.bbox.max[1]).abs() < EPS,
                "{}: {} bottom {} vs {} top {}",
                s.id,
                o.name,
                o.bbox.min[1],
                sup.name,
                sup.bbox.max[1]
            );
            for k in [0, 2] {
                assert!(
                    o.bbox.min[k] >= sup.bbox.min[k] - EPS
                        && o.bbox.max[k] <= sup.bbox.max[k] + EPS,
                    "{}: {} overhangs {}",
                    s.id,
                    o.name,
                    sup.name
                );
            }
            assert_eq!(o.room, sup.room);
            count += 1;
        }
    }
    assert!(count > 100, "only {count} supported objects in the sample");
}

#[test]
fn doors_are_wide_and_never_blocked() {
    for s in sample() {
        assert!(!s.doors.is_empty());
        for d in &s.doors {
            assert!(
                d.width >= 0.9 - 1e-6,
                "{}: door {} width {}",
                s.id,
                d.id,
                d.width
            );
            let zone = door_clearance(d, 1.0, 2.0);
            // Only the door's own leaf, when closed, stands in its doorway.
            let own_closed = |o: &SceneObject| d.is_closed() && d.leaves().any(|l| l == o.id);
            // A doormat or a runner lies flat under a doorway's clearance: it blocks nothing.
            let flat = |o: &SceneObject| matches!(o.class, C::Doormat | C::Runner);
            for o in s.items().filter(|o| !own_closed(o) && !flat(o)) {
                assert!(
                    !o.bbox.intersects(&zone, EPS),
                    "{}: {} in the clearance of door {}",
                    s.id,
                    o.name,
                    d.id
                );
            }
            // The opening itself: no wall or frame inside the clear width below the head.
            let gap = Aabb {
                min: [zone.min[0], d.position[1], zone.min[2]],
                max: [zone.max[0], d.position[1] + 2.0, zone.max[2]],
            };
            for o in s
                .objects
                .iter()
                .filter(|o| matches!(o.class, C::Wall | C::DoorFrame))
            {
                for part in &o.parts {
                    let piece = SceneObject {
                        parts: vec![part.clone()],
                        ..(*o).clone()
                    };
                    assert!(
                        !piece.compute_bbox().intersects(&gap, EPS),
                        "{}: a part of {} blocks door {}",
                        s.id,
                        o.name,
                        d.id
                    );
                }
            }
        }
    }
}

#[test]
fn every_room_is_connected_through_doors() {
    let mut two = 0;
    for s in sample() {
        assert!(
            support::rooms_connected(&s, true),
            "{}: rooms not connected",
            s.id
        );
        if s.is_multi_level() {
            two += 1;
            // Each floor on its own through its doors; the flight is the only way between.
            for mut f in support::floors(&s) {
                let base = f.rooms[0].id;
                for r in f.rooms.iter_mut() {
                    r.id -= base;
                }
                for d in f.doors.iter_mut() {
                    d.rooms = d.rooms.map(|r| r - base);
                }
                assert!(
                    support::rooms_connected(&f, true),
                    "{}: a floor not connected",
                    s.id
                );
            }
            let mut cut = s.clone();
            cut.storeys.stairs.clear();
            assert!(!support::rooms_connected(&cut, true), "{}", s.id);
        }
    }
    assert!(two >= 3, "only {two} two-storey homes in the sample");
}

#[test]
fn objects_are_well_formed() {
    for s in sample() {
        let mut names = BTreeSet::new();
        for (i, o) in s.objects.iter().enumerate() {
            assert_eq!(
                o.id as usize,
                i + 1,
                "{}: ids must be sequential from 1",
                s.id
            );
            assert!(
                names.insert(o.name.clone()),
                "{}: duplicate {}",
                s.id,
                o.name
            );
            assert_eq!(
                o.bbox,
                o.compute_bbox(),
                "{}: stale bbox of {}",
                s.id,
                o.name
            );
            let [x, y, z, _] = o.pose.rotation;
            assert!(
                x.abs() < 1e-6 && z.abs() < 1e-6 && y.is_finite(),
                "{}: not yaw-only",
                o.name
            );
            assert!(o.physics.mass > 0.0 && o.physics.friction > 0.0);
            assert!(!o.color.is_empty() && !o.material.is_empty());
            if let Some(r) = o.room {
                assert!(s.room(r).is_some());
            }
            let door = s.doors.iter().find(|d| d.leaves().any(|l| l == o.id));
            assert_eq!(door.is_some(), o.class == C::Door, "{}: {}", s.id, o.name);
            // (A closed pair of french doors is centred as a pair.)
            let single = |d: &&vlnverse_env::Door| d.second_leaf.is_none();
            if let Some(d) = door.filter(|d| d.is_closed()).filter(single) {
                // A closed leaf is centred in its doorway, between the two rooms.
                let c = o.bbox.center();
                assert!(
                    (c.x - d.position[0]).abs() < 1e-3 && (c.z - d.position[2]).abs() < 1e-3,
                    "{}: closed {} not in door {}",
                    s.id,
                    o.name,
                    d.id
                );
                assert!(d.rooms.contains(&o.room.expect("a leaf has a room")));
            } else if !o.is_structure() {
                let r = s.room(o.room.expect("furniture has a room")).unwrap();
                let c = o.bbox.center();
                assert!(
                    r.contains(c.x, c.z),
                    "{}: {} outside {}",
                    s.id,
                    o.name,
                    r.name
                );
            }
            if o.class == C::Rug {
                assert!(o.bbox.size().y < 0.02, "{}: rug {} not flat", s.id, o.name);
            }
            let light = matches!(o.class, C::Chair | C::Stool | C::OfficeChair)
                || o.class.kind() == ClassKind::Small;
            if light {
                assert_eq!(o.physics.motion, Motion::Dynamic, "{}", o.name);
            }
            if matches!(
                o.class,
                C::Bed | C::Wall | C::Sofa | C::Fridge | C::Wardrobe
            ) {
                assert_eq!(o.physics.motion, Motion::Static, "{}", o.name);
            }
        }
        assert!(s.objects.iter().any(|o| o.class == C::Floor));
        assert!(s.objects.iter().any(|o| o.class == C::Wall));
        assert!(s.objects.iter().all(|o| o.bbox.min[1] >= -0.051));
    }
}

#[test]
fn rooms_have_their_key_furniture() {
    use vlnverse_env::RoomType as R;
    let (mut rooms, mut missing) = (0, Vec::new());
    for s in sample() {
        for r in &s.rooms {
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
            rooms += 1;
            if !s.items().any(|o| o.room == Some(r.id) && o.class == key) {
                missing.push(format!("{} {} lacks a {key}", s.id, r.name));
            }
        }
        // Colour words vary within a home, so "the red mug" can single one out.
        let colors: BTreeSet<&str> = s.items().map(|o| o.color.as_str()).collect();
        assert!(colors.len() >= 3, "{}: colours {colors:?}", s.id);
    }
    // Rooms cut by several wide openings may not fit their key piece; keep that rare.
    assert!(rooms > 150);
    assert!(
        missing.len() * 50 <= rooms,
        "{} of {rooms}: {missing:?}",
        missing.len()
    );
}

#[test]
fn same_seed_gives_the_same_scene_in_any_order_and_thread() {
    let g = tiny();
    let forward: Vec<Scene> = (0..g.len()).map(|i| g.scene(i).unwrap()).collect();
    let mut backward: Vec<Scene> = (0..g.len()).rev().map(|i| g.scene(i).unwrap()).collect();
    backward.reverse();
    assert_eq!(forward, backward);
    let parallel: Vec<Scene> = (0..g.len())
        .into_par_iter()
        .map(|i| g.scene(i).unwrap())
        .collect();
    assert_eq!(forward, parallel);
    // Different indices give different homes.
    assert_ne!(forward[0].objects, forward[1].objects);
    let v = vlnverse();
    let a = v.scene(200).unwrap();
    let b = HomeGenerator::from_preset(Preset::Vlnverse)
        .unwrap()
        .scene(200)
        .unwrap();
    assert_eq!(a, b);
    assert_eq!(a.id, "home_0200");
    assert_eq!(
        serde_json::to_string(&a).ok(),
        serde_json::to_string(&b).ok()
    );
}

#[test]
fn vlnverse_preset_spans_the_paper_ranges() {
    let v = vlnverse();
    assert_eq!(v.len(), 263);
    assert_eq!(v.config(), &ProcgenConfig::default());
    // Rooms and area of the ground floor's plan (the paper's ranges), and whether the home has a
    // second floor.
    let stats: Vec<(usize, f32, bool)> = (0..v.len())
        .into_par_iter()
        .map(|i| {
            let s = v.scene(i).unwrap();
            let ground = support::ground_plan_rooms(&s);
            let area = ground.iter().map(|r| r.area()).sum();
            (ground.len(), area, s.is_multi_level())
        })
        .collect();
    let rooms: BTreeSet<usize> = stats.iter().map(|s| s.0).collect();
    assert_eq!(rooms, (3..=10).collect::<BTreeSet<_>>());
    let min = stats.iter().map(|s| s.1).fold(f32::INFINITY, f32::min);
    let max = stats.iter().map(|s| s.1).fold(0.0, f32::max);
    assert!((25.0..=60.0).contains(&min), "smallest home {min} m^2");
    assert!((200.0..=300.0).contains(&max), "largest home {max} m^2");
    // About 30% on two floors (a home whose footprint takes no stair hall stays on one).
    let two = stats.iter().filter(|s| s.2).count();
    assert!((50..=95).contains(&two), "{two} of 263 homes on two floors");
}

#[test]
fn scene_index_out_of_range_is_an_error() {
    let g = tiny();
    assert!(g.scene(g.len()).is_err());
    assert_eq!(g.scene_id(3), "tiny_0003");
}

fn config_error(body: &str) -> (String, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, body).unwrap();
    match ProcgenConfig::from_toml_file(&path) {
        Err(EnvError::InvalidConfig {
            path: Some(p),
            field,
            value,
            ..
        }) => {
            assert_eq!(p, path);
            (field, value)
        }
        other => panic!("expected InvalidConfig for {body:?}, got {other:?}"),
    }
}

#[test]
fn bad_configs_name_file_field_and_value() {
    let cases = [
        ("[rooms]\ncount_min = 0\n", "rooms.count_min", "0"),
        ("[rooms]\ncount_min = 6\ncount_max = 4\n", "rooms.count_min", "6"),
        ("[doors]\nwidth_min = 0.8\n", "doors.width_min", "0.8"),
        ("[walls]\nthickness = -0.1\n", "walls.thickness", "-0.1"),
        ("[rooms]\nmin_side = -2.0\n", "rooms.min_side", "-2"),
        (
            "[[rooms.kinds]]\nkind = \"bedroom\"\ncount_max = 10\nweight = 1.0\narea_min = 12.0\narea_max = 9.0\n",
            "rooms.kinds[0].area_min",
            "12",
        ),
        ("[furniture]\nnav_radius = 0.0\n", "furniture.nav_radius", "0"),
        ("[doors]\nopen_plan_probability = 1.5\n", "doors.open_plan_probability", "1.5"),
        // Huge values are refused before anything loops or allocates on them.
        ("[furniture]\nattempts = 1000000000\n", "furniture.attempts", "1000000000"),
        (
            "[furniture]\nsmall_objects_max = 1000000000\n",
            "furniture.small_objects_max",
            "1000000000",
        ),
        ("[furniture]\nclutter = 5.0\n", "furniture.clutter", "5"),
        ("[furniture]\ndensity = 1e9\n", "furniture.density", "1000000000"),
        ("[scenes]\ncount = 1000000000\n", "scenes.count", "1000000000"),
        ("[rooms]\nmax_aspect = 1e9\n", "rooms.max_aspect", "1000000000"),
        ("[rooms]\nmin_side = 1e9\n", "rooms.min_side", "1000000000"),
        ("[rooms]\narea_scale_max = 1e9\n", "rooms.area_scale_max", "1000000000"),
        ("[walls]\nheight = 1e9\n", "walls.height", "1000000000"),
        (
            "[[rooms.kinds]]\nkind = \"bedroom\"\ncount_max = 10\nweight = 1.0\narea_min = 12.0\narea_max = 1e9\n",
            "rooms.kinds[0].area_max",
            "1000000000",
        ),
        (
            "[[rooms.kinds]]\nkind = \"bedroom\"\ncount_max = 1000000000\nweight = 1.0\narea_min = 12.0\narea_max = 14.0\n",
            "rooms.kinds[0].count_max",
            "1000000000",
        ),
    ];
    for (body, field, value) in cases {
        let (f, v) = config_error(body);
        assert_eq!((f.as_str(), v.as_str()), (field, value), "for {body:?}");
    }
    // Unknown fields and unknown room kinds are parse errors naming the file.
    let dir = tempfile::tempdir().unwrap();
    for (body, field, value) in [
        ("[rooms]\ncount_mni = 3\n", "count_mni", "3"),
        (
            "[[rooms.kinds]]\nkind = \"ballroom\"\ncount_max = 1\narea_min = 9.0\narea_max = 10.0\n",
            "kind",
            "ballroom",
        ),
        ("[walls]\nthickness = \"thick\"\n", "thickness", "thick"),
    ] {
        let path = dir.path().join("typo.toml");
        std::fs::write(&path, body).unwrap();
        match ProcgenConfig::from_toml_file(&path) {
            Err(e @ EnvError::Parse { .. }) => {
                let e = e.to_string();
                assert!(
                    e.contains("typo.toml") && e.contains(field) && e.contains(value),
                    "{e}"
                );
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
    }
    let missing = dir.path().join("missing.toml");
    let e = ProcgenConfig::from_toml_file(&missing).unwrap_err();
    assert!(matches!(e, EnvError::Io { .. }) && e.to_string().contains("missing.toml"));
    assert!("huge".parse::<Preset>().is_err());
}

#[test]
fn shipped_presets_parse_and_partial_files_take_defaults() {
    for &p in Preset::ALL {
        let c = p.config().unwrap();
        c.validate().unwrap();
        assert_eq!(p.name().parse::<Preset>().unwrap(), p);
    }
    let tiny = Preset::Tiny.config().unwrap();
    assert_eq!(tiny.scenes.count, 5);
    assert_eq!(tiny.doors, ProcgenConfig::default().doors);
}
