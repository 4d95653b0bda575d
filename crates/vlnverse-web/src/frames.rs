//! Pictures sent to the page: the first-person view (RGB, or depth as a grey ramp) encoded as
//! JPEG, and top-down maps with paths encoded as PNG.

use std::io::Cursor;

use glam::{Vec2, Vec3};
use image::codecs::jpeg::JpegEncoder;
use image::{ExtendedColorType, RgbImage};
use vlnverse_env::occupancy::GridMap;
use vlnverse_env::topdown::{render_topdown, TopdownOptions, WorldToPixel};
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{AgentState, Observation, Observations, SensorRig};
use vlnverse_task::Episode;

use crate::error::{ApiError, ApiResult};

/// Which image of the first-person view the page shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ViewKind {
    /// Colour.
    #[default]
    Rgb,
    /// Depth, near bright, far (10 m and beyond) dark.
    Depth,
}

/// Depth (m) shown as black.
const DEPTH_FAR_M: f32 = 10.0;

/// The RGB or depth image of `obs` as `(width, height, rgb bytes)`; `None` when the rig has no
/// such sensor.
pub fn view_pixels(obs: &Observations, kind: ViewKind) -> Option<(u32, u32, Vec<u8>)> {
    for o in obs.values() {
        match (o, kind) {
            (Observation::Rgb(f), ViewKind::Rgb) if !f.rgb.is_empty() => {
                return Some((f.width, f.height, f.rgb.clone()));
            }
            (Observation::Depth(f), ViewKind::Depth) if !f.depth.is_empty() => {
                // Normalised depth is already in [0, 1]; metric depth is scaled to 10 m.
                let max = f.depth.iter().copied().fold(0.0f32, f32::max);
                let scale = if max <= 1.0 { 1.0 } else { DEPTH_FAR_M };
                let rgb = f
                    .depth
                    .iter()
                    .flat_map(|&d| {
                        let t = if d.is_finite() {
                            (d / scale).clamp(0.0, 1.0)
                        } else {
                            1.0
                        };
                        let v = (255.0 * (1.0 - t)).round() as u8;
                        [v, v, v]
                    })
                    .collect();
                return Some((f.width, f.height, rgb));
            }
            _ => {}
        }
    }
    None
}

/// JPEG bytes of an RGB image (quality 1..=100).
pub fn jpeg(width: u32, height: u32, rgb: &[u8], quality: u8) -> ApiResult<Vec<u8>> {
    let mut out = Vec::with_capacity(rgb.len() / 8);
    JpegEncoder::new_with_quality(&mut out, quality.clamp(1, 100))
        .encode(rgb, width, height, ExtendedColorType::Rgb8)
        .map_err(|e| {
            ApiError::internal(format!("JPEG encoding of a {width}x{height} view: {e}"))
        })?;
    Ok(out)
}

/// PNG bytes of an image.
pub fn png(img: &RgbImage) -> ApiResult<Vec<u8>> {
    let mut out = Vec::new();
    img.write_to(&mut Cursor::new(&mut out), image::ImageFormat::Png)
        .map_err(|e| ApiError::internal(format!("PNG encoding: {e}")))?;
    Ok(out)
}

/// Render the view of `rig` standing at `position` with `yaw` in `scene` (loaded into the rig
/// when it shows another scene) and encode it as JPEG.
pub fn render_view(
    rig: &mut SensorRig,
    scene: &Scene,
    position: [f32; 3],
    yaw: f32,
    kind: ViewKind,
    quality: u8,
) -> ApiResult<Vec<u8>> {
    if rig.scene_id() != Some(scene.id.as_str()) {
        rig.set_scene(scene)
            .map_err(|e| ApiError::internal(format!("scene `{}`: {e}", scene.id)))?;
    }
    let pose = Pose::from_yaw(Vec3::from_array(position), yaw);
    rig.reset(pose);
    let obs = rig
        .observe(&AgentState::at(Vec3::from_array(position), yaw))
        .map_err(|e| ApiError::internal(format!("rendering scene `{}`: {e}", scene.id)))?;
    let (w, h, px) = view_pixels(&obs, kind)
        .ok_or_else(|| ApiError::bad_request(format!("the sensor rig has no {kind:?} camera")))?;
    jpeg(w, h, &px, quality)
}

/// Yaw (radians) of an agent looking from `from` toward `to` (floor points `(x, z)`).
pub fn yaw_towards(from: [f32; 3], to: [f32; 3]) -> f32 {
    let d = Vec2::new(to[0] - from[0], to[2] - from[2]);
    if d.length_squared() < 1e-8 {
        0.0
    } else {
        (-d.x).atan2(-d.y)
    }
}

/// A top-down map of an episode: the scene from above, the reference path in green, start
/// (white) and goals (green), and the agent's path in blue when given. Returns the image and
/// its world -> pixel mapping (the page draws the current step on top).
pub fn episode_topdown(
    scene: &Scene,
    navigable: Option<&GridMap>,
    ep: &Episode,
    agent: Option<&[[f32; 3]]>,
) -> (RgbImage, WorldToPixel) {
    let opts = TopdownOptions {
        px_per_m: 40.0,
        max_size: 900,
        labels: false,
        legend: false,
        title: format!("{} - episode {}", ep.scene_id, ep.episode_id),
        ..Default::default()
    };
    let mut td = render_topdown(scene, navigable, &opts);
    let floor = |p: &[f32; 3]| Vec2::new(p[0], p[2]);
    let reference: Vec<Vec2> = ep.reference_path.iter().map(floor).collect();
    td.draw_path(&reference, [40, 170, 60], 4.0);
    if let Some(path) = agent {
        let pts: Vec<Vec2> = path.iter().map(floor).collect();
        td.draw_path(&pts, [30, 90, 220], 2.5);
    }
    td.draw_marker(floor(&ep.start_position), [255, 255, 255], 5.0);
    for g in ep.goal_sequence() {
        td.draw_marker(floor(&g.position), [40, 170, 60], 5.0);
    }
    (td.image, td.frame)
}

/// The world -> pixel mapping as JSON for the page.
pub fn frame_json(f: &WorldToPixel) -> serde_json::Value {
    serde_json::json!({
        "world_min": [f.world_min.x, f.world_min.y],
        "origin_px": [f.origin_px.x, f.origin_px.y],
        "px_per_m": f.px_per_m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaw_towards_matches_the_convention() {
        // Yaw 0 looks along -Z; yaw grows counter-clockwise seen from above (toward -X).
        assert!(yaw_towards([0.0; 3], [0.0, 0.0, -1.0]).abs() < 1e-6);
        let left = yaw_towards([0.0; 3], [-1.0, 0.0, 0.0]);
        assert!((left - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        let p = Pose::from_yaw(Vec3::ZERO, left);
        assert!((p.yaw() - left).abs() < 1e-5);
    }

    #[test]
    fn depth_becomes_a_grey_ramp() {
        let mut obs = Observations::new();
        let f = vlnverse_sensors::Frame {
            width: 2,
            height: 1,
            depth: vec![0.0, 20.0],
            ..Default::default()
        };
        obs.insert("depth".into(), Observation::Depth(f));
        let (w, h, px) = view_pixels(&obs, ViewKind::Depth).unwrap();
        assert_eq!((w, h), (2, 1));
        assert_eq!(px, vec![255, 255, 255, 0, 0, 0]);
        assert!(view_pixels(&obs, ViewKind::Rgb).is_none());
    }
}
