//! The export job: plan the teacher trajectories, render them in parallel into one data file
//! per episode, then write the metadata. Resumable (finished episodes are kept), atomic (every
//! file is written under a temporary name and renamed) and deterministic (the same bytes on
//! any number of threads).

use std::collections::{BTreeMap, HashMap};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use serde_json::json;
use sha2::{Digest, Sha256};
use vlnverse_sensors::{Observation, PanoramaSpec, RigConfig, SensorRig, SensorSpec};
use vlnverse_task::dataset;
use vlnverse_task::eval::{check_split, sim_config, MAX_THREADS};
use vlnverse_task::eval::{
    configured_renderer, rapier_simulator, ActionSpace, EpisodeSettings, EvalConfig, SceneCache,
    Setting,
};
use vlnverse_task::vocab::{Vocab, VOCAB_FILE};
use vlnverse_task::{Episode, OutputLock, Split, Task};

use crate::error::{ExportError, Result};
use crate::lerobot::{self, keys, DType, EpisodeMeta, Feature};
use crate::stats::{PixelAccumulator, Stats};
use crate::table::Table;
use crate::teacher::{self, Step, Worker};

/// Where unfinished work and per-episode summaries live inside the output folder.
pub const PARTS_DIR: &str = ".parts";
/// The Python env's default `instruction_length` (crates/vlnverse-py/src/env.rs).
pub const INSTRUCTION_LENGTH: usize = 200;
/// Bump when the bytes written for the same request change.
const FORMAT_REVISION: u32 = 2;

/// What to export.
#[derive(Debug, Clone)]
pub struct ExportRequest {
    /// Dataset folder (`DIR/<task>/<split>/<split>.json.gz`, `DIR/scenes/`, `DIR/vocab.txt`).
    pub dataset: PathBuf,
    /// Task.
    pub task: Task,
    /// Split.
    pub split: Split,
    /// Output folder (the LeRobot dataset root).
    pub out: PathBuf,
    /// Only the first N episodes of the split (file order).
    pub episodes: Option<usize>,
    /// Protocol seed (sensor noise, as `evaluate --seed`).
    pub seed: u64,
    /// Also render the 12-view panorama.
    pub panorama: bool,
    /// Worker threads (default: all cores). The output does not depend on it.
    pub threads: Option<usize>,
    /// Evaluation setting the teacher acts under (Tel-Hop or Strict).
    pub setting: Setting,
}

impl ExportRequest {
    /// A request with the defaults: every episode, seed 0, no panorama, Tel-Hop.
    pub fn new(
        dataset: impl Into<PathBuf>,
        task: Task,
        split: Split,
        out: impl Into<PathBuf>,
    ) -> Self {
        ExportRequest {
            dataset: dataset.into(),
            task,
            split,
            out: out.into(),
            episodes: None,
            seed: 0,
            panorama: false,
            threads: None,
            setting: Setting::Telhop,
        }
    }
}

/// The stage an export is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Running the teacher without rendering, to lay out the frames.
    Plan,
    /// Rendering and writing episodes.
    Render,
    /// Writing the metadata.
    Assemble,
}

/// A progress report.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Stage.
    pub phase: Phase,
    /// Episodes done in this stage (resumed ones included).
    pub done: usize,
    /// Episodes in this stage.
    pub total: usize,
    /// Frames rendered so far by this call.
    pub frames: u64,
}

/// What an export did.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Output folder.
    pub out: PathBuf,
    /// Episodes in the dataset.
    pub episodes: usize,
    /// Frames in the dataset.
    pub frames: usize,
    /// Episodes found finished from an earlier run.
    pub resumed: usize,
    /// Frames rendered by this call.
    pub rendered_frames: u64,
    /// Seconds spent planning, rendering and assembling.
    pub seconds: [f64; 3],
    /// Thread-seconds of the render stage, summed over workers: simulation and rendering,
    /// encoding (PNG, statistics), writing (Parquet columns, zstd, file).
    pub render_breakdown: [f64; 3],
    /// Bytes of the data files.
    pub data_bytes: u64,
    /// Threads used.
    pub threads: usize,
}

/// One episode's teacher actions (from the plan).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Plan {
    fingerprint: String,
    actions: Vec<Vec<i64>>,
}

/// What a finished episode leaves in `.parts/`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Part {
    fingerprint: String,
    episode_index: usize,
    episode_id: u64,
    length: usize,
    bytes: u64,
    stats: BTreeMap<String, Stats>,
}

fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = tmp_path(path);
    let mut f = std::fs::File::create(&tmp).map_err(|e| ExportError::io(&tmp, e))?;
    f.write_all(bytes).map_err(|e| ExportError::io(&tmp, e))?;
    f.sync_all().map_err(|e| ExportError::io(&tmp, e))?;
    drop(f);
    std::fs::rename(&tmp, path).map_err(|e| ExportError::io(path, e))
}

fn tmp_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    path.with_file_name(name)
}

fn mkdirs(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| ExportError::io(dir, e))
}

fn sha256_file(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|e| ExportError::io(path, e))?;
    Ok(format!("{:x}", Sha256::digest(&bytes)))
}

/// The vocabulary beside the dataset, or one built from the task's training split (as the
/// Python env does).
fn load_vocab(dir: &Path, task: Task, split: Split) -> Result<(Vocab, String)> {
    let file = dir.join(VOCAB_FILE);
    if file.is_file() {
        return Ok((Vocab::load(&file)?, sha256_file(&file)?));
    }
    let from = if dataset::split_path(dir, task, Split::Train).is_file() {
        Split::Train
    } else {
        split
    };
    let eps = dataset::read_split(dir, task, from)?;
    Ok((Vocab::build(&eps), format!("built from {from}")))
}

/// The rig: the protocol's (the paper's RGB 224x224 and depth 256x256, HFOV 90, depth
/// normalised at 10 m), plus a 12-view RGB panorama when asked.
fn rig_config(protocol: &EvalConfig, panorama: bool) -> Result<RigConfig> {
    let mut rig = protocol.rig_config()?;
    if panorama {
        let mut p = PanoramaSpec {
            depth: false,
            ..PanoramaSpec::default()
        };
        p.camera.name = "pano".into();
        rig.sensors.push(SensorSpec::Panorama(p));
    }
    Ok(rig)
}

/// Names and sizes of the rig's sensors used.
#[derive(Debug, Clone)]
struct Sensors {
    rgb: (String, usize, usize),
    depth: (String, usize, usize, f32),
    pano: Option<(String, usize, usize, usize)>,
}

fn sensors(rig: &RigConfig) -> Result<Sensors> {
    let mut rgb = None;
    let mut depth = None;
    let mut pano = None;
    for s in &rig.sensors {
        match s {
            SensorSpec::Rgb(c) if rgb.is_none() => {
                rgb = Some((s.name().to_string(), c.height as usize, c.width as usize))
            }
            SensorSpec::Depth(c) if depth.is_none() => {
                let scale = if c.normalize { 1.0 } else { 1.0 / c.far };
                depth = Some((
                    s.name().to_string(),
                    c.height as usize,
                    c.width as usize,
                    scale,
                ))
            }
            SensorSpec::Panorama(p) if p.rgb => {
                pano = Some((
                    s.name().to_string(),
                    p.views as usize,
                    p.camera.height as usize,
                    p.camera.width as usize,
                ))
            }
            _ => {}
        }
    }
    let missing = |what: &str| {
        ExportError::invalid(
            "rig",
            what,
            "the sensor rig has no such camera; an export needs RGB and depth",
        )
    };
    Ok(Sensors {
        rgb: rgb.ok_or_else(|| missing("rgb"))?,
        depth: depth.ok_or_else(|| missing("depth"))?,
        pano,
    })
}

fn features(s: &Sensors) -> Vec<Feature> {
    let hwc: &[&str] = &["height", "width", "channels"];
    let mut f = vec![
        Feature::new(keys::RGB, DType::Image, &[s.rgb.1, s.rgb.2, 3], Some(hwc)),
        Feature::new(
            keys::DEPTH,
            DType::F32,
            &[s.depth.1, s.depth.2, 1],
            Some(hwc),
        ),
    ];
    if let Some((_, views, h, w)) = s.pano {
        f.push(Feature::new(
            keys::PANO,
            DType::Image,
            &[h, w * views, 3],
            Some(hwc),
        ));
    }
    f.extend([
        Feature::new(keys::POSE, DType::F32, &[4], Some(&["x", "y", "z", "yaw"])),
        Feature::new(keys::COMPASS, DType::F32, &[1], None),
        Feature::new(keys::GPS, DType::F32, &[2], Some(&["forward", "right"])),
        Feature::new(keys::TOKENS, DType::I64, &[INSTRUCTION_LENGTH], None),
        Feature::new(
            keys::ACTION,
            DType::I64,
            &[1],
            Some(&["stop_forward_left_right"]),
        ),
    ]);
    f.extend(lerobot::default_features());
    f
}

