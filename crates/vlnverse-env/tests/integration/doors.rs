//! Doors on a hand-made two-room scene: a closed leaf is an obstacle in the occupancy, ROS and
//! navigable maps and geodesic distance cannot pass it (unreachable when it is the only way);
//! an open leaf leaves the doorway passable. Scene graph, `scene.json` and top-down pictures
//! carry the door's state.

use glam::{Vec2, Vec3};
use vlnverse_env::geodesic::geodesic_distance;
use vlnverse_env::occupancy::{build_maps, CellState, OccupancyConfig};
use vlnverse_env::scene_graph::{DoorNode, Relation, SceneGraph};
use vlnverse_env::topdown::{render_topdown, TopdownOptions};
use vlnverse_env::{
    Door, DoorState, Room, RoomType, Scene, SceneObject, SemanticClass as C, SCENE_FORMAT_VERSION,
};

const LEAF: u32 = 9;

/// Rooms x in [-3, 0] and [0, 3], z in [-2, 2], a wall at x = 0 with a 1 m doorway at z = 0
/// holding a leaf: closed in the doorway, or open (swung into the right room along its jamb).
fn two_rooms(state: DoorState) -> Scene {
    let cub = |id, class, a: [f32; 3], b: [f32; 3]| {
        SceneObject::cuboid(id, class, Vec3::from_array(a), Vec3::from_array(b))
    };
    let mut objects = vec![
        cub(1, C::Floor, [-3.0, -0.05, -2.0], [0.0, 0.0, 2.0]),
        cub(2, C::Floor, [0.0, -0.05, -2.0], [3.0, 0.0, 2.0]),
        cub(3, C::Wall, [-3.1, 0.0, -2.1], [3.1, 2.5, -2.0]),
        cub(4, C::Wall, [-3.1, 0.0, 2.0], [3.1, 2.5, 2.1]),
        cub(5, C::Wall, [-3.1, 0.0, -2.0], [-3.0, 2.5, 2.0]),
        cub(6, C::Wall, [3.0, 0.0, -2.0], [3.1, 2.5, 2.0]),
        cub(7, C::Wall, [-0.05, 0.0, -2.0], [0.05, 2.5, -0.5]),
        cub(8, C::Wall, [-0.05, 0.0, 0.5], [0.05, 2.5, 2.0]),
    ];
    let leaf = match state {
        DoorState::Closed => cub(LEAF, C::Door, [-0.02, 0.02, -0.495], [0.02, 2.0, 0.495]),
        DoorState::Open => cub(LEAF, C::Door, [0.06, 0.02, 0.51], [1.05, 2.0, 0.55]),
    };
    objects.push(SceneObject {
        room: Some(1),
        ..leaf
    });
    let room = |id, x0: f32, x1: f32| Room {
        id,
        kind: RoomType::Bedroom,
        name: format!("bedroom_{}", id + 1),
        polygon: vec![[x0, -2.0], [x0, 2.0], [x1, 2.0], [x1, -2.0]],
    };
    Scene {
        format_version: SCENE_FORMAT_VERSION,
        id: "two_rooms".into(),
        source: "test".into(),
        seed: None,
        floor_height: 0.0,
        rooms: vec![room(0, -3.0, -0.05), room(1, 0.05, 3.0)],
        doors: vec![Door {
            id: 0,
            position: [0.0, 0.0, 0.0],
            width: 1.0,
            normal: [1.0, 0.0],
            rooms: [0, 1],
            open_plan: false,
            state: Some(state),
            leaf: Some(LEAF),
            second_leaf: None,
            kind: Default::default(),
        }],
        objects,
        storeys: Default::default(),
    }
}

