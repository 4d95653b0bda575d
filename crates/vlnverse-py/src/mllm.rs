//! `vlnverse.agents.MLLMAgent` under `vlnverse.evaluate`: the MLLM agent runs in the native
//! evaluator (the CLI's `evaluate --agent mllm`), writing the same run folder.

use std::path::PathBuf;

use pyo3::prelude::*;
use vlnverse_mllm::{write_accounting, MllmConfig, MllmFactory, ACCOUNTING_FILE};
use vlnverse_task::episode::{Split, Task};
use vlnverse_task::eval::agents::Versioned;
use vlnverse_task::eval::{evaluate_with, AgentFactory, EvalRequest, Layers};
use vlnverse_task::sample::Sample;

use crate::{guarded, parse, py_err};

/// Evaluate the MLLM agent on a split; returns `summary.json`'s text (with its `mllm` totals).
#[pyfunction]
#[pyo3(signature = (dataset, task, split, out, *, endpoint, model, config_path = None,
    config_json = None, setting = "telhop", action_space = "discrete", profile = "vlnverse",
    sensors = None, seed = 0, max_steps = None, success_distance = None, episodes = None,
    sample = None, threads = None, version = None, fresh = false, render = true))]
#[allow(clippy::too_many_arguments)]
pub fn evaluate_mllm(
    py: Python<'_>,
    dataset: PathBuf,
    task: &str,
    split: &str,
    out: PathBuf,
    endpoint: String,
    model: String,
    config_path: Option<PathBuf>,
    config_json: Option<String>,
    setting: &str,
    action_space: &str,
    profile: &str,
    sensors: Option<PathBuf>,
    seed: u64,
    max_steps: Option<u32>,
    success_distance: Option<f32>,
    episodes: Option<usize>,
    sample: Option<usize>,
    threads: Option<usize>,
    version: Option<String>,
    fresh: bool,
    render: bool,
) -> PyResult<String> {
    let (task, split): (Task, Split) = (parse("task", task)?, parse("split", split)?);
    let protocol = crate::protocol(
        setting,
        action_space,
        profile,
        sensors,
        seed,
        render,
        None,
        max_steps,
        success_distance,
    )?;
    py.detach(|| {
        guarded("evaluate", || {
            protocol.validate().map_err(py_err)?;
            let mut cfg = match (config_path, config_json) {
                (Some(_), Some(_)) => {
                    return Err(py_err("config: give a file or a dict, not both"));
                }
                (Some(p), None) => MllmConfig::load(&p).map_err(py_err)?,
                (None, Some(j)) => {
                    serde_json::from_str(&j).map_err(|e| py_err(format!("invalid config: {e}")))?
                }
                (None, None) => MllmConfig::default(),
            };
            cfg.endpoint = endpoint;
            cfg.model = model;
            if cfg.cache && cfg.cache_dir.is_none() {
                cfg.cache_dir = Some(out.join(".mllm-cache"));
            }
            let factory = MllmFactory::new(cfg).map_err(py_err)?;
            if fresh {
                let f = out.join(ACCOUNTING_FILE);
                if let Err(e) = std::fs::remove_file(&f) {
                    if e.kind() != std::io::ErrorKind::NotFound {
                        return Err(py_err(format!("{}: {e}", f.display())));
                    }
                }
            }
            let boxed: Box<dyn AgentFactory> = Box::new(factory.clone());
            let boxed: Box<dyn AgentFactory> = match &version {
                Some(v) => Box::new(Versioned::new(boxed, v)),
                None => boxed,
            };
            let req = EvalRequest::new(dataset, task, split, out.clone())
                .episodes(episodes)
                .sample(sample.map(|count| Sample { count, seed }))
                .threads(threads)
                .fresh(fresh)
                .config(protocol);
            evaluate_with(&req, &*boxed, Layers::default()).map_err(py_err)?;
            write_accounting(&out, &factory.config().model, &factory.stats(), None)
                .map_err(py_err)?;
            let summary = out.join("summary.json");
            std::fs::read_to_string(&summary)
                .map_err(|e| py_err(format!("{}: {e}", summary.display())))
        })
    })
}
