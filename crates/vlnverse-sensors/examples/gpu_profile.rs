//! Temporary profiling harness (to be removed).
#![allow(missing_docs)]
use glam::Vec3;
use std::sync::Arc;
use std::time::Instant;
use vlnverse_env::{Pose, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sensors::demo::demo_scene;
use vlnverse_sensors::{CameraSpec, Channels, GpuRenderer, Renderer, SceneMesh, View};

fn rgbd(base: &Pose) -> [View; 2] {
    [
        View { camera: CameraSpec::default().camera(base), channels: Channels { rgb: true, semantic: true, ..Default::default() } },
        View { camera: CameraSpec::depth().camera(base), channels: Channels::DEPTH },
    ]
}

fn cpu() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap();
    let f: Vec<&str> = s.rsplit(')').next().unwrap().split_whitespace().collect();
    (f[11].parse::<f64>().unwrap() + f[12].parse::<f64>().unwrap()) / 100.0
}

fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(300);
    let mut g = GpuRenderer::new().unwrap();
    eprintln!("{}", g.context().adapter_description());
    let homes = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    for scene in [demo_scene(0), homes.scene(0).unwrap()] {
        let mesh = Arc::new(SceneMesh::new(&scene).unwrap());
        g.set_scene(mesh.clone()).unwrap();
        let b = scene.bounds();
        let c = Vec3::new((b.min[0] + b.max[0]) / 2.0, 0.0, (b.min[2] + b.max[2]) / 2.0);
        let ps: Vec<Pose> = (0..64).map(|i| Pose::from_yaw(c + Vec3::new((i % 8) as f32 * 0.1, 0.0, 0.0), i as f32 * 0.4)).collect();
        for _ in 0..20 { g.render(&rgbd(&ps[0])).unwrap(); }
        let t = Instant::now();
        let c0 = cpu();
        for i in 0..n { std::hint::black_box(g.render(&rgbd(&ps[i % 64])).unwrap()); }
        let dt = t.elapsed().as_secs_f64() / n as f64;
        eprintln!("{} tris {}: frame {:.3} ms = {:.0} fps; cpu {:.3} ms/frame", scene.id, mesh.triangle_count(), dt * 1e3, 1.0 / dt, (cpu() - c0) * 1e3 / n as f64);
        let views: Vec<View> = ps[..8].iter().flat_map(rgbd).collect();
        g.render(&views).unwrap();
        let t = Instant::now();
        let c0 = cpu();
        for _ in 0..n / 8 { std::hint::black_box(g.render(&views).unwrap()); }
        let dt = t.elapsed().as_secs_f64() / (n / 8 * 8) as f64;
        eprintln!("   batched8: frame {:.3} ms = {:.0} fps; cpu {:.3} ms/frame", dt * 1e3, 1.0 / dt, (cpu() - c0) * 1e3 / (n / 8 * 8) as f64);
    }
}
