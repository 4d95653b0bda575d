//! LiDAR scans: rays from the sensor against the scene's triangles.
//!
//! Beam `i` of a ring points at azimuth `-hfov/2 + i * step` in the sensor frame (0 = straight
//! ahead, positive = counter-clockwise seen from above, as yaw), with `step = hfov / beams` for a
//! full circle and `hfov / (beams - 1)` otherwise. Ring `k` has elevation
//! `high - k * (high - low) / (channels - 1)` (ring 0 is the highest; one channel is level).

use crate::camera::Mount;
use crate::config::LidarSpec;
use crate::noise::standard_normal;
use crate::raycast::SceneRaycaster;
use glam::{Quat, Vec3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use vlnverse_env::Pose;

/// One scan: `ranges[k * beams + i]` is ring `k`, beam `i`, metres from the sensor origin.
/// No return within `range_max` (or closer than `range_min`) is `f32::INFINITY`; a dropped
/// return is NaN.
#[derive(Clone, Debug, PartialEq)]
pub struct LidarScan {
    /// Rays per ring.
    pub beams: u32,
    /// Rings.
    pub channels: u32,
    /// Ranges, ring-major.
    pub ranges: Vec<f32>,
    /// World pose of the sensor when the scan was taken.
    pub sensor_pose: Pose,
}

/// Azimuth (radians) of beam `i`.
pub fn beam_azimuth(spec: &LidarSpec, i: u32) -> f32 {
    let fov = spec.hfov_deg.to_radians();
    let step = if spec.hfov_deg >= 360.0 || spec.beams == 1 {
        fov / spec.beams as f32
    } else {
        fov / (spec.beams - 1) as f32
    };
    let start = if spec.beams == 1 { 0.0 } else { -fov * 0.5 };
    start + i as f32 * step
}

/// Elevation (radians) of ring `k`.
pub fn ring_elevation(spec: &LidarSpec, k: u32) -> f32 {
    if spec.channels <= 1 {
        return 0.0;
    }
    let [lo, hi] = spec.elevation_deg.map(f32::to_radians);
    hi - k as f32 * (hi - lo) / (spec.channels - 1) as f32
}

/// Unit direction of ring `k`, beam `i` in the sensor frame (forward = -Z).
pub fn beam_direction(spec: &LidarSpec, k: u32, i: u32) -> Vec3 {
    Quat::from_rotation_y(beam_azimuth(spec, i))
        * Quat::from_rotation_x(ring_elevation(spec, k))
        * Vec3::NEG_Z
}

/// World pose of a sensor mounted on an agent.
pub fn sensor_pose(mount: &Mount, base: &Pose) -> Pose {
    mount.world_pose(base)
}

/// Take an exact scan (no noise), rings in parallel.
pub fn scan(spec: &LidarSpec, base: &Pose, rc: &SceneRaycaster) -> LidarScan {
    let pose = sensor_pose(&spec.mount, base);
    let (o, q) = (pose.translation(), pose.quat());
    let mut ranges = vec![f32::INFINITY; (spec.beams * spec.channels) as usize];
    ranges
        .par_chunks_mut(spec.beams as usize)
        .enumerate()
        .for_each(|(k, ring)| {
            for (i, r) in ring.iter_mut().enumerate() {
                let d = q * beam_direction(spec, k as u32, i as u32);
                if let Some(h) = rc.cast(o, d, spec.range_max) {
                    if h.distance >= spec.range_min {
                        *r = h.distance;
                    }
                }
            }
        });
    LidarScan {
        beams: spec.beams,
        channels: spec.channels,
        ranges,
        sensor_pose: pose,
    }
}

/// Apply range noise and dropout to a scan (returns stay within `[range_min, range_max]`).
pub fn apply_noise(spec: &LidarSpec, scan: &mut LidarScan, rng: &mut ChaCha8Rng) {
    for r in scan.ranges.iter_mut().filter(|r| r.is_finite()) {
        if spec.dropout > 0.0 && rng.random::<f32>() < spec.dropout {
            *r = f32::NAN;
        } else if spec.range_stddev > 0.0 {
            *r = (*r + spec.range_stddev * standard_normal(rng))
                .clamp(spec.range_min, spec.range_max);
        }
    }
}
