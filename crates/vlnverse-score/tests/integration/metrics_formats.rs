//! Episode, split and trajectory file formats.

use std::path::Path;

use vlnverse_score::dataset::{read_file, read_split, split_path, to_gzip_bytes, write_split};
use vlnverse_score::trajectory::{parse_trajectories, read_trajectories, write_jsonl};
use vlnverse_score::{
    DataError, Episode, GroundedObject, Role, Side, Split, Style, Task, Trajectory,
};

/// An episode as VLN-CE's R2R_VLNCE_v1-3 files write it (tokens included, no additions).
const VLNCE_EPISODE: &str = r#"{
  "episode_id": 4991,
  "trajectory_id": 3104,
  "scene_id": "mp3d/gZ6f7yhEvPG/gZ6f7yhEvPG.glb",
  "start_position": [-16.267200469970703, 0.15420000255107880, 0.7146999835968018],
  "start_rotation": [0, 0.9817536701745564, 0, -0.19015768435059476],
  "info": {"geodesic_distance": 9.89},
  "goals": [{"position": [-12.1, 0.15, -4.3], "radius": 3.0}],
  "instruction": {
    "instruction_text": "Go down the hall and stop at the bathroom door.",
    "instruction_tokens": [958, 692, 2202, 1010, 2300, 0]
  },
  "reference_path": [[-16.26, 0.15, 0.71], [-14.0, 0.15, -1.0], [-12.1, 0.15, -4.3]]
}"#;

#[test]
fn vlnce_r2r_episode_parses() {
    let ep: Episode = serde_json::from_str(VLNCE_EPISODE).unwrap();
    assert_eq!((ep.episode_id, ep.trajectory_id), (4991, 3104));
    assert_eq!(ep.task, Task::Fine, "VLN-CE files read as fine-grained");
    assert_eq!(ep.goals[0].radius, 3.0);
    assert_eq!(ep.instruction.instruction_tokens.as_ref().unwrap().len(), 6);
    assert_eq!(ep.reference_path.len(), 3);
    assert_eq!(ep.info.geodesic_distance, 9.89);
    // A null radius (some habitat datasets) reads as 3 m.
    let null_radius = VLNCE_EPISODE.replace("\"radius\": 3.0", "\"radius\": null");
    let ep2: Episode = serde_json::from_str(&null_radius).unwrap();
    assert_eq!(ep2.goals[0].radius, 3.0);
}

fn coarse_episode(id: u64) -> Episode {
    let mut ep: Episode = serde_json::from_str(VLNCE_EPISODE).unwrap();
    ep.episode_id = id;
    ep.scene_id = "home_0007".into();
    ep.instruction.instruction_tokens = None;
    ep.task = Task::Coarse;
    ep.instruction.style = Some(Style::Casual);
    ep.instruction.grounding = vec![GroundedObject {
        object_id: 17,
        class: "lamp".into(),
        role: Role::Target,
        side: Some(Side::Left),
        path_index: Some(2),
    }];
    ep.target_object_id = Some(17);
    ep.goals[0].object_id = Some(17);
    ep.info
        .extra
        .insert("rooms".into(), serde_json::json!(["hall", "bathroom"]));
    ep
}

#[test]
fn our_episodes_keep_every_vlnce_key() {
    let v = serde_json::to_value(coarse_episode(1)).unwrap();
    for key in [
        "episode_id",
        "trajectory_id",
        "scene_id",
        "start_position",
        "start_rotation",
        "goals",
        "instruction",
        "reference_path",
        "info",
    ] {
        assert!(v.get(key).is_some(), "missing VLN-CE key {key}");
    }
    assert!(v["instruction"]["instruction_text"].is_string());
    assert!(v["info"]["geodesic_distance"].is_number());
    assert_eq!(v["goals"][0]["radius"], 3.0);
    assert_eq!(v["task"], "coarse");
    assert_eq!(v["instruction"]["style"], "casual");
    assert_eq!(v["instruction"]["grounding"][0]["side"], "left");
    assert_eq!(v["info"]["rooms"][1], "bathroom");
    // Empty additions stay out of the file.
    assert!(v.get("sub_goals").is_none() && v.get("reference_image").is_none());
    assert!(v["instruction"].get("instruction_tokens").is_none());
}

