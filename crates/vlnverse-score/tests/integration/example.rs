//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/score_trajectory.rs"]
mod score_trajectory;

#[test]
fn the_score_trajectory_example_runs() {
    #[allow(unused_variables)]
    let dir = tempfile::tempdir().unwrap();
    let sr = score_trajectory::run().unwrap();
    assert_eq!(sr, 0.5);
}
