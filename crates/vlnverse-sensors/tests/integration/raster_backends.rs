//! The CPU rasteriser against the ray caster (the reference: one exact ray per pixel centre).

use crate::common;

use glam::{Quat, Vec3};
use std::sync::Arc;
use vlnverse_env::{Pose, Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    create_renderer, Backend, Camera, CameraSpec, Channels, Frame, RasterRenderer, RasterScene,
    RaycastRenderer, Renderer, SceneMesh, SceneRaycaster, View,
};

fn test_scenes() -> Vec<Scene> {
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let mut scenes: Vec<Scene> = (0..4).map(|i| homes.scene(i).unwrap()).collect();
    scenes.push(demo_scene(0));
    scenes
}

/// Per-pixel comparison of two frames of the same view; returns (depth-off pixels, pixels whose
/// object differs where depth agrees too, pixels whose colour differs by more than 3/255).
fn compare(a: &Frame, b: &Frame) -> (usize, usize, usize) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let d = common::depth_off(a, b);
    let ids = (0..a.pixels())
        .filter(|&i| a.instance[i] != b.instance[i] && (a.depth[i] - b.depth[i]).abs() > 0.01)
        .count();
    let rgb = a
        .rgb
        .chunks(3)
        .zip(b.rgb.chunks(3))
        .filter(|(x, y)| x.iter().zip(y.iter()).any(|(p, q)| p.abs_diff(*q) > 3))
        .count();
    (d, ids, rgb)
}

#[test]
fn raster_and_raycast_agree_per_pixel_on_generated_homes() {
    let mut raster = RasterRenderer::new();
    let mut cpu = RaycastRenderer::new();
    let (mut depth_bad, mut id_bad, mut rgb_bad, mut pixels) = (0usize, 0usize, 0usize, 0usize);
    let mut seen = 0usize;
    let mut worst: f64 = 0.0;
    for (seed, scene) in test_scenes().iter().enumerate() {
        let mesh = Arc::new(SceneMesh::new(scene).unwrap());
        raster.set_scene(mesh.clone()).unwrap();
        cpu.set_scene(mesh).unwrap();
        let mut poses = common::free_poses(scene, 8, 300 + seed as u64, 1.25, 0.15);
        // Some pitched cameras too (floors and ceilings at grazing angles).
        for (k, p) in poses.iter_mut().enumerate().take(3) {
            let pitch = [-0.5f32, 0.35, -1.2][k];
            p.rotation = (p.quat() * Quat::from_rotation_x(pitch)).to_array();
        }
        let views: Vec<View> = poses
            .iter()
            .map(|p| common::view(p, 256, 256, Channels::ALL))
            .collect();
        let r = raster.render(&views).unwrap();
        let c = cpu.render(&views).unwrap();
        for (a, b) in r.iter().zip(&c) {
            seen += a.instance.iter().filter(|i| **i != 0).count();
            let (d, i, g) = compare(a, b);
            worst = worst.max(d as f64 / a.pixels() as f64);
            depth_bad += d;
            id_bad += i;
            rgb_bad += g;
            pixels += a.pixels();
            // The same class wherever both see the same object.
            for k in 0..a.pixels() {
                if a.instance[k] == b.instance[k] {
                    assert_eq!(a.semantic[k], b.semantic[k]);
                }
            }
        }
    }
    let f = |n: usize| n as f64 / pixels as f64;
    println!(
        "raster vs raycast over {pixels} pixels: depth off {:.6} (worst view {worst:.6}), \
         id off {:.6}, rgb off {:.6}",
        f(depth_bad),
        f(id_bad),
        f(rgb_bad)
    );
    // The images are not trivial: most pixels see something (homes may have no ceiling).
    assert!(f(seen) > 0.5, "only {seen} of {pixels} pixels see geometry");
    // Only silhouette pixels may differ (the two sample the same pixel centres).
    assert!(f(depth_bad) < 1e-3, "depth off on {depth_bad} of {pixels}");
    assert!(worst < 5e-3, "worst view has {worst} of its pixels off");
    assert!(f(id_bad) < 1e-3, "ids off on {id_bad} of {pixels}");
    assert!(f(rgb_bad) < 2e-3, "colours off on {rgb_bad} of {pixels}");
}

#[test]
fn near_plane_clipping_and_culling_match_the_ray_caster_close_to_walls() {
    // Cameras a few centimetres from a wall (closer than `near` for some), looking at it
    // obliquely: the near plane cuts walls and, closer than near, the ray caster sees into them.
    let scene = demo_scene(0);
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let mut raster = RasterRenderer::new();
    let mut cpu = RaycastRenderer::new();
    raster.set_scene(mesh.clone()).unwrap();
    cpu.set_scene(mesh).unwrap();
    let mut views = Vec::new();
    // The -Z outer wall has its inner face at z = 0 (see the `backends` test module).
    for (k, dz) in [0.02f32, 0.04, 0.08, 0.3].iter().enumerate() {
        for yaw in [0.3f32, 0.9, -1.2] {
            let base = Pose::from_yaw(Vec3::new(2.0 + k as f32, 0.0, *dz), yaw);
            views.push(common::view(&base, 96, 96, Channels::ALL));
        }
    }
    let r = raster.render(&views).unwrap();
    let c = cpu.render(&views).unwrap();
    let mut bad = 0;
    for (a, b) in r.iter().zip(&c) {
        bad += common::depth_off(a, b);
    }
    let total = views.len() * 96 * 96;
    println!("close-up views: depth off on {bad} of {total} pixels");
    assert!((bad as f64) < 2e-3 * total as f64, "{bad} of {total}");
}

