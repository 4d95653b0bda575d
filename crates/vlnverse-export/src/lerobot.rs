//! The LeRobot v3.0 layout: feature declarations, the per-episode data file, and the
//! metadata files (`meta/info.json`, `meta/stats.json`, `meta/tasks.parquet`,
//! `meta/episodes/chunk-000/file-000.parquet`).

use std::collections::BTreeMap;

use serde_json::{json, Value};

use crate::stats::Stats;
use crate::table::Table;

/// The LeRobot format version written.
pub const CODEBASE_VERSION: &str = "v3.0";
/// Frames per second (timestamps are `frame_index / FPS`).
pub const FPS: u32 = 10;
/// Data files per chunk folder (LeRobot's default `chunks_size`).
pub const CHUNK_SIZE: usize = 1000;

/// Feature keys.
pub mod keys {
    /// RGB image.
    pub const RGB: &str = "observation.images.rgb";
    /// The panorama image (views side by side).
    pub const PANO: &str = "observation.images.pano";
    /// Normalised depth.
    pub const DEPTH: &str = "observation.depth";
    /// `[x, y, z, yaw]`.
    pub const POSE: &str = "observation.pose";
    /// Heading relative to the start.
    pub const COMPASS: &str = "observation.compass";
    /// Position in the start frame.
    pub const GPS: &str = "observation.gps";
    /// Instruction token ids.
    pub const TOKENS: &str = "observation.instruction_tokens";
    /// Teacher action.
    pub const ACTION: &str = "action";
}

/// Element type of a feature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DType {
    /// An encoded image (PNG), `[h, w, 3]`.
    Image,
    /// 32-bit float.
    F32,
    /// 64-bit integer.
    I64,
}

impl DType {
    fn name(self) -> &'static str {
        match self {
            DType::Image => "image",
            DType::F32 => "float32",
            DType::I64 => "int64",
        }
    }
}

/// One feature of `meta/info.json`.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    /// Key.
    pub key: String,
    /// Element type.
    pub dtype: DType,
    /// Shape of one frame's value.
    pub shape: Vec<usize>,
    /// Names of the axes or dimensions (`null` when absent).
    pub names: Option<Vec<String>>,
}

impl Feature {
    /// A feature.
    pub fn new(key: &str, dtype: DType, shape: &[usize], names: Option<&[&str]>) -> Self {
        Feature {
            key: key.into(),
            dtype,
            shape: shape.to_vec(),
            names: names.map(|n| n.iter().map(|s| s.to_string()).collect()),
        }
    }

    /// The `info.json` entry.
    pub fn info(&self) -> Value {
        json!({"dtype": self.dtype.name(), "shape": self.shape, "names": self.names})
    }

    /// The Hugging Face `datasets` feature (as LeRobot's `get_hf_features_from_features`).
    pub fn hf(&self) -> Value {
        let d = self.dtype.name();
        match (self.dtype, self.shape.len()) {
            (DType::Image, _) => json!({"_type": "Image"}),
            _ if self.shape == [1] => json!({"dtype": d, "_type": "Value"}),
            (_, 1) => {
                json!({"feature": {"dtype": d, "_type": "Value"}, "length": self.shape[0], "_type": "List"})
            }
            (_, n) => json!({"shape": self.shape, "dtype": d, "_type": format!("Array{n}D")}),
        }
    }
}

/// LeRobot's own per-frame columns.
pub fn default_features() -> Vec<Feature> {
    vec![
        Feature::new("timestamp", DType::F32, &[1], None),
        Feature::new("frame_index", DType::I64, &[1], None),
        Feature::new("episode_index", DType::I64, &[1], None),
        Feature::new("index", DType::I64, &[1], None),
        Feature::new("task_index", DType::I64, &[1], None),
    ]
}

/// The `huggingface` key of a data file's metadata: its `datasets` features.
pub fn hf_metadata(features: &[Feature]) -> String {
    let f: serde_json::Map<String, Value> =
        features.iter().map(|f| (f.key.clone(), f.hf())).collect();
    json!({"info": {"features": f}}).to_string()
}

/// Path of episode `index`'s data file, relative to the dataset root.
pub fn data_path(index: usize) -> String {
    format!(
        "data/chunk-{:03}/file-{:03}.parquet",
        index / CHUNK_SIZE,
        index % CHUNK_SIZE
    )
}

/// What `meta/episodes` and `meta/vlnverse_episodes.jsonl` say of one episode.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EpisodeMeta {
    /// Index in this dataset.
    pub episode_index: usize,
    /// VLN episode id.
    pub episode_id: u64,
    /// Scene id.
    pub scene_id: String,
    /// Task name.
    pub task: String,
    /// Split name.
    pub split: String,
    /// Geodesic start-goal distance (m).
    pub geodesic_distance: f64,
    /// Instruction text (the LeRobot task string).
    pub instruction: String,
    /// Frames.
    pub length: usize,
    /// Index of the first frame in the whole dataset.
    pub from_index: usize,
    /// Task index of the instruction.
    pub task_index: usize,
}

