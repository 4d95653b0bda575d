//! The dataset pipeline: scenes in parallel (maps, graph, sampling, instructions, images), one
//! part file per scene and task, then the split files assembled from the parts in scene order.
//!
//! Layout of a dataset folder `DIR`:
//! - `DIR/scenes/<scene_id>/...`: complete scene folders (the env crate's bundle).
//! - `DIR/.parts/manifest.json`: the config, the tasks and the scene ids of the run.
//! - `DIR/.parts/<scene_id>/<task>.json`: the episodes of one scene and task (written
//!   atomically, last, so a present part means that scene and task are done; a rerun skips it).
//! - `DIR/<task>/<split>/<split>.json.gz`: the split files; `DIR/visual_reference/<split>/
//!   images/<episode_id>.png`: reference images.
//! - `DIR/generation_report.json`: counts per task and split, rejections by reason.
//!
//! Episode ids come from the plan, so a shard (`scene index % N == K`) writes exactly the parts
//! a single run would, and [`merge`] joins shard folders into the bytes of a single run.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use vlnverse_env::io::{is_complete_scene_dir, load_scene};
use vlnverse_env::occupancy::{build_maps, OccupancyConfig};
use vlnverse_env::scene_graph::SceneGraph;
use vlnverse_env::{Scene, SceneSource};

use super::episodes::{ScenePart, SceneTaskContext, Stage, StageTimes};
use super::presets::GenerateConfig;
use super::sampler::{Reject, SceneSampler};
use super::seed::derive_seed;
use super::splits::{plan, Plan};
use crate::dataset::{write_atomic, write_split};
use crate::episode::{Episode, Split, Task};
use crate::error::{Result, TaskError};
use crate::instructions::InstructionGenerator;

/// Folder of the part files.
pub const PARTS_DIR: &str = ".parts";
/// Manifest of a run inside [`PARTS_DIR`].
pub const MANIFEST_FILE: &str = "manifest.json";
/// The generation report at the top of a dataset folder.
pub const REPORT_FILE: &str = "generation_report.json";

/// What a dataset folder was generated from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The config (after rescaling to the scene count).
    pub config: GenerateConfig,
    /// The tasks generated.
    pub tasks: Vec<Task>,
    /// Scene ids by index.
    pub scene_ids: Vec<String>,
}

/// Options of a run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Dataset folder.
    pub out: PathBuf,
    /// Tasks to generate.
    pub tasks: Vec<Task>,
    /// `(k, n)`: handle the scenes with `index % n == k`; split files are assembled only when
    /// `n == 1` (else by [`merge`]).
    pub shard: (usize, usize),
    /// Occupancy settings of the maps.
    pub occupancy: OccupancyConfig,
}

/// What a run did.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    /// Scenes processed in this shard.
    pub scenes_done: usize,
    /// Scenes whose parts were all present already.
    pub scenes_skipped: usize,
    /// Episodes in the assembled split files (0 when not assembled).
    pub episodes: usize,
    /// Whether split files were written.
    pub assembled: bool,
}

