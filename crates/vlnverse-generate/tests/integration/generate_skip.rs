//! Scenes that cannot provide a task's episodes (no furniture, like the imported Godot living
//! room) are skipped for that task with a reason in the report, without aborting the run; a
//! (task, split) left with no episodes at all is an error that leaves no split files. Merge
//! checks its inputs first and writes nothing on failure.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::{Scene, SceneSource};
use vlnverse_generate::{assign_scene_splits, plan};
use vlnverse_generate::{merge, run, GenerateSummary, GenerationReport, RunOptions, REPORT_FILE};
use vlnverse_generate::{GeneratePreset, StageTimes};
use vlnverse_instructions::TemplateGenerator;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_score::{Split, Task};

/// The tiny homes, with the furniture of one scene removed (walls and floors stay).
struct Stripped {
    inner: HomeGenerator,
    bare: usize,
}

impl SceneSource for Stripped {
    fn len(&self) -> usize {
        self.inner.len()
    }
    fn scene_id(&self, index: usize) -> String {
        self.inner.scene_id(index)
    }
    fn scene(&self, index: usize) -> vlnverse_env::Result<Scene> {
        let mut s = self.inner.scene(index)?;
        if index == self.bare {
            s.objects.retain(|o| o.is_structure());
        }
        Ok(s)
    }
}

fn gen(
    out: &Path,
    bare: usize,
    threads: usize,
    shard: (usize, usize),
) -> vlnverse_score::Result<GenerateSummary> {
    let source = Stripped {
        inner: HomeGenerator::from_preset(Preset::Tiny).unwrap(),
        bare,
    };
    let opts = RunOptions {
        out: out.to_path_buf(),
        tasks: Task::ALL.to_vec(),
        shard,
        occupancy: OccupancyConfig::default(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        run(
            &source,
            &GeneratePreset::Tiny.config().unwrap(),
            &opts,
            &TemplateGenerator::default(),
            &StageTimes::default(),
            &|_| {},
        )
    })
}

/// Index of the first tiny scene in `split`.
fn scene_in(split: Split) -> usize {
    let cfg = GeneratePreset::Tiny.config().unwrap();
    assign_scene_splits(&cfg)
        .iter()
        .position(|&s| s == split)
        .unwrap()
}

fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_path_buf();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

#[test]
fn a_scene_without_targets_is_skipped_for_its_tasks_and_reported() {
    let bare = scene_in(Split::Train);
    let d = tempfile::tempdir().unwrap();
    let one = d.path().join("one");
    let s = gen(&one, bare, 2, (0, 1)).unwrap();
    let cfg = GeneratePreset::Tiny.config().unwrap();
    let id = format!("tiny_{bare:04}");
    // Skipped for every task that needs target objects, not for fine paths.
    let skipped: Vec<Task> = s.skipped.iter().map(|k| k.task).collect();
    assert_eq!(
        skipped,
        vec![
            Task::Coarse,
            Task::VisualReference,
            Task::LongHorizon,
            Task::Dialogue
        ]
    );
    for k in &s.skipped {
        assert_eq!(k.scene_id, id);
        assert!(k.reason.contains("found 0"), "{}", k.reason);
        let line = k.to_string();
        assert!(
            line.starts_with(&format!("{id}: {} needs", k.task)),
            "{line}"
        );
    }
    assert!(s.skipped[2]
        .reason
        .contains("long_horizon needs 2 distinct targets"));
    // The report lists the skips; the counts are the plan's minus the bare scene's shares.
    let report: GenerationReport =
        serde_json::from_slice(&std::fs::read(one.join(REPORT_FILE)).unwrap()).unwrap();
    assert_eq!(report.skipped, s.skipped);
    let p = plan(&cfg, &Task::ALL);
    for task in Task::ALL {
        for split in Split::ALL {
            let lost: usize = if task == Task::Fine {
                0
            } else {
                p.scenes[bare]
                    .shares
                    .iter()
                    .filter(|x| x.task == task && x.split == split)
                    .map(|x| x.episodes())
                    .sum()
            };
            let eps = vlnverse_score::dataset::read_split(&one, task, split).unwrap();
            assert_eq!(eps.len(), p.episodes(task, split) - lost, "{task} {split}");
            assert_eq!(report.tasks[&task].episodes[&split], eps.len());
            assert!(eps.iter().all(|e| task == Task::Fine || e.scene_id != id));
        }
    }
    // No orphan reference images of the bare scene.
    let images: usize = Split::ALL
        .iter()
        .map(|s| {
            let dir = one.join("visual_reference").join(s.name()).join("images");
            std::fs::read_dir(dir).map(|r| r.count()).unwrap_or(0)
        })
        .sum();
    assert_eq!(
        images,
        report.tasks[&Task::VisualReference]
            .episodes
            .values()
            .sum::<usize>()
    );
    // Deterministic: 1 thread and shards + merge give the same bytes.
    let single = d.path().join("single");
    gen(&single, bare, 1, (0, 1)).unwrap();
    assert!(tree(&single) == tree(&one), "1 thread differs from 2");
    let (a, b) = (d.path().join("a"), d.path().join("b"));
    let sa = gen(&a, bare, 1, (0, 2)).unwrap();
    let sb = gen(&b, bare, 2, (1, 2)).unwrap();
    assert_eq!(sa.skipped.len() + sb.skipped.len(), 4);
    let merged = d.path().join("merged");
    merge(&merged, &[a, b]).unwrap();
    assert!(tree(&merged) == tree(&one), "shards + merge differ");
}

