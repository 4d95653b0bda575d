//! The things issue 26 added (doormats, hallway runners, grand pianos, hot tubs, game
//! machines...): each turns up in the `vlnverse` preset, and the mats lie where people expect
//! them: a doormat inside a door from a porch or a garage, a runner down a hallway.

use rayon::prelude::*;
use std::collections::BTreeMap;
use std::sync::LazyLock;
use vlnverse_env::{RoomType as R, Scene, SceneObject, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset};

static HOMES: LazyLock<Vec<Scene>> = LazyLock::new(|| {
    let g = HomeGenerator::from_preset(Preset::Vlnverse).expect("vlnverse preset");
    (0..g.len())
        .into_par_iter()
        .map(|i| g.scene(i).expect("scene"))
        .collect()
});

fn is_thing(c: C) -> bool {
    c.id() >= C::Doormat.id()
}

fn room_kind(s: &Scene, o: &SceneObject) -> R {
    o.room
        .and_then(|r| s.room(r))
        .map(|r| r.kind)
        .unwrap_or_else(|| panic!("{}: {} stands in no room", s.id, o.name))
}

/// Centre and size of an object's floor footprint.
fn foot(o: &SceneObject) -> ([f32; 2], [f32; 2]) {
    let (lo, hi) = (o.bbox.min, o.bbox.max);
    (
        [(lo[0] + hi[0]) * 0.5, (lo[2] + hi[2]) * 0.5],
        [hi[0] - lo[0], hi[2] - lo[2]],
    )
}

#[test]
fn every_new_thing_turns_up_several_times_in_the_preset() {
    let mut count: BTreeMap<C, usize> = C::ALL
        .iter()
        .filter(|c| is_thing(**c))
        .map(|&c| (c, 0))
        .collect();
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| is_thing(o.class)) {
            *count.entry(o.class).or_default() += 1;
            let room = o.room.and_then(|r| s.room(r)).expect("a room");
            let (c, _) = foot(o);
            assert!(
                room.contains(c[0], c[1]),
                "{}: {} outside its room",
                s.id,
                o.name
            );
        }
    }
    let rare: Vec<_> = count.iter().filter(|(_, n)| **n < 3).collect();
    assert!(rare.is_empty(), "placed fewer than 3 times: {rare:?}");
}

#[test]
fn doormats_lie_inside_a_door_from_a_porch_or_a_garage() {
    let outdoorsy = |k: R| matches!(k, R::Porch | R::Garage);
    let mut mats = 0;
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| o.class == C::Doormat) {
            mats += 1;
            assert!(
                o.bbox.max[1] - o.bbox.min[1] < 0.02,
                "{}: thick {}",
                s.id,
                o.name
            );
            assert!(!outdoorsy(room_kind(s, o)), "{}: {} outdoors", s.id, o.name);
            let (c, _) = foot(o);
            let at_door = s.doors.iter().any(|d| {
                let other = if Some(d.rooms[0]) == o.room {
                    d.rooms[1]
                } else if Some(d.rooms[1]) == o.room {
                    d.rooms[0]
                } else {
                    return false;
                };
                let near = (d.position[0] - c[0]).hypot(d.position[2] - c[1]) < 0.6;
                near && s.room(other).is_some_and(|r| outdoorsy(r.kind))
            });
            assert!(at_door, "{}: {} at no door from outside", s.id, o.name);
        }
    }
    assert!(mats >= 5, "only {mats} doormats");
}

#[test]
fn runners_run_down_hallways_under_nothing() {
    let mut runners = 0;
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| o.class == C::Runner) {
            runners += 1;
            assert_eq!(room_kind(s, o), R::Hallway, "{}: {}", s.id, o.name);
            assert!(
                o.bbox.max[1] - o.bbox.min[1] < 0.02,
                "{}: thick {}",
                s.id,
                o.name
            );
            let room = o.room.and_then(|r| s.room(r)).expect("a room");
            let xs = room.polygon.iter().map(|p| p[0]);
            let zs = room.polygon.iter().map(|p| p[1]);
            let span = |v: &mut dyn Iterator<Item = f32>| {
                let (lo, hi) = v.fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(x), b.max(x)));
                hi - lo
            };
            let (rw, rd) = (span(&mut xs.clone()), span(&mut zs.clone()));
            let (_, size) = foot(o);
            assert_eq!(
                size[0] > size[1],
                rw > rd,
                "{}: {} across the hall",
                s.id,
                o.name
            );
            // Nothing standing on the floor of the hall lies on it (door leaves, hung
            // pictures and curtains aside).
            let (lo, hi) = (o.bbox.min, o.bbox.max);
            let under = s.objects.iter().find(|p| {
                p.room == o.room
                    && p.id != o.id
                    && !p.class.is_structure()
                    && !matches!(p.class, C::Door | C::Curtain | C::PictureFrame)
                    && p.bbox.min[1] < 0.3
                    && overlaps_on_floor(p, lo, hi)
            });
            assert!(
                under.is_none(),
                "{}: {} under {:?}",
                s.id,
                o.name,
                under.map(|p| &p.name)
            );
        }
    }
    assert!(runners >= 10, "only {runners} runners");
}

