//! Scene-graph relations, viewpoint sides and JSON on hand-made fixtures.

use crate::scene_graph_fixture as fixture;

use fixture::*;
use glam::{Quat, Vec2, Vec3};
use std::f32::consts::{FRAC_PI_2, PI};
use vlnverse_env::scene_graph::{
    footprint_distance, side_of, yaw_from_direction, NodeRef, Relation, SceneGraph, Side,
};
use vlnverse_env::{EnvError, ObjectId, Pose};

fn obj_ref(id: ObjectId) -> NodeRef {
    NodeRef::Object(id)
}

fn on_pairs(g: &SceneGraph) -> Vec<(NodeRef, NodeRef)> {
    g.edges()
        .filter(|e| e.relation == Relation::On)
        .map(|e| (e.source, e.target))
        .collect()
}

#[test]
fn nodes_are_rooms_and_non_structure_objects() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    assert_eq!(g.room_count(), 3);
    assert_eq!(g.object_count(), scene.items().count());
    assert!(g.object(WALL).is_none(), "walls are structure, not nodes");
    assert!(!g
        .edges()
        .any(|e| e.source == obj_ref(WALL) || e.target == obj_ref(WALL)));
    let mug = g.object(RED_MUG).unwrap();
    assert_eq!(mug.color, "red");
    assert_eq!(mug.room, Some(LIVING));
    let center = scene.object(RED_MUG).unwrap().bbox.center();
    assert_eq!(mug.position, center.to_array());
}

#[test]
fn in_relation_uses_room_field_or_position() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    for o in scene.items() {
        let expected = o.room.unwrap_or(KITCHEN); // only the fridge has no room
        assert!(
            g.has_relation(obj_ref(o.id), Relation::In, NodeRef::Room(expected)),
            "{} not in room {expected}",
            o.name
        );
        assert_eq!(g.room_of(o.id), Some(expected));
    }
    assert_eq!(scene.object(FRIDGE).unwrap().room, None);
    assert_eq!(
        g.objects_in_room(KITCHEN),
        vec![COUNTER, WHITE_MUG_A, WHITE_MUG_B, FRIDGE, KITCHEN_BOOK]
    );
}

#[test]
fn on_relation_from_declared_support_and_geometry() {
    let g = SceneGraph::build(&home());
    let mut expected = vec![
        (obj_ref(RED_MUG), obj_ref(TABLE)),
        (obj_ref(BLUE_MUG), obj_ref(TABLE)), // geometry only
        (obj_ref(NIGHTSTAND_MUG), obj_ref(NIGHTSTAND)),
        (obj_ref(WHITE_MUG_A), obj_ref(COUNTER)),
        (obj_ref(WHITE_MUG_B), obj_ref(COUNTER)),
    ];
    expected.sort();
    assert_eq!(on_pairs(&g), expected);
    assert_eq!(g.supported(TABLE), vec![RED_MUG, BLUE_MUG]);
    assert_eq!(g.supports_of(BLUE_MUG), vec![TABLE]);
    // A sofa standing on a 1 cm rug is not "on" it.
    assert!(!g.has_relation(obj_ref(GREEN_SOFA), Relation::On, obj_ref(RUG)));
}

#[test]
fn near_and_next_to_follow_footprint_distance_within_a_room() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    let near = |a, b| g.has_relation(obj_ref(a), Relation::Near, obj_ref(b));
    let next = |a, b| g.has_relation(obj_ref(a), Relation::NextTo, obj_ref(b));
    // 0.1 m apart.
    assert!(next(LAMP, TABLE) && near(TABLE, LAMP));
    assert!(next(CHAIR_BY_SOFA, GREEN_SOFA) && next(BED, NIGHTSTAND));
    // 0.7 m apart: near, not next to.
    assert!(near(LAMP, RED_SOFA) && !next(LAMP, RED_SOFA));
    // Two mugs on the same table, 0.42 m apart.
    assert!(near(RED_MUG, BLUE_MUG));
    // Support is "on", not "near".
    assert!(!near(RED_MUG, TABLE) && !next(RED_MUG, TABLE));
    // Exactly 1.0 m apart: not near.
    assert!(!near(TABLE, RED_SOFA));
    // 0.6 m apart but through a wall, in different rooms.
    let d = footprint_distance(
        &scene.object(RED_SOFA).unwrap().bbox,
        &scene.object(BED).unwrap().bbox,
    );
    assert!(d < 1.0);
    assert!(!near(RED_SOFA, BED));
    // Every stored distance is the footprint distance, below the threshold.
    for e in g
        .edges()
        .filter(|e| matches!(e.relation, Relation::Near | Relation::NextTo))
    {
        let (NodeRef::Object(a), NodeRef::Object(b)) = (e.source, e.target) else {
            panic!("near edge between rooms: {e:?}");
        };
        assert!(a < b, "symmetric edge stored once, smaller id first");
        let d = footprint_distance(
            &scene.object(a).unwrap().bbox,
            &scene.object(b).unwrap().bbox,
        );
        assert_eq!(e.distance, Some(d));
        let limit = if e.relation == Relation::Near {
            1.0
        } else {
            0.3
        };
        assert!(d < limit);
    }
    let n = g.neighbours(LAMP, Relation::Near);
    assert_eq!(n.first().map(|x| x.0), Some(TABLE), "closest first: {n:?}");
}

