//! Levels and stairs in the scene model: old files load unchanged, two-level scenes round-trip,
//! bad levels are refused with the field named.

use crate::io_common::fixture_scene;
use std::path::Path;
use vlnverse_env::io::json::{scene_from_json, scene_to_json};
use vlnverse_env::{Level, Scene, Stairs, Storeys};

fn two_levels() -> Scene {
    let mut s = fixture_scene();
    let ids: Vec<u32> = s.rooms.iter().map(|r| r.id).collect();
    let (ground, upper) = ids.split_at(ids.len() / 2);
    s.storeys = Storeys {
        levels: vec![
            Level {
                id: 0,
                name: "ground floor".into(),
                floor_height: s.floor_height,
                rooms: ground.to_vec(),
            },
            Level {
                id: 1,
                name: "upper floor".into(),
                floor_height: s.floor_height + 2.8,
                rooms: upper.to_vec(),
            },
        ],
        stairs: vec![Stairs {
            id: 0,
            levels: [0, 1],
            object: None,
            footprint: vec![[0.0, 0.0], [0.0, 4.2], [1.0, 4.2], [1.0, 0.0]],
            foot: [0.5, 0.0, -0.6],
            head: [0.5, 2.8, 4.8],
            steps: 16,
            rise: 0.175,
            run: 0.28,
            width: 1.0,
        }],
    };
    s
}

#[test]
fn single_storey_files_have_no_level_keys_and_one_implicit_level() {
    let s = fixture_scene();
    let text = String::from_utf8(scene_to_json(&s)).unwrap();
    assert!(!text.contains("\"levels\"") && !text.contains("\"stairs\""));
    let back = scene_from_json(text.as_bytes(), Path::new("scene.json")).unwrap();
    // Mesh vertices live in scene.glb: compare what scene.json holds.
    assert_eq!(scene_to_json(&back), text.as_bytes());
    assert!(back.storeys.is_empty());
    assert_eq!(back.level_count(), 1);
    assert!(!back.is_multi_level());
    assert_eq!(back.level_height(0), Some(s.floor_height));
    assert_eq!(back.level_height(1), None);
    for r in &back.rooms {
        assert_eq!(back.room_level(r.id), Some(0));
    }
}

#[test]
fn two_level_scene_round_trips_and_answers_level_queries() {
    let s = two_levels();
    let bytes = scene_to_json(&s);
    let back = scene_from_json(&bytes, Path::new("scene.json")).unwrap();
    assert_eq!(back.storeys, s.storeys);
    assert_eq!(scene_to_json(&back), bytes);
    assert_eq!(back.level_count(), 2);
    assert_eq!(back.level_height(1), Some(s.floor_height + 2.8));
    assert_eq!(back.level_at_height(s.floor_height + 1.0), 0);
    assert_eq!(back.level_at_height(s.floor_height + 2.7), 1);
    let st = &back.storeys.stairs[0];
    // 15 treads of 0.28 m rising 2.8 m, plus 0.6 m of flat walk at either end.
    let flight = (4.2f32 * 4.2 + 2.8 * 2.8).sqrt();
    assert!(
        (st.walk_length() - (flight + 1.2)).abs() < 1e-3,
        "{}",
        st.walk_length()
    );
    assert!((st.pitch().to_degrees() - 32.0).abs() < 0.1);
}

#[test]
fn bad_levels_are_refused_naming_the_field() {
    let mut s = two_levels();
    s.storeys.levels[1].rooms.clear();
    let e = scene_from_json(&scene_to_json(&s), Path::new("x/scene.json")).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("every room must be on exactly one"), "{text}");
    assert!(text.contains("x/scene.json"), "{text}");

    let mut s = two_levels();
    s.storeys.stairs[0].levels = [1, 0];
    let text = s.validate_storeys().unwrap_err().to_string();
    assert!(text.contains("stairs[0].levels"), "{text}");

    let mut s = two_levels();
    s.storeys.levels[1].floor_height = -1.0;
    let text = s.validate_storeys().unwrap_err().to_string();
    assert!(text.contains("levels[1].floor_height"), "{text}");

    let mut s = two_levels();
    s.storeys.stairs[0].rise = f32::NAN;
    let text = s.validate_storeys().unwrap_err().to_string();
    assert!(text.contains("stairs[0].rise"), "{text}");
}

