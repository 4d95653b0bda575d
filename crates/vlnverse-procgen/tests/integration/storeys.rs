//! Homes on two floors (`floors.two_storey_share`, docs/storeys.md): the levels and stairs are
//! valid and within the stair limits, every room of both floors is reachable through the
//! stairs, the output does not depend on the thread count, and share 0 changes nothing.

use glam::Vec2;
use rayon::prelude::*;
use vlnverse_env::geodesic::{LevelPoint, MultiLevelMap, RouteLeg};
use vlnverse_env::occupancy::{build_level_maps, build_maps, OccupancyConfig};
use vlnverse_env::{RoomType, Scene, SceneSource, SemanticClass as C};
use vlnverse_procgen::{HomeGenerator, Preset, ProcgenConfig};

fn two_storey(count: usize, seed: u64) -> HomeGenerator {
    let mut cfg =
        ProcgenConfig::from_toml_str(include_str!("../../configs/scenes/two_storey.toml"), None)
            .unwrap();
    cfg.scenes.count = count;
    cfg.scenes.seed = seed;
    HomeGenerator::new(cfg).unwrap()
}

/// A navigable cell centre inside the room, on its level's map.
fn point_in(m: &MultiLevelMap, s: &Scene, room: u32) -> Option<LevelPoint> {
    let level = s.room_level(room)?;
    let r = s.room(room)?;
    let map = m.level(level)?;
    map.free_cells()
        .map(|(c, w)| map.cell_center(c, w))
        .find(|p| r.contains(p.x, p.y))
        .map(|point| LevelPoint { level, point })
}

#[test]
fn two_storey_homes_are_valid_and_every_room_is_reachable_through_the_stairs() {
    let g = two_storey(40, 31);
    let cfg = OccupancyConfig::default();
    let scenes: Vec<Scene> = (0..g.len())
        .into_par_iter()
        .map(|i| g.scene(i).unwrap())
        .collect();
    let two = scenes.iter().filter(|s| s.is_multi_level()).count();
    assert!(two >= 36, "only {two} of 40 homes got an upper floor");
    for s in scenes.iter().filter(|s| s.is_multi_level()) {
        s.validate_storeys().unwrap();
        assert_eq!(s.level_count(), 2);
        // Boxes of the lifted upper floor are made from their pose and parts, as all boxes are.
        for o in &s.objects {
            assert_eq!(
                o.bbox,
                o.compute_bbox(),
                "{}: stale box of {}",
                s.id,
                o.name
            );
        }
        let st = &s.storeys.stairs[0];
        assert!(st.rise <= g.config().floors.max_riser + 1e-6, "{}", s.id);
        let pitch = st.pitch().to_degrees();
        assert!((25.0..=37.0).contains(&pitch), "{}: pitch {pitch}", s.id);
        let upper = s.level_height(1).unwrap();
        assert!((st.rise * st.steps as f32 - upper).abs() < 1e-3);
        let flight = s.object(st.object.unwrap()).unwrap();
        assert_eq!(flight.class, C::Stairs);
        assert!((flight.bbox.max[1] - (upper - st.rise)).abs() < 1e-3);
        assert!(s.objects.iter().any(|o| o.class == C::Railing));
        // The upper floor: bedrooms and a bathroom; nothing from the ground floor's list.
        let up: Vec<RoomType> = s.storeys.levels[1]
            .rooms
            .iter()
            .map(|&r| s.room(r).unwrap().kind)
            .collect();
        assert!(up.contains(&RoomType::Bedroom) && up.contains(&RoomType::Bathroom));
        assert!(!up.contains(&RoomType::Kitchen) && !up.contains(&RoomType::LivingRoom));
        // Every object of the upper floor stands on or above it; ids stay sorted and unique.
        assert!(s.objects.windows(2).all(|w| w[0].id + 1 == w[1].id));
        for o in s.objects.iter().filter(|o| o.room.is_some()) {
            let level = s.room_level(o.room.unwrap()).unwrap();
            let floor = s.level_height(level).unwrap();
            assert!(
                o.bbox.min[1] >= floor - 0.06,
                "{}: {} below its floor",
                s.id,
                o.name
            );
        }

        let m = MultiLevelMap::from_scene(s, &cfg).unwrap();
        let living = s
            .rooms
            .iter()
            .find(|r| r.kind == RoomType::LivingRoom)
            .unwrap();
        let start = point_in(&m, s, living.id).unwrap();
        assert_eq!(start.level, 0);
        for r in &s.rooms {
            let p = point_in(&m, s, r.id)
                .unwrap_or_else(|| panic!("{}: {} has no navigable cell", s.id, r.name));
            let route = m
                .shortest_route(start, p)
                .unwrap()
                .unwrap_or_else(|| panic!("{}: {} unreachable from the living room", s.id, r.name));
            assert_eq!(
                route.stairs_taken(),
                p.level as usize,
                "{}: {}",
                s.id,
                r.name
            );
            if p.level == 1 {
                // Up the stairs: the walk to the foot, the flight, the walk from the head.
                assert!(matches!(route.legs[1], RouteLeg::Stairs { up: true, .. }));
                let d = m.geodesic_distance(p, start).unwrap().meters().unwrap();
                assert!((d - route.length).abs() < 0.05 * route.length.max(1.0));
            }
        }
    }
}

