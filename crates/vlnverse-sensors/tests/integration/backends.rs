//! The two renderer backends against each other and against direct ray casts.

use crate::common;

use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::{Pose, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{
    CameraSpec, Channels, RasterRenderer, RaycastRenderer, Renderer, SceneMesh, SceneRaycaster,
    View,
};

#[test]
fn wgpu_and_raycast_depth_agree_per_pixel() {
    let Some(mut gpu) = common::gpu("wgpu_and_raycast_depth_agree_per_pixel") else {
        return;
    };
    let mut cpu = RaycastRenderer::new();
    let mut worst: f64 = 0.0;
    let mut total = 0.0;
    let mut n = 0;
    let mut rgb_worst: f64 = 1.0;
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let mut scenes: Vec<_> = (0..3).map(|i| homes.scene(i).unwrap()).collect();
    scenes.push(demo_scene(0));
    for (seed, scene) in scenes.iter().enumerate() {
        let seed = seed as u64;
        let mesh = Arc::new(SceneMesh::new(scene).unwrap());
        gpu.set_scene(mesh.clone()).unwrap();
        cpu.set_scene(mesh).unwrap();
        let views: Vec<View> = common::free_poses(scene, 8, 100 + seed, 1.25, 0.15)
            .iter()
            .map(|p| common::view(p, 256, 256, Channels::ALL))
            .collect();
        let g = gpu.render(&views).unwrap();
        let c = cpu.render(&views).unwrap();
        for (a, b) in g.iter().zip(&c) {
            assert_eq!((a.width, a.height), (256, 256));
            let m = common::depth_off(a, b) as f64 / a.depth.len() as f64;
            worst = worst.max(m);
            total += m;
            n += 1;
            // The images are not trivial: some pixels see geometry closer than far.
            assert!(a.depth.iter().any(|d| *d < 9.0));
            // Instance ids may differ only on coplanar faces of two objects (e.g. overlapping
            // wall segments), where both backends see the same depth and, here, the same class.
            let same_class = a
                .semantic
                .iter()
                .zip(&b.semantic)
                .filter(|(x, y)| x == y)
                .count();
            let id_off_depth = (0..a.instance.len())
                .filter(|&i| {
                    a.instance[i] != b.instance[i] && (a.depth[i] - b.depth[i]).abs() > 0.01
                })
                .count();
            assert!(
                same_class as f64 > 0.995 * a.semantic.len() as f64,
                "classes agree on {same_class} pixels"
            );
            assert!(
                (id_off_depth as f64) < 0.01 * a.instance.len() as f64,
                "{id_off_depth} pixels"
            );
            // Same lighting model: colours match up to rounding except on a few edge pixels.
            let rgb_close = a
                .rgb
                .chunks(3)
                .zip(b.rgb.chunks(3))
                .filter(|(x, y)| x.iter().zip(y.iter()).all(|(p, q)| p.abs_diff(*q) <= 3))
                .count();
            rgb_worst = rgb_worst.min(rgb_close as f64 / a.pixels() as f64);
            assert!(
                rgb_close as f64 > 0.95 * a.pixels() as f64,
                "rgb close on {rgb_close} pixels"
            );
        }
    }
    println!("depth mismatch fraction: mean {:.5}, worst view {:.5}; rgb within 3/255: worst view {rgb_worst:.4}", total / n as f64, worst);
    assert!(worst < 0.01, "worst view has {worst} of pixels off");
}

#[test]
fn centre_pixel_instance_is_the_object_the_centre_ray_hits() {
    let scene = demo_scene(7);
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let rc = SceneRaycaster::new(mesh.clone()).unwrap();
    let mut backends: Vec<Box<dyn Renderer>> = vec![Box::new(RaycastRenderer::new())];
    if let Some(g) = common::gpu("centre_pixel_instance_is_the_object_the_centre_ray_hits") {
        backends.push(Box::new(g));
    }
    let poses = common::free_poses(&scene, 16, 5, 1.25, 0.15);
    // Odd size: the centre pixel's ray is the optical axis.
    let views: Vec<View> = poses
        .iter()
        .map(|p| common::view(p, 65, 65, Channels::ALL))
        .collect();
    for r in &mut backends {
        r.set_scene(mesh.clone()).unwrap();
        let frames = r.render(&views).unwrap();
        for (v, f) in views.iter().zip(&frames) {
            let c = &v.camera;
            let hit = rc
                .cast(c.position, c.forward(), c.far)
                .expect("a closed home");
            let i = f.index(32, 32);
            assert_eq!(f.instance[i], hit.object, "{} backend", r.name());
            assert_eq!(f.semantic[i], mesh.class(hit.object));
            assert!(
                (f.depth[i] - hit.distance).abs() < 0.01,
                "{} vs {}",
                f.depth[i],
                hit.distance
            );
        }
    }
}

#[test]
fn depth_is_along_the_optical_axis_and_fov_is_respected() {
    // Facing the -Z outer wall (inner face at z = 0) from z = 3: every wall pixel reads 3 m.
    let scene = demo_scene(0);
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let mut backends: Vec<Box<dyn Renderer>> = vec![Box::new(RaycastRenderer::new())];
    if let Some(g) = common::gpu("depth_is_along_the_optical_axis_and_fov_is_respected") {
        backends.push(Box::new(g));
    }
    for r in &mut backends {
        r.set_scene(mesh.clone()).unwrap();
        for (w, h, hfov) in [(64u32, 48u32, 40.0f32), (31, 57, 25.0)] {
            let spec = CameraSpec {
                width: w,
                height: h,
                hfov_deg: hfov,
                mount: vlnverse_sensors::Mount {
                    offset: [0.0, 1.6, 0.0],
                    pitch_deg: 0.0,
                },
                ..CameraSpec::default()
            };
            let cam = spec.camera(&Pose::from_yaw(Vec3::new(6.5, 0.0, 3.0), 0.0));
            assert!((cam.fx() - w as f32 / 2.0 / (hfov.to_radians() / 2.0).tan()).abs() < 1e-3);
            let f = &r
                .render(&[View {
                    camera: cam,
                    channels: Channels::ALL,
                }])
                .unwrap()[0];
            assert_eq!((f.width, f.height), (w, h));
            assert_eq!(f.depth.len(), (w * h) as usize);
            assert_eq!(f.rgb.len(), (w * h * 3) as usize);
            // The wall spans x in [-0.1, 8.1]; with a narrow fov only the wall (or the wardrobe,
            // placed near x = 7.3, z = 1) is seen. Wall pixels all read 3 m.
            let wall_ids: Vec<u32> = scene
                .objects
                .iter()
                .filter(|o| o.class == vlnverse_env::SemanticClass::Wall)
                .map(|o| o.id)
                .collect();
            let mut wall_px = 0;
            for (d, id) in f.depth.iter().zip(&f.instance) {
                if wall_ids.contains(id) {
                    wall_px += 1;
                    assert!(
                        (d - 3.0).abs() < 0.01,
                        "{} backend: wall depth {d}",
                        r.name()
                    );
                }
            }
            assert!(wall_px > 0);
        }
    }
}

#[test]
fn resolution_and_fov_changes_move_the_image_of_a_box_as_fx_says() {
    let scene = common::one_box_scene();
    let id = scene.objects[0].id;
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let mut backends: Vec<Box<dyn Renderer>> = vec![
        Box::new(RaycastRenderer::new()),
        Box::new(RasterRenderer::new()),
    ];
    if let Some(g) = common::gpu("resolution_and_fov_changes_move_the_image_of_a_box_as_fx_says") {
        backends.push(Box::new(g));
    }
    for r in &mut backends {
        r.set_scene(mesh.clone()).unwrap();
        for (w, h, hfov) in [(64u32, 48u32, 40.0f32), (120, 90, 90.0), (33, 71, 25.0)] {
            let cam =
                vlnverse_sensors::Camera::new(&Pose::IDENTITY, w, h, hfov.to_radians(), 0.05, 10.0);
            let f = &r
                .render(&[View {
                    camera: cam,
                    channels: Channels::ALL,
                }])
                .unwrap()[0];
            assert_eq!((f.width, f.height), (w, h));
            assert_eq!(f.rgb.len(), (w * h * 3) as usize);
            let what = format!("{} backend, {w}x{h} hfov {hfov}", r.name());
            common::assert_one_box_image(f, &cam, id, &what);
        }
    }
}

/// Without a GPU device node, `auto` picks the CPU rasteriser without probing the graphics
/// stack (a probe makes Mesa print `XDG_RUNTIME_DIR is invalid` on headless machines). Skipped
/// where a GPU node exists or `WGPU_BACKEND` asks for a probe.
#[test]
fn auto_without_gpu_device_nodes_is_the_rasteriser() {
    let has = |dir: &str, prefix: &str| {
        std::fs::read_dir(dir).is_ok_and(|d| {
            d.flatten()
                .any(|e| e.file_name().to_string_lossy().starts_with(prefix))
        })
    };
    if !cfg!(target_os = "linux")
        || has("/dev/dri", "renderD")
        || has("/dev", "nvidia")
        || std::env::var_os("WGPU_BACKEND").is_some()
    {
        eprintln!("skipped: this machine has a GPU device node or WGPU_BACKEND is set");
        return;
    }
    for _ in 0..2 {
        let r = vlnverse_sensors::create_renderer(vlnverse_sensors::Backend::Auto).unwrap();
        assert_eq!(r.name(), "raster");
    }
}
