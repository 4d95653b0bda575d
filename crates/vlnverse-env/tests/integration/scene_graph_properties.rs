//! Property tests: the room-bucketed sweep finds exactly the pairs a brute-force scan finds, and
//! the JSON round trip is lossless on random scenes.

use crate::scene_graph_fixture as fixture;

use fixture::*;
use proptest::prelude::*;
use vlnverse_env::scene_graph::{footprint_distance, NodeRef, Relation, SceneGraph};
use vlnverse_env::{RoomType, Scene, SemanticClass};

/// Boxes in two side-by-side rooms (x 0..4 and 4..8, z 0..4): (x, z, w, d, h, y0 choice, room).
fn random_scene() -> impl Strategy<Value = Scene> {
    let item = (
        0.0f32..7.5,
        0.0f32..3.5,
        0.05f32..1.5,
        0.05f32..1.5,
        0.05f32..1.0,
        0u8..3,
    );
    proptest::collection::vec(item, 1..40).prop_map(|items| {
        let mut objects = Vec::new();
        for (i, (x, z, w, d, h, base)) in items.into_iter().enumerate() {
            let id = i as u32 + 1;
            // Some boxes start at a height an earlier box may end at, so stacking happens.
            let y0 = [0.0, 0.5, 0.75][base as usize];
            let room = if x + w * 0.5 < 4.0 { 1 } else { 2 };
            let class = if y0 > 0.0 {
                SemanticClass::Vase
            } else {
                SemanticClass::Cabinet
            };
            let top = if base == 0 {
                [0.5, 0.75][i % 2]
            } else {
                y0 + h
            };
            objects.push(obj(
                id,
                class,
                "red",
                Some(room),
                [x, y0, z],
                [x + w, top, z + d],
                None,
            ));
        }
        scene(
            "random",
            vec![
                room(1, RoomType::Office, rect(0.0, 0.0, 4.0, 4.0)),
                room(2, RoomType::Bedroom, rect(4.0, 0.0, 8.0, 4.0)),
            ],
            vec![],
            objects,
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn pairwise_relations_match_brute_force(scene in random_scene()) {
        let g = SceneGraph::build(&scene);
        let items: Vec<_> = scene.items().collect();
        for (i, a) in items.iter().enumerate() {
            for b in &items[i + 1..] {
                let (ra, rb) = (NodeRef::Object(a.id), NodeRef::Object(b.id));
                let on_ab = a.bbox.intersects_xz(&b.bbox, 0.0)
                    && (a.bbox.min[1] - b.bbox.max[1]).abs() <= 0.03
                    && a.bbox.min[1] > b.bbox.min[1] + 0.03;
                let on_ba = a.bbox.intersects_xz(&b.bbox, 0.0)
                    && (b.bbox.min[1] - a.bbox.max[1]).abs() <= 0.03
                    && b.bbox.min[1] > a.bbox.min[1] + 0.03;
                prop_assert_eq!(g.has_relation(ra, Relation::On, rb), on_ab);
                prop_assert_eq!(g.has_relation(rb, Relation::On, ra), on_ba && !on_ab);
                let d = footprint_distance(&a.bbox, &b.bbox);
                let close = a.room == b.room && !on_ab && !on_ba;
                prop_assert_eq!(g.has_relation(ra, Relation::Near, rb), close && d < 1.0);
                prop_assert_eq!(g.has_relation(ra, Relation::NextTo, rb), close && d < 0.3);
            }
        }
    }

    #[test]
    fn json_round_trip_on_random_scenes(scene in random_scene()) {
        let g = SceneGraph::build(&scene);
        let text = g.to_json_string();
        let back = SceneGraph::from_json(&text).unwrap();
        prop_assert_eq!(&back, &g);
        prop_assert_eq!(back.to_json_string(), text);
    }
}
