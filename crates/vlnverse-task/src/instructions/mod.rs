//! Instruction generation: the [`InstructionGenerator`] swap point.
//!
//! The default generator is deterministic and template-based, grounded in the scene graph; an
//! optional LLM-backed stage implements the same trait.

use crate::episode::{Instruction, Style};
use crate::error::Result;
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{ObjectId, Scene};

/// Everything an instruction generator may look at for one trajectory.
#[derive(Clone, Copy)]
pub struct PathContext<'a> {
    /// The scene the path lies in.
    pub scene: &'a Scene,
    /// Its scene graph.
    pub graph: &'a SceneGraph,
    /// The navigable map (line of sight for landmark visibility).
    pub navigable: &'a GridMap,
    /// Reference path from the start to the goal (waypoints on the floor).
    pub path: &'a [[f32; 3]],
    /// Heading of the agent at the start (radians, yaw 0 looks along -Z).
    pub start_yaw: f32,
}

/// Turns a trajectory into natural-language instructions with grounding metadata.
///
/// Implementations are deterministic: the same context and seed give the same text.
pub trait InstructionGenerator: Send + Sync {
    /// A fine-grained, step-by-step instruction following `ctx.path` (landmarks, their side,
    /// action verbs, the end point).
    fn fine(&self, ctx: &PathContext<'_>, seed: u64) -> Result<Instruction>;

    /// A coarse-grained goal description of `target` (class, attribute, relation to a reference
    /// object or room, unique within the scene) in one style.
    fn coarse(
        &self,
        ctx: &PathContext<'_>,
        target: ObjectId,
        style: Style,
        seed: u64,
    ) -> Result<Instruction>;

    /// One long-horizon instruction chaining coarse sub-instructions in order.
    fn chain(&self, parts: &[Instruction], seed: u64) -> Result<Instruction>;
}