/// `meta/episodes/chunk-000/file-000.parquet`: LeRobot's columns (with each episode's
/// statistics, `stats/<feature>/<stat>`, which LeRobot's dataset tools read to split or edit a
/// dataset) plus `vlnverse/*` ones.
pub fn episodes_table(
    eps: &[EpisodeMeta],
    features: &[Feature],
    stats: &[BTreeMap<String, Stats>],
) -> Table {
    let mut t = Table::new(eps.len());
    let col = |f: &dyn Fn(&EpisodeMeta) -> i64| eps.iter().map(f).collect::<Vec<i64>>();
    t.i64("episode_index", col(&|e| e.episode_index as i64));
    let tasks: Vec<Vec<String>> = eps.iter().map(|e| vec![e.instruction.clone()]).collect();
    t.list_string("tasks", &tasks);
    t.i64("length", col(&|e| e.length as i64));
    t.i64(
        "data/chunk_index",
        col(&|e| (e.episode_index / CHUNK_SIZE) as i64),
    );
    t.i64(
        "data/file_index",
        col(&|e| (e.episode_index % CHUNK_SIZE) as i64),
    );
    t.i64("dataset_from_index", col(&|e| e.from_index as i64));
    t.i64(
        "dataset_to_index",
        col(&|e| (e.from_index + e.length) as i64),
    );
    for f in features {
        let per: Vec<&Stats> = stats.iter().filter_map(|m| m.get(&f.key)).collect();
        if per.len() != eps.len() {
            continue;
        }
        let key = |stat: &str| format!("stats/{}/{stat}", f.key);
        let int = f.dtype == DType::I64;
        let image = f.dtype == DType::Image;
        let mut named: Vec<(&str, Vec<Vec<f64>>, bool)> = vec![
            ("min", per.iter().map(|s| s.min.clone()).collect(), int),
            ("max", per.iter().map(|s| s.max.clone()).collect(), int),
            ("mean", per.iter().map(|s| s.mean.clone()).collect(), false),
            ("std", per.iter().map(|s| s.std.clone()).collect(), false),
        ];
        for (k, q) in crate::stats::QUANTILE_KEYS.iter().enumerate() {
            named.push((
                q,
                per.iter().map(|s| s.quantiles[k].clone()).collect(),
                false,
            ));
        }
        for (i, (stat, rows, as_int)) in named.into_iter().enumerate() {
            if image {
                let dims = [rows.first().map_or(3, Vec::len), 1, 1];
                t.array3_f64(&key(stat), &rows, dims);
            } else if as_int {
                let rows: Vec<Vec<i64>> = rows
                    .iter()
                    .map(|r| r.iter().map(|&v| v as i64).collect())
                    .collect();
                t.list_i64(&key(stat), &rows);
            } else {
                t.list_f64(&key(stat), &rows);
            }
            if i == 3 {
                // LeRobot's order: min, max, mean, std, count, quantiles.
                let counts: Vec<Vec<i64>> = per.iter().map(|s| vec![s.count as i64]).collect();
                t.list_i64(&key("count"), &counts);
            }
        }
    }
    t.i64("meta/episodes/chunk_index", col(&|_| 0));
    t.i64("meta/episodes/file_index", col(&|_| 0));
    t.i64("vlnverse/episode_id", col(&|e| e.episode_id as i64));
    let s = |f: &dyn Fn(&EpisodeMeta) -> String| eps.iter().map(f).collect::<Vec<String>>();
    t.string("vlnverse/scene_id", &s(&|e| e.scene_id.clone()));
    t.string("vlnverse/task", &s(&|e| e.task.clone()));
    t.string("vlnverse/split", &s(&|e| e.split.clone()));
    t.f64(
        "vlnverse/geodesic_distance",
        eps.iter().map(|e| e.geodesic_distance).collect(),
    );
    t
}

/// `meta/tasks.parquet`: `task_index` with the task strings as the pandas index, as LeRobot
/// (pandas `to_parquet`) writes it.
pub fn tasks_table(tasks: &[String]) -> Table {
    let mut t = Table::new(tasks.len());
    t.i64("task_index", (0..tasks.len() as i64).collect());
    t.string("__index_level_0__", tasks);
    let pandas = json!({
        "index_columns": ["__index_level_0__"],
        "column_indexes": [{"name": null, "field_name": null, "pandas_type": "unicode",
                            "numpy_type": "object", "metadata": {"encoding": "UTF-8"}}],
        "columns": [
            {"name": "task_index", "field_name": "task_index", "pandas_type": "int64",
             "numpy_type": "int64", "metadata": null},
            {"name": null, "field_name": "__index_level_0__", "pandas_type": "unicode",
             "numpy_type": "object", "metadata": null}
        ],
        "attributes": {},
        "creator": {"library": "vlnverse-export", "version": env!("CARGO_PKG_VERSION")},
        "pandas_version": "2.2.0"
    });
    t.metadata("pandas", pandas.to_string());
    t
}

/// `meta/info.json`.
pub fn info_json(
    features: &[Feature],
    episodes: usize,
    frames: usize,
    tasks: usize,
    vlnverse: Value,
) -> Value {
    let f: serde_json::Map<String, Value> =
        features.iter().map(|f| (f.key.clone(), f.info())).collect();
    json!({
        "codebase_version": CODEBASE_VERSION,
        "robot_type": "vlnverse",
        "total_episodes": episodes,
        "total_frames": frames,
        "total_tasks": tasks,
        "chunks_size": CHUNK_SIZE,
        "data_files_size_in_mb": 100,
        "video_files_size_in_mb": 200,
        "fps": FPS,
        "splits": {"train": format!("0:{episodes}")},
        "data_path": "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet",
        "video_path": null,
        "features": f,
        "vlnverse": vlnverse,
    })
}

/// `meta/stats.json` from per-episode statistics (in episode order).
pub fn stats_json(features: &[Feature], per_episode: &[BTreeMap<String, Stats>]) -> Value {
    let mut out = serde_json::Map::new();
    for f in features {
        let list: Vec<&Stats> = per_episode.iter().filter_map(|m| m.get(&f.key)).collect();
        if let Some(s) = Stats::aggregate(&list) {
            out.insert(
                f.key.clone(),
                s.to_json(f.dtype == DType::Image, f.dtype == DType::I64),
            );
        }
    }
    Value::Object(out)
}
