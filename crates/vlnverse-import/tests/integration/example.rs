//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/import_glb.rs"]
mod import_glb;

#[test]
fn the_import_glb_example_runs() {
    #[allow(unused_variables)]
    let dir = tempfile::tempdir().unwrap();
    let objects = import_glb::run(None).unwrap();
    assert!(objects > 10, "{objects}");
}