/// Two 6 x 6 m open rooms stacked 3 m apart (walls 2.5 m, the upper floor slab on top), a
/// 1 x 3 m flight at x in [4.5, 5.5], z in [1, 4] rising towards -z, foot at z = 4.6, head at
/// z = 0.5.
fn stacked_rooms() -> Scene {
    use crate::occupancy_fixtures::{boxed, open_room};
    use vlnverse_env::{Room, RoomType, SemanticClass};
    let ground = open_room(6.0);
    let mut s = ground.clone();
    let n = s.objects.len() as u32;
    for o in &ground.objects {
        let mut o = o.clone();
        o.id += n;
        o.name = format!("{}_{}", o.class.name(), o.id);
        o.pose.position[1] += 3.0;
        o.bbox.min[1] += 3.0;
        o.bbox.max[1] += 3.0;
        s.objects.push(o);
    }
    // The flight: a block to just under the upper floor on the ground floor.
    s.objects.push(boxed(
        2 * n + 1,
        SemanticClass::Stairs,
        [4.5, 0.0, 1.0],
        [5.5, 2.8, 4.0],
    ));
    // Ceiling of the ground floor (a slab under the upper floor, holed over the flight).
    s.objects.push(boxed(
        2 * n + 2,
        SemanticClass::Ceiling,
        [0.0, 2.5, 0.0],
        [4.5, 2.55, 6.0],
    ));
    let room = |id: u32, name: &str| Room {
        id,
        kind: RoomType::Hallway,
        name: name.into(),
        polygon: vec![[0.0, 0.0], [0.0, 6.0], [6.0, 6.0], [6.0, 0.0]],
    };
    s.rooms = vec![room(0, "hallway_1"), room(1, "hallway_2")];
    s.doors.clear();
    s.storeys = Storeys {
        levels: vec![
            Level {
                id: 0,
                name: "ground floor".into(),
                floor_height: 0.0,
                rooms: vec![0],
            },
            Level {
                id: 1,
                name: "upper floor".into(),
                floor_height: 3.0,
                rooms: vec![1],
            },
        ],
        stairs: vec![Stairs {
            id: 0,
            levels: [0, 1],
            object: Some(2 * n + 1),
            footprint: vec![[4.5, 1.0], [4.5, 4.0], [5.5, 4.0], [5.5, 1.0]],
            foot: [5.0, 0.0, 4.6],
            head: [5.0, 3.0, 0.5],
            steps: 12,
            rise: 0.25,
            run: 3.0 / 11.0,
            width: 1.0,
        }],
    };
    s.validate_storeys().unwrap();
    s
}

#[test]
fn level_maps_join_through_the_stairs_and_single_levels_are_unchanged() {
    use glam::Vec2;
    use vlnverse_env::geodesic::{geodesic_distance, LevelPoint, MultiLevelMap};
    use vlnverse_env::occupancy::{build_level_maps, build_maps, OccupancyConfig};
    let cfg = OccupancyConfig::default();
    let s = stacked_rooms();
    let maps = build_level_maps(&s, &cfg).unwrap();
    assert_eq!(maps.len(), 2);
    assert_eq!(build_maps(&s, &cfg).unwrap(), maps[0]);
    // The same room on both levels, the flight occupied on both: the same maps.
    assert_eq!(maps[0].navigable, maps[1].navigable);
    let flight = Vec2::new(5.0, 2.5);
    assert!(!maps[1].occupancy.is_free_at(flight));
    assert!(maps[0].navigable.is_free_at(Vec2::new(2.0, 2.0)));
    // One level: exactly the single-level maps.
    let one = crate::occupancy_fixtures::open_room(6.0);
    assert_eq!(
        build_level_maps(&one, &cfg).unwrap(),
        vec![build_maps(&one, &cfg).unwrap()]
    );

    let m = MultiLevelMap::from_scene(&s, &cfg).unwrap();
    let a = LevelPoint::new(0, 2.0, 5.0);
    let b = LevelPoint::new(1, 2.0, 1.0);
    let st = &s.storeys.stairs[0];
    let nav = &maps[0].navigable;
    let leg = |p: Vec2, q: [f32; 3]| {
        geodesic_distance(nav, p, Vec2::new(q[0], q[2]))
            .unwrap()
            .meters()
            .unwrap()
    };
    let want = leg(a.point, st.foot) + st.walk_length() + leg(b.point, st.head);
    let got = m.geodesic_distance(a, b).unwrap().meters().unwrap();
    assert!((got - want).abs() < 1e-3, "{got} vs {want}");
    assert_eq!(
        LevelPoint::from_world(&s, [2.0, 3.0, 1.0]),
        LevelPoint::new(1, 2.0, 1.0)
    );

    // The picture of a floor holds that floor: its room, its walls, the flight on both.
    let up = s.level_view(1).unwrap();
    assert_eq!(up.floor_height, 3.0);
    assert_eq!(up.rooms.len(), 1);
    assert!(up
        .objects
        .iter()
        .any(|o| o.class == vlnverse_env::SemanticClass::Stairs));
    assert!(up
        .objects
        .iter()
        .filter(|o| o.class == vlnverse_env::SemanticClass::Wall)
        .all(|o| o.bbox.min[1] >= 2.9));
    let t = vlnverse_env::topdown::render_topdown_level(
        &s,
        1,
        Some(&maps[1].navigable),
        &Default::default(),
    )
    .unwrap();
    assert!(t.image.width() > 100);
}

