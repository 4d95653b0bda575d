//! RGB-D frames/s (RGB 224 + semantic, depth 256) of the CPU rasteriser in generated homes
//! read from scene folders, and how their triangles split between small objects (clutter:
//! boxes under 40 cm on every side) and the rest: for comparing a dataset with clutter against
//! the same seeds without it, and for profiling (`perf record` on this binary).
//!
//! `cargo run --release -p vlnverse-sensors --example clutter_rate -- [--frames N] [--reps R]
//! DATASET_OR_SCENE_DIR...` (a dataset: its `scenes/*` folders; an imported home, as
//! `xtask import` writes the AWS house, takes its poses from its navigable map). Several
//! datasets are rendered alternately, `R` times each, so that load on the machine falls on all
//! alike; CPU time per frame (all threads, from the scheduler's counts) is printed beside
//! frames/s, and a hash of every image of the first rep (to check that two builds draw the same
//! images).

use glam::Vec3;
use rand::{Rng, SeedableRng};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;
use vlnverse_env::{Pose, Scene};
use vlnverse_sensors::{CameraSpec, Channels, RasterRenderer, Renderer, SceneMesh, View};

/// `n` seeded poses on the floor of a room, camera 1.25 m up and 15 cm outside every box.
fn floor_poses(scene: &Scene, n: usize, seed: u64) -> Vec<Pose> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let b = scene.bounds();
    let mut out = Vec::new();
    for _ in 0..200_000 {
        if out.len() == n {
            break;
        }
        let p = Vec3::new(
            rng.random_range(b.min[0]..b.max[0]),
            scene.floor_height,
            rng.random_range(b.min[2]..b.max[2]),
        );
        let cam = p + Vec3::Y * 1.25;
        let blocked = scene.objects.iter().any(|o| {
            let (lo, hi) = (o.bbox.min_v() - 0.15, o.bbox.max_v() + 0.15);
            cam.cmpge(lo).all() && cam.cmple(hi).all()
        });
        if !blocked && scene.room_at(p.x, p.z).is_some() {
            out.push(Pose::from_yaw(
                p,
                rng.random_range(0.0..std::f32::consts::TAU),
            ));
        }
    }
    out
}

/// `n` seeded poses on free cells of the scene's navigable map (default occupancy settings),
/// random headings: for imported homes (the AWS house), where one box spans the whole home and
/// [`floor_poses`] finds none.
fn navigable_poses(
    scene: &Scene,
    n: usize,
    seed: u64,
) -> Result<Vec<Pose>, Box<dyn std::error::Error>> {
    let bundle = vlnverse_env::io::scene_bundle(scene.clone(), &Default::default())?;
    let nav = &bundle.maps.navigable;
    let (lo, hi) = nav.bounds();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    for _ in 0..200_000 {
        if out.len() == n {
            break;
        }
        let (x, z) = (rng.random_range(lo.x..hi.x), rng.random_range(lo.y..hi.y));
        if nav.is_free_at(glam::Vec2::new(x, z)) {
            out.push(Pose::from_yaw(
                Vec3::new(x, scene.floor_height, z),
                rng.random_range(0.0..std::f32::consts::TAU),
            ));
        }
    }
    Ok(out)
}

fn rgbd(p: &Pose) -> [View; 2] {
    [
        View {
            camera: CameraSpec::default().camera(p),
            channels: Channels {
                rgb: true,
                semantic: true,
                ..Default::default()
            },
        },
        View {
            camera: CameraSpec::depth().camera(p),
            channels: Channels::DEPTH,
        },
    ]
}

/// Scene folders of a dataset (its `scenes/*`) or the folder itself.
fn scene_dirs(p: &Path) -> Vec<PathBuf> {
    let scenes = p.join("scenes");
    if scenes.is_dir() {
        let mut v: Vec<PathBuf> = std::fs::read_dir(&scenes)
            .map(|r| {
                r.flatten()
                    .map(|e| e.path())
                    .filter(|p| p.is_dir())
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    } else {
        vec![p.to_path_buf()]
    }
}

/// CPU seconds this process has run (every thread, nanosecond counts of the scheduler in
/// `/proc/self/task/*/schedstat`; Linux, 0 elsewhere): less sensitive than wall time to other
/// work on the machine.
fn cpu_seconds() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0.0;
    };
    let ns: u64 = tasks
        .flatten()
        .filter_map(|t| std::fs::read_to_string(t.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .sum();
    ns as f64 * 1e-9
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let (mut frames, mut reps, mut sets) = (200usize, 3usize, Vec::new());
    while let Some(a) = args.next() {
        match a.as_str() {
            "--frames" => frames = args.next().ok_or("--frames N")?.parse()?,
            "--reps" => reps = args.next().ok_or("--reps R")?.parse()?,
            _ => sets.push(PathBuf::from(a)),
        }
    }
    // Per dataset: renderers and poses of each home.
    let mut fixtures = Vec::new();
    for set in &sets {
        let mut homes = Vec::new();
        let (mut tri, mut small_tri, mut small) = (0usize, 0usize, 0usize);
        for dir in scene_dirs(set) {
            let scene = vlnverse_env::io::scene_dir::load_scene(&dir)?;
            let mesh = Arc::new(SceneMesh::new(&scene)?);
            tri += mesh.triangle_count();
            for o in &mesh.objects {
                let e = o.bbox.max_v() - o.bbox.min_v();
                if e.max_element() < 0.4 {
                    small += 1;
                    small_tri += o.count as usize;
                }
            }
            let mut poses = floor_poses(&scene, frames, 1);
            if poses.is_empty() {
                poses = navigable_poses(&scene, frames, 1)?;
            }
            let mut r = RasterRenderer::new();
            r.set_scene(mesh)?;
            homes.push((r, poses));
        }
        println!(
            "{}: {} homes, {:.0} triangles a home, {:.0} small objects a home with {:.0} triangles",
            set.display(),
            homes.len(),
            tri as f64 / homes.len().max(1) as f64,
            small as f64 / homes.len().max(1) as f64,
            small_tri as f64 / homes.len().max(1) as f64,
        );
        fixtures.push((set.display().to_string(), homes));
    }
    for rep in 0..reps {
        for (name, homes) in &mut fixtures {
            let mut n = 0;
            let (t, cpu) = (Instant::now(), cpu_seconds());
            // FNV-1a over every image of the rep: equal between builds when the images are.
            let mut hash = 0xcbf2_9ce4_8422_2325u64;
            let mut eat = |b: &[u8]| {
                for v in b {
                    hash = (hash ^ *v as u64).wrapping_mul(0x100_0000_01b3);
                }
            };
            for (r, poses) in homes.iter_mut() {
                for p in poses.iter() {
                    let frames = r.render(&rgbd(p))?;
                    if rep == 0 {
                        for f in &frames {
                            eat(&f.rgb);
                            f.depth.iter().for_each(|d| eat(&d.to_le_bytes()));
                            f.semantic.iter().for_each(|c| eat(&c.to_le_bytes()));
                        }
                    }
                    std::hint::black_box(frames);
                    n += 1;
                }
            }
            if rep == 0 {
                println!("{name}: images hash {hash:016x}");
            }
            let s = t.elapsed().as_secs_f64();
            let cpu = cpu_seconds() - cpu;
            println!(
                "rep {rep} {name}: {n} frames, {:.0} frames/s, {:.3} CPU ms a frame",
                n as f64 / s,
                1e3 * cpu / n as f64
            );
        }
    }
    Ok(())
}
