//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/drive_fps.rs"]
mod drive_fps;

#[test]
fn the_drive_fps_example_measures_frames_and_memory() {
    let dir = tempfile::tempdir().unwrap();
    crate::support::make_dataset(dir.path(), 2);
    let f = drive_fps::run(
        dir.path(),
        "fine",
        "val_unseen",
        2,
        Some(dir.path().join("protocols")),
    )
    .unwrap();
    assert_eq!(f.drivers, 2);
    assert!(f.frames > 4, "{f:?}");
    assert!(f.fps_alone > 0.0 && f.fps_each_concurrent > 0.0, "{f:?}");
    if cfg!(target_os = "linux") {
        assert!(f.rss_per_driver.is_some());
    }
}
