//! Shared helpers of the integration tests.
#![allow(dead_code)]

use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{GpuRenderer, SensorError};

/// The shared wgpu renderer, or None (with a skip message) when no adapter exists and
/// `VLNVERSE_REQUIRE_GPU_BACKEND` is not set; with it set, a missing adapter fails the test.
pub fn gpu(test: &str) -> Option<GpuRenderer> {
    match GpuRenderer::new() {
        Ok(r) => Some(r),
        Err(e @ SensorError::NoAdapter(_)) => {
            if std::env::var_os("VLNVERSE_REQUIRE_GPU_BACKEND").is_some() {
                panic!("{test}: VLNVERSE_REQUIRE_GPU_BACKEND is set but {e}");
            }
            eprintln!("skipping the wgpu part of {test}: {e}");
            None
        }
        Err(e) => panic!("{test}: {e}"),
    }
}

/// Random agent base poses in free space: the camera (at `cam_height`) is at least `clearance`
/// away from every object's box.
pub fn free_poses(
    scene: &Scene,
    n: usize,
    seed: u64,
    cam_height: f32,
    clearance: f32,
) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let b = scene.bounds();
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < n {
        tries += 1;
        assert!(tries < 100_000, "no free pose found");
        let p = Vec3::new(
            rng.random_range(b.min[0]..b.max[0]),
            scene.floor_height,
            rng.random_range(b.min[2]..b.max[2]),
        );
        let cam = p + Vec3::Y * cam_height;
        let inside_some = scene.objects.iter().any(|o| {
            let (lo, hi) = (o.bbox.min_v() - clearance, o.bbox.max_v() + clearance);
            cam.cmpge(lo).all() && cam.cmple(hi).all()
        });
        // Inside the house: the floor is below and the ceiling above.
        let in_house = scene.room_at(p.x, p.z).is_some();
        if !inside_some && in_house {
            out.push(Pose::from_yaw(
                p,
                rng.random_range(-std::f32::consts::PI..std::f32::consts::PI),
            ));
        }
    }
    out
}
