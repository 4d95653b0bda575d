//! Door leaves: one per framed doorway, closed ones keep every room reachable and block the maps
//! and geodesic routes, open ones leave the doorway free; deterministic.

use crate::support;
use glam::Vec2;
use rayon::prelude::*;
use vlnverse_env::geodesic::geodesic_distance;
use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
use vlnverse_env::{DoorState, Motion, Scene, SceneObject, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset};

fn tiny() -> HomeGenerator {
    HomeGenerator::from_preset(Preset::Tiny).unwrap()
}

fn vlnverse() -> HomeGenerator {
    HomeGenerator::from_preset(Preset::Vlnverse).unwrap()
}

/// Every tiny home and 30 homes spread over the vlnverse preset.
fn sample() -> Vec<Scene> {
    let (t, v) = (tiny(), vlnverse());
    (0..t.len())
        .into_par_iter()
        .map(|i| t.scene(i).unwrap())
        .chain(
            (0..30)
                .into_par_iter()
                .map(|k| v.scene(k * 263 / 30).unwrap()),
        )
        .collect()
}

/// Whether every room reaches every other through open doors, open-plan openings and stairs.
fn rooms_connected(s: &Scene) -> bool {
    support::rooms_connected(s, false)
}

fn leaf<'a>(s: &'a Scene, d: &vlnverse_env::Door) -> &'a SceneObject {
    s.object(d.leaf.expect("a leaf"))
        .expect("the leaf object exists")
}

#[test]
fn every_framed_doorway_has_a_leaf_and_open_plan_openings_none() {
    let (mut framed, mut bare) = (0, 0);
    for s in sample() {
        for d in &s.doors {
            if d.open_plan {
                assert_eq!((d.state, d.leaf), (None, None), "{}: door {}", s.id, d.id);
                continue;
            }
            // An arch has no leaf by design (`doors_kinds.rs`).
            if d.kind == vlnverse_env::scene::DoorKind::Arched {
                continue;
            }
            framed += 1;
            let Some(state) = d.state else {
                assert_eq!(d.leaf, None);
                bare += 1;
                continue;
            };
            let o = leaf(&s, d);
            assert_eq!(o.class, C::Door, "{}: door {}", s.id, d.id);
            assert_eq!(
                o.physics.motion,
                Motion::Static,
                "a door is never pushed open"
            );
            assert!(d.rooms.contains(&o.room.unwrap()));
            assert!(!o.color.is_empty());
            // Glass (sliding, french) leaves are checked in `doors_kinds.rs`.
            if d.kind != vlnverse_env::scene::DoorKind::Hinged {
                continue;
            }
            // A slab and a handle (rose and lever) on each face.
            assert_eq!(o.parts.len(), 5);
            let c = Vec2::new(d.position[0], d.position[2]);
            let n = Vec2::from_array(d.normal);
            let lc = Vec2::new(o.bbox.center().x, o.bbox.center().z);
            match state {
                // Centred in the opening, filling its width, in the plane of the wall.
                DoorState::Closed => {
                    assert!((lc - c).length() < 1e-3, "{}: door {}", s.id, d.id);
                    let span = o.bbox.size().x.max(o.bbox.size().z);
                    assert!(span > d.width - 0.02 && span <= d.width + 1e-4);
                }
                // Swung into a room: the leaf stands off the wall by about its width.
                DoorState::Open => {
                    let depth = (lc - c).dot(n).abs();
                    assert!(
                        (depth - d.width * 0.5).abs() < 0.15,
                        "{}: door {} leaf at depth {depth}",
                        s.id,
                        d.id
                    );
                }
            }
        }
    }
    assert!(framed > 150, "{framed} framed doorways");
    // Left bare only where no swing fits (tight, furnished rooms) and closing would cut a
    // room off: rare.
    assert!(
        bare * 30 <= framed,
        "{bare} of {framed} doorways without a leaf"
    );
}

#[test]
fn open_leaves_keep_the_doorway_clear_and_touch_no_furniture() {
    for s in sample() {
        let clearance = vlnverse().config().doors.clearance;
        for d in s.doors.iter().filter(|d| d.leaf.is_some()) {
            let o = leaf(&s, d);
            if d.state == Some(DoorState::Open) {
                support::assert_leaf_clear_of_doorways(&s, o, clearance);
            }
            support::assert_leaf_touches_nothing(&s, o);
        }
    }
}

#[test]
fn closed_doors_leave_every_room_reachable_in_every_home() {
    let (t, v) = (tiny(), vlnverse());
    let homes: Vec<(usize, usize, usize, usize)> = (0..t.len())
        .map(|i| (0, i))
        .chain((0..v.len()).map(|i| (1, i)))
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|(g, i)| {
            let s = if g == 0 { t.scene(i) } else { v.scene(i) }.unwrap();
            assert!(
                rooms_connected(&s),
                "{}: a closed door cuts a room off",
                s.id
            );
            let framed = s.doors.iter().filter(|d| d.leaf.is_some()).count();
            let closed = s.doors.iter().filter(|d| d.is_closed()).count();
            // Doors with a leaf that could close (alone) without cutting a room off.
            let closable = s
                .doors
                .iter()
                .filter(|d| d.leaf.is_some())
                .filter(|d| {
                    let mut t = s.clone();
                    for e in t.doors.iter_mut() {
                        if e.id == d.id {
                            e.state = Some(DoorState::Closed);
                        } else if e.is_closed() {
                            e.state = Some(DoorState::Open);
                        }
                    }
                    rooms_connected(&t)
                })
                .count();
            (g, framed, closed, closable)
        })
        .collect();
    let vln: Vec<_> = homes.iter().filter(|h| h.0 == 1).collect();
    let leaves: usize = vln.iter().map(|h| h.1).sum();
    let closed: usize = vln.iter().map(|h| h.2).sum();
    let closable: usize = vln.iter().map(|h| h.3).sum();
    eprintln!(
        "vlnverse: {:.2} door leaves per home, {closed} of {leaves} closed ({:.1}%), \
         {closable} could close without cutting a room off, {} of {} homes with a closed door",
        leaves as f32 / vln.len() as f32,
        100.0 * closed as f32 / leaves.max(1) as f32,
        vln.iter().filter(|h| h.2 > 0).count(),
        vln.len()
    );
    // Floorplans are a spanning tree plus a few extra doors, so few doors can close at all; of
    // those, about `closed_probability` (0.3) do.
    assert!(closed > 0, "no closed door in the preset");
    let share = closed as f32 / closable.max(1) as f32;
    assert!(
        (0.1..=0.6).contains(&share),
        "{closed} of {closable} closable"
    );
}

