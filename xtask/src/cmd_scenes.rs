//! `cargo xtask scenes`: generate procedural homes and write one complete folder per scene
//! (`scene.glb`, `scene.json`, `scene_graph.json`, `occupancy.{pgm,yaml}`,
//! `navigable.{pgm,yaml}`), in parallel, resuming where an earlier run stopped.
//!
//! The output folder is locked for the job (a second job on it is refused); temporary entries
//! an interrupted run left are removed first; complete scene folders made with another seed
//! are refused (`--force` replaces them) instead of being kept as if they were this run's.

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::time::Instant;
use vlnverse_env::io::{
    is_complete_scene_dir, remove_temp_leftovers, write_source_bundles, BundleOutcome, SCENE_JSON,
};
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::SceneSource;
use vlnverse_procgen::{scene_seed, HomeGenerator, Preset, ProcgenConfig};
use vlnverse_task::OutputLock;

/// Arguments of `cargo xtask scenes`.
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Shipped preset: `tiny` (a handful of homes) or `vlnverse` (the 263-home world).
    #[arg(long, default_value = "tiny")]
    pub preset: Preset,
    /// A procgen TOML config to use instead of the preset.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Override the base seed of the config.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Only the first N scenes.
    #[arg(long)]
    pub count: Option<usize>,
    /// Worker threads (default: all cores). Output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Output folder; scene `<id>` goes to `<out>/<id>/`.
    #[arg(long, default_value = "datasets/scenes")]
    pub out: PathBuf,
    /// Rewrite scenes whose folder is already complete.
    #[arg(long)]
    pub force: bool,
}

/// What a run did.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Scenes written.
    pub written: usize,
    /// Complete scenes left alone.
    pub skipped: usize,
    /// Total navigable area of the written scenes (m^2).
    pub navigable_m2: f64,
    /// Seconds taken.
    pub seconds: f64,
}

/// Generate the scenes; returns what happened (used by `run` and the tests).
pub fn generate(args: &Args, show_progress: bool) -> anyhow::Result<Summary> {
    let start = Instant::now();
    let mut config = match &args.config {
        Some(p) => ProcgenConfig::from_toml_file(p)?,
        None => args.preset.config()?,
    };
    if let Some(seed) = args.seed {
        config.scenes.seed = seed;
    }
    if let Some(n) = args.count {
        config.scenes.count = config.scenes.count.min(n);
    }
    let generator = HomeGenerator::new(config)?;
    let created = !args.out.exists();
    let lock = OutputLock::acquire(&args.out, "scenes")?;
    let result = generate_locked(args, &generator, show_progress, start);
    // The folder holds only scene folders once the job is over.
    let _ = std::fs::remove_file(lock.path());
    drop(lock);
    if created && result.is_err() {
        let _ = std::fs::remove_dir(&args.out);
    }
    result
}

/// Base seed of a procedural scene from its scene seed and index: the inverse of
/// [`scene_seed`] (a bijection of the SplitMix64 finaliser).
pub fn base_seed_of(seed: u64, index: usize) -> u64 {
    fn unshift(mut y: u64, k: u32) -> u64 {
        // Inverse of x ^ (x >> k).
        let mut x = y;
        for _ in 0..64 / k {
            y >>= k;
            x ^= y;
        }
        x
    }
    fn inverse(a: u64) -> u64 {
        // Newton's iteration for the inverse of an odd number modulo 2^64.
        let mut x = a;
        for _ in 0..6 {
            x = x.wrapping_mul(2u64.wrapping_sub(a.wrapping_mul(x)));
        }
        x
    }
    let mut z = unshift(seed, 31);
    z = z.wrapping_mul(inverse(0x94D0_49BB_1331_11EB));
    z = unshift(z, 27);
    z = z.wrapping_mul(inverse(0xBF58_476D_1CE4_E5B9));
    z = unshift(z, 30);
    z.wrapping_sub(0x9E37_79B9_7F4A_7C15)
        .wrapping_sub((index as u64).wrapping_mul(0xD1B5_4A32_D192_ED03))
}

/// Refuse an output folder whose complete scene folders (those a run would skip) were made
/// with another seed than `generator`'s, naming the folder, the old and the new seed.
pub fn check_existing_seeds(generator: &HomeGenerator, out: &Path) -> anyhow::Result<()> {
    #[derive(serde::Deserialize)]
    struct Head {
        source: Option<String>,
        seed: Option<u64>,
    }
    let seed = generator.config().scenes.seed;
    for i in 0..generator.len() {
        let dir = out.join(generator.scene_id(i));
        if !is_complete_scene_dir(&dir) {
            continue;
        }
        let json = dir.join(SCENE_JSON);
        let raw = std::fs::read(&json).with_context(|| format!("reading {}", json.display()))?;
        let head: Head = serde_json::from_slice(&raw)
            .with_context(|| format!("{}: invalid scene", json.display()))?;
        let fix = "use another --out folder, or --force to replace its scenes";
        match head.seed {
            Some(s) if s == scene_seed(seed, i) => {}
            Some(s) => anyhow::bail!(
                "invalid `--out` = {}: holds scenes made with seed {} ({}: field `seed` = {s}), \
                 not seed {seed}; {fix}",
                out.display(),
                base_seed_of(s, i),
                json.display()
            ),
            None => anyhow::bail!(
                "invalid `--out` = {}: holds scene {} that is not a procedural home ({}: field \
                 `source` = `{}`, no `seed`), not one made with seed {seed}; {fix}",
                out.display(),
                generator.scene_id(i),
                json.display(),
                head.source.unwrap_or_default()
            ),
        }
    }
    Ok(())
}