/// Path of a part file.
pub fn part_path(out: &Path, scene_id: &str, task: Task) -> PathBuf {
    out.join(PARTS_DIR)
        .join(scene_id)
        .join(format!("{}.json", task.name()))
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T> {
    let raw = std::fs::read(path).map_err(|e| TaskError::io(path, e))?;
    serde_json::from_slice(&raw)
        .map_err(|e| TaskError::parse(path, format!("line {}", e.line()), e))
}

fn to_json<T: Serialize>(v: &T, what: &str) -> Result<Vec<u8>> {
    serde_json::to_vec(v).map_err(|e| TaskError::invalid(what, "<value>", e.to_string()))
}

/// Read a manifest.
pub fn read_manifest(dir: &Path) -> Result<Manifest> {
    read_json(&dir.join(PARTS_DIR).join(MANIFEST_FILE))
}

/// Generate (this shard of) a dataset from `source` with `cfg` (whose scene count must equal
/// the source's; see [`GenerateConfig::rescaled`]). `on_scene` is called once per scene of the
/// shard, from worker threads. Runs on the current rayon pool; output does not depend on its
/// size.
pub fn run(
    source: &dyn SceneSource,
    cfg: &GenerateConfig,
    opts: &RunOptions,
    instructions: &dyn InstructionGenerator,
    times: &StageTimes,
    on_scene: &(dyn Fn(&str) + Sync),
) -> Result<RunSummary> {
    cfg.validate()?;
    let (k, n) = opts.shard;
    if n == 0 || k >= n {
        return Err(TaskError::invalid(
            "shard",
            format!("{k}/{n}"),
            "expected K/N with 0 <= K < N",
        ));
    }
    if source.len() != cfg.splits.total() {
        return Err(TaskError::invalid(
            "splits",
            cfg.splits.total(),
            format!(
                "the config's splits need that many scenes but the source has {}",
                source.len()
            ),
        ));
    }
    let mut tasks = opts.tasks.clone();
    tasks.sort_unstable();
    tasks.dedup();
    let manifest = Manifest {
        config: cfg.clone(),
        tasks: tasks.clone(),
        scene_ids: (0..source.len()).map(|i| source.scene_id(i)).collect(),
    };
    let mpath = opts.out.join(PARTS_DIR).join(MANIFEST_FILE);
    if mpath.exists() {
        let old: Manifest = read_json(&mpath)?;
        if old != manifest {
            return Err(TaskError::invalid(
                "out",
                opts.out.display(),
                "holds parts of a different config, task list or scene set; use a fresh folder",
            ));
        }
    } else {
        write_atomic(&mpath, &to_json(&manifest, "manifest")?)?;
    }
    let plan = plan(cfg, &tasks);
    let mine: Vec<usize> = (0..source.len()).filter(|i| i % n == k).collect();
    let skipped: Vec<bool> = mine
        .par_iter()
        .map(|&i| -> Result<bool> {
            let id = &manifest.scene_ids[i];
            let todo: Vec<Task> = tasks
                .iter()
                .copied()
                .filter(|&t| !part_path(&opts.out, id, t).exists())
                .collect();
            let skip = todo.is_empty() && is_complete_scene_dir(opts.out.join("scenes").join(id));
            if !skip {
                generate_scene(source, i, cfg, &plan, &todo, opts, instructions, times)?;
            }
            on_scene(id);
            Ok(skip)
        })
        .collect::<Result<Vec<bool>>>()?;
    let mut summary = RunSummary {
        scenes_done: mine.len(),
        scenes_skipped: skipped.iter().filter(|&&s| s).count(),
        ..RunSummary::default()
    };
    if n == 1 {
        summary.episodes = times.time(Stage::Writing, || assemble(&opts.out, &manifest))?;
        summary.assembled = true;
    }
    Ok(summary)
}

/// Generate one scene: the scene folder (when missing) and the parts of `todo`.
fn generate_scene(
    source: &dyn SceneSource,
    index: usize,
    cfg: &GenerateConfig,
    plan: &Plan,
    todo: &[Task],
    opts: &RunOptions,
    instructions: &dyn InstructionGenerator,
    times: &StageTimes,
) -> Result<()> {
    let scene: Scene = times.time(Stage::Scenes, || source.scene(index))?;
    let (maps, graph) = times.time(Stage::Maps, || -> Result<_> {
        Ok((
            build_maps(&scene, &opts.occupancy)?,
            SceneGraph::build(&scene),
        ))
    })?;
    let scenes_dir = opts.out.join("scenes");
    let bundle = vlnverse_env::io::SceneBundle { scene, maps, graph };
    if !is_complete_scene_dir(scenes_dir.join(&bundle.scene.id)) {
        times.time(Stage::Writing, || bundle.write(&scenes_dir))?;
    }
    generate_parts(
        &bundle.scene,
        &bundle.maps,
        &bundle.graph,
        index,
        cfg,
        plan,
        todo,
        opts,
        instructions,
        times,
    )
}

fn generate_parts(
    scene: &Scene,
    maps: &vlnverse_env::occupancy::OccupancyMaps,
    graph: &SceneGraph,
    index: usize,
    cfg: &GenerateConfig,
    plan: &Plan,
    todo: &[Task],
    opts: &RunOptions,
    instructions: &dyn InstructionGenerator,
    times: &StageTimes,
) -> Result<()> {
    if todo.is_empty() {
        return Ok(());
    }
    let sampler = times.time(Stage::Sampling, || {
        SceneSampler::new(
            scene,
            maps,
            graph,
            &cfg.sampling,
            derive_seed(cfg.seed, &[index as u64, 0x007A_59E7]),
        )
    });
    let ctx = SceneTaskContext {
        sampler: &sampler,
        scene_index: index,
        config: cfg,
        instructions,
        out: &opts.out,
        times,
    };
    for &task in todo {
        let mut part = ScenePart {
            scene_id: scene.id.clone(),
            task,
            episodes: BTreeMap::new(),
            rejections: sampler.target_rejections.clone(),
        };
        for share in plan.scenes[index].shares.iter().filter(|s| s.task == task) {
            let (eps, rej) = ctx.generate_share(share)?;
            for (r, c) in rej {
                *part.rejections.entry(r).or_default() += c;
            }
            part.episodes.insert(share.split, eps);
        }
        times.time(Stage::Writing, || -> Result<()> {
            write_atomic(
                &part_path(&opts.out, &scene.id, task),
                &to_json(&part, "part")?,
            )
        })?;
    }
    Ok(())
}

/// Counts of one task in the generation report.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TaskReport {
    /// Episodes per split.
    pub episodes: BTreeMap<Split, usize>,
    /// Scenes with at least one episode, per split.
    pub scenes: BTreeMap<Split, usize>,
    /// Rejected samples by reason, over all scenes.
    pub rejections: BTreeMap<Reject, u64>,
}

