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
