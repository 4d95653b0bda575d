//! Kinds of doorway: hinged, sliding and french doors and arches, drawn across the preset; glass
//! leaves that block when closed and leave the doorway free when open; arches with no leaf and
//! the agent's clearance; old scene files without a kind load as hinged.

use crate::support;
use glam::Vec2;
use rayon::prelude::*;
use std::collections::BTreeMap;
use vlnverse_env::geodesic::geodesic_distance;
use vlnverse_env::occupancy::{build_level_maps, OccupancyConfig};
use vlnverse_env::scene::DoorKind;
use vlnverse_env::{Door, DoorState, Scene, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset};

fn vlnverse() -> HomeGenerator {
    HomeGenerator::from_preset(Preset::Vlnverse).unwrap()
}

/// Every home of the preset.
fn preset() -> Vec<Scene> {
    let v = vlnverse();
    (0..v.len())
        .into_par_iter()
        .map(|i| v.scene(i).unwrap())
        .collect()
}

/// The leaf objects of a door.
fn leaves<'a>(s: &'a Scene, d: &Door) -> Vec<&'a vlnverse_env::SceneObject> {
    d.leaves()
        .map(|id| s.object(id).expect("the leaf object exists"))
        .collect()
}

#[test]
fn every_kind_is_drawn_in_the_preset_with_the_leaves_it_needs() {
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    let mut with_leaf: BTreeMap<&str, usize> = BTreeMap::new();
    for s in preset() {
        for d in &s.doors {
            if d.open_plan {
                assert_eq!(d.kind, DoorKind::Hinged, "{}: door {}", s.id, d.id);
                continue;
            }
            *counts.entry(d.kind.name()).or_default() += 1;
            let ls = leaves(&s, d);
            if !ls.is_empty() {
                *with_leaf.entry(d.kind.name()).or_default() += 1;
            }
            assert_eq!(
                d.second_leaf.is_some(),
                d.kind == DoorKind::French && d.leaf.is_some()
            );
            for o in &ls {
                assert_eq!(o.class, C::Door);
                let glass = o.material == "glass";
                assert_eq!(glass, d.kind.is_glass(), "{}: door {}", s.id, d.id);
                // A glass leaf has a pane: its largest part, one centimetre thick.
                if glass {
                    let pane = &o.parts[0];
                    let vlnverse_env::Shape::Cuboid { half_extents, .. } = pane.shape else {
                        panic!("a box pane");
                    };
                    assert!(half_extents[2] < 0.006 && half_extents[1] > 0.5);
                }
            }
            match d.kind {
                DoorKind::Arched => {
                    assert_eq!((d.state, d.leaf), (None, None), "{}: door {}", s.id, d.id)
                }
                DoorKind::French => {
                    assert_eq!(ls.len(), 2, "{}: door {}", s.id, d.id);
                    // Each leaf is half the doorway wide.
                    for o in &ls {
                        let span = o.bbox.size().x.max(o.bbox.size().z);
                        assert!(span < d.width * 0.5 + 0.08, "{}: {}", s.id, o.name);
                    }
                }
                DoorKind::Sliding | DoorKind::Hinged => assert!(ls.len() <= 1),
            }
        }
    }
    eprintln!("doorways by kind: {counts:?}; with a leaf: {with_leaf:?}");
    for k in DoorKind::ALL {
        let n = with_leaf.get(k.name()).copied().unwrap_or(0);
        let n = if k == DoorKind::Arched {
            counts.get(k.name()).copied().unwrap_or(0)
        } else {
            n
        };
        assert!(n >= 10, "only {n} {} doorways", k.name());
    }
}

#[test]
fn open_glass_leaves_keep_clear_of_doorways_and_a_sliding_one_lies_along_the_wall() {
    let clearance = vlnverse().config().doors.clearance;
    let t = vlnverse().config().walls.thickness;
    let mut sliding = 0;
    for s in preset() {
        for d in s.doors.iter().filter(|d| d.kind.is_glass()) {
            if d.state != Some(DoorState::Open) {
                continue;
            }
            for o in leaves(&s, d) {
                support::assert_leaf_clear_of_doorways(&s, o, clearance);
                support::assert_leaf_touches_nothing(&s, o);
                if d.kind == DoorKind::Sliding {
                    // Flat against the wall: no more than a few centimetres proud of its face.
                    let c = Vec2::new(d.position[0], d.position[2]);
                    let n = Vec2::from_array(d.normal);
                    let (lo, hi) = (o.bbox.min_v(), o.bbox.max_v());
                    let depth = [(lo.x, lo.z), (hi.x, hi.z)]
                        .map(|(x, z)| (Vec2::new(x, z) - c).dot(n).abs());
                    let far = depth[0].max(depth[1]);
                    assert!(
                        far < t * 0.5 + 0.1,
                        "{}: {} stands {far} m out",
                        s.id,
                        o.name
                    );
                    sliding += 1;
                }
            }
        }
    }
    assert!(sliding >= 10, "only {sliding} open sliding doors");
}