/// `generation_report.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GenerationReport {
    /// Config name.
    pub name: String,
    /// Scenes in the dataset.
    pub scenes: usize,
    /// Per task.
    pub tasks: BTreeMap<Task, TaskReport>,
}

/// Write the split files and the report of a dataset folder from its parts (every scene's
/// parts must be present); returns the number of episodes.
pub fn assemble(out: &Path, manifest: &Manifest) -> Result<usize> {
    let mut report = GenerationReport {
        name: manifest.config.name.clone(),
        scenes: manifest.scene_ids.len(),
        tasks: BTreeMap::new(),
    };
    let mut total = 0;
    for &task in &manifest.tasks {
        let mut by_split: BTreeMap<Split, Vec<Episode>> = BTreeMap::new();
        let mut tr = TaskReport::default();
        for id in &manifest.scene_ids {
            let path = part_path(out, id, task);
            if !path.exists() {
                return Err(TaskError::invalid(
                    "parts",
                    path.display(),
                    "missing: generate or merge every shard before assembling",
                ));
            }
            let part: ScenePart = read_json(&path)?;
            if part.scene_id != *id || part.task != task {
                return Err(TaskError::parse(
                    &path,
                    "scene_id/task",
                    "part of another scene or task",
                ));
            }
            for (r, c) in part.rejections {
                *tr.rejections.entry(r).or_default() += c;
            }
            for (split, eps) in part.episodes {
                if !eps.is_empty() {
                    *tr.scenes.entry(split).or_default() += 1;
                }
                by_split.entry(split).or_default().extend(eps);
            }
        }
        for split in Split::ALL {
            let eps = by_split.remove(&split).unwrap_or_default();
            tr.episodes.insert(split, eps.len());
            total += eps.len();
            write_split(out, task, split, &eps)?;
        }
        report.tasks.insert(task, tr);
    }
    let mut bytes = serde_json::to_vec_pretty(&report)
        .map_err(|e| TaskError::invalid("report", "<report>", e.to_string()))?;
    bytes.push(b'\n');
    write_atomic(&out.join(REPORT_FILE), &bytes)?;
    Ok(total)
}

fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    let entries = std::fs::read_dir(from).map_err(|e| TaskError::io(from, e))?;
    std::fs::create_dir_all(to).map_err(|e| TaskError::io(to, e))?;
    let mut names: Vec<_> = entries.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    names.sort();
    for p in names {
        let Some(name) = p.file_name() else { continue };
        let dest = to.join(name);
        if p.is_dir() {
            copy_tree(&p, &dest)?;
        } else if !dest.exists() {
            std::fs::copy(&p, &dest).map_err(|e| TaskError::io(&p, e))?;
        }
    }
    Ok(())
}

/// Join shard folders into `out` (scene folders, parts, reference images) and assemble the
/// split files; the result is byte-identical to a single run. Every part folder must come from
/// the same config, tasks and scenes. Returns the number of episodes.
pub fn merge(out: &Path, parts: &[PathBuf]) -> Result<usize> {
    let Some(first) = parts.first() else {
        return Err(TaskError::invalid(
            "parts",
            "none",
            "give at least one part folder",
        ));
    };
    let manifest = read_manifest(first)?;
    for p in parts {
        let m = read_manifest(p)?;
        if m != manifest {
            return Err(TaskError::invalid(
                "parts",
                p.display(),
                format!(
                    "generated with another config, task list or scene set than {}",
                    first.display()
                ),
            ));
        }
    }
    let mpath = out.join(PARTS_DIR).join(MANIFEST_FILE);
    if mpath.exists() && read_manifest(out)? != manifest {
        return Err(TaskError::invalid(
            "out",
            out.display(),
            "holds a dataset of another config; use a fresh folder",
        ));
    }
    for p in parts {
        for sub in ["scenes", PARTS_DIR] {
            if p.join(sub).is_dir() {
                copy_tree(&p.join(sub), &out.join(sub))?;
            }
        }
        for split in Split::ALL {
            let imgs = p
                .join(Task::VisualReference.name())
                .join(split.name())
                .join("images");
            if imgs.is_dir() {
                copy_tree(
                    &imgs,
                    &out.join(Task::VisualReference.name())
                        .join(split.name())
                        .join("images"),
                )?;
            }
        }
    }
    assemble(out, &manifest)
}

/// Scenes from a folder of scene folders (`<dir>/<id>/scene.json` + `scene.glb`, e.g. written
/// by `cargo xtask import` or `cargo xtask scenes`), in sorted order.
pub struct FolderSource {
    dirs: Vec<PathBuf>,
}

impl FolderSource {
    /// Every complete scene folder directly under `dir`, sorted by name.
    pub fn new(dir: &Path) -> Result<Self> {
        let entries = std::fs::read_dir(dir).map_err(|e| TaskError::io(dir, e))?;
        let mut dirs: Vec<PathBuf> = entries
            .filter_map(|e| e.ok())
            .map(|e| e.path())
            .filter(|p| p.join("scene.json").is_file())
            .collect();
        dirs.sort();
        if dirs.is_empty() {
            return Err(TaskError::invalid(
                "scenes-from",
                dir.display(),
                "no scene folders (`<id>/scene.json`) in it",
            ));
        }
        Ok(FolderSource { dirs })
    }
}

impl SceneSource for FolderSource {
    fn len(&self) -> usize {
        self.dirs.len()
    }

    fn scene_id(&self, index: usize) -> String {
        self.dirs[index]
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    }

    fn scene(&self, index: usize) -> vlnverse_env::Result<Scene> {
        let mut s = load_scene(&self.dirs[index])?;
        // The folder name is the id datasets refer to.
        s.id = self.scene_id(index);
        Ok(s)
    }
}

/// Wall-clock helper for callers that print a breakdown.
pub fn elapsed_s(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}