#[test]
fn split_files_round_trip_with_deterministic_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let eps: Vec<Episode> = (0..5).map(coarse_episode).collect();
    let path = write_split(dir.path(), Task::Coarse, Split::ValUnseen, &eps).unwrap();
    assert_eq!(
        path,
        dir.path().join("coarse/val_unseen/val_unseen.json.gz")
    );
    assert_eq!(path, split_path(dir.path(), Task::Coarse, Split::ValUnseen));
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..2], &[0x1f, 0x8b]);
    assert_eq!(
        &bytes[4..8],
        &[0, 0, 0, 0],
        "no timestamp in the gzip header"
    );
    assert_eq!(
        bytes,
        to_gzip_bytes(&eps).unwrap(),
        "same episodes, same bytes"
    );
    write_split(dir.path(), Task::Coarse, Split::ValUnseen, &eps).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
    let back = read_split(dir.path(), Task::Coarse, Split::ValUnseen).unwrap();
    assert_eq!(back, eps);
    // No temporary files left behind.
    let names: Vec<_> = std::fs::read_dir(path.parent().unwrap()).unwrap().collect();
    assert_eq!(names.len(), 1);
}

#[test]
fn malformed_split_names_file_episode_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let good = serde_json::to_value(coarse_episode(1)).unwrap();
    let mut bad = serde_json::to_value(coarse_episode(2)).unwrap();
    bad["start_position"] = serde_json::json!([1.0, 2.0]);
    let file = dir.path().join("bad.json");
    std::fs::write(
        &file,
        serde_json::json!({ "episodes": [good, bad] }).to_string(),
    )
    .unwrap();
    let err = read_file(&file).unwrap_err().to_string();
    assert!(err.contains("bad.json"), "{err}");
    assert!(
        err.contains("episodes[1]") && err.contains("episode_id 2"),
        "{err}"
    );
    assert!(err.contains("start_position"), "{err}");

    let mut bad_style = serde_json::to_value(coarse_episode(3)).unwrap();
    bad_style["instruction"]["style"] = serde_json::json!("poetic");
    std::fs::write(
        &file,
        serde_json::json!({ "episodes": [bad_style] }).to_string(),
    )
    .unwrap();
    let err = read_file(&file).unwrap_err().to_string();
    assert!(
        err.contains("instruction") && err.contains("poetic"),
        "{err}"
    );

    let missing = read_split(dir.path(), Task::Fine, Split::Test).unwrap_err();
    assert!(matches!(missing, DataError::Io { .. }));
    assert!(missing.to_string().contains("fine/test/test.json.gz"));
}

#[test]
fn task_and_split_names_parse_back() {
    for t in Task::ALL {
        assert_eq!(t.name().parse::<Task>().unwrap(), t);
        assert_eq!(serde_json::to_value(t).unwrap(), t.name());
    }
    for s in Split::ALL {
        assert_eq!(s.name().parse::<Split>().unwrap(), s);
        assert_eq!(serde_json::to_value(s).unwrap(), s.name());
    }
    let err = "valseen".parse::<Split>().unwrap_err().to_string();
    assert!(err.contains("valseen") && err.contains("val_seen"), "{err}");
}

#[test]
fn jsonl_trajectories_with_defaults() {
    let text = r#"{"episode_id": 3, "positions": [[0,0,0],[0.25,0,0],[0.5,0,0]], "stopped": true}

{"episode_id": "4", "positions": [[1,0,1]], "stopped": false, "collisions": 2, "steps": 9, "headings": [0.5]}
"#;
    let ts = parse_trajectories(Path::new("t.jsonl"), text).unwrap();
    assert_eq!(ts.len(), 2);
    assert_eq!((ts[0].episode_id, ts[0].steps, ts[0].collisions), (3, 2, 0));
    assert!(ts[0].stopped && ts[0].headings.is_none());
    assert_eq!((ts[1].episode_id, ts[1].steps, ts[1].collisions), (4, 9, 2));
    assert_eq!(ts[1].headings, Some(vec![0.5]));
}

