//! Scene listings skip dot-entries (an interrupted writer's temporary folders), the leftovers
//! of interrupted writers are recognised and removed, and a GLB accessor out of range is named.

use vlnverse_env::io::glb::read_glb_bytes;
use vlnverse_env::io::{is_temp_leftover, list_scene_dirs, remove_temp_leftovers, write_scene_dir};

use super::io_common::fixture_scene;

#[test]
fn a_scene_listing_ignores_dot_folders() {
    let d = tempfile::tempdir().unwrap();
    let scene = fixture_scene();
    let dir = write_scene_dir(d.path(), &scene, &[]).unwrap();
    // A killed writer's temporary folder holds a scene.json too.
    let tmp = d.path().join(format!(".{}.tmp-4242", scene.id));
    std::fs::create_dir(&tmp).unwrap();
    std::fs::copy(dir.join("scene.json"), tmp.join("scene.json")).unwrap();
    std::fs::write(d.path().join(".lock"), b"").unwrap();
    assert_eq!(list_scene_dirs(d.path()).unwrap(), vec![dir.clone()]);
    let removed = remove_temp_leftovers(d.path()).unwrap();
    assert_eq!(removed, vec![tmp.clone()]);
    assert!(!tmp.exists() && dir.is_dir());
    // Not a temp entry: the lock file stays.
    assert!(d.path().join(".lock").is_file());
}

#[test]
fn temp_leftover_names() {
    for n in [
        ".home_0013.tmp-123",
        ".1939.png.tmp77",
        ".train.json.gz.tmp-5",
        "1939.png.link99",
        ".1939.png.link99",
    ] {
        assert!(is_temp_leftover(n), "{n}");
    }
    for n in [
        ".lock",
        ".tmp-12",
        "home_0013",
        ".home.tmp-",
        "scene.json",
        ".gitignore",
        ".png.link3",
        "a.tmp-3",
    ] {
        assert!(!is_temp_leftover(n), "{n}");
    }
}

/// A GLB with one triangle mesh whose POSITION accessor claims `count` vertices of a 36-byte
/// buffer (3 vertices).
pub fn glb_with_position_count(count: usize) -> Vec<u8> {
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],"buffers":[{{"byteLength":36}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":{count},"type":"VEC3","min":[0,0,0],"max":[1,1,1]}}]}}"#
    );
    let bin: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    vlnverse_env::io::glb::glb_container(json.as_bytes(), &bin)
}

#[test]
fn an_out_of_range_accessor_is_named_with_its_mesh_and_primitive() {
    let path = std::path::Path::new("bad.glb");
    let ok = read_glb_bytes(&glb_with_position_count(3), path).unwrap();
    assert_eq!(ok.meshes[0].positions.len(), 3);
    let e = read_glb_bytes(&glb_with_position_count(30), path)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bad.glb")
            && e.contains("mesh 0 primitive 0")
            && e.contains("POSITION")
            && e.contains("accessor 0 is out of range")
            && e.contains("buffer 0, which holds 36 bytes"),
        "{e}"
    );
}