/// Whether `p`'s footprint overlaps the box from `lo` to `hi` on the floor (x and z).
fn overlaps_on_floor(p: &vlnverse_env::SceneObject, lo: [f32; 3], hi: [f32; 3]) -> bool {
    p.bbox.min[0] < hi[0] && lo[0] < p.bbox.max[0] && p.bbox.min[2] < hi[2] && lo[2] < p.bbox.max[2]
}

/// Classes of the second lot of things (`more_things.rs`).
fn is_late_thing(c: C) -> bool {
    c.id() >= C::Sectional.id()
}

#[test]
fn ceiling_fans_hang_above_the_agent_over_nothing_tall() {
    let mut fans = 0;
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| o.class == C::CeilingFan) {
            fans += 1;
            let floor = s
                .objects
                .iter()
                .filter(|f| f.class == C::Floor && f.room == o.room)
                .map(|f| f.bbox.max[1])
                .fold(f32::NEG_INFINITY, f32::max);
            let floor = if floor.is_finite() { floor } else { 0.0 };
            assert!(
                o.bbox.min[1] - floor > 2.1,
                "{}: {} hangs down to {}",
                s.id,
                o.name,
                o.bbox.min[1] - floor
            );
            let (lo, hi) = (o.bbox.min, o.bbox.max);
            let under = s.objects.iter().find(|p| {
                p.room == o.room
                    && p.id != o.id
                    && !p.class.is_structure()
                    && p.bbox.max[1] > lo[1] - 0.05
                    && overlaps_on_floor(p, lo, hi)
            });
            assert!(
                under.is_none(),
                "{}: {} over {:?}",
                s.id,
                o.name,
                under.map(|p| &p.name)
            );
        }
    }
    assert!(fans >= 20, "only {fans} ceiling fans");
}

#[test]
fn candelabras_stand_on_a_table_or_a_buffet() {
    let mut n = 0;
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| o.class == C::Candelabra) {
            n += 1;
            let sup = o
                .supported_by
                .and_then(|id| s.object(id))
                .unwrap_or_else(|| panic!("{}: {} stands on nothing", s.id, o.name));
            assert!(
                matches!(
                    sup.class,
                    C::DiningTable | C::Buffet | C::ConsoleTable | C::SideTable | C::CoffeeTable
                ),
                "{}: {} on a {:?}",
                s.id,
                o.name,
                sup.class
            );
            assert!((o.bbox.min[1] - sup.bbox.max[1]).abs() < 0.01, "{}", s.id);
            let (c, _) = foot(o);
            let on = (sup.bbox.min[0]..=sup.bbox.max[0]).contains(&c[0])
                && (sup.bbox.min[2]..=sup.bbox.max[2]).contains(&c[1]);
            assert!(on, "{}: {} off its {:?}", s.id, o.name, sup.class);
        }
    }
    assert!(n >= 10, "only {n} candelabras");
}

#[test]
fn wall_things_hang_against_a_wall() {
    let on_wall = [
        C::Whiteboard,
        C::BulletinBoard,
        C::Sword,
        C::BasketballHoop,
        C::Buffet,
        C::MiniFridge,
    ];
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| on_wall.contains(&o.class)) {
            let room = o.room.and_then(|r| s.room(r)).expect("a room");
            let xs = room.polygon.iter().map(|p| p[0]);
            let zs = room.polygon.iter().map(|p| p[1]);
            let (x0, x1) = xs.fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(x), b.max(x)));
            let (z0, z1) = zs.fold((f32::MAX, f32::MIN), |(a, b), z| (a.min(z), b.max(z)));
            let (lo, hi) = (o.bbox.min, o.bbox.max);
            let gap = (lo[0] - x0).min(x1 - hi[0]).min(lo[2] - z0).min(z1 - hi[2]);
            assert!(gap < 0.05, "{}: {} {gap} m off the walls", s.id, o.name);
        }
    }
}

