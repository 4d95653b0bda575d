//! Set-up shared by the sensor benches (`mod support;` in `render.rs`, `raster.rs` and
//! `real_scene.rs`): seeded agent poses, the paper's RGB-D views and panorama, the backends
//! that start here, thread pools. The AWS small house of `../shared/scenes/` comes from
//! `vlnverse_testkit::real_scenes` (shared with the `vlnverse-import` bench).

// Each bench uses a part of this module.
#![allow(dead_code)]

use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{
    CameraSpec, Channels, GpuRenderer, RasterRenderer, RaycastRenderer, Renderer, View,
};

/// `n` seeded agent poses on the floor of a room, random headings, with the camera (1.25 m up)
/// at least 15 cm outside every object's box.
pub fn floor_poses(scene: &Scene, n: usize, seed: u64) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let b = scene.bounds();
    let mut out = Vec::new();
    for _ in 0..100_000 {
        if out.len() == n {
            break;
        }
        let p = Vec3::new(
            rng.random_range(b.min[0]..b.max[0]),
            scene.floor_height,
            rng.random_range(b.min[2]..b.max[2]),
        );
        let cam = p + Vec3::Y * 1.25;
        let blocked = scene.objects.iter().any(|o| {
            let (lo, hi) = (o.bbox.min_v() - 0.15, o.bbox.max_v() + 0.15);
            cam.cmpge(lo).all() && cam.cmple(hi).all()
        });
        if !blocked && scene.room_at(p.x, p.z).is_some() {
            out.push(Pose::from_yaw(
                p,
                rng.random_range(0.0..std::f32::consts::TAU),
            ));
        }
    }
    assert_eq!(out.len(), n, "scene {} has no free floor", scene.id);
    out
}

/// The paper's observation of one agent pose: RGB 224 (+ semantic) and depth 256.
pub fn rgbd(base: &Pose) -> [View; 2] {
    [
        View {
            camera: CameraSpec::default().camera(base),
            channels: Channels {
                rgb: true,
                semantic: true,
                ..Default::default()
            },
        },
        View {
            camera: CameraSpec::depth().camera(base),
            channels: Channels::DEPTH,
        },
    ]
}

/// A panorama: 12 RGB + depth views of 224x224 at 30 degree yaw steps.
pub fn panorama(base: &Pose) -> Vec<View> {
    let cam = CameraSpec::default().camera(base);
    (0..12)
        .map(|k| View {
            camera: cam.yawed((30.0 * k as f32).to_radians()),
            channels: Channels {
                rgb: true,
                depth: true,
                ..Default::default()
            },
        })
        .collect()
}

/// Every backend that starts here: wgpu when an adapter exists (e.g. lavapipe), the CPU
/// rasteriser and the CPU ray caster.
pub fn backends() -> Vec<Box<dyn Renderer>> {
    let mut v: Vec<Box<dyn Renderer>> = Vec::new();
    match GpuRenderer::new() {
        Ok(g) => {
            eprintln!("wgpu adapter: {}", g.context().adapter_description());
            v.push(Box::new(g));
        }
        Err(e) => eprintln!("no wgpu bench: {e}"),
    }
    v.push(Box::new(RasterRenderer::new()));
    v.push(Box::new(RaycastRenderer::new()));
    v
}

/// A rayon pool of `threads` threads.
pub fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool")
}
