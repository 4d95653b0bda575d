//! The native part of the `vlnverse` Python package (`vlnverse._native`).
//!
//! Python users import `vlnverse`, whose Gymnasium classes (in `python/vlnverse/`) wrap what
//! is here: [`env::NativeVecEnv`], a batch of environments stepped in Rust with the GIL
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
mod layout;
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

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("VLNVerseError", m.py().get_type::<VLNVerseError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<env::NativeVecEnv>()?;
    m.add_class::<run::RunFolder>()?;
    m.add_function(wrap_pyfunction!(run::load_episodes, m)?)?;
    m.add_function(wrap_pyfunction!(run::score, m)?)?;
    Ok(())
}
