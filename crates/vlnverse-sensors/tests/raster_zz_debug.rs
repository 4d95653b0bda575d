mod common;
use std::sync::Arc;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::*;
#[test]
fn dbg() {
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    for i in 0..4 {
    let scene = homes.scene(i).unwrap();
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let mut r = RasterRenderer::new();
    let mut c = RaycastRenderer::new();
    r.set_scene(mesh.clone()).unwrap();
    c.set_scene(mesh.clone()).unwrap();
    for p in common::free_poses(&scene, 8, 300 + i as u64, 1.25, 0.15) {
    let cam = CameraSpec{width:256,height:256,..CameraSpec::depth()}.camera(&p);
    let v = View{camera:cam, channels:Channels::ALL};
    let a = &r.render(&[v]).unwrap()[0];
    let b = &c.render(&[v]).unwrap()[0];
    for k in 0..a.pixels() { if a.instance[k]==b.instance[k] && a.rgb[3*k..3*k+3] != b.rgb[3*k..3*k+3] { println!("({},{}) {:?} {:?} id {} d {} {}", k%256, k/256, &a.rgb[3*k..3*k+3], &b.rgb[3*k..3*k+3], a.instance[k], a.depth[k], b.depth[k]); } }
    }
    }
}
