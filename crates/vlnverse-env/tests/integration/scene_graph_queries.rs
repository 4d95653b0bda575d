//! Task-layer queries: referring expressions, landmarks along a path, rooms along a path.

use crate::scene_graph_fixture as fixture;

use fixture::*;
use glam::{Vec2, Vec3};
use vlnverse_env::scene_graph::{
    footprint_distance, rooms_along_path, side_of, yaw_from_direction, Landmark,
    ReferringExpression, Relation, SceneGraph, Side,
};
use vlnverse_env::{ObjectId, RoomType, Scene, SemanticClass};

fn describe(scene: &Scene, g: &SceneGraph, id: ObjectId) -> ReferringExpression {
    let e = g
        .referring_expression(scene, id)
        .unwrap_or_else(|| panic!("no description for object {id}"));
    assert_eq!(e.target, id);
    assert_eq!(
        e.matches(scene, g),
        vec![id],
        "`{}` is not unique",
        e.text()
    );
    e
}

/// Every description obtained by dropping one part of `e`.
fn simpler(e: &ReferringExpression) -> Vec<ReferringExpression> {
    let mut out = Vec::new();
    if e.color.is_some() {
        out.push(ReferringExpression {
            color: None,
            ..e.clone()
        });
    }
    if e.support.is_some() {
        out.push(ReferringExpression {
            support: None,
            ..e.clone()
        });
    }
    if e.room.is_some() {
        out.push(ReferringExpression {
            room: None,
            ..e.clone()
        });
    }
    if e.reference.is_some() {
        out.push(ReferringExpression {
            reference: None,
            relation: None,
            ..e.clone()
        });
    }
    if let Some(m) = &e.support {
        if m.color.is_some() {
            let mut s = e.clone();
            s.support.as_mut().unwrap().color = None;
            out.push(s);
        }
    }
    out
}

#[test]
fn referring_expressions_are_the_expected_shortest_ones() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    let text = |id| describe(&scene, &g, id).text();
    // Class alone.
    assert_eq!(text(TABLE), "the coffee table");
    assert_eq!(text(FRIDGE), "the fridge");
    // Colour + class.
    assert_eq!(text(RED_SOFA), "the red sofa");
    assert_eq!(text(BLUE_MUG), "the blue mug");
    // Class + support.
    assert_eq!(text(NIGHTSTAND_MUG), "the mug on the nightstand");
    // Class + room.
    assert_eq!(text(BEDROOM_BOOK), "the book in the bedroom");
    assert_eq!(text(KITCHEN_BOOK), "the book in the kitchen");
    // Colour + class + support: red alone and "on the coffee table" alone both fit two mugs.
    assert_eq!(text(RED_MUG), "the red mug on the coffee table");
    // Reference objects, themselves unique.
    assert_eq!(text(CHAIR_BY_SOFA), "the chair next to the green sofa");
    assert_eq!(text(CHAIR_BY_TABLE), "the chair near the coffee table");
}

#[test]
fn referring_expression_parts_are_structured() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    let e = describe(&scene, &g, RED_MUG);
    assert_eq!(e.class, SemanticClass::Mug);
    assert_eq!(e.color.as_deref(), Some("red"));
    assert_eq!(e.support.as_ref().map(|m| m.object), Some(TABLE));
    assert_eq!(e.room, None);
    assert_eq!(e.parts(), 2);
    let e = describe(&scene, &g, BEDROOM_BOOK);
    assert_eq!(
        e.room.map(|r| (r.room, r.kind)),
        Some((BEDROOM, RoomType::Bedroom))
    );
    let e = describe(&scene, &g, CHAIR_BY_SOFA);
    assert_eq!(e.relation, Some(Relation::NextTo));
    let r = e.reference.unwrap();
    assert_eq!((r.object, r.color.as_deref()), (GREEN_SOFA, Some("green")));
}

#[test]
fn every_describable_object_gets_a_unique_minimal_expression() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    let mut described = 0;
    for o in scene.items() {
        let Some(e) = g.referring_expression(&scene, o.id) else {
            continue;
        };
        described += 1;
        assert_eq!(e.matches(&scene, &g), vec![o.id], "`{}`", e.text());
        for s in simpler(&e) {
            assert_ne!(
                s.matches(&scene, &g),
                vec![o.id],
                "`{}` could be shortened to `{}`",
                e.text(),
                s.text()
            );
        }
    }
    // All but the two identical white mugs.
    assert_eq!(described, scene.items().count() - 2);
}

