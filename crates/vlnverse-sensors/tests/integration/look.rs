//! Images that look like rooms: textures, baked shadow and occlusion, determinism.

use crate::common;

use glam::Vec3;
use std::sync::Arc;
use vlnverse_env::light::{bake, bake_fresh};
use vlnverse_env::{Part, Pose, Scene, SceneObject, SceneSource, SemanticClass, Shape};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::{Channels, RasterRenderer, RasterScene, Renderer, SceneMesh};

fn cuboid(id: u32, class: SemanticClass, min: Vec3, max: Vec3, rgb: [f32; 3]) -> SceneObject {
    let c = (min + max) * 0.5;
    let mut o = SceneObject::from_parts(
        id,
        class,
        Pose::from_yaw(c, 0.0),
        vec![Part {
            shape: Shape::Cuboid {
                half_extents: ((max - min) * 0.5).to_array(),
                bevel: 0.0,
            },
            transform: Pose::IDENTITY,
            color: rgb,
        }],
    );
    o.room = Some(0);
    o
}

/// A 4 m x 4 m procedural-style room (walls 2.6 m, one lamp at the centre) with a table
/// standing at (0.9, 0.9).
fn room_with_table() -> Scene {
    let g = [0.7; 3];
    let objects = vec![
        cuboid(
            1,
            SemanticClass::Floor,
            Vec3::new(-2.0, -0.05, -2.0),
            Vec3::new(2.0, 0.0, 2.0),
            g,
        ),
        cuboid(
            2,
            SemanticClass::Wall,
            Vec3::new(-2.05, 0.0, -2.05),
            Vec3::new(-1.95, 2.6, 2.05),
            g,
        ),
        cuboid(
            3,
            SemanticClass::Wall,
            Vec3::new(1.95, 0.0, -2.05),
            Vec3::new(2.05, 2.6, 2.05),
            g,
        ),
        cuboid(
            4,
            SemanticClass::Wall,
            Vec3::new(-2.05, 0.0, -2.05),
            Vec3::new(2.05, 2.6, -1.95),
            g,
        ),
        cuboid(
            5,
            SemanticClass::Wall,
            Vec3::new(-2.05, 0.0, 1.95),
            Vec3::new(2.05, 2.6, 2.05),
            g,
        ),
        cuboid(
            6,
            SemanticClass::DiningTable,
            Vec3::new(0.4, 0.7, 0.5),
            Vec3::new(1.4, 0.75, 1.3),
            [0.4, 0.25, 0.12],
        ),
    ];
    common::living_room("room", objects)
}

/// Linear luminance of the colour the renderers give to object `id` at world point `q` (on its
/// surface, facing `n`).
fn brightness(mesh: &SceneMesh, id: u32, q: Vec3, n: Vec3) -> f32 {
    let r = mesh.objects.iter().find(|r| r.id == id).unwrap();
    for t in r.first as usize..(r.first + r.count) as usize {
        let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[3 * t + k]);
        if mesh.normal(t).dot(n) < 0.99 {
            continue;
        }
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(p, q2)| (*q2 - *p).cross(q - *p).dot(n) >= -1e-6);
        if inside {
            // Linear luminance: compare light, not its sRGB encoding.
            let s = mesh.shade(t, q).map(|c| (c as f32 / 255.0).powf(2.2));
            return 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2];
        }
    }
    panic!("no triangle of object {id} at {q}")
}

#[test]
fn floor_under_a_table_is_in_shadow() {
    let scene = room_with_table();
    let mesh = SceneMesh::new(&scene).unwrap();
    let under = brightness(&mesh, 1, Vec3::new(0.9, 0.0, 0.9), Vec3::Y);
    // Open floor as far from the lamp (at the centre) as the spot under the table.
    let open = brightness(&mesh, 1, Vec3::new(-0.9, 0.0, 0.9), Vec3::Y);
    assert!(
        under < 0.6 * open,
        "floor under the table {under} is not darker than open floor {open}"
    );
}

#[test]
fn inside_corner_is_darker_than_mid_wall() {
    let scene = room_with_table();
    let mesh = SceneMesh::new(&scene).unwrap();
    // Wall 2 (inner face x = -1.95, facing +x): at 1.2 m, mid-wall and 5 cm from the corner.
    let mid = brightness(&mesh, 2, Vec3::new(-1.95, 1.2, 0.0), Vec3::X);
    let corner = brightness(&mesh, 2, Vec3::new(-1.95, 1.2, -1.9), Vec3::X);
    assert!(corner < 0.8 * mid, "corner {corner} vs mid-wall {mid}");
    // And the wall's foot (floor edge) is darker than its middle too.
    let foot = brightness(&mesh, 2, Vec3::new(-1.95, 0.05, 0.0), Vec3::X);
    assert!(foot < mid, "wall foot {foot} vs mid-wall {mid}");
}