#[test]
fn the_second_lot_of_things_stands_in_the_rooms_that_list_them() {
    let rooms: &[(C, &[R])] = &[
        (
            C::WaterHeater,
            &[
                R::Garage,
                R::LaundryRoom,
                R::Closet,
                R::Pantry,
                R::MudRoom,
                R::Workshop,
            ],
        ),
        (C::Rocks, &[R::Porch, R::Balcony, R::LivingRoom]),
        (C::TeddyBear, &[R::Bedroom, R::Room, R::Playroom]),
        (C::Buffet, &[R::DiningRoom, R::Kitchen]),
    ];
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| is_late_thing(o.class)) {
            if let Some((_, kinds)) = rooms.iter().find(|(c, _)| *c == o.class) {
                let k = room_kind(s, o);
                assert!(kinds.contains(&k), "{}: {} in a {k:?}", s.id, o.name);
            }
        }
    }
}

/// Height of the floor of `o`'s room (upper floors stand on a slab; the skirting boards, also
/// of class floor, stand higher).
fn floor_of(s: &Scene, o: &SceneObject) -> f32 {
    let floor = s
        .objects
        .iter()
        .filter(|f| f.class == C::Floor && f.room == o.room)
        .map(|f| f.bbox.max[1])
        .fold(f32::INFINITY, f32::min);
    if floor.is_finite() {
        floor
    } else {
        0.0
    }
}

/// How far `o` stands out of the nearest wall of its room, and its depth across that wall.
fn off_wall(s: &Scene, o: &SceneObject) -> (f32, f32) {
    let room = o.room.and_then(|r| s.room(r)).expect("a room");
    let xs = room.polygon.iter().map(|p| p[0]);
    let zs = room.polygon.iter().map(|p| p[1]);
    let (x0, x1) = xs.fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (z0, z1) = zs.fold((f32::MAX, f32::MIN), |(a, b), z| (a.min(z), b.max(z)));
    let (lo, hi) = (o.bbox.min, o.bbox.max);
    [
        (lo[0] - x0, hi[0] - lo[0]),
        (x1 - hi[0], hi[0] - lo[0]),
        (lo[2] - z0, hi[2] - lo[2]),
        (z1 - hi[2], hi[2] - lo[2]),
    ]
    .into_iter()
    .fold(
        (f32::MAX, 0.0),
        |a, b| if b.0.abs() < a.0.abs() { b } else { a },
    )
}

#[test]
fn wall_fixtures_lie_flat_on_a_wall_at_their_height() {
    // (class, lowest and highest bottom above the floor)
    let fixtures: &[(C, f32, f32)] = &[
        (C::LightSwitch, 1.1, 1.2),
        (C::Outlet, 0.25, 0.3),
        (C::Thermostat, 1.35, 1.55),
        (C::AirVent, 0.1, 2.2),
        (C::Calendar, 1.2, 1.4),
        (C::AirConditioner, 1.95, 2.1),
    ];
    let mut seen = BTreeMap::new();
    for s in HOMES.iter() {
        for o in s.objects.iter() {
            let Some(&(_, y0, y1)) = fixtures.iter().find(|f| f.0 == o.class) else {
                continue;
            };
            *seen.entry(o.class).or_insert(0) += 1;
            let (gap, depth) = off_wall(s, o);
            assert!(
                gap.abs() < 0.003,
                "{}: {} {gap} m off the wall",
                s.id,
                o.name
            );
            let deep = if o.class == C::AirConditioner {
                0.25
            } else {
                0.021
            };
            assert!(depth < deep, "{}: {} {depth} m deep", s.id, o.name);
            let y = o.bbox.min[1] - floor_of(s, o);
            assert!((y0..=y1).contains(&y), "{}: {} at {y} m", s.id, o.name);
        }
    }
    for (c, ..) in fixtures {
        assert!(seen.get(c).copied().unwrap_or(0) >= 10, "{c:?}: {seen:?}");
    }
}

#[test]
fn light_switches_are_beside_a_doorway_of_their_room() {
    for s in HOMES.iter() {
        for o in s.objects.iter().filter(|o| o.class == C::LightSwitch) {
            let (c, _) = foot(o);
            let near = s.doors.iter().any(|d| {
                d.rooms.iter().any(|r| Some(*r) == o.room)
                    && (d.position[0] - c[0]).hypot(d.position[2] - c[1]) < d.width * 0.5 + 0.45
            });
            assert!(near, "{}: {} by no doorway", s.id, o.name);
        }
    }
}

