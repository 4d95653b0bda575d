//! Memory per environment, measured with a counting global allocator: builds the physics
//! world of procgen's `tiny` scene 0 once, then resets 64 environments sharing it.
//!
//! `cargo run --release -p vlnverse-sim --example memory`
#![allow(unsafe_code)] // a GlobalAlloc wrapper is unsafe by definition

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};
use std::sync::Arc;
use vlnverse_env::{Pose, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_sim::{PhysicsScene, RapierSimulator, SimConfig, Simulator};

struct Counting;
static LIVE: AtomicIsize = AtomicIsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        LIVE.fetch_add(l.size() as isize, Ordering::Relaxed);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size() as isize, Ordering::Relaxed);
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static A: Counting = Counting;

fn live() -> f64 {
    LIVE.load(Ordering::Relaxed) as f64 / (1024.0 * 1024.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = HomeGenerator::from_preset(Preset::Tiny)?.scene(0)?;
    let cfg = SimConfig::default();
    let m0 = live();
    let physics = Arc::new(PhysicsScene::build(&scene, &cfg.agent)?);
    let m1 = live();
    let start = Pose::from_yaw(glam::Vec3::ZERO, 0.0);
    let n = 64;
    let mut envs = Vec::new();
    for _ in 0..n {
        let mut s = RapierSimulator::new(cfg.clone())?;
        s.reset_in(Arc::clone(&physics), start)?;
        envs.push(s);
    }
    let m2 = live();
    let mut own = RapierSimulator::new(cfg.clone())?;
    own.reset(&scene, start)?;
    let m3 = live();
    let snap = own.snapshot();
    let m4 = live();
    println!(
        "scene {}: {} objects, {} colliders",
        scene.id,
        scene.objects.len(),
        physics.collider_count()
    );
    println!("shared physics world:            {:8.3} MiB", m1 - m0);
    println!(
        "  the physics cache's estimate:   {:8.3} MiB",
        PhysicsScene::estimated_bytes(&scene) as f64 / (1024.0 * 1024.0)
    );
    println!(
        "per environment (shared world):  {:8.3} MiB",
        (m2 - m1) / n as f64
    );
    println!("one environment, own world:      {:8.3} MiB", m3 - m2);
    println!("one snapshot:                    {:8.3} MiB", m4 - m3);
    drop((envs, snap));
    Ok(())
}