fn png(rgb: &[u8], width: usize, height: usize) -> Result<Vec<u8>> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    let mut out = Vec::with_capacity(rgb.len() / 2);
    PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Adaptive)
        .write_image(
            rgb,
            width as u32,
            height as u32,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| ExportError::invalid("rgb", format!("{width}x{height}"), e.to_string()))?;
    Ok(out)
}

/// Frames of one episode, column by column.
#[derive(Default)]
struct Columns {
    rgb: Vec<Vec<u8>>,
    depth: Vec<Vec<f32>>,
    pano: Vec<Vec<u8>>,
    pose: Vec<Vec<f32>>,
    compass: Vec<f32>,
    gps: Vec<Vec<f32>>,
    action: Vec<i64>,
}

struct Job<'a> {
    req: &'a ExportRequest,
    settings: EpisodeSettings,
    protocol: EvalConfig,
    rig: RigConfig,
    sensors: Sensors,
    features: Vec<Feature>,
    scenes: SceneCache,
    workers: Mutex<Vec<Worker>>,
    fingerprint: String,
    /// Thread-nanoseconds: simulate + render, encode (PNG, statistics), write (Parquet).
    nanos: [AtomicU64; 3],
}

impl Job<'_> {
    fn worker(&self, render: bool) -> Result<Worker> {
        let pooled = self
            .workers
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .iter()
            .position(|w| w.rig.is_some() == render);
        if let Some(i) = pooled {
            return Ok(self
                .workers
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .swap_remove(i));
        }
        let sim = rapier_simulator(&sim_config(&self.protocol)?)?;
        let rig = if render {
            let r = configured_renderer(&self.rig)?;
            Some(SensorRig::with_renderer(self.rig.clone(), r))
        } else {
            None
        };
        Ok(Worker::new(sim, rig))
    }

    fn give_back(&self, w: Worker) {
        self.workers
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(w);
    }

    fn with_worker<T>(&self, render: bool, f: impl FnOnce(&mut Worker) -> Result<T>) -> Result<T> {
        let mut w = self.worker(render)?;
        let r = f(&mut w);
        if r.is_ok() {
            self.give_back(w);
        }
        r
    }

    fn plan_one(&self, ep: &Episode) -> Result<Vec<i64>> {
        let scene = self.scenes.get(&ep.scene_id).map_err(|e| {
            ExportError::invalid(
                &format!("episode {}.scene_id", ep.episode_id),
                &ep.scene_id,
                e.to_string(),
            )
        })?;
        self.with_worker(false, |w| {
            teacher::run(w, ep, &scene, &self.settings, |_| Ok(()))
        })
    }

    /// Render episode `index` and write its data file; returns its summary.
    fn render_one(
        &self,
        index: usize,
        ep: &Episode,
        meta: &EpisodeMeta,
        planned: &[i64],
        tokens: &[i64],
    ) -> Result<Part> {
        let scene = self.scenes.get(&ep.scene_id).map_err(|e| {
            ExportError::invalid(
                &format!("episode {}.scene_id", ep.episode_id),
                &ep.scene_id,
                e.to_string(),
            )
        })?;
        let s = &self.sensors;
        let mut cols = Columns::default();
        let mut rgb_acc = PixelAccumulator::new(3, 256);
        let mut pano_acc = PixelAccumulator::new(3, 256);
        let mut depth_acc = PixelAccumulator::new(1, 1001);
        let locate = |what: &str| format!("episode {}: {what}", ep.episode_id);
        let started = Instant::now();
        let mut encode = std::time::Duration::ZERO;
        let actions = self.with_worker(true, |w| {
            teacher::run(w, ep, &scene, &self.settings, |step: &Step<'_>| {
                let t = Instant::now();
                let obs = step.observations;
                let Some(Observation::Rgb(f)) = obs.get(&s.rgb.0) else {
                    return Err(ExportError::invalid(
                        &locate("observations"),
                        &s.rgb.0,
                        "no RGB image",
                    ));
                };
                rgb_acc.add_u8(&f.rgb);
                cols.rgb
                    .push(png(&f.rgb, f.width as usize, f.height as usize)?);
                let Some(Observation::Depth(f)) = obs.get(&s.depth.0) else {
                    return Err(ExportError::invalid(
                        &locate("observations"),
                        &s.depth.0,
                        "no depth image",
                    ));
                };
                let scale = s.depth.3;
                let d: Vec<f32> = if scale == 1.0 {
                    f.depth.clone()
                } else {
                    f.depth.iter().map(|v| v * scale).collect()
                };
                depth_acc.add_f32(&d);
                cols.depth.push(d);
                if let Some((name, views, h, w)) = &s.pano {
                    let Some(Observation::Panorama(v)) = obs.get(name) else {
                        return Err(ExportError::invalid(
                            &locate("observations"),
                            name,
                            "no panorama",
                        ));
                    };
                    let stitched = stitch(v.iter().map(|f| f.rgb.as_slice()), *views, *h, *w);
                    pano_acc.add_u8(&stitched);
                    cols.pano.push(png(&stitched, w * views, *h)?);
                }
                cols.pose.push(step.pose4().to_vec());
                cols.compass.push(step.compass());
                cols.gps.push(step.gps().to_vec());
                cols.action.push(step.action);
                encode += t.elapsed();
                Ok(())
            })
        })?;
        let run = started.elapsed();
        self.nanos[0].fetch_add((run - encode.min(run)).as_nanos() as u64, Ordering::Relaxed);
        self.nanos[1].fetch_add(encode.as_nanos() as u64, Ordering::Relaxed);
        let written = Instant::now();
        if actions != planned {
            return Err(ExportError::invalid(
                &locate("teacher actions"),
                format!("{} actions", actions.len()),
                format!(
                    "differ from the {} planned without rendering: the simulation is not \
                     deterministic here",
                    planned.len()
                ),
            ));
        }
        let n = actions.len();
        let frame_index: Vec<i64> = (0..n as i64).collect();
        let timestamp: Vec<f32> = (0..n).map(|i| i as f32 / lerobot::FPS as f32).collect();
        let global: Vec<i64> = (0..n).map(|i| (meta.from_index + i) as i64).collect();
        // Statistics, before the columns move into the table.
        let mut stats = BTreeMap::new();
        stats.insert(keys::RGB.to_string(), rgb_acc.stats());
        if s.pano.is_some() {
            stats.insert(keys::PANO.to_string(), pano_acc.stats());
        }
        stats.insert(keys::DEPTH.to_string(), depth_acc.stats());
        let flat = |rows: &[Vec<f32>]| {
            rows.iter()
                .flatten()
                .map(|&v| f64::from(v))
                .collect::<Vec<f64>>()
        };
        stats.insert(keys::POSE.to_string(), Stats::exact(&flat(&cols.pose), 4));
        let compass: Vec<f64> = cols.compass.iter().map(|&v| f64::from(v)).collect();
        stats.insert(keys::COMPASS.to_string(), Stats::exact(&compass, 1));
        stats.insert(keys::GPS.to_string(), Stats::exact(&flat(&cols.gps), 2));
        let tok: Vec<f64> = (0..n)
            .flat_map(|_| tokens.iter().map(|&t| t as f64))
            .collect();
        stats.insert(keys::TOKENS.to_string(), Stats::exact(&tok, tokens.len()));
        let ints = |v: &[i64]| v.iter().map(|&x| x as f64).collect::<Vec<f64>>();
        stats.insert(
            keys::ACTION.to_string(),
            Stats::exact(&ints(&cols.action), 1),
        );
        let ts: Vec<f64> = timestamp.iter().map(|&v| f64::from(v)).collect();
        stats.insert("timestamp".into(), Stats::exact(&ts, 1));
        stats.insert("frame_index".into(), Stats::exact(&ints(&frame_index), 1));
        stats.insert(
            "episode_index".into(),
            Stats::exact(&vec![index as f64; n], 1),
        );
        stats.insert("index".into(), Stats::exact(&ints(&global), 1));
        stats.insert(
            "task_index".into(),
            Stats::exact(&vec![meta.task_index as f64; n], 1),
        );

        let mut t = Table::new(n);
        t.image(keys::RGB, std::mem::take(&mut cols.rgb));
        let depth_rows: Vec<&[f32]> = cols.depth.iter().map(Vec::as_slice).collect();
        t.array3_f32(keys::DEPTH, &depth_rows, [s.depth.1, s.depth.2, 1]);
        if s.pano.is_some() {
            t.image(keys::PANO, std::mem::take(&mut cols.pano));
        }
        t.list_f32(keys::POSE, &cols.pose);
        t.f32(keys::COMPASS, cols.compass);
        t.list_f32(keys::GPS, &cols.gps);
        t.list_i64(keys::TOKENS, &vec![tokens.to_vec(); n]);
        t.i64(keys::ACTION, cols.action);
        t.f32("timestamp", timestamp);
        t.i64("frame_index", frame_index);
        t.i64("episode_index", vec![index as i64; n]);
        t.i64("index", global);
        t.i64("task_index", vec![meta.task_index as i64; n]);
        t.metadata("huggingface", lerobot::hf_metadata(&self.features));

        let path = self.req.out.join(lerobot::data_path(index));
        if let Some(dir) = path.parent() {
            mkdirs(dir)?;
        }
        let tmp = tmp_path(&path);
        t.write(&tmp)?;
        std::fs::rename(&tmp, &path).map_err(|e| ExportError::io(&path, e))?;
        let bytes = std::fs::metadata(&path)
            .map_err(|e| ExportError::io(&path, e))?
            .len();
        self.nanos[2].fetch_add(written.elapsed().as_nanos() as u64, Ordering::Relaxed);
        let part = Part {
            fingerprint: self.fingerprint.clone(),
            episode_index: index,
            episode_id: ep.episode_id,
            length: n,
            bytes,
            stats,
        };
        let part_path = parts_dir(&self.req.out).join(format!("episode-{index:06}.json"));
        write_atomic(&part_path, &serde_json::to_vec(&part).unwrap_or_default())?;
        Ok(part)
    }
}