#[test]
fn a_split_left_without_episodes_fails_naming_it_and_writes_no_split_files() {
    // The only test scene has no furniture: the coarse-based tasks have no test episodes.
    let bare = scene_in(Split::Test);
    let d = tempfile::tempdir().unwrap();
    let e = gen(d.path(), bare, 2, (0, 1)).unwrap_err().to_string();
    let id = format!("tiny_{bare:04}");
    assert!(e.contains("coarse test"), "{e}");
    assert!(e.contains("0 episodes"), "{e}");
    assert!(e.contains(&id) && e.contains("found 0"), "{e}");
    assert!(!d.path().join(REPORT_FILE).exists());
    for task in Task::ALL {
        for split in Split::ALL {
            let f = vlnverse_score::dataset::split_path(d.path(), task, split);
            assert!(!f.exists(), "{}", f.display());
        }
    }
    assert!(
        !d.path().join("fine").exists(),
        "empty split folders are removed"
    );
}

#[test]
fn merge_names_a_missing_or_duplicate_shard_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("p0"), d.path().join("p1"));
    let bare = usize::MAX; // every scene furnished
    gen(&a, bare, 2, (0, 2)).unwrap();
    let out = d.path().join("m2");
    let e = merge(&out, std::slice::from_ref(&a))
        .unwrap_err()
        .to_string();
    assert!(e.contains("shard 1/2 is missing"), "{e}");
    assert!(e.contains("tiny_0001") && e.contains("tiny_0003"), "{e}");
    assert!(!out.exists(), "a failed merge wrote {}", out.display());
    let e = merge(&out, &[a.clone(), a.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.contains("shard 0/2 is given twice"), "{e}");
    assert!(!out.exists());
    // An unfinished shard is named with the scenes it lacks.
    gen(&b, bare, 2, (1, 2)).unwrap();
    std::fs::remove_dir_all(b.join(".parts/tiny_0003")).unwrap();
    let e = merge(&out, &[a.clone(), b.clone()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("shard 1/2 is incomplete") && e.contains("tiny_0003"),
        "{e}"
    );
    assert!(!out.exists());
    // Nothing beside `out` is left either.
    let names: Vec<String> = std::fs::read_dir(d.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    // Shard arguments count from 0.
    let e = gen(&d.path().join("x"), bare, 1, (2, 2))
        .unwrap_err()
        .to_string();
    assert!(e.contains("K counts from 0, so use 0/2 and 1/2"), "{e}");
}