#[test]
fn identical_objects_have_no_referring_expression() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    assert_eq!(g.referring_expression(&scene, WHITE_MUG_A), None);
    assert_eq!(g.referring_expression(&scene, WHITE_MUG_B), None);
    // Structure and unknown ids neither.
    assert_eq!(g.referring_expression(&scene, WALL), None);
    assert_eq!(g.referring_expression(&scene, 999), None);
    // Repaint one: both become describable by colour.
    let mut scene = scene;
    scene
        .objects
        .iter_mut()
        .find(|o| o.id == WHITE_MUG_B)
        .unwrap()
        .color = "yellow".into();
    let g = SceneGraph::build(&scene);
    assert_eq!(describe(&scene, &g, WHITE_MUG_B).text(), "the yellow mug");
    assert_eq!(
        describe(&scene, &g, WHITE_MUG_A).text(),
        "the white mug",
        "the only white mug now"
    );
}

#[test]
fn matches_evaluates_words_not_ids() {
    let scene = home();
    let g = SceneGraph::build(&scene);
    // "the mug on the coffee table" fits both mugs on it, whatever the support id says.
    let mut e = describe(&scene, &g, RED_MUG);
    e.color = None;
    assert_eq!(e.matches(&scene, &g), vec![RED_MUG, BLUE_MUG]);
    // "the red mug" fits both red mugs.
    e.support = None;
    e.color = Some("red".into());
    assert_eq!(e.matches(&scene, &g), vec![RED_MUG, NIGHTSTAND_MUG]);
}

// ---- landmarks ----

use SemanticClass as C;

const SOFA: ObjectId = 2;
const WARDROBE: ObjectId = 3;
const FRIDGE_L: ObjectId = 4;
const BED_L: ObjectId = 5;
const BOOKSHELF: ObjectId = 6;
const CABINET: ObjectId = 7;
const CUP: ObjectId = 8;
const ARMCHAIR: ObjectId = 9;
const PLANT: ObjectId = 10;
const RUG_L: ObjectId = 11;

/// One 10 x 10 m room and an L-shaped path: (1, 9) -> (1, 1) heading -Z, then -> (9, 1)
/// heading +X.
fn l_scene() -> (Scene, Vec<Vec3>) {
    let r = Some(1);
    let objects = vec![
        obj(
            1,
            C::Floor,
            "grey",
            None,
            [0.0, -0.1, 0.0],
            [10.0, 0.0, 10.0],
            None,
        ),
        // First leg: right (+X) 0.5 m, left (-X) 0.4 m.
        obj(
            SOFA,
            C::Sofa,
            "red",
            r,
            [1.5, 0.0, 4.0],
            [2.5, 0.9, 6.0],
            None,
        ),
        obj(
            WARDROBE,
            C::Wardrobe,
            "white",
            r,
            [0.0, 0.0, 4.0],
            [0.6, 2.0, 6.0],
            None,
        ),
        // Second leg (heading +X): -Z is left, +Z right.
        obj(
            FRIDGE_L,
            C::Fridge,
            "silver",
            r,
            [5.0, 0.0, 0.0],
            [6.0, 1.8, 0.5],
            None,
        ),
        obj(
            BED_L,
            C::Bed,
            "blue",
            r,
            [5.0, 0.0, 1.6],
            [7.0, 0.6, 3.0],
            None,
        ),
        // Too far.
        obj(
            BOOKSHELF,
            C::Bookshelf,
            "brown",
            r,
            [5.0, 0.0, 6.0],
            [6.0, 2.0, 7.0],
            None,
        ),
        // Close, but hidden by the test's fake wall.
        obj(
            CABINET,
            C::Cabinet,
            "brown",
            r,
            [1.8, 0.0, 7.0],
            [2.3, 1.0, 7.5],
            None,
        ),
        // Close but tiny.
        obj(
            CUP,
            C::Cup,
            "red",
            r,
            [1.2, 0.0, 3.0],
            [1.3, 0.1, 3.1],
            None,
        ),
        // Behind the corner once the agent has turned.
        obj(
            ARMCHAIR,
            C::Armchair,
            "green",
            r,
            [0.0, 0.0, 0.0],
            [0.4, 0.9, 0.6],
            None,
        ),
        // Beyond the end of the path.
        obj(
            PLANT,
            C::PottedPlant,
            "green",
            r,
            [9.3, 0.0, 0.8],
            [9.7, 1.2, 1.2],
            None,
        ),
        // Walked over: never a landmark.
        obj(
            RUG_L,
            C::Rug,
            "beige",
            r,
            [0.5, 0.0, 2.0],
            [1.5, 0.01, 3.0],
            None,
        ),
    ];
    let scene = scene(
        "l_room",
        vec![room(1, RoomType::LivingRoom, rect(0.0, 0.0, 10.0, 10.0))],
        vec![],
        objects,
    );
    let path = vec![
        Vec3::new(1.0, 0.0, 9.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(9.0, 0.0, 1.0),
    ];
    (scene, path)
}

/// A fake wall along x = 1.5 for z in 6.5..8: sight lines crossing it are blocked.
fn fake_wall(a: Vec2, b: Vec2) -> bool {
    if (a.x - 1.5) * (b.x - 1.5) >= 0.0 {
        return true;
    }
    let t = (1.5 - a.x) / (b.x - a.x);
    let z = a.y + (b.y - a.y) * t;
    !(6.5..=8.0).contains(&z)
}

#[test]
fn landmarks_on_an_l_shaped_path() {
    let (scene, path) = l_scene();
    let g = SceneGraph::build(&scene);
    let lms = g.landmarks_along_path(&scene, &path, fake_wall, 1.0);
    let got: Vec<(ObjectId, usize, Side)> = lms
        .iter()
        .map(|l| (l.object, l.path_index, l.side))
        .collect();
    assert_eq!(
        got,
        vec![
            (WARDROBE, 0, Side::Left),
            (SOFA, 0, Side::Right),
            (FRIDGE_L, 1, Side::Left),
            (BED_L, 1, Side::Right),
            (ARMCHAIR, 1, Side::Behind),
            (PLANT, 2, Side::Ahead),
        ]
    );
    let close = |l: &Landmark, d: f32| (l.distance - d).abs() < 1e-5;
    assert!(close(&lms[0], 0.4) && close(&lms[1], 0.5) && close(&lms[3], 0.6));
    // The hidden cabinet appears once sight is free.
    let all = g.landmarks_along_path(&scene, &path, |_, _| true, 1.0);
    assert!(all
        .iter()
        .any(|l| l.object == CABINET && l.side == Side::Right));
    assert!(all
        .iter()
        .all(|l| ![BOOKSHELF, CUP, RUG_L, 1].contains(&l.object)));
}

#[test]
fn landmarks_are_consistent_with_geometry() {
    let (scene, path) = l_scene();
    let g = SceneGraph::build(&scene);
    let lms = g.landmarks_along_path(&scene, &path, |_, _| true, 1.5);
    let mut ids: Vec<_> = lms.iter().map(|l| l.object).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), lms.len(), "each object once");
    assert!(lms.windows(2).all(|w| w[0].path_index <= w[1].path_index));
    for l in &lms {
        let o = scene.object(l.object).unwrap();
        let p = Vec3::new(l.point.x, 0.0, l.point.y);
        let at = vlnverse_env::Aabb::new(p, p);
        assert!((footprint_distance(&o.bbox, &at) - l.distance).abs() < 1e-4);
        assert!(l.distance <= 1.5);
        let seg = l.path_index.min(path.len() - 2);
        let d = path[seg + 1] - path[seg];
        let yaw = yaw_from_direction(Vec2::new(d.x, d.z));
        let c = o.bbox.center();
        assert_eq!(side_of(l.point, yaw, Vec2::new(c.x, c.z)), l.side);
    }
}