#[test]
fn two_storey_homes_are_the_same_on_any_thread_count() {
    let g = two_storey(6, 5);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let a: Vec<Vec<u8>> = one.install(|| {
        (0..g.len())
            .map(|i| vlnverse_env::io::json::scene_to_json(&g.scene(i).unwrap()))
            .collect()
    });
    let b: Vec<Vec<u8>> = (0..g.len())
        .into_par_iter()
        .map(|i| vlnverse_env::io::json::scene_to_json(&g.scene(i).unwrap()))
        .collect();
    assert_eq!(a, b);
    assert!(a
        .iter()
        .any(|j| String::from_utf8_lossy(j).contains("\"stairs\"")));
}

#[test]
fn share_zero_leaves_every_home_on_one_floor_and_as_it_was() {
    let preset = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    assert_eq!(preset.config().floors.two_storey_share, 0.3);
    let mut cfg = preset.config().clone();
    cfg.floors.two_storey_share = 0.0;
    let flat = HomeGenerator::new(cfg.clone()).unwrap();
    // The rest of the floors section is not drawn from at share 0: the same bytes.
    cfg.floors.max_riser = 0.15;
    let other = HomeGenerator::new(cfg).unwrap();
    for i in [0, 7, 100] {
        let (a, b) = (flat.scene(i).unwrap(), other.scene(i).unwrap());
        assert!(!a.is_multi_level() && a.storeys.is_empty());
        assert_eq!(
            vlnverse_env::io::json::scene_to_json(&a),
            vlnverse_env::io::json::scene_to_json(&b)
        );
        // One level: the level maps are the maps.
        let cfg = OccupancyConfig::default();
        assert_eq!(
            build_level_maps(&a, &cfg).unwrap(),
            vec![build_maps(&a, &cfg).unwrap()]
        );
    }
}

#[test]
fn level_maps_show_the_flight_as_a_block_below_and_a_railed_hole_above() {
    let g = two_storey(3, 9);
    let s = (0..g.len())
        .map(|i| g.scene(i).unwrap())
        .find(|s| s.is_multi_level())
        .unwrap();
    let maps = build_level_maps(&s, &OccupancyConfig::default()).unwrap();
    assert_eq!(maps.len(), 2);
    let st = &s.storeys.stairs[0];
    let (x, z) = (
        st.footprint.iter().map(|p| p[0]).sum::<f32>() / 4.0,
        st.footprint.iter().map(|p| p[1]).sum::<f32>() / 4.0,
    );
    for m in &maps {
        assert!(!m.occupancy.is_free_at(Vec2::new(x, z)));
        assert!(!m.navigable.is_free_at(Vec2::new(x, z)));
    }
    assert!(maps[0]
        .navigable
        .is_free_at(Vec2::new(st.foot[0], st.foot[2])));
    assert!(maps[1]
        .navigable
        .is_free_at(Vec2::new(st.head[0], st.head[2])));
    // The ground floor's map of a two-storey home is its level-0 map.
    assert_eq!(
        build_maps(&s, &OccupancyConfig::default()).unwrap(),
        maps[0]
    );
}

#[test]
fn floors_config_is_range_checked_with_the_field_named() {
    for (text, field) in [
        (
            "[floors]\ntwo_storey_share = 1.5\n",
            "floors.two_storey_share",
        ),
        ("[floors]\nmax_riser = 0.3\n", "floors.max_riser"),
        ("[floors]\ntread = 0.1\n", "floors.tread"),
        ("[floors]\nslab = -1.0\n", "floors.slab"),
        ("[floors]\nstair_width = 0.5\n", "floors.stair_width"),
    ] {
        let e = ProcgenConfig::from_toml_str(text, Some(std::path::Path::new("x.toml")))
            .unwrap_err()
            .to_string();
        assert!(e.contains(field) && e.contains("x.toml"), "{e}");
    }
    let e = ProcgenConfig::from_toml_str("[floors]\nstairs = 2\n", None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("stairs"), "{e}");
}

