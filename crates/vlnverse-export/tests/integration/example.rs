//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/export_tiny.rs"]
mod export_tiny;

#[test]
fn the_export_example_runs() {
    let out = tempfile::tempdir().unwrap();
    let s = export_tiny::run(
        super::support::tiny().to_path_buf(),
        out.path().join("ds"),
        1,
    )
    .unwrap();
    assert_eq!(s.episodes, 1);
    assert!(s.frames >= 2, "an episode has at least a move and a STOP");
    assert!(out.path().join("ds/meta/info.json").is_file());
}
