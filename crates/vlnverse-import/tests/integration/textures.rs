//! Imported base-colour textures: kept with their texture coordinates, written into and read
//! back from the scene folder, and a broken image falling back to the factor colour.

use std::path::Path;
use vlnverse_env::io::{load_scene, write_scene_dir, SCENE_GLB};
use vlnverse_env::scene::MeshTexture;
use vlnverse_env::{Scene, SceneObject, Shape};
use vlnverse_import::{import_scene, ImportOptions};
use vlnverse_testkit::textured_glb::{self as fx, SIDE};

fn import(dir: &Path, glb: &[u8]) -> Scene {
    let path = dir.join("textured.glb");
    std::fs::write(&path, glb).unwrap();
    let opts = ImportOptions {
        segment_rooms: false,
        ..Default::default()
    };
    import_scene(&path, &opts).unwrap().0
}

fn named<'a>(scene: &'a Scene, name: &str) -> &'a SceneObject {
    scene.objects.iter().find(|o| o.name == name).unwrap()
}

/// The mesh data of an object's only part.
fn mesh(o: &SceneObject) -> &vlnverse_env::MeshData {
    assert_eq!(o.parts.len(), 1, "{}", o.name);
    match &o.parts[0].shape {
        Shape::Mesh(m) => m,
        s => panic!("{}: {s:?}", o.name),
    }
}

#[test]
fn imported_parts_keep_their_texture_coordinates_and_image() {
    let d = tempfile::tempdir().unwrap();
    let scene = import(d.path(), &fx::checker_glb());
    for (name, uv) in [
        (
            "floor",
            (|p: [f32; 3]| fx::floor_uv(p[0], p[2])) as fn([f32; 3]) -> [f32; 2],
        ),
        ("wall", |p: [f32; 3]| fx::wall_uv(p[0], p[1])),
    ] {
        let o = named(&scene, name);
        let m = mesh(o);
        let t = m.texture.as_ref().expect("the part keeps its texture");
        assert_eq!((t.width, t.height), (SIDE, SIDE));
        assert_eq!(*t.texels, fx::texels());
        assert_eq!(t.factor, [1.0; 3]);
        assert_eq!(m.uvs.len(), m.positions.len());
        for (p, got) in m.positions.iter().zip(&m.uvs) {
            let w = o
                .pose
                .transform_point(glam::Vec3::from_array(*p))
                .to_array();
            assert_eq!(*got, uv(w), "{name} vertex {w:?}");
        }
        // The flat colour (maps, language) is the image's mean, not the white factor.
        let mean = t.mean_linear();
        assert_eq!(o.parts[0].color, mean);
        assert!(mean.iter().all(|c| *c < 0.6), "{mean:?}");
    }
    // Both parts share one image in memory.
    let a = mesh(named(&scene, "floor")).texture.as_ref().unwrap();
    let b = mesh(named(&scene, "wall")).texture.as_ref().unwrap();
    assert!(std::sync::Arc::ptr_eq(&a.texels, &b.texels));
}

#[test]
fn the_scene_folder_round_trip_keeps_texture_coordinates_and_image_bytes() {
    let d = tempfile::tempdir().unwrap();
    let scene = import(d.path(), &fx::checker_glb());
    let dir = write_scene_dir(d.path().join("out"), &scene, &[]).unwrap();
    let json = std::fs::read_to_string(dir.join("scene.json")).unwrap();
    assert!(json.contains("\"texture\""), "{json}");
    assert!(!json.contains("texels"), "pixels belong in scene.glb");
    let back = load_scene(&dir).unwrap();
    let (mut a, mut b) = (scene.clone(), back.clone());
    vlnverse_env::io::glb::assign_glb_mesh_indices(&mut a);
    vlnverse_env::io::glb::assign_glb_mesh_indices(&mut b);
    assert_eq!(a, b);
    let m = mesh(named(&back, "wall"));
    assert_eq!(*m.texture.as_ref().unwrap().texels, fx::texels());
    assert!(!m.uvs.is_empty());
    // Writing the loaded scene again gives the same file.
    let again = write_scene_dir(d.path().join("again"), &back, &[]).unwrap();
    assert_eq!(
        std::fs::read(dir.join(SCENE_GLB)).unwrap(),
        std::fs::read(again.join(SCENE_GLB)).unwrap()
    );
}