#[test]
fn rooms_connected_through_doors() {
    let g = SceneGraph::build(&home());
    let connected: Vec<_> = g
        .edges()
        .filter(|e| e.relation == Relation::Connected)
        .map(|e| (e.source, e.target, e.door, e.open_plan))
        .collect();
    assert_eq!(
        connected,
        vec![
            (
                NodeRef::Room(LIVING),
                NodeRef::Room(BEDROOM),
                Some(1),
                Some(false)
            ),
            (
                NodeRef::Room(LIVING),
                NodeRef::Room(KITCHEN),
                Some(2),
                Some(true)
            ),
        ]
    );
    assert_eq!(g.connected_rooms(KITCHEN), vec![(LIVING, 2, true)]);
    assert_eq!(
        g.connected_rooms(LIVING),
        vec![(BEDROOM, 1, false), (KITCHEN, 2, true)]
    );
    assert!(g.connected_rooms(BEDROOM).iter().all(|r| r.0 != KITCHEN));
}

#[test]
fn build_is_deterministic_and_independent_of_input_order() {
    let scene = home();
    let a = SceneGraph::build(&scene).to_json_string();
    let mut shuffled = scene.clone();
    shuffled.objects.reverse();
    shuffled.rooms.reverse();
    shuffled.doors.reverse();
    assert_eq!(a, SceneGraph::build(&shuffled).to_json_string());
}

#[test]
fn side_of_at_yaw_0_90_180() {
    let o = Vec2::ZERO;
    let (px, nx, pz, nz) = (
        Vec2::new(1.0, 0.0),
        Vec2::new(-1.0, 0.0),
        Vec2::new(0.0, 1.0),
        Vec2::new(0.0, -1.0),
    );
    // Yaw 0 looks along -Z: -X left, +X right.
    assert_eq!(side_of(o, 0.0, nz), Side::Ahead);
    assert_eq!(side_of(o, 0.0, pz), Side::Behind);
    assert_eq!(side_of(o, 0.0, nx), Side::Left);
    assert_eq!(side_of(o, 0.0, px), Side::Right);
    // Yaw 90 deg (counter-clockwise from above) looks along -X: +Z left, -Z right.
    assert_eq!(side_of(o, FRAC_PI_2, nx), Side::Ahead);
    assert_eq!(side_of(o, FRAC_PI_2, px), Side::Behind);
    assert_eq!(side_of(o, FRAC_PI_2, pz), Side::Left);
    assert_eq!(side_of(o, FRAC_PI_2, nz), Side::Right);
    // Yaw 180 deg looks along +Z: +X left, -X right.
    assert_eq!(side_of(o, PI, pz), Side::Ahead);
    assert_eq!(side_of(o, PI, nz), Side::Behind);
    assert_eq!(side_of(o, PI, px), Side::Left);
    assert_eq!(side_of(o, PI, nx), Side::Right);
    // Viewpoint away from the origin, target slightly off the axis.
    let v = Vec2::new(3.0, 2.0);
    assert_eq!(side_of(v, 0.0, v + Vec2::new(-2.0, -0.5)), Side::Left);
    assert_eq!(side_of(v, 0.0, v + Vec2::new(0.3, -2.0)), Side::Ahead);
}

#[test]
fn side_of_agrees_with_the_pose_convention() {
    for yaw in [-2.0f32, -0.7, 0.0, 0.4, 1.3, 2.9] {
        let q: Quat = Pose::from_yaw(Vec3::ZERO, yaw).quat();
        let fwd = q * Vec3::NEG_Z;
        let right = q * Vec3::X;
        let v = Vec2::new(1.0, -2.0);
        let at = |d: Vec3| v + Vec2::new(d.x, d.z) * 2.0;
        assert_eq!(side_of(v, yaw, at(fwd)), Side::Ahead, "yaw {yaw}");
        assert_eq!(side_of(v, yaw, at(right)), Side::Right, "yaw {yaw}");
        assert_eq!(side_of(v, yaw, at(-right)), Side::Left, "yaw {yaw}");
        assert_eq!(side_of(v, yaw, at(-fwd)), Side::Behind, "yaw {yaw}");
        let back = yaw_from_direction(Vec2::new(fwd.x, fwd.z));
        assert!((back - yaw).abs() < 1e-5, "{yaw} -> {back}");
    }
}