/// In a home on several floors each room's lamps hang under its own floor's walls: the ground
/// floor's under the ground floor's ceiling, not at the upper floor's height.
#[test]
fn lamps_hang_under_the_walls_of_their_own_floor() {
    let mut s = stacked_rooms();
    s.source = "procgen".into();
    let lamps = vlnverse_env::light::lamps(&s);
    assert_eq!(lamps.len(), 4, "two rooms of 6 m, two lamps each");
    let ys: Vec<f32> = lamps.iter().map(|p| p.y).collect();
    // Walls of the fixture stand 2.5 m on each floor (the upper floor at 3 m).
    assert!(ys[..2].iter().all(|&y| y > 1.5 && y < 2.5), "{ys:?}");
    assert!(ys[2..].iter().all(|&y| y > 4.5 && y < 5.5), "{ys:?}");
    // One floor: every lamp at the one height, as before.
    let mut one = crate::occupancy_fixtures::open_room(6.0);
    one.source = "procgen".into();
    let flat = vlnverse_env::light::lamps(&one);
    assert!(flat.windows(2).all(|w| w[0].y == w[1].y), "{flat:?}");
}

/// The distance to an upstairs goal across floors: the route's length from the ground floor,
/// the rest of the flight from a tread, the walk on the goal's floor up there; a point right
/// below the goal is as far as the walk through the stairs; the way there goes to the foot,
/// then along the flight.
#[test]
fn a_level_field_measures_across_floors_and_guides_up_the_flight() {
    use glam::Vec2;
    use vlnverse_env::geodesic::{Guide, LevelField, LevelPoint, MultiLevelMap};
    use vlnverse_env::occupancy::OccupancyConfig;
    let s = stacked_rooms();
    let m = MultiLevelMap::from_scene(&s, &OccupancyConfig::default()).unwrap();
    let st = &s.storeys.stairs[0];
    let goal = LevelPoint::new(1, 2.0, 1.0);
    let f = LevelField::new(&m, &[0.0, 3.0], &[0.5 * st.width], goal).unwrap();
    let from = |p: [f32; 3]| f.distance(p).meters().unwrap();
    let via = |a: LevelPoint| m.geodesic_distance(a, goal).unwrap().meters().unwrap();
    // From the ground floor: the route across floors (the field's cells vs A*: within 5 cm).
    let below = from([2.0, 0.0, 1.0]);
    assert!(
        (below - via(LevelPoint::new(0, 2.0, 1.0))).abs() < 0.05,
        "{below}"
    );
    assert!(below > 5.0, "right below the goal is far from it: {below}");
    // Upstairs: the walk on the goal's floor.
    let up = from([2.0, 3.0, 2.0]);
    assert!((up - 1.0).abs() < 0.05, "{up}");
    // Halfway up the flight: half its length and the rest.
    let mid = [5.0, 1.5, 2.5];
    let head_rest = via(LevelPoint::new(1, st.head[0], st.head[2]));
    let half = from(mid);
    assert!(
        (half - (0.5 * st.walk_length() + head_rest)).abs() < 0.3,
        "{half}"
    );
    // The way: from the ground floor down a field (to the foot), on the flight toward the head.
    assert!(matches!(f.guide([2.0, 0.0, 5.0]), Some(Guide::Walk { rest, .. }) if rest > 1.0));
    match f.guide(mid) {
        Some(Guide::Flight { up, to, .. }) => {
            assert!(up);
            assert_eq!(to, Vec2::new(st.head[0], st.head[2]));
        }
        g => panic!("{g:?}"),
    }
    assert!(matches!(
        f.guide(st.foot),
        Some(Guide::Flight { up: true, .. })
    ));
    assert!(matches!(f.guide([2.0, 3.0, 2.0]), Some(Guide::Walk { rest, .. }) if rest == 0.0));
}
