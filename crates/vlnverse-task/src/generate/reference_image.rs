//! Reference images of the visual-reference task: an RGB view from the goal point facing the
//! target, rendered with the sensors crate's CPU ray caster (runs anywhere, deterministic) and
//! encoded as PNG.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{Camera, Channels, SceneMesh, SceneRaycaster, View};

use super::presets::ImageConfig;
use crate::error::{Result, TaskError};

/// Near clipping distance of the reference camera (m).
const NEAR: f32 = 0.05;
/// Far clipping distance of the reference camera (m).
const FAR: f32 = 20.0;

/// Renders reference images in one scene.
pub struct ReferenceRenderer {
    raycaster: SceneRaycaster,
    floor: f32,
    cfg: ImageConfig,
}

impl ReferenceRenderer {
    /// Build the ray-cast BVH of a scene.
    pub fn new(scene: &Scene, cfg: &ImageConfig) -> Result<Self> {
        let err = |e: vlnverse_sensors::SensorError| {
            TaskError::invalid("scene", &scene.id, format!("cannot render: {e}"))
        };
        let mesh = SceneMesh::new(scene).map_err(err)?;
        let raycaster = SceneRaycaster::new(Arc::new(mesh)).map_err(err)?;
        Ok(ReferenceRenderer {
            raycaster,
            floor: scene.floor_height,
            cfg: *cfg,
        })
    }

    /// RGB pixels (row-major, top row first) seen from `goal` `(x, z)` at `yaw`.
    pub fn render_rgb(&self, goal: Vec2, yaw: f32) -> Vec<u8> {
        let pose = Pose::from_yaw(
            Vec3::new(goal.x, self.floor + self.cfg.camera_height, goal.y),
            yaw,
        );
        let camera = Camera::new(
            &pose,
            self.cfg.width,
            self.cfg.height,
            self.cfg.hfov_deg.to_radians(),
            NEAR,
            FAR,
        );
        self.raycaster
            .render_view(&View {
                camera,
                channels: Channels::RGB,
            })
            .rgb
    }

    /// PNG bytes of the view from `goal` at `yaw`.
    pub fn render_png(&self, goal: Vec2, yaw: f32) -> Result<Vec<u8>> {
        let rgb = self.render_rgb(goal, yaw);
        encode_png(&rgb, self.cfg.width, self.cfg.height)
    }
}

/// Encode RGB8 pixels as PNG (fixed settings, so the same pixels give the same bytes).
pub fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>> {
    let mut out = Vec::with_capacity(rgb.len() / 2);
    PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Sub)
        .write_image(rgb, width, height, ExtendedColorType::Rgb8)
        .map_err(|e| TaskError::invalid("image", format!("{width}x{height}"), e.to_string()))?;
    Ok(out)
}
