//! Reference images of the visual-reference task: an RGB view from the goal point facing the
//! target, rendered with the sensors crate's CPU rasteriser (runs anywhere, deterministic; it
//! agrees per pixel with the ray caster and is ~50x faster) and encoded as PNG.

use std::sync::Arc;

use glam::{Quat, Vec2, Vec3};
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{Camera, Channels, RasterScene, SceneMesh, View};

use super::presets::ImageConfig;
use vlnverse_score::{DataError, Result};

/// Near clipping distance of the reference camera (m).
const NEAR: f32 = 0.05;
/// Far clipping distance of the reference camera (m), the paper's depth range.
const FAR: f32 = 10.0;
/// Steepest camera pitch towards a target (radians, 50 degrees).
pub const MAX_PITCH: f32 = 0.87;

/// Renders reference images in one scene.
pub struct ReferenceRenderer {
    raster: RasterScene,
    floor: f32,
    cfg: ImageConfig,
}

impl ReferenceRenderer {
    /// Prepare a scene for rendering.
    pub fn new(scene: &Scene, cfg: &ImageConfig) -> Result<Self> {
        let err = |e: vlnverse_sensors::SensorError| {
            DataError::invalid("scene", &scene.id, format!("cannot render: {e}"))
        };
        let mesh = SceneMesh::new(scene).map_err(err)?;
        let raster = RasterScene::new(Arc::new(mesh));
        Ok(ReferenceRenderer {
            raster,
            floor: scene.floor_height,
            cfg: *cfg,
        })
    }

    /// RGB pixels (row-major, top row first) seen from `goal` `(x, z)` at `yaw`, the camera
    /// pitched by `pitch` (radians, positive looks up).
    pub fn render_rgb(&self, goal: Vec2, yaw: f32, pitch: f32) -> Vec<u8> {
        self.render_rgb_on(self.floor, goal, yaw, pitch)
    }

    /// [`ReferenceRenderer::render_rgb`] standing on the floor at height `floor` (a level of a
    /// home on several floors).
    pub fn render_rgb_on(&self, floor: f32, goal: Vec2, yaw: f32, pitch: f32) -> Vec<u8> {
        let position = Vec3::new(goal.x, floor + self.cfg.camera_height, goal.y);
        let rotation = Quat::from_rotation_y(yaw) * Quat::from_rotation_x(pitch);
        let pose = Pose {
            position: position.to_array(),
            rotation: rotation.to_array(),
        };
        let camera = Camera::new(
            &pose,
            self.cfg.width,
            self.cfg.height,
            self.cfg.hfov_deg.to_radians(),
            NEAR,
            FAR,
        );
        // One band: generation already runs scenes in parallel.
        self.raster
            .render_view(
                &View {
                    camera,
                    channels: Channels::RGB,
                },
                1,
            )
            .rgb
    }

    /// PNG bytes of the view from `goal` facing `target` (a 3-D point, e.g. the centre of the
    /// target object's box): turned towards it and pitched towards it within
    /// [-`MAX_PITCH`, `MAX_PITCH`].
    pub fn render_png(&self, goal: Vec2, target: Vec3) -> Result<Vec<u8>> {
        self.render_png_on(self.floor, goal, target)
    }

    /// [`ReferenceRenderer::render_png`] standing on the floor at height `floor`.
    pub fn render_png_on(&self, floor: f32, goal: Vec2, target: Vec3) -> Result<Vec<u8>> {
        let (yaw, pitch) = self.aim_on(floor, goal, target);
        let rgb = self.render_rgb_on(floor, goal, yaw, pitch);
        encode_png(&rgb, self.cfg.width, self.cfg.height)
    }

    /// Yaw and pitch that look from the camera above `goal` at `target`.
    pub fn aim(&self, goal: Vec2, target: Vec3) -> (f32, f32) {
        self.aim_on(self.floor, goal, target)
    }

    /// [`ReferenceRenderer::aim`] from a camera standing on the floor at height `floor`.
    pub fn aim_on(&self, floor: f32, goal: Vec2, target: Vec3) -> (f32, f32) {
        let flat = Vec2::new(target.x, target.z) - goal;
        let yaw = if flat.length_squared() > 1e-10 {
            vlnverse_env::scene_graph::yaw_from_direction(flat)
        } else {
            0.0
        };
        let dy = target.y - (floor + self.cfg.camera_height);
        let pitch = dy
            .atan2(flat.length().max(0.05))
            .clamp(-MAX_PITCH, MAX_PITCH);
        (yaw, pitch)
    }
}

/// Encode RGB8 pixels as PNG (fixed settings, so the same pixels give the same bytes).
pub fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>> {
    let mut out = Vec::with_capacity(rgb.len() / 2);
    PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Sub)
        .write_image(rgb, width, height, ExtendedColorType::Rgb8)
        .map_err(|e| DataError::invalid("image", format!("{width}x{height}"), e.to_string()))?;
    Ok(out)
}
