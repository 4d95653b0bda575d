//! The crate's example runs (it is part of the docs: it must not rot).

#[path = "../../examples/custom_agent.rs"]
mod custom_agent;

#[test]
fn the_custom_agent_example_runs() {
    #[allow(unused_variables)]
    let dir = tempfile::tempdir().unwrap();
    let sr = custom_agent::run(Some(dir.path().to_path_buf())).unwrap();
    assert_eq!(sr, 1.0, "the path follower reaches its goal");
}