#[test]
fn visibility_is_asked_from_the_path_towards_the_object() {
    let (scene, path) = l_scene();
    let g = SceneGraph::build(&scene);
    let asked = std::cell::RefCell::new(Vec::new());
    g.landmarks_along_path(
        &scene,
        &path,
        |a, b| {
            asked.borrow_mut().push((a, b));
            true
        },
        1.0,
    );
    let asked = asked.into_inner();
    assert!(!asked.is_empty());
    for (a, b) in asked {
        // From a point on the path (x = 1 or z = 1), to a point outside the object it aims at.
        assert!((a.x - 1.0).abs() < 1e-5 || (a.y - 1.0).abs() < 1e-5, "{a}");
        assert!(scene.items().all(|o| {
            let (lo, hi) = (o.bbox.min_v(), o.bbox.max_v());
            o.class == C::Rug || !(b.x > lo.x && b.x < hi.x && b.y > lo.z && b.y < hi.z)
        }));
    }
}

#[test]
fn short_paths_have_no_landmarks() {
    let (scene, path) = l_scene();
    let g = SceneGraph::build(&scene);
    assert!(g
        .landmarks_along_path(&scene, &path[..1], |_, _| true, 5.0)
        .is_empty());
    assert!(g
        .landmarks_along_path(&scene, &[], |_, _| true, 5.0)
        .is_empty());
}

#[test]
fn rooms_along_a_path_through_two_doors() {
    let scene = home();
    // Bedroom -> living room (through door 1 at x = 5) -> kitchen (through the opening).
    let path = vec![
        Vec3::new(7.0, 0.0, 2.0),
        Vec3::new(2.5, 0.0, 2.0),
        Vec3::new(2.5, 0.0, 6.0),
    ];
    assert_eq!(
        rooms_along_path(&scene, &path),
        vec![(0, BEDROOM), (0, LIVING), (1, KITCHEN)]
    );
    assert_eq!(rooms_along_path(&scene, &path[..1]), vec![(0, BEDROOM)]);
    assert!(rooms_along_path(&scene, &[Vec3::new(50.0, 0.0, 50.0)]).is_empty());
}
