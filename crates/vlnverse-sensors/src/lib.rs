#![doc = include_str!("../README.md")]

pub mod bvh;
pub mod camera;
pub mod config;
pub mod demo;
pub mod error;
pub mod frame;
#[cfg(feature = "wgpu")]
pub mod gpu;
pub mod lidar;
pub mod noise;
pub mod output;
pub mod raster;
pub mod raycast;
pub mod renderer;
pub mod rig;
pub mod scene_mesh;
pub mod shading;

pub use camera::{Camera, Frustum, Mount};
pub use config::{
    Backend, CameraSpec, LidarSpec, Noise, PanoramaSpec, Rate, RigConfig, SensorSpec, StateSpec,
};
pub use error::{Result, SensorError};
pub use frame::{Channels, Frame, Intrinsics, View};
#[cfg(feature = "wgpu")]
pub use gpu::{shared_context, GpuContext, GpuRenderer};
pub use lidar::LidarScan;
pub use raster::{RasterRenderer, RasterScene, SCENE_CACHE_MB, SCENE_CACHE_MB_VAR};
pub use raycast::{Hit, RaycastRenderer, SceneRaycaster};
pub use renderer::{create_renderer, Renderer};
pub use rig::{AgentState, CollisionInfo, Observation, Observations, SensorRig};
pub use scene_mesh::SceneMesh;
