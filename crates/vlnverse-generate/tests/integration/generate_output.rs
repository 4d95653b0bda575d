//! The output folder of `generate`: one writer at a time (the output lock), leftovers of an
//! interrupted run removed on resume, a failed start leaving the folder as it was, and merge
//! errors naming the user's files.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::SceneSource;
use vlnverse_generate::{merge, part_path, run, RunOptions};
use vlnverse_generate::{FolderSource, GenerateConfig, GeneratePreset, StageTimes};
use vlnverse_instructions::TemplateGenerator;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::{OutputLock, Split, Task};

fn run_on(
    source: &dyn SceneSource,
    cfg: &GenerateConfig,
    out: &Path,
    shard: (usize, usize),
    tasks: &[Task],
) -> vlnverse_score::Result<vlnverse_generate::GenerateSummary> {
    let opts = RunOptions {
        out: out.to_path_buf(),
        tasks: tasks.to_vec(),
        shard,
        occupancy: OccupancyConfig::default(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| {
        run(
            source,
            cfg,
            &opts,
            &TemplateGenerator::default(),
            &StageTimes::default(),
            &|_| {},
        )
    })
}

fn tiny(
    out: &Path,
    shard: (usize, usize),
    tasks: &[Task],
) -> vlnverse_score::Result<vlnverse_generate::GenerateSummary> {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    let source = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    run_on(&source, &cfg, out, shard, tasks)
}

/// Every file under `dir` (relative path -> bytes).
fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                // Empty folders count too (a leftover temp folder is one).
                out.insert(p.strip_prefix(root).unwrap().join(""), Vec::new());
                walk(root, &p, out);
            } else {
                out.insert(
                    p.strip_prefix(root).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                );
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn generate_on_a_locked_folder_is_refused_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("ds");
    let held = OutputLock::acquire(&out, "generate").unwrap();
    let e = tiny(&out, (0, 1), &[Task::Fine]).unwrap_err().to_string();
    assert!(
        e.contains("another job is writing into this folder")
            && e.contains(&out.display().to_string()),
        "{e}"
    );
    // Only the lock the test holds is there.
    assert_eq!(names(&out), [".lock"]);
    drop(held);
    // Once released, the folder is usable, and the lock file does not stay in the dataset.
    tiny(&out, (0, 1), &[Task::Fine]).unwrap();
    assert!(!out.join(".lock").exists());
    assert!(out.join("fine/train/train.json.gz").is_file());
}

#[test]
fn a_resumed_run_removes_leftovers_of_a_killed_run_and_gives_the_same_bytes() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    tiny(&a, (0, 1), &Task::ALL).unwrap();
    tiny(&b, (0, 1), &Task::ALL).unwrap();
    let clean = tree(&a);
    // A run killed mid-way: a part and a scene folder missing, temporary entries left.
    std::fs::remove_file(part_path(&b, "tiny_0002", Task::Coarse)).unwrap();
    std::fs::remove_dir_all(b.join("scenes/tiny_0003")).unwrap();
    let tmp_scene = b.join("scenes/.tiny_0003.tmp-4242");
    std::fs::create_dir(&tmp_scene).unwrap();
    std::fs::copy(
        a.join("scenes/tiny_0003/scene.json"),
        tmp_scene.join("scene.json"),
    )
    .unwrap();
    let images = Split::ALL
        .iter()
        .map(|s| b.join("visual_reference").join(s.name()).join("images"))
        .find(|p| p.is_dir())
        .unwrap();
    for f in [".1.png.tmp4242", "1.png.link4242", ".2.png.link4242"] {
        std::fs::write(images.join(f), b"partial").unwrap();
    }
    std::fs::write(b.join(".parts/.manifest.json.tmp-4242"), b"{").unwrap();
    std::fs::write(b.join(".parts/tiny_0001/.fine.json.tmp4242"), b"{").unwrap();
    std::fs::write(b.join("fine/train/.train.json.gz.tmp4242"), b"x").unwrap();
    std::fs::write(b.join(".generation_report.json.tmp4242"), b"{").unwrap();
    // Listing the scenes of the folder skips the temp folder (it has a scene.json).
    assert_eq!(FolderSource::new(&b.join("scenes")).unwrap().len(), 4);
    tiny(&b, (0, 1), &Task::ALL).unwrap();
    let resumed = tree(&b);
    assert_eq!(
        resumed.keys().collect::<Vec<_>>(),
        clean.keys().collect::<Vec<_>>(),
        "file lists differ"
    );
    for (k, v) in &clean {
        assert!(v == &resumed[k], "{} differs", k.display());
    }
}

#[test]
fn a_failed_scenes_from_run_leaves_the_folder_as_it_was() {
    let d = tempfile::tempdir().unwrap();
    // Three scene folders whose scene.glb is corrupt: listed, but none loads.
    let scenes = d.path().join("scenes");
    let home = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    for i in 0..3 {
        let dir = vlnverse_env::io::write_scene_dir(&scenes, &home.scene(i).unwrap(), &[]).unwrap();
        std::fs::write(dir.join("scene.glb"), b"not a glb").unwrap();
    }
    let source = FolderSource::new(&scenes).unwrap();
    let cfg = GeneratePreset::Tiny
        .config()
        .unwrap()
        .rescaled(source.len());
    // A new folder is not left behind.
    let out = d.path().join("new");
    let e = run_on(&source, &cfg, &out, (0, 1), &[Task::Fine])
        .unwrap_err()
        .to_string();
    assert!(e.contains("scene.glb"), "{e}");
    assert!(!out.exists(), "left {:?}", tree(&out).keys());
    // An existing folder keeps exactly what it held.
    let out = d.path().join("old");
    std::fs::create_dir_all(out.join("notes")).unwrap();
    std::fs::write(out.join("notes/keep.txt"), b"mine").unwrap();
    let before = tree(&out);
    run_on(&source, &cfg, &out, (0, 1), &[Task::Fine]).unwrap_err();
    assert_eq!(tree(&out), before);
}

#[test]
fn a_corrupt_merge_part_is_named_by_the_users_file() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    tiny(&a, (0, 2), &[Task::Fine]).unwrap();
    tiny(&b, (1, 2), &[Task::Fine]).unwrap();
    let bad = part_path(&b, "tiny_0001", Task::Fine);
    std::fs::write(&bad, b"{ broken").unwrap();
    let e = merge(&d.path().join("m"), &[a, b]).unwrap_err().to_string();
    assert!(e.contains(&bad.display().to_string()), "{e}");
    assert!(!e.contains("merging"), "{e}");
    assert!(!d.path().join("m").exists());
}
