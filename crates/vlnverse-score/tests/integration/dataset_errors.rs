//! Split files that are not what they claim: errors say what is wrong in words a user acts on.

use vlnverse_score::dataset::{read_file, read_split, to_gzip_bytes, write_split};
use vlnverse_score::episode::{Goal, Instruction};
use vlnverse_score::{Episode, Split, Task};

/// A well-formed fine episode: a goal 2 m ahead, its path and an instruction.
fn episode(id: u64) -> Episode {
    Episode {
        episode_id: id,
        scene_id: "home".into(),
        goals: vec![Goal {
            position: [0.0, 0.0, -2.0],
            radius: 3.0,
            object_id: None,
        }],
        reference_path: vec![[0.0; 3], [0.0, 0.0, -2.0]],
        instruction: Instruction {
            instruction_text: "Walk ahead and stop.".into(),
            ..Default::default()
        },
        ..Default::default()
    }
}

#[test]
fn a_gz_file_that_is_not_gzip_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    std::fs::write(&path, "this is not a split file").unwrap();
    let err = read_file(&path).unwrap_err().to_string();
    assert!(
        err.contains("test.json.gz") && err.contains("not gzip-compressed"),
        "{err}"
    );
}

#[test]
fn nan_and_infinity_are_named_with_the_text_around_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json");
    let good = String::from_utf8(flate2_free_json(&[episode(1)])).unwrap();
    let bad = good.replacen(
        "\"start_position\":[0.0,0.0,0.0]",
        "\"start_position\":[NaN,0.0,0.0]",
        1,
    );
    assert_ne!(good, bad, "the fixture has a start_position to spoil");
    std::fs::write(&path, bad).unwrap();
    let err = read_file(&path).unwrap_err().to_string();
    assert!(
        err.contains("test.json")
            && err.contains("NaN and Infinity are not JSON numbers")
            && err.contains("start_position"),
        "{err}"
    );
}

#[test]
fn a_repeated_episode_id_names_both_indices() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    std::fs::write(
        &path,
        to_gzip_bytes(&[episode(4), episode(5), episode(4)]).unwrap(),
    )
    .unwrap();
    let err = read_file(&path).unwrap_err().to_string();
    assert!(
        err.contains("episodes[2].episode_id")
            && err.contains("episodes[0]")
            && err.contains("used twice"),
        "{err}"
    );
}

#[test]
fn scene_ids_and_reference_images_that_leave_the_dataset_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    let read = |e: Episode| {
        std::fs::write(&path, to_gzip_bytes(&[episode(1), e]).unwrap()).unwrap();
        read_file(&path).map(|_| ()).map_err(|e| e.to_string())
    };
    for bad in ["/etc", "../other_dataset/scenes/home", "home/../../x"] {
        let err = read(Episode {
            scene_id: bad.into(),
            ..episode(2)
        })
        .unwrap_err();
        assert!(
            err.contains("episodes[1].scene_id") && err.contains(bad),
            "{err}"
        );
    }
    let err = read(Episode {
        reference_image: Some("../../secret.png".into()),
        ..episode(2)
    })
    .unwrap_err();
    assert!(err.contains("episodes[1].reference_image"), "{err}");
    // Nested ids (VLN-CE's `mp3d/ID/ID.glb`) and plain relative images stay readable.
    read(Episode {
        scene_id: "mp3d/17DRP5sb8fy/17DRP5sb8fy.glb".into(),
        reference_image: Some("images/2.png".into()),
        ..episode(2)
    })
    .unwrap();
}

#[test]
fn a_nan_inside_a_gzip_split_is_named_not_called_a_compression_problem() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    let good = String::from_utf8(flate2_free_json(&[episode(1)])).unwrap();
    let bad = good.replacen("\"geodesic_distance\":0.0", "\"geodesic_distance\":NaN", 1);
    assert_ne!(good, bad, "the fixture has a geodesic_distance to spoil");
    std::fs::write(
        &path,
        vlnverse_score::dataset::gzip(bad.as_bytes()).unwrap(),
    )
    .unwrap();
    let err = read_file(&path).unwrap_err().to_string();
    assert!(
        err.contains("NaN and Infinity are not JSON numbers")
            && err.contains("geodesic_distance")
            && err.contains("line 1")
            && !err.contains("not gzip"),
        "{err}"
    );
}