#[test]
fn glass_doors_block_when_closed_and_let_the_agent_through_when_open() {
    // Glass doors lead to balconies and porches or join rooms routes cannot go round, so in the
    // preset they all stand open (a closed one is checked in the unit tests of `doors.rs`).
    let cfg = OccupancyConfig::default();
    let homes: Vec<Scene> = preset()
        .into_iter()
        .filter(|s| {
            s.doors
                .iter()
                .any(|d| d.kind.is_glass() && d.leaf.is_some())
        })
        .collect();
    let (mut closed, mut open) = (0, 0);
    for s in &homes {
        let levels = build_level_maps(s, &cfg).unwrap();
        for d in s.doors.iter().filter(|d| d.kind.is_glass()) {
            let maps = &levels[support::door_level(s, d) as usize];
            let c = Vec2::new(d.position[0], d.position[2]);
            let n = Vec2::from_array(d.normal);
            let g = geodesic_distance(&maps.navigable, c + n * 0.6, c - n * 0.6).unwrap();
            match d.state {
                Some(DoorState::Closed) => {
                    for k in 0..=20 {
                        let p = c + n.perp() * d.width * (k as f32 / 20.0 - 0.5);
                        assert!(
                            !maps.occupancy.is_free_at(p),
                            "{}: door {} at {p}",
                            s.id,
                            d.id
                        );
                    }
                    assert!(
                        g.meters().is_none_or(|m| m > 1.7),
                        "{}: door {}",
                        s.id,
                        d.id
                    );
                    closed += 1;
                }
                Some(DoorState::Open) => {
                    assert!(
                        g.meters().is_some_and(|m| m < 1.25),
                        "{}: open door {}: {g:?}",
                        s.id,
                        d.id
                    );
                    open += 1;
                }
                None => {}
            }
        }
    }
    eprintln!("glass doors: {closed} closed, {open} open");
    assert!(open >= 20, "only {open} open glass doors");
}

#[test]
fn an_arched_doorway_has_no_leaf_and_clears_the_agent() {
    let occ = OccupancyConfig::default();
    let v = vlnverse();
    let head = v.config().doors.head_height;
    assert!(head >= occ.agent_height);
    let mut checked = 0;
    for s in preset().iter().take(120) {
        let arches: Vec<&Door> = s
            .doors
            .iter()
            .filter(|d| d.kind == DoorKind::Arched)
            .collect();
        if arches.is_empty() {
            continue;
        }
        let levels = build_level_maps(s, &occ).unwrap();
        for d in arches {
            assert_eq!((d.state, d.leaf, d.second_leaf), (None, None, None));
            // The frame around it: nothing of it over the clear width is below the door head,
            // and the arch rises above the head in the middle.
            let y = d.position[1];
            let c = Vec2::new(d.position[0], d.position[2]);
            let frame = s
                .objects
                .iter()
                .filter(|o| o.class == C::DoorFrame)
                .find(|o| Vec2::new(o.pose.position[0], o.pose.position[2]).distance(c) < 1e-3)
                .expect("an arch's frame");
            let mut crown = f32::MAX;
            for part in &frame.parts {
                let one = vlnverse_env::SceneObject::from_parts(
                    0,
                    C::DoorFrame,
                    frame.pose,
                    vec![part.clone()],
                );
                let b = one.bbox;
                let (lo, hi) = (b.min_v(), b.max_v());
                let across = Vec2::new((lo.x + hi.x) * 0.5, (lo.z + hi.z) * 0.5) - c;
                if across.length() < d.width * 0.5 - 0.01 {
                    assert!(lo.y - y >= head - 1e-3, "{}: door {}: {lo}", s.id, d.id);
                    if across.length() < 0.1 {
                        crown = crown.min(lo.y - y);
                    }
                }
            }
            assert!(crown > head + 0.3, "{}: door {}: crown {crown}", s.id, d.id);
            // The agent walks straight through.
            let maps = &levels[support::door_level(s, d) as usize];
            let n = Vec2::from_array(d.normal);
            let g = geodesic_distance(&maps.navigable, c + n * 0.6, c - n * 0.6).unwrap();
            assert!(
                g.meters().is_some_and(|m| m < 1.25),
                "{}: arch {}",
                s.id,
                d.id
            );
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} arches");
}

#[test]
fn a_door_without_a_kind_loads_as_hinged_and_kinds_round_trip() {
    let old = r#"{"id": 3, "position": [1.0, 0.0, 2.0], "width": 0.9, "normal": [1.0, 0.0],
        "rooms": [0, 1], "open_plan": false, "state": "open", "leaf": 7}"#;
    let d: Door = serde_json::from_str(old).unwrap();
    assert_eq!(d.kind, DoorKind::Hinged);
    assert_eq!(d.second_leaf, None);
    assert_eq!(d.leaves().collect::<Vec<_>>(), vec![7]);
    for k in DoorKind::ALL {
        let json = serde_json::to_string(&Door {
            kind: k,
            ..d.clone()
        })
        .unwrap();
        // Hinged, the default, is not written.
        let written = json.contains(&format!("\"kind\":\"{}\"", k.name()));
        assert_eq!(written, k != DoorKind::Hinged, "{json}");
        let back: Door = serde_json::from_str(&json).unwrap();
        assert_eq!(back.kind, k);
    }
}

#[test]
fn a_doorways_kind_depends_on_the_home_and_the_door_alone() {
    let v = vlnverse();
    let mut cfg = v.config().clone();
    cfg.doors.leaves = false;
    let bare = HomeGenerator::new(cfg).unwrap();
    for i in [0, 50, 100, 200] {
        let (a, b) = (v.scene(i).unwrap(), bare.scene(i).unwrap());
        for (x, y) in a.doors.iter().zip(&b.doors) {
            // Without leaves only the arches keep their kind; the rest are bare doorways.
            match x.kind {
                DoorKind::Arched => assert_eq!(y.kind, DoorKind::Arched),
                _ => assert_eq!(y.kind, DoorKind::Hinged),
            }
        }
    }
}
