//! The light a home's `scene.glb` holds is read back instead of baked again: it equals a fresh
//! bake part for part, loading a scene folder hands it to the renderers' cache, and a file of
//! another home is not taken for this one's.

use vlnverse_env::io::glb::{read_baked_light, write_glb};
use vlnverse_env::io::{load_scene, write_scene_dir, SCENE_GLB};
use vlnverse_env::{light, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};

#[test]
fn the_light_in_scene_glb_is_the_bake_part_for_part() {
    let homes = HomeGenerator::from_preset(Preset::Vlnverse).unwrap();
    for i in 0..3 {
        let scene = homes.scene(i).unwrap();
        let fresh = light::bake_fresh(&scene);
        let glb = write_glb(&scene);
        let read = read_baked_light(&scene, &glb, "scene.glb".as_ref())
            .unwrap()
            .expect("the file fits its scene");
        assert_eq!(read.parts.len(), fresh.parts.len(), "home {i}");
        assert_eq!(read, fresh, "home {i}");
    }
}

#[test]
fn a_loaded_home_is_not_baked_again_and_another_homes_file_does_not_fit() {
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let (mut a, b) = (homes.scene(0).unwrap(), homes.scene(1).unwrap());
    // A home of its own (the light cache is shared by the tests of this binary): one object
    // moved by a millimetre.
    let last = a.objects.len() - 1;
    a.objects[last].pose.position[0] += 1e-3;
    let dir = tempfile::tempdir().unwrap();
    let folder = write_scene_dir(dir.path(), &a, &[]).unwrap();
    // Light that differs from the bake in one value, written into the file: loading must hand
    // this light on (a bake would give the other value).
    let mut marked = light::bake_fresh(&a);
    let k = marked.parts.iter().position(|p| !p.is_empty()).unwrap();
    marked.parts[k][0] = [1, 2, 3];
    let glb = vlnverse_env::io::glb::write_glb_with(&a, &marked);
    std::fs::write(folder.join(SCENE_GLB), &glb).unwrap();
    let loaded = load_scene(&folder).unwrap();
    assert_eq!(*light::bake(&loaded), marked);
    assert_eq!(
        read_baked_light(&b, &glb, "scene.glb".as_ref()).unwrap(),
        None
    );
}