#[test]
fn json_round_trip_is_lossless() {
    let g = SceneGraph::build(&home());
    let text = g.to_json_string();
    let back = SceneGraph::from_json(&text).unwrap();
    assert_eq!(back, g);
    assert_eq!(back.to_json_string(), text);
    // The Value form parses too.
    let from_value = SceneGraph::from_json(&g.to_json().to_string()).unwrap();
    assert_eq!(from_value, g);
    // Queries on the reloaded graph answer the same.
    assert_eq!(back.supported(TABLE), g.supported(TABLE));
    assert_eq!(
        back.neighbours(LAMP, Relation::Near),
        g.neighbours(LAMP, Relation::Near)
    );
}

#[test]
fn json_layout_has_documented_fields() {
    let v = SceneGraph::build(&home()).to_json();
    assert_eq!(v["format_version"], 1);
    assert_eq!(v["scene_id"], "fixture_home");
    let nodes = v["nodes"].as_array().unwrap();
    let room = &nodes[0];
    assert_eq!(room["id"], "room:1");
    assert_eq!(room["type"], "room");
    assert_eq!(room["kind"], "living_room");
    let mug = nodes.iter().find(|n| n["id"] == "object:11").unwrap();
    assert_eq!(mug["type"], "object");
    assert_eq!(mug["class"], "mug");
    assert_eq!(mug["color"], "red");
    assert_eq!(mug["room"], 1);
    assert_eq!(mug["position"].as_array().unwrap().len(), 3);
    let edges = v["edges"].as_array().unwrap();
    assert!(edges.iter().any(|e| e["source"] == "object:11"
        && e["target"] == "object:10"
        && e["relation"] == "on"));
    let door = edges.iter().find(|e| e["relation"] == "connected").unwrap();
    assert_eq!(door["door"], 1);
    assert_eq!(door["open_plan"], false);
}

fn parse_error(text: &str) -> String {
    match SceneGraph::from_json(text) {
        Err(e @ EnvError::Parse { .. }) => e.to_string(),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn from_json_rejects_corrupt_input_with_clear_errors() {
    let good = SceneGraph::build(&home()).to_json();
    let text = good.to_string();

    assert!(parse_error("not json").contains("scene_graph.json"));
    assert!(parse_error(&text[..text.len() / 2]).contains("scene_graph.json"));

    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = good.clone();
        f(&mut v);
        parse_error(&v.to_string())
    };
    let msg = edit(&|v| v["format_version"] = 99.into());
    assert!(
        msg.contains("format_version") && msg.contains("99"),
        "{msg}"
    );
    let msg = edit(&|v| v["edges"][0]["target"] = "object:999".into());
    assert!(
        msg.contains("edges[0].target") && msg.contains("object:999"),
        "{msg}"
    );
    let msg = edit(&|v| v["nodes"][3]["id"] = "sofa:1".into());
    assert!(msg.contains("sofa:1"), "{msg}");
    let msg = edit(&|v| v["nodes"][4] = v["nodes"][3].clone());
    assert!(msg.contains("duplicate"), "{msg}");
    let msg = edit(&|v| v["edges"][0]["relation"] = "under".into());
    assert!(msg.contains("under"), "{msg}");
    let msg = edit(&|v| v["nodes"][5]["class"] = "spaceship".into());
    assert!(msg.contains("spaceship"), "{msg}");
    // As written to disk (pretty-printed): a wrongly typed value is quoted with its field.
    let mut v = good.clone();
    v["format_version"] = "one".into();
    let msg = parse_error(&serde_json::to_string_pretty(&v).unwrap());
    assert!(msg.contains("\"format_version\": \"one\""), "{msg}");
    let msg = edit(&|v| v["nodes"][5]["room"] = 77.into());
    assert!(msg.contains("nodes[5].room") && msg.contains("77"), "{msg}");
    let msg = edit(&|v| {
        let e = v["edges"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .find(|e| e["relation"] == "near")
            .unwrap();
        e.as_object_mut().unwrap().remove("distance");
    });
    assert!(msg.contains("near"), "{msg}");
    // An `in` edge pointing at an object is malformed.
    let msg = edit(&|v| {
        let e = v["edges"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .find(|e| e["relation"] == "in")
            .unwrap();
        e["target"] = "object:10".into();
    });
    assert!(msg.contains("malformed"), "{msg}");
}

#[test]
fn save_and_load_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let g = SceneGraph::build(&home());
    g.save(dir.path()).unwrap();
    assert_eq!(SceneGraph::load(dir.path()).unwrap(), g);

    let missing = tempfile::tempdir().unwrap();
    let e = SceneGraph::load(missing.path()).unwrap_err();
    assert!(matches!(e, EnvError::Io { .. }));
    assert!(e.to_string().contains("scene_graph.json"));

    std::fs::write(dir.path().join("scene_graph.json"), "{\"nodes\": 3}").unwrap();
    let e = SceneGraph::load(dir.path()).unwrap_err().to_string();
    assert!(
        e.contains(&dir.path().join("scene_graph.json").display().to_string()),
        "{e}"
    );
}
