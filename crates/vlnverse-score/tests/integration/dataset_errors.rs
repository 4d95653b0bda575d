//! Split files that are not what they claim: errors say what is wrong in words a user acts on.

use vlnverse_score::dataset::{read_file, to_gzip_bytes};
use vlnverse_score::Episode;

fn episode(id: u64) -> Episode {
    Episode {
        episode_id: id,
        scene_id: "home".into(),
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

/// The plain JSON of a split (what the gzip holds).
fn flate2_free_json(episodes: &[Episode]) -> Vec<u8> {
    serde_json::to_vec(&vlnverse_score::Dataset {
        episodes: episodes.to_vec(),
    })
    .unwrap()
}