#[test]
fn a_two_storey_folder_holds_ros_maps_and_pictures_per_floor() {
    let g = two_storey(2, 3);
    let s = (0..g.len())
        .map(|i| g.scene(i).unwrap())
        .find(|s| s.is_multi_level())
        .unwrap();
    let cfg = OccupancyConfig::default();
    let tmp = tempfile::tempdir().unwrap();
    let (_, dir) = vlnverse_env::io::write_scene_bundle(tmp.path(), s.clone(), &cfg).unwrap();
    assert!(vlnverse_env::io::is_complete_scene_dir(&dir));
    let levels = build_level_maps(&s, &cfg).unwrap();
    let ground = vlnverse_env::occupancy::GridMap::load_ros(dir.join("navigable.yaml")).unwrap();
    assert_eq!(ground, levels[0].navigable);
    for stem in ["occupancy", "navigable"] {
        let m = vlnverse_env::occupancy::GridMap::load_ros(dir.join(format!("{stem}_level1.yaml")))
            .unwrap();
        let want = if stem == "navigable" {
            &levels[1].navigable
        } else {
            &levels[1].occupancy
        };
        assert_eq!(&m, want, "{stem}_level1");
    }
    assert!(!dir.join("navigable_level2.yaml").exists());
    let back = vlnverse_env::io::load_scene(&dir).unwrap();
    assert_eq!(back.storeys, s.storeys);

    // Each floor's picture shows that floor's rooms: the views split the rooms.
    let views: Vec<Scene> = (0..2).map(|l| s.level_view(l).unwrap()).collect();
    assert_eq!(views[0].rooms.len() + views[1].rooms.len(), s.rooms.len());
    assert!(views
        .iter()
        .all(|v| v.objects.iter().any(|o| o.class == C::Stairs)));
    assert!(views[1].objects.iter().any(|o| o.class == C::Railing));
    assert!(!views[0].objects.iter().any(|o| o.class == C::Railing));
    assert!(s.level_view(2).is_none());
    let opts = vlnverse_env::topdown::TopdownOptions {
        title: s.id.clone(),
        ..Default::default()
    };
    for (l, m) in levels.iter().enumerate() {
        let t =
            vlnverse_env::topdown::render_topdown_level(&s, l as u32, Some(&m.navigable), &opts)
                .unwrap();
        assert!(t.image.width() > 100 && t.image.height() > 100);
    }
}

#[test]
fn the_scene_graph_knows_the_floors() {
    use vlnverse_env::scene_graph::{rooms_along_path, Node, SceneGraph};
    let g = two_storey(2, 11);
    let s = (0..g.len())
        .map(|i| g.scene(i).unwrap())
        .find(|s| s.is_multi_level())
        .unwrap();
    let graph = SceneGraph::build(&s);
    for n in graph.nodes() {
        match n {
            Node::Room(r) => {
                let level = s.room_level(r.room).unwrap();
                assert_eq!(r.level, Some(level));
                assert_eq!(r.position[1], s.level_height(level).unwrap());
            }
            Node::Object(o) => {
                // An object's room is on the level it stands on.
                if let Some(room) = o.room {
                    let floor = s.level_height(s.room_level(room).unwrap()).unwrap();
                    assert!(o.bbox.min[1] >= floor - 0.06, "{}", o.name);
                }
            }
        }
    }
    // A route up the stairs passes the hall below, then the landing above.
    let st = &s.storeys.stairs[0];
    let path = [
        glam::Vec3::from_array(st.foot),
        glam::Vec3::from_array(st.head),
    ];
    let rooms = rooms_along_path(&s, &path);
    let levels: Vec<u32> = rooms
        .iter()
        .map(|&(_, r)| s.room_level(r).unwrap())
        .collect();
    assert_eq!(levels.first(), Some(&0));
    assert_eq!(levels.last(), Some(&1));
    // Single-storey graphs carry no levels.
    let one = HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(0)
        .unwrap();
    let json = SceneGraph::build(&one).to_json_string();
    assert!(!json.contains("\"level\""));
}

#[test]
fn a_share_gives_that_share_and_leaves_the_other_homes_as_they_were() {
    // The preset draws 30% two-storey homes; each home left on one floor is the home the same
    // config gives at share 0, byte for byte.
    let mixed = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    let mut cfg = mixed.config().clone();
    cfg.floors.two_storey_share = 0.0;
    let base = HomeGenerator::new(cfg).unwrap();
    let n = 60;
    let results: Vec<(bool, bool)> = (0..n)
        .into_par_iter()
        .map(|i| {
            let (a, b) = (base.scene(i).unwrap(), mixed.scene(i).unwrap());
            let same = vlnverse_env::io::json::scene_to_json(&a)
                == vlnverse_env::io::json::scene_to_json(&b);
            (b.is_multi_level(), same)
        })
        .collect();
    let two = results.iter().filter(|r| r.0).count();
    assert!(
        (8..=30).contains(&two),
        "{two} of {n} homes on two floors at share 0.3"
    );
    assert!(results.iter().all(|&(multi, same)| multi != same));
}
