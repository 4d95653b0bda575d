//! Shared helpers of the integration tests.
#![allow(dead_code)]

use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vlnverse_env::{ObjectId, Pose, Room, RoomType, Scene, SceneObject};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{Camera, CameraSpec, Channels, Frame, GpuRenderer, SensorError, View};

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

/// A view of the default depth camera at `w` x `h` from the agent base `base`.
pub fn view(base: &Pose, w: u32, h: u32, channels: Channels) -> View {
    let spec = CameraSpec {
        width: w,
        height: h,
        ..CameraSpec::depth()
    };
    View {
        camera: spec.camera(base),
        channels,
    }
}

/// Pixels whose depth in `a` differs from the reference `b` by more than 1 cm (0.5 % beyond 2 m).
pub fn depth_off(a: &Frame, b: &Frame) -> usize {
    a.depth
        .iter()
        .zip(&b.depth)
        .filter(|(x, y)| {
            let tol = if **y > 2.0 { 0.005 * **y } else { 0.01 };
            (**x - **y).abs() > tol
        })
        .count()
}

/// The demo scene reduced to one red 1 m cube centred 5 m ahead of the origin (front face at
/// z = -4.5), so where it lands in an image follows from the intrinsics alone.
pub fn one_box_scene() -> Scene {
    let mut s = demo_scene(0);
    s.objects
        .retain(|o| o.class == vlnverse_env::SemanticClass::Bookshelf);
    let o = &mut s.objects[0];
    o.pose = Pose::from_yaw(Vec3::new(0.0, 0.0, -5.0), 0.0);
    o.parts = vec![vlnverse_env::Part {
        shape: vlnverse_env::Shape::Cuboid {
            half_extents: [0.5, 0.5, 0.5],
            bevel: 0.0,
        },
        transform: Pose::IDENTITY,
        color: [1.0, 0.0, 0.0],
    }];
    o.bbox = o.compute_bbox();
    s
}

/// Checks a frame of [`one_box_scene`] seen from the origin through `cam`: the box `id` covers
/// exactly the pixel centres inside its projected front face, at depth 4.5 m, and the rest of
/// the image is empty at the far plane (10 m).
pub fn assert_one_box_image(f: &Frame, cam: &Camera, id: ObjectId, what: &str) {
    let (w, h) = (f.width, f.height);
    let cols: Vec<u32> = (0..w)
        .filter(|&u| (0..h).any(|v| f.instance[f.index(u, v)] == id))
        .collect();
    let rows: Vec<u32> = (0..h)
        .filter(|&v| (0..w).any(|u| f.instance[f.index(u, v)] == id))
        .collect();
    // Pixel centres inside the projected front face: |u + 0.5 - cx| < fx * 0.5 / 4.5.
    let half = cam.fx() * 0.5 / 4.5;
    let exp_cols: Vec<u32> = (0..w)
        .filter(|&u| (u as f32 + 0.5 - cam.cx()).abs() < half)
        .collect();
    let exp_rows: Vec<u32> = (0..h)
        .filter(|&v| (v as f32 + 0.5 - cam.cy()).abs() < half)
        .collect();
    assert_eq!(cols, exp_cols, "{what}");
    assert_eq!(rows, exp_rows, "{what}");
    for ((d, i), px) in f.depth.iter().zip(&f.instance).zip(f.rgb.chunks(3)) {
        let want = if *i == id { 4.5 } else { 10.0 };
        assert!((d - want).abs() < 1e-3, "{what}: depth {d}, want {want}");
        // Red where the box is, black elsewhere.
        assert_eq!(px[0] > 0, *i == id, "{what}: rgb {px:?}");
        assert_eq!(px[1], 0, "{what}: rgb {px:?}");
    }
}

/// A procedural-style scene `id` (seed 3) of one 4 m x 4 m living room centred on the origin
/// holding `objects`.
pub fn living_room(id: &str, objects: Vec<SceneObject>) -> Scene {
    Scene {
        format_version: 1,
        id: id.into(),
        source: "procgen".into(),
        seed: Some(3),
        floor_height: 0.0,
        rooms: vec![Room {
            id: 0,
            kind: RoomType::LivingRoom,
            name: "living_room_1".into(),
            polygon: vec![[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]],
        }],
        doors: vec![],
        objects,
        storeys: Default::default(),
    }
}
