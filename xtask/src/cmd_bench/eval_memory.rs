//! The `eval_memory` case (issue 28 items 2 and 5): the peak resident size of an evaluation
//! over about N homes against the same number of episodes over about 3N homes.
//!
//! Each evaluation runs as a child process (this binary, `xtask evaluate --agent oracle
//! --setting strict --task coarse --sample K --threads 2 --fresh`), so that one run's caches,
//! heap and fragmentation do not carry into the other's figure. Its peak is the kernel's
//! high-water mark of the child's resident set, `VmHWM` of `/proc/<pid>/status`, read every
//! 20 ms while the child runs (the last read before it exits is the figure; a rise in its last
//! 20 ms would be missed). That is safe Rust and needs no new dependency, but it is Linux-only:
//! elsewhere the case stops with an error that says so. (`getrusage(RUSAGE_CHILDREN)` or
//! `wait4` would give the exact figure but need `unsafe` or a crate xtask does not depend on.)
//! The child runs with one glibc malloc arena and gives freed memory back every 250 ms, as
//! every `xtask evaluate` does (`malloc_arena.rs`).
//!
//! The homes: by default the case generates a small dataset of its own from the `vlnverse`
//! preset's homes (coarse task only, 4 test homes and 12 train homes, the same number of
//! episodes in both splits, seconds to generate), and evaluates the whole test split and the
//! whole train split. With `VLNVERSE_BENCH_DATASET=D` it evaluates a seeded sample of K
//! episodes of D's coarse test and coarse train splits instead (53 and 177 homes in the
//! `vlnverse` preset), spread over the split's homes.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use anyhow::Context;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_task::generate::GeneratePreset;
use vlnverse_task::{Split, Task};

use super::{HomeFolders, Repetition, Sample, Scale};

/// Test homes of the generated dataset (N); the train split has three times as many.
pub const TEST_HOMES: usize = 4;
/// Coarse episodes of each split of the generated dataset (a multiple of 3: a coarse
/// trajectory gives three episodes).
pub const EPISODES: usize = 96;

/// The generation config of the case's own dataset: the `tiny` preset's settings on the
/// `vlnverse` preset's homes, coarse only, `TEST_HOMES` test homes and three times as many
/// train homes, `EPISODES` coarse episodes in each.
pub fn dataset_config() -> anyhow::Result<vlnverse_task::generate::GenerateConfig> {
    let mut cfg = GeneratePreset::Tiny.config()?;
    cfg.name = "bench-eval-memory".into();
    cfg.scene_preset = "vlnverse".into();
    cfg.splits.train = 3 * TEST_HOMES;
    cfg.splits.val_unseen = 1;
    cfg.splits.test = TEST_HOMES;
    let coarse = &mut cfg.tasks.coarse;
    coarse.episodes.train = EPISODES;
    coarse.episodes.val_seen = 3;
    coarse.episodes.val_unseen = 3;
    coarse.episodes.test = EPISODES;
    coarse.scenes.train = 3 * TEST_HOMES;
    coarse.scenes.val_seen = 1;
    coarse.scenes.val_unseen = 1;
    coarse.scenes.test = TEST_HOMES;
    cfg.validate()?;
    Ok(cfg)
}

/// The first `4 * TEST_HOMES + 1` homes of the `vlnverse` preset (the same homes as the
/// preset's: a home's seed depends on its index only).
pub fn homes() -> anyhow::Result<HomeGenerator> {
    let mut cfg = Preset::Vlnverse.config()?;
    cfg.scenes.count = 4 * TEST_HOMES + 1;
    Ok(HomeGenerator::new(cfg)?)
}

/// The high-water mark of the resident set in a `/proc/<pid>/status` text, in bytes
/// (`VmHWM:   123456 kB`); `None` when the line is missing (a process that has exited).
pub fn vm_hwm_bytes(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut words = line["VmHWM:".len()..].split_whitespace();
    let kb: u64 = words.next()?.parse().ok()?;
    (words.next()? == "kB").then_some(kb * 1024)
}

