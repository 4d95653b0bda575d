//! The native part of the `vlnverse` Python package (`vlnverse._native`).
//!
//! Python users import `vlnverse`, whose Gymnasium classes (in `python/vlnverse/`) wrap what
//! is here: `env::NativeVecEnv`, a batch of environments stepped in Rust with the GIL
//! released and observations written into preallocated NumPy arrays, and a few functions that
//! mirror the CLI (`load_episodes`, `score`, the run folder of `evaluate`). Every error reaches
//! Python as `vlnverse.VLNVerseError` (a `ValueError`) with the message the CLI prints; a Rust
//! panic is caught and reported the same way, never as `PanicException`.
//!
//! Built by maturin: `pip install ./crates/vlnverse-py`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

mod actions;
mod env;
mod generate;
mod layout;
mod mllm;
mod run;

create_exception!(
    _native,
    VLNVerseError,
    PyValueError,
    "Bad input or a failed job; the message names the file, field and value."
);

/// Any displayable error as a `VLNVerseError`.
pub(crate) fn py_err(e: impl std::fmt::Display) -> PyErr {
    VLNVerseError::new_err(e.to_string())
}

/// Run `f`, turning a panic into a `VLNVerseError` (panics must not reach Python raw).
pub(crate) fn guarded<T>(what: &str, f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic".into());
            Err(VLNVerseError::new_err(format!(
                "{what}: internal error ({msg}); please report it"
            )))
        }
    }
}

/// Parse a named argument (`task`, `split`, `setting`, ...); the error names it and the value.
pub(crate) fn parse<T: std::str::FromStr>(field: &str, v: &str) -> PyResult<T>
where
    T::Err: std::fmt::Display,
{
    v.parse::<T>()
        .map_err(|e| py_err(format!("invalid {field} `{v}`: {e}")))
}

/// The protocol the Python arguments describe (the CLI's defaults for the setting otherwise).
#[allow(clippy::too_many_arguments)]
pub(crate) fn protocol(
    setting: &str,
    action_space: &str,
    profile: &str,
    sensors: Option<std::path::PathBuf>,
    seed: u64,
    render: bool,
    backend: Option<&str>,
    max_steps: Option<u32>,
    success_distance: Option<f32>,
) -> PyResult<vlnverse_task::eval::EvalConfig> {
    use vlnverse_task::eval::{ActionSpace, EvalConfig, Setting};
    let setting: Setting = parse("setting", setting)?;
    let mut cfg = EvalConfig::for_setting(setting);
    cfg.action_space = match action_space {
        "discrete" => ActionSpace::Discrete,
        "continuous" | "velocity" => ActionSpace::Continuous,
        "waypoint" => ActionSpace::Waypoint,
        other => {
            return Err(py_err(format!(
                "invalid action_space `{other}`: expected discrete, continuous or waypoint"
            )))
        }
    };
    cfg.agent_profile = profile.to_string();
    cfg.seed = seed;
    cfg.render = render;
    if let Some(s) = sensors {
        cfg.rig = s.display().to_string();
    }
    if let Some(b) = backend {
        cfg.backend = Some(parse("backend", b)?);
    }
    if let Some(m) = max_steps {
        cfg.max_steps = m;
    }
    if let Some(d) = success_distance {
        cfg.success_distance = d;
    }
    Ok(cfg)
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("VLNVerseError", m.py().get_type::<VLNVerseError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<env::NativeVecEnv>()?;
    m.add_class::<run::RunFolder>()?;
    m.add_function(wrap_pyfunction!(run::load_episodes, m)?)?;
    m.add_function(wrap_pyfunction!(run::score, m)?)?;
    m.add_function(wrap_pyfunction!(generate::generate, m)?)?;
    m.add_function(wrap_pyfunction!(generate::merge, m)?)?;
    m.add_function(wrap_pyfunction!(mllm::evaluate_mllm, m)?)?;
    Ok(())
}
