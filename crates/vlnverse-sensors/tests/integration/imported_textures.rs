//! Imported glTF textures appear in renders: a textured floor and wall written by the test,
//! imported, and rendered by the ray caster, the CPU rasteriser and wgpu (where an adapter
//! exists); each sampled pixel is the texel under it times the light.

use glam::Quat;
use std::sync::Arc;
use vlnverse_env::light::bake;
use vlnverse_env::{Pose, Scene};
use vlnverse_import::{import_scene, ImportOptions};
use vlnverse_sensors::{
    Camera, Channels, Frame, RasterRenderer, RaycastRenderer, Renderer, SceneMesh, View,
};

use vlnverse_testkit::textured_glb as fx;

fn textured_scene() -> Scene {
    let d = tempfile_dir();
    let path = d.join("textured.glb");
    std::fs::write(&path, fx::checker_glb()).unwrap();
    let opts = ImportOptions {
        segment_rooms: false,
        ..Default::default()
    };
    let scene = import_scene(&path, &opts).unwrap().0;
    let _ = std::fs::remove_dir_all(&d);
    scene
}

/// A fresh folder under the system temporary directory (no tempfile dependency here).
fn tempfile_dir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!(
        "vlnverse-imported-textures-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Checks every floor and wall pixel of `f` whose point lies clear of a texel border: the
/// pixel must be `tone x light x texel` per channel (within 3 levels) for one light value, with
/// `tone` the encoded light colour. Returns (pixels checked, distinct texels seen, pixels far
/// from the texture's mean colour).
fn check_pixels(scene: &Scene, cam: &Camera, f: &Frame, who: &str) -> (usize, usize, usize) {
    let id = |n: &str| scene.objects.iter().find(|o| o.name == n).unwrap().id;
    let (floor, wall) = (id("floor"), id("wall"));
    let tint = bake(scene).tint;
    let tint = if tint == [0.0; 3] { [1.0; 3] } else { tint };
    let tone = tint.map(|c| c.powf(1.0 / 2.2));
    let texels = fx::texels();
    let mean = [0, 1, 2].map(|k| texels.iter().map(|t| t[k] as f32).sum::<f32>() / 64.0);
    let (mut checked, mut far_from_mean) = (0, 0);
    let mut seen = std::collections::BTreeSet::new();
    let fwd = cam.forward();
    for v in 0..f.height {
        for u in 0..f.width {
            let i = f.index(u, v);
            let obj = f.instance[i];
            if obj != floor && obj != wall {
                continue;
            }
            let dir = cam.pixel_ray(u, v);
            let p = cam.position + dir * (f.depth[i] / dir.dot(fwd));
            let uv = if obj == floor {
                fx::floor_uv(p.x, p.z)
            } else {
                fx::wall_uv(p.x, p.y)
            };
            let t = uv.map(|c| c * fx::SIDE as f32);
            if t.iter().any(|c| (c - c.floor() - 0.5).abs() > 0.4) {
                continue; // Too close to a texel border for the depth's precision.
            }
            let (tx, ty) = (
                t[0].floor() as u32 % fx::SIDE,
                t[1].floor() as u32 % fx::SIDE,
            );
            let texel = fx::texel(tx, ty);
            let px = [0, 1, 2].map(|k| f.rgb[3 * i + k] as f32);
            // The light from the brightest channel of the texel, then every channel must agree.
            let k = (0..3).max_by_key(|&k| texel[k]).unwrap();
            let light = px[k] / (tone[k] * texel[k] as f32);
            assert!(
                light > 0.05 && light < 1.02,
                "{who}: pixel ({u}, {v}) = {px:?} over texel {texel:?}: light {light}"
            );
            for c in 0..3 {
                let want = tone[c] * light * texel[c] as f32;
                assert!(
                    (px[c] - want).abs() <= 3.0,
                    "{who}: pixel ({u}, {v}) = {px:?}, texel ({tx}, {ty}) = {texel:?} times light \
                     {light} gives {want} in channel {c}"
                );
            }
            checked += 1;
            seen.insert((tx, ty));
            if (0..3).any(|c| (px[c] - tone[c] * light * mean[c]).abs() > 20.0) {
                far_from_mean += 1;
            }
        }
    }
    (checked, seen.len(), far_from_mean)
}

#[test]
fn imported_textures_appear_in_every_backend() {
    let scene = textured_scene();
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    assert_eq!(mesh.images.len(), 1, "floor and wall share one image");
    assert_eq!(mesh.images[0].texels, fx::texels());
    assert!(mesh.look.iter().all(|l| l.image == Some(0)));
    // Looking at the wall from inside the room, pitched down to see the floor too.
    let pose = Pose {
        position: [0.3, 1.2, 1.2],
        rotation: (Quat::from_rotation_y(0.15) * Quat::from_rotation_x(-0.35)).to_array(),
    };
    let cam = Camera::new(&pose, 96, 72, 70f32.to_radians(), 0.05, 20.0);
    let mut backends: Vec<Box<dyn Renderer>> = vec![
        Box::new(RaycastRenderer::new()),
        Box::new(RasterRenderer::new()),
    ];
    // wgpu where an adapter exists (CI: Mesa's software Vulkan driver).
    if let Some(gpu) = crate::common::gpu("imported_textures_appear_in_every_backend") {
        backends.push(Box::new(gpu));
    }
    for mut r in backends {
        r.set_scene(mesh.clone()).unwrap();
        let f = &r
            .render(&[View {
                camera: cam,
                channels: Channels::ALL,
            }])
            .unwrap()[0];
        let (checked, distinct, far) = check_pixels(&scene, &cam, f, &r.name());
        assert!(checked > 1000, "{}: {checked} pixels checked", r.name());
        assert!(
            distinct >= 32,
            "{}: {distinct} distinct texels seen",
            r.name()
        );
        assert!(
            far * 10 > checked * 8,
            "{}: {far} of {checked} differ from the mean colour",
            r.name()
        );
        // Both surfaces are seen.
        let ids: std::collections::BTreeSet<u32> = f.instance.iter().copied().collect();
        assert!(ids.len() >= 2, "{}: {ids:?}", r.name());
    }
}
