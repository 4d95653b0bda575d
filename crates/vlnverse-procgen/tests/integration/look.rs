//! A generated home's `scene.glb` carries its look: textured materials, texture coordinates
//! and baked light, readable by any glTF reader (here the `gltf` crate).

use vlnverse_env::io::glb::write_glb;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};

#[test]
fn scene_glb_has_materials_texture_coordinates_and_baked_light() {
    let scene = HomeGenerator::from_preset(Preset::Tiny)
        .unwrap()
        .scene(0)
        .unwrap();
    let bytes = write_glb(&scene);
    let (doc, buffers, images) = gltf::import_slice(&bytes).expect("scene.glb imports");
    assert!(doc.extensions_used().any(|e| e == "KHR_materials_unlit"));
    // Several procedural textures (walls, floors, furniture), each a real image.
    assert!(images.len() >= 3, "{} images", images.len());
    for im in &images {
        assert_eq!((im.width, im.height), (128, 128));
    }
    let names: Vec<String> = doc
        .materials()
        .filter_map(|m| m.name().map(str::to_owned))
        .collect();
    for surface in ["plaster", "wood"] {
        assert!(
            names.iter().any(|n| n.starts_with(surface)),
            "no {surface} material in {names:?}"
        );
    }
    let (mut prims, mut lights) = (0, std::collections::BTreeSet::new());
    for mesh in doc.meshes() {
        for p in mesh.primitives() {
            prims += 1;
            let m = p.material();
            let tex = m.pbr_metallic_roughness().base_color_texture();
            assert!(tex.is_some(), "material {:?} has no texture", m.name());
            let r = p.reader(|b| Some(&buffers[b.index()]));
            let n = r.read_positions().unwrap().count();
            let uv: Vec<[f32; 2]> = r.read_tex_coords(0).unwrap().into_f32().collect();
            assert_eq!(uv.len(), n);
            assert!(uv.iter().flatten().all(|x| x.is_finite()));
            let c: Vec<[u8; 4]> = r.read_colors(0).unwrap().into_rgba_u8().collect();
            assert_eq!(c.len(), n);
            lights.extend(c.iter().map(|c| c[1]));
        }
    }
    assert!(prims > 20);
    // Light varies (shadow, occlusion, falloff), it is not one flat value.
    assert!(lights.len() > 50, "{} distinct light levels", lights.len());
}