/// Views side by side, view 0 (straight ahead) on the left, then counter-clockwise.
fn stitch<'a>(views: impl Iterator<Item = &'a [u8]>, n: usize, h: usize, w: usize) -> Vec<u8> {
    let mut out = vec![0u8; n * h * w * 3];
    for (k, v) in views.take(n).enumerate() {
        for y in 0..h {
            let src = &v[y * w * 3..(y + 1) * w * 3];
            let at = (y * n * w + k * w) * 3;
            out[at..at + w * 3].copy_from_slice(src);
        }
    }
    out
}

fn parts_dir(out: &Path) -> PathBuf {
    out.join(PARTS_DIR)
}

fn read_json<T: for<'de> Deserialize<'de>>(path: &Path) -> Option<T> {
    let bytes = std::fs::read(path).ok()?;
    serde_json::from_slice(&bytes).ok()
}

/// Export `req`'s episodes as a LeRobot dataset, reporting progress to `progress`.
pub fn export(req: &ExportRequest, progress: &(dyn Fn(Progress) + Sync)) -> Result<ExportSummary> {
    let (episodes, split_file) = load_episodes(req)?;
    let mut protocol = EvalConfig::for_setting(req.setting);
    protocol.action_space = ActionSpace::Discrete;
    protocol.seed = req.seed;
    protocol.render = true;
    let rig = rig_config(&protocol, req.panorama)?;
    let sensors = sensors(&rig)?;
    let features = features(&sensors);
    let mut settings = EpisodeSettings::new(&protocol)?;
    settings.split = Some(req.split);
    settings.reference_dir = split_file.parent().map(Path::to_path_buf);
    let (vocab, vocab_source) = load_vocab(&req.dataset, req.task, req.split)?;
    let (tasks, task_index) = task_strings(&episodes);

    let identity = json!({
        "format": "lerobot",
        "revision": FORMAT_REVISION,
        "task": req.task.to_string(),
        "split": req.split.to_string(),
        "episode_ids": episodes.iter().map(|e| e.episode_id).collect::<Vec<_>>(),
        "split_sha256": sha256_file(&split_file)?,
        "vocab": vocab_source,
        "seed": req.seed,
        "panorama": req.panorama,
        "setting": req.setting.name(),
        "max_steps": protocol.max_steps,
        "agent_profile": protocol.agent_profile,
        "rig": serde_json::to_value(&rig).unwrap_or_default(),
    });
    let fingerprint = format!("{:x}", Sha256::digest(identity.to_string().as_bytes()));

    let threads = req
        .threads
        .unwrap_or_else(rayon::current_num_threads)
        .max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| ExportError::invalid("threads", threads, e.to_string()))?;
    let scenes = SceneCache::new(&req.dataset, 2 * threads + 2);
    // Every episode is checked in its scene before the output folder is touched.
    pool.install(|| check_split(&split_file, &episodes, &scenes))?;

    let (_lock, parts) = claim_output(req, &fingerprint, &identity)?;

    let job = Job {
        req,
        settings,
        protocol: protocol.clone(),
        rig: rig.clone(),
        sensors,
        features: features.clone(),
        scenes,
        workers: Mutex::new(Vec::new()),
        fingerprint: fingerprint.clone(),
        nanos: Default::default(),
    };

    // 1. Plan: the teacher's actions without rendering (cheap), for the frame layout.
    let t0 = Instant::now();
    let plan = plan_actions(&job, &pool, &episodes, &parts, progress)?;
    let plan_s = t0.elapsed().as_secs_f64();
    let (metas, total_frames) = episode_metas(req, &episodes, &plan, &task_index);

    // 2. Render what is not finished yet.
    let t1 = Instant::now();
    let rendered = render_missing(
        &job, &pool, &episodes, &metas, &plan, &vocab, &parts, progress,
    )?;
    let render_s = t1.elapsed().as_secs_f64();

    // 3. Metadata.
    let t2 = Instant::now();
    progress(Progress {
        phase: Phase::Assemble,
        done: 0,
        total: 1,
        frames: rendered.frames,
    });
    write_metadata(
        req,
        &metas,
        &features,
        &rendered.parts,
        &tasks,
        total_frames,
        &fingerprint,
    )?;
    let assemble_s = t2.elapsed().as_secs_f64();
    progress(Progress {
        phase: Phase::Assemble,
        done: 1,
        total: 1,
        frames: rendered.frames,
    });
    Ok(ExportSummary {
        out: req.out.clone(),
        episodes: metas.len(),
        frames: total_frames,
        resumed: rendered.resumed,
        rendered_frames: rendered.frames,
        seconds: [plan_s, render_s, assemble_s],
        render_breakdown: job
            .nanos
            .each_ref()
            .map(|n| n.load(Ordering::Relaxed) as f64 * 1e-9),
        data_bytes: rendered.parts.iter().map(|p| p.bytes).sum(),
        threads,
    })
}