#[test]
fn the_written_scene_glb_has_texcoords_and_the_base_color_texture() {
    let d = tempfile::tempdir().unwrap();
    let scene = import(d.path(), &fx::checker_glb());
    let dir = write_scene_dir(d.path().join("out"), &scene, &[]).unwrap();
    let (doc, buffers, images) = gltf::import(dir.join(SCENE_GLB)).unwrap();
    for name in ["floor", "wall"] {
        let node = doc.nodes().find(|n| n.name() == Some(name)).unwrap();
        let part = node.children().next().expect("mesh part child node");
        let mesh = part.mesh().expect("the part node has a mesh");
        let prim = mesh.primitives().next().unwrap();
        let uvs: Vec<[f32; 2]> = prim
            .reader(|b| Some(&buffers[b.index()].0))
            .read_tex_coords(0)
            .expect("TEXCOORD_0")
            .into_f32()
            .collect();
        assert_eq!(uvs, mesh_uvs(&scene, name));
        let info = prim
            .material()
            .pbr_metallic_roughness()
            .base_color_texture()
            .expect("baseColorTexture");
        assert_eq!(info.tex_coord(), 0);
        let img = &images[info.texture().source().index()];
        assert_eq!((img.width, img.height), (SIDE, SIDE));
        assert_eq!(img.format, gltf::image::Format::R8G8B8);
        assert_eq!(img.pixels, fx::texels().concat());
    }
}

fn mesh_uvs(scene: &Scene, name: &str) -> Vec<[f32; 2]> {
    mesh(named(scene, name)).uvs.clone()
}

#[test]
fn a_broken_image_leaves_the_factor_colour_without_failing() {
    let d = tempfile::tempdir().unwrap();
    let good = fx::png(SIDE, SIDE, &fx::texels());
    for bad in [
        b"not a png at all".to_vec(),
        good[..good.len() / 2].to_vec(),
    ] {
        let scene = import(d.path(), &fx::glb(&bad));
        for name in ["floor", "wall"] {
            let o = named(&scene, name);
            assert_eq!(mesh(o).texture, None);
            assert!(mesh(o).uvs.is_empty());
            assert_eq!(o.parts[0].color, [1.0; 3], "the factor (white)");
        }
        // The scene still writes and loads.
        let dir = write_scene_dir(d.path().join("out"), &scene, &[]).unwrap();
        load_scene(&dir).unwrap();
    }
}

#[test]
fn other_sizes_are_resampled_to_powers_of_two() {
    let d = tempfile::tempdir().unwrap();
    // 12 x 5: width grows to 16 (nearest texel), height shrinks to 4 (the last row averages
    // source rows 3 and 4).
    let (w, h) = (12u32, 5u32);
    let src: Vec<[u8; 3]> = (0..h)
        .flat_map(|y| (0..w).map(move |x| [(x * 20) as u8, (y * 50) as u8, 7]))
        .collect();
    let scene = import(d.path(), &fx::glb(&fx::png(w, h, &src)));
    let t: &MeshTexture = mesh(named(&scene, "floor")).texture.as_ref().unwrap();
    assert_eq!((t.width, t.height), (16, 4));
    assert!(t.is_valid());
    assert_eq!(t.texels[0], [0, 0, 7]);
    // Column 15 of 16 is source column 11; row 3 of 4 covers source rows 3..5 (150, 200).
    assert_eq!(t.texels[3 * 16 + 15], [220, 175, 7]);
}