#[test]
fn a_closed_door_blocks_the_maps_and_routes_go_round_it() {
    let cfg = OccupancyConfig::default();
    let v = vlnverse();
    // The homes with a closed door (few: see above), and a sample of the rest.
    let homes: Vec<Scene> = (0..v.len())
        .into_par_iter()
        .map(|i| v.scene(i).unwrap())
        .filter(|s| s.id.ends_with('0') || s.doors.iter().any(|d| d.is_closed()))
        .collect();
    let mut checked = 0;
    for s in homes {
        // Each door is checked on the map of its own floor.
        let levels = build_level_maps(&s, &cfg).unwrap();
        let maps_of = |d: &vlnverse_env::Door| &levels[support::door_level(&s, d) as usize];
        for d in s.doors.iter().filter(|d| d.is_closed()) {
            let maps = maps_of(d);
            let c = Vec2::new(d.position[0], d.position[2]);
            let n = Vec2::from_array(d.normal);
            let t = n.perp();
            // Every cell across the doorway, jamb to jamb, is an obstacle.
            let steps = 20;
            for k in 0..=steps {
                let p = c + t * d.width * (k as f32 / steps as f32 - 0.5);
                assert!(
                    !maps.occupancy.is_free_at(p),
                    "{}: door {} not occupied at {p}",
                    s.id,
                    d.id
                );
                assert!(!maps.navigable.is_free_at(p));
            }
            // Both sides are reachable, but only the long way round.
            let (a, b) = (c + n * 0.6, c - n * 0.6);
            let g = geodesic_distance(&maps.navigable, a, b).unwrap();
            let m = g
                .meters()
                .unwrap_or_else(|| panic!("{}: door {}", s.id, d.id));
            assert!(m > 1.2 + 0.5, "{}: door {}: {m} m", s.id, d.id);
            checked += 1;
        }
        // An open door is passable straight through.
        for d in s.doors.iter().filter(|d| d.state == Some(DoorState::Open)) {
            let maps = maps_of(d);
            let c = Vec2::new(d.position[0], d.position[2]);
            let n = Vec2::from_array(d.normal);
            let g = geodesic_distance(&maps.navigable, c + n * 0.6, c - n * 0.6).unwrap();
            assert!(
                g.meters().is_some_and(|m| m < 1.2 + 0.05),
                "{}: open door {}: {g:?}",
                s.id,
                d.id
            );
        }
    }
    assert!(checked > 5, "only {checked} closed doors in the sample");
}

#[test]
fn leaves_are_deterministic_and_turning_them_off_changes_no_furniture() {
    let v = vlnverse();
    let idx: Vec<usize> = (0..12).map(|k| k * 21).collect();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let a: Vec<String> = one.install(|| {
        idx.iter()
            .map(|&i| serde_json::to_string(&v.scene(i).unwrap()).unwrap())
            .collect()
    });
    let b: Vec<String> = idx
        .par_iter()
        .map(|&i| serde_json::to_string(&v.scene(i).unwrap()).unwrap())
        .collect();
    assert_eq!(a, b);

    let mut cfg = v.config().clone();
    cfg.doors.leaves = false;
    let bare = HomeGenerator::new(cfg).unwrap();
    for &i in &idx {
        let (with, without) = (v.scene(i).unwrap(), bare.scene(i).unwrap());
        assert!(without
            .doors
            .iter()
            .all(|d| d.state.is_none() && d.leaf.is_none()));
        assert!(without.objects.iter().all(|o| o.class != C::Door));
        // Everything before the first leaf is the same home.
        let first = with
            .objects
            .iter()
            .position(|o| o.class == C::Door)
            .unwrap_or(with.objects.len());
        assert_eq!(
            with.objects[..first],
            without.objects[..first],
            "{}",
            with.id
        );
        assert_eq!(with.rooms, without.rooms);
    }
}

#[test]
fn doors_on_a_path_are_found_in_order() {
    let s = tiny().scene(0).unwrap();
    for d in &s.doors {
        let c = [d.position[0], d.position[2]];
        let n = d.normal;
        let a = [c[0] - n[0], c[1] - n[1]];
        let b = [c[0] + n[0], c[1] + n[1]];
        let hits: Vec<u32> = s.doors_on_path(&[a, c, b]).iter().map(|x| x.id).collect();
        assert_eq!(hits, vec![d.id], "through door {} once", d.id);
        // Alongside the wall, 0.3 m off it: no door.
        let off = [c[0] + n[0] * 0.3, c[1] + n[1] * 0.3];
        let along = [off[0] - n[1] * 0.2, off[1] + n[0] * 0.2];
        assert!(s.doors_on_path(&[off, along]).is_empty());
    }
}