/// The request's episodes, checked: at least one, from a split file that exists.
fn load_episodes(req: &ExportRequest) -> Result<(Vec<Episode>, PathBuf)> {
    if req.episodes == Some(0) {
        return Err(ExportError::invalid(
            "episodes",
            0,
            "must be at least 1 (leave it out for the whole split)",
        ));
    }
    if let Some(n) = req.threads.filter(|n| !(1..=MAX_THREADS).contains(n)) {
        return Err(ExportError::invalid(
            "threads",
            n,
            format!("must be in [1, {MAX_THREADS}] (leave it out for one per core)"),
        ));
    }
    if !req.dataset.is_dir() {
        return Err(ExportError::invalid(
            "dataset",
            req.dataset.display(),
            "no such folder (make one with `cargo xtask generate`)",
        ));
    }
    let split_file = dataset::split_path(&req.dataset, req.task, req.split);
    if !split_file.is_file() {
        return Err(ExportError::invalid(
            "split",
            format!("{}/{}", req.task, req.split),
            format!("{} does not exist in this dataset", split_file.display()),
        ));
    }
    let mut episodes = dataset::read_split(&req.dataset, req.task, req.split)?;
    if let Some(n) = req.episodes {
        episodes.truncate(n);
    }
    if episodes.is_empty() {
        return Err(ExportError::invalid(
            "split",
            split_file.display(),
            "the split has no episodes",
        ));
    }
    Ok((episodes, split_file))
}

