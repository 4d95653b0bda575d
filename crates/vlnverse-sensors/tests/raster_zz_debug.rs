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
    println!("scene {i}: {} tris, {} objects, {} closed", mesh.triangle_count(), mesh.objects.len(), r.scene().unwrap().closed_objects());
    for (k, mut p) in common::free_poses(&scene, 8, 300 + i as u64, 1.25, 0.15).into_iter().enumerate() {
 if k < 3 { let pitch = [-0.5f32, 0.35, -1.2][k]; p.rotation = (p.quat() * glam::Quat::from_rotation_x(pitch)).to_array(); }
    let cam = CameraSpec{width:64,height:64,..CameraSpec::depth()}.camera(&p);
    let v = View{camera:cam, channels:Channels::ALL};
    let a = &r.render(&[v]).unwrap()[0];
    let b = &c.render(&[v]).unwrap()[0];
    let bad = a.depth.iter().zip(&b.depth).filter(|(x,y)| (*x-*y).abs() > 0.01).count();
    let seen_a = a.instance.iter().filter(|i| **i != 0).count();
    let seen_b = b.instance.iter().filter(|i| **i != 0).count();
    println!("bad {bad} seen {seen_a} {seen_b}");
    if bad > 0 {
      for k in 0..4096 { if (a.depth[k]-b.depth[k]).abs() > 0.01 { println!("({},{}) {} {} ids {} {}", k%64, k/64, a.depth[k], b.depth[k], a.instance[k], b.instance[k]); } }
      let rc = SceneRaycaster::new(mesh.clone()).unwrap();
      let dir = cam.pixel_ray(13, 30);
      let h = rc.cast(cam.position, dir, 10.0).unwrap();
      println!("cam {:?} rot {:?} hit {:?}", cam.position, cam.rotation, h);
      let t = h.triangle as usize;
      let tri = &mesh.positions[3*t..3*t+3];
      println!("tri {:?} normal {:?} n.(a-cam) {}", tri, mesh.normal(t), mesh.normal(t).dot(tri[0]-cam.position));
      let o = mesh.objects.iter().find(|o| o.id == 31).unwrap();
      println!("obj {:?}", o);
      for k in o.first..o.first+o.count { let k = k as usize; let tri = &mesh.positions[3*k..3*k+3]; println!("  {k} {:?} n {:?} s {}", tri, mesh.normal(k), mesh.normal(k).dot(tri[0]-cam.position)); }
      return;
    }
    }
    }
}
