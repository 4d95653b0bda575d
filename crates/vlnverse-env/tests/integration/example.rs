//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/scene_maps.rs"]
mod scene_maps;

#[test]
fn the_scene_maps_example_runs() {
    #[allow(unused_variables)]
    let dir = tempfile::tempdir().unwrap();
    let len = scene_maps::run(Some(dir.path().to_path_buf())).unwrap();
    assert!(len > 1.0, "{len}");
}