/// Task strings by first appearance, and each episode's index into them.
fn task_strings(episodes: &[Episode]) -> (Vec<String>, Vec<usize>) {
    let mut tasks: Vec<String> = Vec::new();
    let mut task_of: HashMap<String, usize> = HashMap::new();
    let task_index: Vec<usize> = episodes
        .iter()
        .map(|e| {
            let text = e.instruction.instruction_text.clone();
            *task_of.entry(text.clone()).or_insert_with(|| {
                tasks.push(text);
                tasks.len() - 1
            })
        })
        .collect();

    (tasks, task_index)
}

/// Lock `req.out` and make sure it holds this request's export or nothing: returns the lock and
/// the folder of the parts.
fn claim_output(
    req: &ExportRequest,
    fingerprint: &str,
    identity: &serde_json::Value,
) -> Result<(OutputLock, PathBuf)> {
    let parts = parts_dir(&req.out);
    let request_file = parts.join("request.json");
    // Refuse a folder of something else before touching it (no lock file is left there), and
    // again under the lock, where no other job can change it meanwhile.
    if req.out.is_dir() {
        check_output_holds(&req.out, &request_file, fingerprint)?;
    }
    mkdirs(&req.out)?;
    let lock = OutputLock::acquire(&req.out, "export").map_err(|e| ExportError::Output {
        path: req.out.clone(),
        reason: e.to_string(),
    })?;
    if !check_output_holds(&req.out, &request_file, fingerprint)? {
        mkdirs(&parts)?;
        write_atomic(
            &request_file,
            &serde_json::to_vec_pretty(&json!({"fingerprint": fingerprint, "request": identity}))
                .unwrap_or_default(),
        )?;
    }
    Ok((lock, parts))
}