/// Read one spoilt episode (after a good one) and return the error.
fn refused(spoil: impl FnOnce(&mut Episode)) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    let mut bad = episode(2);
    spoil(&mut bad);
    std::fs::write(&path, to_gzip_bytes(&[episode(1), bad]).unwrap()).unwrap();
    match read_file(&path) {
        Ok(_) => panic!("a spoilt episode was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_episode_fields_are_refused_naming_field_and_value() {
    let goal = |r: f32| Goal {
        position: [0.0, 0.0, -2.0],
        radius: r,
        object_id: None,
    };
    let cases: Vec<(&str, &str, Box<dyn FnOnce(&mut Episode)>)> = vec![
        (
            "instruction.instruction_text",
            "empty",
            Box::new(|e| e.instruction.instruction_text = "  ".into()),
        ),
        (
            "info.geodesic_distance",
            "-5",
            Box::new(|e| e.info.geodesic_distance = -5.0),
        ),
        (
            "reference_path",
            "empty",
            Box::new(|e| e.reference_path.clear()),
        ),
        (
            "start_rotation",
            "[0.0, 0.0, 0.0, 0.0]",
            Box::new(|e| e.start_rotation = [0.0; 4]),
        ),
        (
            "start_rotation",
            "[0.0, 0.0, 0.0, 2.0]",
            Box::new(|e| e.start_rotation = [0.0, 0.0, 0.0, 2.0]),
        ),
        (
            "start_rotation",
            "[0.5, 0.0, 0.0, 0.8660254]",
            Box::new(|e| e.start_rotation = [0.5, 0.0, 0.0, 0.866_025_4]),
        ),
        (
            "goals[0].radius",
            "-1",
            Box::new(move |e| e.goals = vec![goal(-1.0)]),
        ),
        ("goals", "empty", Box::new(|e| e.goals.clear())),
        (
            "sub_goals",
            "empty",
            Box::new(|e| e.task = Task::LongHorizon),
        ),
        (
            "sub_goals[1].radius",
            "0",
            Box::new(move |e| {
                e.task = Task::LongHorizon;
                e.sub_goals = vec![goal(3.0), goal(0.0)];
            }),
        ),
    ];
    for (field, value, spoil) in cases {
        let err = refused(spoil);
        assert!(
            err.contains(&format!("episodes[1].{field}"))
                && err.contains("episode_id 2")
                && err.contains(value),
            "{field} = {value}: {err}"
        );
    }
    // A yaw-only unit rotation (90 degrees about +Y) is fine.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.json.gz");
    let turned = Episode {
        start_rotation: [
            0.0,
            std::f32::consts::FRAC_1_SQRT_2,
            0.0,
            std::f32::consts::FRAC_1_SQRT_2,
        ],
        ..episode(2)
    };
    std::fs::write(&path, to_gzip_bytes(&[episode(1), turned]).unwrap()).unwrap();
    read_file(&path).unwrap();
}

#[test]
fn an_episode_of_another_task_in_a_split_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let coarse = Episode {
        task: Task::Coarse,
        ..episode(7)
    };
    write_split(dir.path(), Task::Fine, Split::Test, &[episode(1), coarse]).unwrap();
    let err = read_split(dir.path(), Task::Fine, Split::Test)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("episodes[1].task") && err.contains("coarse") && err.contains("fine"),
        "{err}"
    );
}

/// The plain JSON of a split (what the gzip holds).
fn flate2_free_json(episodes: &[Episode]) -> Vec<u8> {
    serde_json::to_vec(&vlnverse_score::Dataset {
        episodes: episodes.to_vec(),
    })
    .unwrap()
}

#[test]
fn a_nan_in_a_trajectory_file_gets_a_hint() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("traj.jsonl");
    std::fs::write(
        &path,
        "{\"episode_id\": 1, \"positions\": [[0,0,0]], \"stopped\": true}\n\
         {\"episode_id\": 2, \"positions\": [[0,0,0],[NaN,0,1]], \"stopped\": true}\n",
    )
    .unwrap();
    let err = vlnverse_score::trajectory::read_trajectories(&path)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("traj.jsonl")
            && err.contains("line 2")
            && err.contains("NaN and Infinity are not JSON numbers"),
        "{err}"
    );
}