#[test]
fn a_closed_door_is_an_obstacle_in_every_map_and_cuts_the_only_route() {
    let s = two_rooms(DoorState::Closed);
    let maps = build_maps(&s, &OccupancyConfig::default()).unwrap();
    for k in 0..=10 {
        let p = Vec2::new(0.0, -0.5 + k as f32 * 0.1);
        assert!(!maps.occupancy.is_free_at(p), "{p}");
        assert!(!maps.navigable.is_free_at(p), "{p}");
        // The ROS map (PGM) marks it occupied too.
        let (c, r) = maps.occupancy.world_to_cell(p).unwrap();
        assert_eq!(maps.occupancy.state(c, r), CellState::Occupied);
    }
    let pgm = maps.occupancy.to_pgm_bytes();
    let (c, r) = maps.occupancy.world_to_cell(Vec2::ZERO).unwrap();
    let header = pgm.len() - (maps.occupancy.width * maps.occupancy.height) as usize;
    assert_eq!(pgm[header + (r * maps.occupancy.width + c) as usize], 0);
    // The one way between the rooms is shut: no geodesic route.
    let d = geodesic_distance(&maps.occupancy, Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0));
    assert!(!d.unwrap().is_reachable());
}

#[test]
fn an_open_leaf_leaves_the_doorway_passable() {
    let s = two_rooms(DoorState::Open);
    let maps = build_maps(&s, &OccupancyConfig::default()).unwrap();
    assert!(maps.navigable.is_free_at(Vec2::ZERO));
    let d = geodesic_distance(&maps.navigable, Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0))
        .unwrap()
        .meters()
        .expect("reachable through the open door");
    assert!((d - 2.0).abs() < 0.05, "{d}");
}

#[test]
fn the_scene_graph_and_scene_json_carry_the_door_state() {
    for state in [DoorState::Open, DoorState::Closed] {
        let s = two_rooms(state);
        let g = SceneGraph::build(&s);
        let node = g.object(LEAF).expect("the leaf is an object node");
        assert_eq!(node.class, C::Door);
        assert_eq!(
            node.door,
            Some(DoorNode {
                id: 0,
                state,
                rooms: [0, 1]
            })
        );
        let edge = g
            .edges()
            .find(|e| e.relation == Relation::Connected)
            .unwrap();
        assert_eq!(edge.state, Some(state));
        let back = SceneGraph::from_json(&g.to_json_string()).unwrap();
        assert_eq!(back.object(LEAF).unwrap().door, node.door);
        let json = serde_json::to_string(&s).unwrap();
        assert!(json.contains(&format!("\"state\":\"{}\"", state.name())));
        let again: Scene = serde_json::from_str(&json).unwrap();
        assert_eq!(again.doors, s.doors);
    }
    // A scene.json written before doors had leaves still loads: no state, no leaf.
    let old = r#"{"id":3,"position":[0.0,0.0,0.0],"width":0.9,"normal":[1.0,0.0],"rooms":[0,1],"open_plan":false}"#;
    let d: Door = serde_json::from_str(old).unwrap();
    assert_eq!((d.state, d.leaf), (None, None));
    assert!(!d.is_closed());
    assert_eq!(serde_json::to_string(&d).unwrap(), old);
}

#[test]
fn top_down_pictures_draw_open_and_closed_doors_differently() {
    let colour = |state| {
        let s = two_rooms(state);
        let opts = TopdownOptions {
            labels: false,
            room_names: false,
            ..TopdownOptions::default()
        };
        let t = render_topdown(&s, None, &opts);
        let p = t.frame.to_pixel(Vec2::ZERO);
        t.image.get_pixel(p.x as u32, p.y as u32).0
    };
    let (open, closed) = (colour(DoorState::Open), colour(DoorState::Closed));
    assert_ne!(open, closed);
    // Closed doors are red, open ones orange.
    assert!(closed[0] > 150 && closed[1] < 80, "{closed:?}");
    assert!(open[0] > 150 && open[1] > 100, "{open:?}");
}

#[test]
fn doors_on_a_path_in_crossing_order() {
    let s = two_rooms(DoorState::Open);
    let through = s.doors_on_path(&[[-1.0, 0.2], [1.0, -0.2]]);
    assert_eq!(through.len(), 1);
    assert_eq!(through[0].leaf, Some(LEAF));
    // Through the wall beside the doorway: not a door.
    assert!(s.doors_on_path(&[[-1.0, 1.0], [1.0, 1.0]]).is_empty());
    // There and back: the door twice; a vertex in the doorway counts once.
    let twice = s.doors_on_path(&[[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0], [-1.0, 0.1]]);
    assert_eq!(twice.len(), 2);
}
