#![doc = include_str!("../README.md")]

pub mod action;
pub mod config;
pub mod error;
pub mod physics_cache;
pub mod rapier_sim;
pub mod simulator;
pub mod vec_sim;
pub mod world;

pub use action::{Action, WaypointMode};
pub use config::{
    ActuationNoise, AgentConfig, AgentShape, CollisionSetting, DifferentialDrive, SimConfig,
};
pub use error::{Result, SimError};
pub use physics_cache::PhysicsCache;
pub use rapier_sim::{RapierSimulator, RapierSnapshot};
pub use simulator::{Failure, Hop, Simulator, StepOutcome};
pub use vec_sim::VecSimulator;
pub use world::PhysicsScene;
