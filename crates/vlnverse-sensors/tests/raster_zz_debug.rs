mod common;
use std::sync::Arc;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::*;
#[test]
fn work() {
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let scene = homes.scene(0).unwrap();
    let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
    let mut r = RasterRenderer::new();
    r.set_scene(mesh.clone()).unwrap();
    let poses = common::free_poses(&scene, 64, 1, 1.25, 0.15);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let n: usize = std::env::var("N").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let t = std::time::Instant::now();
    for i in 0..n {
        let p = &poses[i % 64];
        let v = [View{camera: CameraSpec::default().camera(p), channels: Channels{rgb:true, semantic:true, ..Default::default()}},
                 View{camera: CameraSpec::depth().camera(p), channels: Channels::DEPTH}];
        let f = pool.install(|| r.render(&v).unwrap());
        std::hint::black_box(f);
    }
    if n > 0 { eprintln!("{:.1} us/frame", t.elapsed().as_secs_f64() * 1e6 / n as f64); }
}