#[test]
fn centre_pixel_sees_the_object_the_centre_ray_hits() {
    let mut raster = RasterRenderer::new();
    let mut hits = 0;
    for (seed, scene) in test_scenes().iter().enumerate() {
        let mesh = Arc::new(SceneMesh::new(scene).unwrap());
        let rc = SceneRaycaster::new(mesh.clone()).unwrap();
        raster.set_scene(mesh.clone()).unwrap();
        let poses = common::free_poses(scene, 16, 40 + seed as u64, 1.25, 0.15);
        // Odd size: the centre pixel's ray is the optical axis.
        let views: Vec<View> = poses
            .iter()
            .map(|p| common::view(p, 65, 65, Channels::ALL))
            .collect();
        for (v, f) in views.iter().zip(raster.render(&views).unwrap()) {
            let c = &v.camera;
            let i = f.index(32, 32);
            // Generated homes may be open to the sky: a miss is nothing at the far plane.
            match rc.cast(c.position, c.forward(), c.far) {
                Some(hit) => {
                    assert_eq!(f.instance[i], hit.object);
                    assert_eq!(f.semantic[i], mesh.class(hit.object));
                    assert!((f.depth[i] - hit.distance).abs() < 0.01);
                    hits += 1;
                }
                None => assert_eq!((f.instance[i], f.depth[i]), (0, c.far)),
            }
        }
    }
    assert!(hits > 60, "only {hits} centre rays hit");
}

#[test]
fn batches_and_panoramas_equal_single_renders() {
    let scene = &test_scenes()[1];
    let mesh = Arc::new(SceneMesh::new(scene).unwrap());
    let mut raster = RasterRenderer::new();
    raster.set_scene(mesh).unwrap();
    let base = common::free_poses(scene, 1, 9, 1.25, 0.15)[0];
    let cam = CameraSpec::default().camera(&base);
    let mut views: Vec<View> = (0..12)
        .map(|k| View {
            camera: cam.yawed((30.0 * k as f32).to_radians()),
            channels: Channels::ALL,
        })
        .collect();
    // Mixed sizes and channel sets in one batch.
    views.push(common::view(&base, 256, 256, Channels::DEPTH));
    views.push(common::view(&base, 31, 17, Channels::RGB));
    let batch = raster.render(&views).unwrap();
    assert_eq!(batch.len(), views.len());
    for (v, b) in views.iter().zip(&batch) {
        let single = raster.render(std::slice::from_ref(v)).unwrap();
        assert_eq!(&single[0], b);
    }
    // Only the requested channels are filled.
    assert!(batch[12].rgb.is_empty() && batch[12].instance.is_empty());
    assert_eq!(batch[12].depth.len(), 256 * 256);
    assert!(batch[13].depth.is_empty() && batch[13].semantic.is_empty());
    assert_eq!(batch[13].rgb.len(), 31 * 17 * 3);
    // Panorama views differ (the camera really turns).
    assert_ne!(batch[0].depth, batch[6].depth);
    // Rendering on one thread or many gives the same images.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| raster.render(&views).unwrap());
    assert_eq!(one, batch);
}

#[test]
fn a_closed_box_is_culled_from_outside() {
    // Its image per resolution and FoV is checked for every backend in `backends`.
    let mut raster = RasterRenderer::new();
    raster
        .set_scene(Arc::new(SceneMesh::new(&common::one_box_scene()).unwrap()))
        .unwrap();
    assert_eq!(raster.scene().map(|s| s.closed_objects()), Some(1));
}

#[test]
fn far_plane_clips_depth_and_ids() {
    // The box front face at 4.5 m disappears with far = 4 m and is seen with far = 5 m.
    let scene = common::one_box_scene();
    let mut raster = RasterRenderer::new();
    raster
        .set_scene(Arc::new(SceneMesh::new(&scene).unwrap()))
        .unwrap();
    for far in [4.0f32, 5.0] {
        let cam = Camera::new(&Pose::IDENTITY, 32, 32, 1.0, 0.05, far);
        let f = &raster
            .render(&[View {
                camera: cam,
                channels: Channels::ALL,
            }])
            .unwrap()[0];
        let seen = f.instance.iter().filter(|i| **i != 0).count();
        assert_eq!(seen > 0, far > 4.5, "far {far}");
        assert!(f.depth.iter().all(|d| *d <= far && *d > 0.0));
        assert!(f.depth.contains(&far));
    }
}

#[test]
fn raster_backend_is_selectable_and_needs_a_scene() {
    assert_eq!("raster".parse::<Backend>().unwrap(), Backend::Raster);
    let cfg: vlnverse_sensors::RigConfig = toml::from_str("backend = \"raster\"").unwrap();
    assert_eq!(cfg.backend, Backend::Raster);
    let mut r = create_renderer(Backend::Raster).unwrap();
    assert_eq!(r.name(), "raster");
    let v = common::view(&Pose::IDENTITY, 8, 8, Channels::ALL);
    assert!(matches!(
        r.render(&[v]),
        Err(vlnverse_sensors::SensorError::NoScene)
    ));
    // The prepared scene knows the mesh it was given, without keeping it alive.
    let mesh = Arc::new(SceneMesh::new(&demo_scene(0)).unwrap());
    let s = RasterScene::new(mesh.clone());
    assert!(Arc::ptr_eq(&s.mesh().unwrap(), &mesh));
    assert!(s.closed_objects() > 0);
    drop(mesh);
    assert!(s.mesh().is_none());
}