#[test]
fn smoke_detectors_are_on_the_ceiling_and_range_hoods_over_a_stove() {
    let (mut detectors, mut hoods) = (0, 0);
    for s in HOMES.iter() {
        for o in s.objects.iter() {
            let y = o.bbox.max[1] - floor_of(s, o);
            if o.class == C::SmokeDetector {
                detectors += 1;
                let ceiling = s
                    .objects
                    .iter()
                    .find(|c| c.class == C::Ceiling && c.room == o.room)
                    .map_or(f32::NAN, |c| c.bbox.min[1]);
                let gap = ceiling - o.bbox.max[1];
                assert!(
                    (0.0..0.05).contains(&gap),
                    "{}: {} tops at {y}",
                    s.id,
                    o.name
                );
            }
            if o.class == C::RangeHood {
                hoods += 1;
                let (c, _) = foot(o);
                let stove = s.objects.iter().find(|p| {
                    p.class == C::Stove
                        && p.room == o.room
                        && (p.bbox.min[0]..=p.bbox.max[0]).contains(&c[0])
                        && (p.bbox.min[2]..=p.bbox.max[2]).contains(&c[1])
                });
                let stove = stove.unwrap_or_else(|| panic!("{}: {} over no stove", s.id, o.name));
                let above = o.bbox.min[1] - stove.bbox.max[1];
                assert!(
                    (0.6..0.7).contains(&above),
                    "{}: {} {above} m up",
                    s.id,
                    o.name
                );
            }
        }
    }
    assert!(
        detectors >= 20 && hoods >= 20,
        "{detectors} detectors, {hoods} hoods"
    );
}

#[test]
fn the_third_lot_stands_where_it_belongs() {
    let rooms: &[(C, &[R])] = &[
        (C::BathroomScale, &[R::Bathroom]),
        (C::KnifeBlock, &[R::Kitchen]),
        (C::SpiceRack, &[R::Kitchen]),
        (C::Wheelbarrow, &[R::Garage, R::Porch]),
        (C::Shovel, &[R::Garage, R::Porch]),
        (C::GardenHose, &[R::Garage, R::Porch, R::Balcony]),
        (C::Typewriter, &[R::Office, R::Library]),
    ];
    let on: &[(C, &[C])] = &[
        (C::KnifeBlock, &[C::Counter, C::KitchenIsland]),
        (
            C::SewingMachine,
            &[C::Desk, C::DiningTable, C::ConsoleTable],
        ),
        (C::Typewriter, &[C::Desk, C::ConsoleTable, C::SideTable]),
        (
            C::RecordPlayer,
            &[
                C::ConsoleTable,
                C::Cabinet,
                C::Buffet,
                C::TvStand,
                C::Dresser,
                C::SideTable,
                C::Desk,
            ],
        ),
        (
            C::Radio,
            &[
                C::Counter,
                C::Nightstand,
                C::Dresser,
                C::Desk,
                C::KitchenIsland,
                C::Cabinet,
                C::ConsoleTable,
            ],
        ),
    ];
    for s in HOMES.iter() {
        for o in s.objects.iter() {
            if let Some((_, kinds)) = rooms.iter().find(|(c, _)| *c == o.class) {
                let k = room_kind(s, o);
                assert!(kinds.contains(&k), "{}: {} in a {k:?}", s.id, o.name);
            }
            if let Some((_, sups)) = on.iter().find(|(c, _)| *c == o.class) {
                let sup = o
                    .supported_by
                    .and_then(|id| s.object(id))
                    .unwrap_or_else(|| panic!("{}: {} stands on nothing", s.id, o.name));
                assert!(
                    sups.contains(&sup.class),
                    "{}: {} on {:?}",
                    s.id,
                    o.name,
                    sup.class
                );
                assert!((o.bbox.min[1] - sup.bbox.max[1]).abs() < 0.02, "{}", s.id);
            }
            if o.class == C::Firewood && room_kind(s, o) != R::Porch {
                let fire = s
                    .objects
                    .iter()
                    .any(|p| p.class == C::Fireplace && p.room == o.room);
                assert!(fire, "{}: {} in a room with no fireplace", s.id, o.name);
            }
        }
    }
}