#[test]
fn walls_and_floors_are_textured_in_rendered_views() {
    let home = HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(0)
        .unwrap();
    let mesh = Arc::new(SceneMesh::new(&home).unwrap());
    let mut r = RasterRenderer::new();
    r.set_scene(mesh).unwrap();
    let poses = common::free_poses(&home, 6, 11, 1.25, 0.3);
    let views: Vec<_> = poses
        .iter()
        .map(|p| common::view(p, 224, 224, Channels::ALL))
        .collect();
    let frames = r.render(&views).unwrap();
    let (wall, floor) = (SemanticClass::Wall.id(), SemanticClass::Floor.id());
    let mut checked = 0;
    for f in &frames {
        // 12 x 12 blocks entirely on one wall or one floor object: not one colour.
        for by in (0..224 - 12).step_by(12) {
            for bx in (0..224 - 12).step_by(12) {
                let idx: Vec<usize> = (0..144)
                    .map(|k| (by + k / 12) * 224 + bx + k % 12)
                    .collect();
                let id = f.instance[idx[0]];
                let class = f.semantic[idx[0]];
                if id == 0 || (class != wall && class != floor) {
                    continue;
                }
                if idx.iter().any(|&i| f.instance[i] != id) {
                    continue;
                }
                let colours: std::collections::BTreeSet<[u8; 3]> = idx
                    .iter()
                    .map(|&i| [f.rgb[3 * i], f.rgb[3 * i + 1], f.rgb[3 * i + 2]])
                    .collect();
                assert!(
                    colours.len() >= 4,
                    "a {}x12 block of class {class} has {} colours",
                    12,
                    colours.len()
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 50, "only {checked} wall/floor blocks seen");
}

#[test]
fn baked_light_and_images_are_the_same_on_one_and_two_threads() {
    let home = HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(1)
        .unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            // Computed, not taken from the cache of `bake`.
            let light = bake_fresh(&home);
            let glb = vlnverse_env::io::glb::write_glb_with(&home, &light);
            let mesh = Arc::new(SceneMesh::with_light(&home, &light).unwrap());
            // Prepared here, not taken from the cache of `RasterScene::shared`.
            let r = RasterScene::new(mesh);
            let frames: Vec<_> = common::free_poses(&home, 4, 5, 1.25, 0.3)
                .iter()
                .map(|p| r.render_view(&common::view(p, 128, 128, Channels::ALL), 4))
                .collect();
            (light, glb, frames)
        })
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.0, b.0, "baked light differs");
    // The cached bake gives the same light.
    assert_eq!(*bake(&home), a.0);
    assert!(a.1 == b.1, "scene.glb bytes differ");
    for (x, y) in a.2.iter().zip(&b.2) {
        assert_eq!(x.rgb, y.rgb);
        assert_eq!(x.instance, y.instance);
    }
}

#[test]
fn prepared_scenes_are_shared_by_content_and_render_like_fresh_ones() {
    let gen = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let (home, other) = (gen.scene(2).unwrap(), gen.scene(3).unwrap());
    // Two meshes made apart from one home: one prepared scene.
    let mesh = Arc::new(SceneMesh::new(&home).unwrap());
    let a = RasterScene::shared(mesh.clone());
    let b = RasterScene::shared(Arc::new(SceneMesh::new(&home).unwrap()));
    assert!(Arc::ptr_eq(&a, &b), "the same home was prepared twice");
    assert!(!Arc::ptr_eq(
        &a,
        &RasterScene::shared(Arc::new(SceneMesh::new(&other).unwrap()))
    ));
    // Any change to the mesh is another scene (here the light at one corner).
    let mut changed = (*mesh).clone();
    changed.look[0].light[0] += 0.01;
    assert_ne!(changed.content_key(), mesh.content_key());
    assert!(!Arc::ptr_eq(&a, &RasterScene::shared(Arc::new(changed))));
    // A cached scene renders the bytes of a freshly prepared one.
    let fresh = RasterScene::new(mesh);
    for p in common::free_poses(&home, 3, 9, 1.25, 0.3) {
        let v = common::view(&p, 96, 96, Channels::ALL);
        let (x, y) = (a.render_view(&v, 2), fresh.render_view(&v, 2));
        assert_eq!((x.rgb, x.depth, x.instance), (y.rgb, y.depth, y.instance));
    }
    assert!(a.bytes() > a.face_texture_bytes());
}