/// Whether `out` holds this request's export (true) or nothing yet (false); an error when it
/// holds another request's export or anything else.
fn check_output_holds(out: &Path, request_file: &Path, fingerprint: &str) -> Result<bool> {
    match read_json::<serde_json::Value>(request_file) {
        Some(v) if v.get("fingerprint").and_then(|f| f.as_str()) == Some(fingerprint) => Ok(true),
        Some(_) => Err(ExportError::Output {
            path: out.to_path_buf(),
            reason: "holds an export of another request (dataset split, episodes, seed, \
                     setting or panorama differ); choose another --out or delete it"
                .into(),
        }),
        None => {
            let foreign = std::fs::read_dir(out)
                .map_err(|e| ExportError::io(out, e))?
                .filter_map(|e| e.ok())
                .any(|e| {
                    let n = e.file_name();
                    n != PARTS_DIR && n != vlnverse_score::lock::LOCK_FILE
                });
            if foreign {
                return Err(ExportError::Output {
                    path: out.to_path_buf(),
                    reason: "is not empty and holds no export of this command; choose an \
                             empty or new folder"
                        .into(),
                });
            }
            Ok(false)
        }
    }
}

/// The teacher's actions of every episode, without rendering (cheap), for the frame layout;
/// read back from `plan.json` when a previous run of the same request made it.
fn plan_actions(
    job: &Job,
    pool: &rayon::ThreadPool,
    episodes: &[Episode],
    parts: &Path,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Plan> {
    let fingerprint = &job.fingerprint;
    let plan_file = parts.join("plan.json");
    Ok(match read_json::<Plan>(&plan_file) {
        Some(p) if p.fingerprint == *fingerprint && p.actions.len() == episodes.len() => p,
        _ => {
            let done = AtomicUsize::new(0);
            let total = episodes.len();
            progress(Progress {
                phase: Phase::Plan,
                done: 0,
                total,
                frames: 0,
            });
            let actions = pool.install(|| {
                episodes
                    .par_iter()
                    .with_max_len(1)
                    .map(|ep| {
                        let a = job.plan_one(ep);
                        let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                        progress(Progress {
                            phase: Phase::Plan,
                            done: d,
                            total,
                            frames: 0,
                        });
                        a
                    })
                    .collect::<Result<Vec<_>>>()
            })?;
            let p = Plan {
                fingerprint: fingerprint.clone(),
                actions,
            };
            write_atomic(&plan_file, &serde_json::to_vec(&p).unwrap_or_default())?;
            p
        }
    })
}

/// Per-episode metadata, with each episode's first frame index; and the number of frames.
fn episode_metas(
    req: &ExportRequest,
    episodes: &[Episode],
    plan: &Plan,
    task_index: &[usize],
) -> (Vec<EpisodeMeta>, usize) {
    let mut metas = Vec::with_capacity(episodes.len());
    let mut from = 0;
    for (i, ep) in episodes.iter().enumerate() {
        let length = plan.actions[i].len();
        metas.push(EpisodeMeta {
            episode_index: i,
            episode_id: ep.episode_id,
            scene_id: ep.scene_id.clone(),
            task: req.task.to_string(),
            split: req.split.to_string(),
            geodesic_distance: f64::from(ep.info.geodesic_distance),
            instruction: ep.instruction.instruction_text.clone(),
            length,
            from_index: from,
            task_index: task_index[i],
        });
        from += length;
    }

    (metas, from)
}

/// Parts of the episodes, finished: those a previous run left and the ones rendered now.
struct Rendered {
    parts: Vec<Part>,
    resumed: usize,
    frames: u64,
}

/// Render the episodes that have no finished part yet, in parallel on `pool`.
fn render_missing(
    job: &Job,
    pool: &rayon::ThreadPool,
    episodes: &[Episode],
    metas: &[EpisodeMeta],
    plan: &Plan,
    vocab: &Vocab,
    parts: &Path,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Rendered> {
    let req = job.req;
    let fingerprint = &job.fingerprint;
    let part_path = |i: usize| parts.join(format!("episode-{i:06}.json"));
    let mut parts_done: Vec<Option<Part>> = (0..episodes.len())
        .map(|i| {
            read_json::<Part>(&part_path(i)).filter(|p| {
                p.fingerprint == *fingerprint
                    && p.length == metas[i].length
                    && req.out.join(lerobot::data_path(i)).is_file()
            })
        })
        .collect();
    let resumed = parts_done.iter().filter(|p| p.is_some()).count();
    let todo: Vec<usize> = (0..episodes.len())
        .filter(|&i| parts_done[i].is_none())
        .collect();
    let done = AtomicUsize::new(resumed);
    let frames = AtomicU64::new(0);
    let total = episodes.len();
    progress(Progress {
        phase: Phase::Render,
        done: resumed,
        total,
        frames: 0,
    });
    let rendered: Vec<(usize, Part)> = pool.install(|| {
        todo.par_iter()
            .with_max_len(1)
            .map(|&i| {
                let ep = &episodes[i];
                let tokens: Vec<i64> = vocab
                    .encode(&ep.instruction.instruction_text, INSTRUCTION_LENGTH)
                    .into_iter()
                    .map(i64::from)
                    .collect();
                let part = job.render_one(i, ep, &metas[i], &plan.actions[i], &tokens)?;
                let f =
                    frames.fetch_add(part.length as u64, Ordering::Relaxed) + part.length as u64;
                let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress(Progress {
                    phase: Phase::Render,
                    done: d,
                    total,
                    frames: f,
                });
                Ok((i, part))
            })
            .collect::<Result<Vec<_>>>()
    })?;
    for (i, p) in rendered {
        parts_done[i] = Some(p);
    }
    let parts_done: Vec<Part> = parts_done.into_iter().flatten().collect();
    Ok(Rendered {
        parts: parts_done,
        resumed,
        frames: frames.load(Ordering::Relaxed),
    })
}

/// `meta/`: the episodes and tasks tables, statistics, our per-episode JSON lines and, last
/// (its presence marks a complete dataset), `info.json`.
fn write_metadata(
    req: &ExportRequest,
    metas: &[EpisodeMeta],
    features: &[Feature],
    parts_done: &[Part],
    tasks: &[String],
    total_frames: usize,
    fingerprint: &str,
) -> Result<()> {
    let meta_dir = req.out.join("meta");
    mkdirs(&meta_dir.join("episodes/chunk-000"))?;
    let episodes_file = meta_dir.join("episodes/chunk-000/file-000.parquet");
    let tmp = tmp_path(&episodes_file);
    let per_episode: Vec<BTreeMap<String, Stats>> =
        parts_done.iter().map(|p| p.stats.clone()).collect();
    lerobot::episodes_table(metas, features, &per_episode).write(&tmp)?;
    std::fs::rename(&tmp, &episodes_file).map_err(|e| ExportError::io(&episodes_file, e))?;
    let tasks_file = meta_dir.join("tasks.parquet");
    let tmp = tmp_path(&tasks_file);
    lerobot::tasks_table(tasks).write(&tmp)?;
    std::fs::rename(&tmp, &tasks_file).map_err(|e| ExportError::io(&tasks_file, e))?;
    let stats = lerobot::stats_json(features, &per_episode);
    write_atomic(&meta_dir.join("stats.json"), &pretty(&stats))?;
    let mut jsonl = String::new();
    for m in metas {
        jsonl.push_str(&serde_json::to_string(m).unwrap_or_default());
        jsonl.push('\n');
    }
    write_atomic(&meta_dir.join("vlnverse_episodes.jsonl"), jsonl.as_bytes())?;
    let info = lerobot::info_json(
        features,
        metas.len(),
        total_frames,
        tasks.len(),
        json!({
            "task": req.task.to_string(),
            "split": req.split.to_string(),
            "setting": req.setting.name(),
            "seed": req.seed,
            "instruction_length": INSTRUCTION_LENGTH,
            "vocab": "vocab.txt of the dataset (ids of observation.instruction_tokens; 0 pads)",
            "actions": ["stop", "move_forward", "turn_left", "turn_right"],
            "depth": "metres / 10, clipped to [0, 1]",
            "fingerprint": fingerprint,
        }),
    );
    // info.json last: its presence marks a complete dataset.
    write_atomic(&meta_dir.join("info.json"), &pretty(&info))?;
    Ok(())
}

fn pretty(v: &serde_json::Value) -> Vec<u8> {
    let mut b = serde_json::to_vec_pretty(v).unwrap_or_default();
    b.push(b'\n');
    b
}
