//! Test homes and paths from `vlnverse-testkit`, as the instruction generator's `PathContext`.
#![allow(dead_code)]

use vlnverse_instructions::PathContext;
pub use vlnverse_testkit::homes::{paths, worlds, Sample, World};
pub use vlnverse_testkit::llm_stub::{stub, Seen};

/// The generator's view of a sample path in a test home.
pub trait Ctx {
    /// The context of sample `s` in this home.
    fn ctx<'a>(&'a self, s: &'a Sample) -> PathContext<'a>;
}

impl Ctx for World {
    fn ctx<'a>(&'a self, s: &'a Sample) -> PathContext<'a> {
        PathContext {
            scene: &self.scene,
            graph: &self.graph,
            navigable: &self.maps.navigable,
            path: &s.path,
            start_yaw: s.start_yaw,
            whole_home: None,
        }
    }
}