/// Runs `cmd` to its end and returns its peak resident bytes (polled `VmHWM`).
pub fn peak_rss_of(mut cmd: Command) -> anyhow::Result<u64> {
    anyhow::ensure!(
        Path::new("/proc/self/status").exists(),
        "eval_memory reads a child's peak RSS from /proc/<pid>/status (Linux only)"
    );
    let mut child = cmd.spawn().context("starting the child process")?;
    let status_file = PathBuf::from(format!("/proc/{}/status", child.id()));
    let mut peak = 0u64;
    let exit = loop {
        if let Some(b) = std::fs::read_to_string(&status_file)
            .ok()
            .as_deref()
            .and_then(vm_hwm_bytes)
        {
            peak = peak.max(b);
        }
        if let Some(exit) = child.try_wait()? {
            break exit;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    anyhow::ensure!(exit.success(), "the child process failed ({exit})");
    anyhow::ensure!(peak > 0, "no VmHWM read from {}", status_file.display());
    Ok(peak)
}

/// One evaluation as a child process: the peak resident bytes and the distinct homes of
/// the episodes it ran (from its `episodes.csv`).
fn evaluate_child(
    dataset: &Path,
    split: Split,
    episodes: usize,
    out: &Path,
) -> anyhow::Result<(u64, usize)> {
    let exe = std::env::current_exe().context("finding the xtask binary")?;
    let log = out.with_extension("log");
    let mut cmd = Command::new(exe);
    cmd.arg("evaluate")
        .arg("--dataset")
        .arg(dataset)
        .args(["--task", "coarse", "--split", split.name()])
        .args(["--agent", "oracle", "--setting", "strict"])
        .args([
            "--sample",
            &episodes.to_string(),
            "--threads",
            "2",
            "--fresh",
        ])
        .arg("--out")
        .arg(out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&log)?);
    let peak = peak_rss_of(cmd).with_context(|| {
        let tail = std::fs::read_to_string(&log).unwrap_or_default();
        let tail: String = tail.lines().rev().take(5).collect::<Vec<_>>().join(" | ");
        format!(
            "xtask evaluate --split {} (stderr, last lines: {tail})",
            split.name()
        )
    })?;
    Ok((peak, homes_in(&out.join("episodes.csv"))?))
}

/// Distinct values of the `scene_id` column of an `episodes.csv`.
fn homes_in(csv: &Path) -> anyhow::Result<usize> {
    let text = std::fs::read_to_string(csv).with_context(|| format!("{}", csv.display()))?;
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    let col = header
        .split(',')
        .position(|c| c == "scene_id")
        .with_context(|| format!("{}: no scene_id column", csv.display()))?;
    Ok(lines
        .filter_map(|l| l.split(',').nth(col))
        .collect::<BTreeSet<_>>()
        .len())
}

pub fn eval_memory(scale: Scale) -> anyhow::Result<Repetition> {
    let root = std::env::temp_dir().join(format!("vlnverse-bench-eval-mem-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root)?;
    let folders = HomeFolders {
        root: root.clone(),
        dirs: Vec::new(),
    };
    let (dataset, episodes) = match std::env::var_os("VLNVERSE_BENCH_DATASET") {
        Some(d) => (PathBuf::from(d), scale.pick(300, 60)),
        None => {
            let dataset = root.join("dataset");
            super::generate_quietly(&homes()?, &dataset_config()?, &dataset, vec![Task::Coarse])
                .with_context(|| {
                    format!("generating the case's dataset into {}", dataset.display())
                })?;
            (dataset, scale.pick(EPISODES, EPISODES / 2))
        }
    };
    let mut rep = 0usize;
    Ok(Box::new(move || {
        rep += 1;
        let mut peaks = Vec::new();
        for split in [Split::Test, Split::Train] {
            let out = folders.root.join(format!("run-{}-{rep}", split.name()));
            let (peak, homes) = evaluate_child(&dataset, split, episodes, &out)
                .with_context(|| format!("dataset {}", dataset.display()))?;
            let _ = std::fs::remove_dir_all(&out);
            peaks.push((split, peak, homes));
        }
        let [(_, test, test_homes), (_, train, train_homes)] = peaks[..] else {
            unreachable!("two splits")
        };
        let detail = |homes: usize, split: Split| {
            format!(
                "oracle, coarse {}, {episodes} episodes over {homes} homes, 2 threads, child VmHWM",
                split.name()
            )
        };
        Ok(vec![
            Sample::size(
                "eval_memory/peak_n_homes",
                test as usize,
                1,
                "run",
                detail(test_homes, Split::Test),
            ),
            Sample::size(
                "eval_memory/peak_3n_homes",
                train as usize,
                1,
                "run",
                detail(train_homes, Split::Train),
            ),
            Sample::ratio(
                "eval_memory/ratio_3n_over_n",
                train as f64 / test as f64,
                "peak over 3N homes / peak over N homes (issue 28: within 1.10)".into(),
            ),
        ])
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vm_hwm_is_read_in_bytes() {
        let status = "Name:\txtask\nVmPeak:\t  900 kB\nVmHWM:\t  123456 kB\nVmRSS:\t 100 kB\n";
        assert_eq!(vm_hwm_bytes(status), Some(123_456 * 1024));
        assert_eq!(vm_hwm_bytes("Name:\txtask\nState:\tZ (zombie)\n"), None);
        assert_eq!(vm_hwm_bytes("VmHWM:\t12 MB\n"), None);
    }

    #[test]
    fn a_childs_peak_is_at_least_what_it_touched() {
        if !Path::new("/proc/self/status").exists() {
            return;
        }
        // A child that holds ~64 MB resident (a shell variable of that size).
        let mut cmd = Command::new("sh");
        cmd.args([
            "-c",
            "x=$(head -c 67108864 /dev/zero | tr '\\0' a); sleep 0.2",
        ]);
        let peak = peak_rss_of(cmd).unwrap();
        assert!(peak >= 64 << 20, "peak {peak} B");
        let mut failing = Command::new("sh");
        failing.args(["-c", "exit 3"]);
        assert!(peak_rss_of(failing).is_err());
    }

    #[test]
    fn the_generated_dataset_has_three_times_the_homes_in_train() {
        let cfg = dataset_config().unwrap();
        assert_eq!(cfg.tasks.coarse.scenes.test, TEST_HOMES);
        assert_eq!(cfg.tasks.coarse.scenes.train, 3 * TEST_HOMES);
        assert_eq!(
            cfg.tasks.coarse.episodes.train,
            cfg.tasks.coarse.episodes.test
        );
        assert_eq!(cfg.splits.total(), 4 * TEST_HOMES + 1);
        assert_eq!(
            vlnverse_env::SceneSource::len(&homes().unwrap()),
            cfg.splits.total()
        );
    }
}
