//! `vlnverse.generate`: the dataset generation of `cargo xtask generate`, from Python.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use vlnverse_task::episode::Task;
use vlnverse_task::generate::{GenerateRequest, StageTimes};

use crate::{guarded, parse, py_err};

/// Generate a dataset into `out` (resumable, byte-identical on any number of threads); returns
/// a dict: `scenes_done`, `scenes_skipped`, `episodes`, `assembled`, `skipped` (scene/task
/// pairs that gave no episodes, with the reason). `on_scene(done, total)` is called after
/// each scene.
#[pyfunction]
#[pyo3(signature = (out, *, preset = "tiny", config = None, seed = None, tasks = None,
    shard = None, threads = None, scenes_from = None, on_scene = None))]
#[allow(clippy::too_many_arguments)]
pub fn generate<'py>(
    py: Python<'py>,
    out: PathBuf,
    preset: &str,
    config: Option<PathBuf>,
    seed: Option<u64>,
    tasks: Option<Vec<String>>,
    shard: Option<(usize, usize)>,
    threads: Option<usize>,
    scenes_from: Option<PathBuf>,
    on_scene: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let tasks = tasks
        .unwrap_or_default()
        .iter()
        .map(|t| parse::<Task>("tasks", t))
        .collect::<PyResult<Vec<_>>>()?;
    let req = GenerateRequest {
        preset: preset.to_string(),
        config,
        seed,
        out,
        tasks,
        shard: shard.unwrap_or((0, 1)),
        scenes_from,
    };
    // The first error the callback raised: re-raised after the run.
    let callback_error: Mutex<Option<PyErr>> = Mutex::new(None);
    let summary = py.detach(|| {
        guarded("generate", || {
            let run = req.prepare().map_err(py_err)?;
            let total = run.scenes_in_shard();
            let done = AtomicUsize::new(0);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads.unwrap_or(0))
                .build()
                .map_err(|e| py_err(format!("cannot start the worker threads: {e}")))?;
            let report = |_: &str| {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                if let Some(cb) = &on_scene {
                    Python::attach(|py| {
                        if let Err(e) = cb.call1(py, (k, total)) {
                            let mut slot = callback_error.lock().unwrap_or_else(|p| p.into_inner());
                            slot.get_or_insert(e);
                        }
                    });
                }
            };
            let times = StageTimes::default();
            pool.install(|| run.run(&times, &report)).map_err(py_err)
        })
    })?;
    if let Some(e) = callback_error
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
    {
        return Err(e);
    }
    let d = PyDict::new(py);
    d.set_item("scenes_done", summary.scenes_done)?;
    d.set_item("scenes_skipped", summary.scenes_skipped)?;
    d.set_item("episodes", summary.episodes)?;
    d.set_item("assembled", summary.assembled)?;
    let skipped: Vec<(String, String, String)> = summary
        .skipped
        .iter()
        .map(|s| {
            (
                s.scene_id.clone(),
                s.task.name().to_string(),
                s.reason.clone(),
            )
        })
        .collect();
    d.set_item("skipped", skipped)?;
    Ok(d)
}

/// Join shard folders (each generated with `shard=(k, n)`) into `out`, byte-identical to a
/// single run, like `cargo xtask merge`; returns the number of episodes. The inputs are
/// checked first (every shard given once, complete, one config); a failed merge writes
/// nothing into `out`.
#[pyfunction]
pub fn merge(py: Python<'_>, out: PathBuf, parts: Vec<PathBuf>) -> PyResult<usize> {
    if parts.is_empty() {
        return Err(py_err("merge: no shard folders given"));
    }
    py.detach(|| {
        guarded("merge", || {
            vlnverse_task::generate::merge(&out, &parts).map_err(py_err)
        })
    })
}