fn generate_locked(
    args: &Args,
    generator: &HomeGenerator,
    show_progress: bool,
    start: Instant,
) -> anyhow::Result<Summary> {
    // Under the lock no other job writes here: dot-entries like `.<id>.tmp-<pid>/` are leftovers.
    for p in remove_temp_leftovers(&args.out)? {
        tracing::info!("removed {} (left by an interrupted run)", p.display());
    }
    if !args.force {
        check_existing_seeds(generator, &args.out)?;
    }
    let occupancy = OccupancyConfig::default();
    let indices: Vec<usize> = (0..generator.len()).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")?;
    let pb = crate::progress::bar(indices.len() as u64, "scenes");
    if !show_progress {
        pb.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let outcomes = pool.install(|| {
        write_source_bundles(
            generator,
            &indices,
            &args.out,
            &occupancy,
            args.force,
            &|_| pb.inc(1),
        )
    });
    pb.finish_and_clear();
    let outcomes = outcomes?;
    let mut s = Summary {
        written: 0,
        skipped: 0,
        navigable_m2: 0.0,
        seconds: 0.0,
    };
    for o in &outcomes {
        match o {
            BundleOutcome::Written { navigable_m2, .. } => {
                s.written += 1;
                s.navigable_m2 += *navigable_m2 as f64;
            }
            BundleOutcome::Skipped { .. } => s.skipped += 1,
        }
    }
    s.seconds = start.elapsed().as_secs_f64();
    Ok(s)
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    let s = generate(&args, true)?;
    let threads = args.threads.unwrap_or_else(rayon::current_num_threads);
    println!(
        "scenes: {} written, {} complete skipped -> {} ({:.2} s, {}, mean navigable {:.1} m2)",
        s.written,
        s.skipped,
        args.out.display(),
        s.seconds,
        crate::progress::threads(threads),
        if s.written > 0 {
            s.navigable_m2 / s.written as f64
        } else {
            0.0
        }
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(seed: u64, out: &Path, force: bool) -> Args {
        Args {
            preset: Preset::Tiny,
            config: None,
            seed: Some(seed),
            count: Some(1),
            threads: Some(1),
            out: out.to_path_buf(),
            force,
        }
    }

    #[test]
    fn base_seed_inverts_scene_seed() {
        for (base, i) in [
            (7u64, 0usize),
            (8, 3),
            (u64::MAX, 262),
            (0x1234_5678_9abc, 41),
        ] {
            assert_eq!(base_seed_of(scene_seed(base, i), i), base);
        }
    }

    /// A folder of seed-7 homes is refused for seed 8, naming the folder and both seeds, and
    /// left alone; the same seed resumes; `--force` replaces the homes.
    #[test]
    fn scenes_over_a_folder_of_another_seed_are_refused() {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("scenes");
        let s = generate(&args(7, &out, false), false).unwrap();
        assert_eq!(s.written, 1);
        assert!(!out.join(".lock").exists());
        let json = std::fs::read(out.join("tiny_0000/scene.json")).unwrap();
        let e = format!("{:#}", generate(&args(8, &out, false), false).unwrap_err());
        assert!(
            e.contains(&out.display().to_string())
                && e.contains("seed 7")
                && e.contains("not seed 8"),
            "{e}"
        );
        assert_eq!(
            std::fs::read(out.join("tiny_0000/scene.json")).unwrap(),
            json
        );
        assert!(!out.join(".lock").exists());
        let s = generate(&args(7, &out, false), false).unwrap();
        assert_eq!((s.written, s.skipped), (0, 1));
        let s = generate(&args(8, &out, true), false).unwrap();
        assert_eq!(s.written, 1);
        generate(&args(8, &out, false), false).unwrap();
    }

    /// A second job on the folder is refused while the first holds it.
    #[test]
    fn scenes_on_a_locked_folder_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let out = d.path().join("scenes");
        let held = OutputLock::acquire(&out, "scenes").unwrap();
        let e = format!("{:#}", generate(&args(7, &out, false), false).unwrap_err());
        assert!(e.contains("another job is writing"), "{e}");
        assert!(!out.join("tiny_0000").exists());
        drop(held);
    }
}