#[test]
fn malformed_trajectory_line_is_named() {
    let text = concat!(
        r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": true}"#,
        "\n",
        r#"{"episode_id": 2, "positions": [[0,0,0]], "stopped": true}"#,
        "\n",
        r#"{"episode_id": 3, "positions": [[0,0]], "stopped": true}"#,
        "\n",
    );
    let err = parse_trajectories(Path::new("runs/robot.jsonl"), text)
        .unwrap_err()
        .to_string();
    assert!(err.contains("runs/robot.jsonl"), "{err}");
    assert!(err.contains("line 3"), "{err}");
    assert!(err.contains("`positions`"), "{err}");

    let cases = [
        (
            r#"{"positions": [[0,0,0]], "stopped": true}"#,
            "`episode_id`",
        ),
        (r#"{"episode_id": 1, "positions": [[0,0,0]]}"#, "`stopped`"),
        (
            r#"{"episode_id": -1, "positions": [[0,0,0]], "stopped": true}"#,
            "`episode_id`",
        ),
        (
            r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": "yes"}"#,
            "`stopped`",
        ),
        (
            r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": true, "stops": [4]}"#,
            "`stops`",
        ),
        (
            r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": true, "headings": [1, 2]}"#,
            "`headings`",
        ),
        (
            r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": true, "collisions": 1.5}"#,
            "`collisions`",
        ),
        (
            r#"{"episode_id": 1, "positions": [[0,0,0]], "stopped": true"#,
            "line 1",
        ),
        (r#"[1, 2]"#, "line 1"),
    ];
    for (line, needle) in cases {
        let err = parse_trajectories(Path::new("x.jsonl"), line)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(needle) && err.contains("line 1"),
            "{line}: {err}"
        );
    }
}

#[test]
fn vlnce_inference_format_is_read() {
    let text = r#"{
      "12": [{"position": [0, 0, 0], "heading": 0.0, "stop": false},
             {"position": [0.25, 0, 0], "heading": 0.0, "stop": false},
             {"position": [0.25, 0, 0], "heading": 0.26, "stop": true}],
      "3": [{"position": [1, 0, 1], "heading": 1.0, "stop": false}]
    }"#;
    let ts = parse_trajectories(Path::new("inference.json"), text).unwrap();
    let ids: Vec<u64> = ts.iter().map(|t| t.episode_id).collect();
    assert_eq!(ids, [3, 12], "sorted by episode id");
    let t = &ts[1];
    assert!(t.stopped && t.steps == 2 && t.collisions == 0);
    assert_eq!(t.positions.len(), 3);
    assert_eq!(t.headings.as_deref(), Some(&[0.0, 0.0, 0.26][..]));
    assert!(!ts[0].stopped);

    let bad = r#"{"12": [{"heading": 0.0, "stop": true}]}"#;
    let err = parse_trajectories(Path::new("inference.json"), bad)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("inference.json") && err.contains("episode `12`"),
        "{err}"
    );
    assert!(err.contains("position"), "{err}");
}

#[test]
fn jsonl_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let mut a = Trajectory::from_positions(7, vec![[0.0, 0.0, 0.0], [0.25, 0.0, 0.0]], true);
    a.headings = Some(vec![0.0, 0.1]);
    a.collisions = 1;
    a.stops = vec![1];
    a.actions = Some(vec!["move_forward".into(), "stop".into()]);
    let b = Trajectory::from_positions(8, vec![[1.0, 0.0, 0.5]], false);
    let path = dir.path().join("trajectories.jsonl");
    write_jsonl(&path, &[a.clone(), b.clone()]).unwrap();
    assert_eq!(read_trajectories(&path).unwrap(), vec![a, b]);
}
