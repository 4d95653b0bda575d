//! The swap point of the simulator layer: anything that can put an agent in a [`Scene`] and
//! move it under [`Action`]s.

use crate::{Action, Result};
use serde::{Deserialize, Serialize};
use vlnverse_env::{ObjectId, Pose, Scene};

/// Why an episode ended failed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Failure {
    /// Strict setting: a noticeable collision with these objects.
    Collision {
        /// Objects hit (ids, ascending).
        hit: Vec<ObjectId>,
    },
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Collision { hit } if hit.is_empty() => f.write_str("noticeable collision"),
            Failure::Collision { hit } => write!(f, "noticeable collision with objects {hit:?}"),
        }
    }
}

/// Result of a Tel-Hop (waypoint hop, or any move in the Tel-Hop setting).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Hop {
    /// Landed on the commanded spot, or `shift` metres from it (nearest free spot).
    Landed {
        /// Distance from the commanded spot to where the agent landed (m).
        shift: f32,
    },
    /// No free spot within `radius` of the commanded spot: the agent did not move.
    NoFreeSpot {
        /// Search radius (m).
        radius: f32,
    },
    /// The hop would pass through a closed door (agents cannot open doors yet): the agent did
    /// not move.
    ClosedDoor {
        /// Id of the door in the scene's `doors`.
        door: u32,
    },
}

/// What one [`Simulator::step`] did. Displacements are horizontal `[dx, dz]` in metres.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepOutcome {
    /// Agent base pose after the action (feet on the floor, yaw only).
    pub pose: Pose,
    /// The agent touched something during the action.
    pub collided: bool,
    /// `|commanded - achieved| > collision_threshold`: count these for the collision rate.
    pub noticeable: bool,
    /// Objects touched (ids, ascending, no duplicates).
    pub hit: Vec<ObjectId>,
    /// Horizontal displacement the action asked for.
    pub commanded: [f32; 2],
    /// Horizontal displacement that happened.
    pub achieved: [f32; 2],
    /// Outcome of a hop, for hops.
    pub hop: Option<Hop>,
    /// The episode is over (Stop, or a failure).
    pub done: bool,
    /// Why the episode failed, if it did.
    pub failure: Option<Failure>,
}

/// An embodied agent in a physics world.
///
/// Implementations must be deterministic (same scene, start and actions give bit-identical
/// poses) and `Send`, so that batches run on a thread pool ([`crate::VecSimulator`]).
///
/// ```
/// use vlnverse_sim::{Action, RapierSimulator, SimConfig, Simulator};
/// use vlnverse_env::{Pose, Scene};
///
/// /// Run actions until the episode ends; return the final pose.
/// fn run<S: Simulator>(sim: &mut S, scene: &Scene, start: Pose, actions: &[Action]) -> Pose {
///     sim.reset(scene, start).unwrap();
///     for a in actions {
///         if sim.step(*a).unwrap().done {
///             break;
///         }
///     }
///     sim.pose()
/// }
///
/// let scene = Scene { format_version: 1, id: "empty".into(), source: "doc".into(), seed: None,
///     floor_height: 0.0, rooms: vec![], doors: vec![], objects: vec![],
///     storeys: Default::default() };
/// let mut sim = RapierSimulator::new(SimConfig::default()).unwrap();
/// let end = run(&mut sim, &scene, Pose::IDENTITY, &[Action::MoveForward(1.0), Action::Stop]);
/// assert!((end.position[2] + 1.0).abs() < 1e-5); // yaw 0 looks along -Z
/// ```
pub trait Simulator: Send {
    /// What this simulator is, for logs and a run's `run.json` (`"rapier"`; a wrapper says
    /// what it wraps: `"noisy(rapier)"`). A resume of a run made with another name is refused.
    fn name(&self) -> String;

    /// Start an episode in `scene` with the agent at `start` (its yaw is used; the
    /// position's y is the floor the agent stands on). Returns the start pose.
    ///
    /// Called once per episode: whatever a backend builds from a scene (Rapier: its static
    /// colliders) it keeps and shares itself, keyed by the scene's content, so that episodes
    /// in a scene seen before start without rebuilding it.
    fn reset(&mut self, scene: &Scene, start: Pose) -> Result<Pose>;

    /// Apply one action. Invalid actions give an error and change nothing.
    fn step(&mut self, action: Action) -> Result<StepOutcome>;

    /// Current agent base pose.
    fn pose(&self) -> Pose;

    /// Current camera pose: the base pose raised to the sensor height and pitched by
    /// `LookUp` / `LookDown`.
    fn camera_pose(&self) -> Pose;
}
