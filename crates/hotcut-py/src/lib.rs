//! # hotcut-py — hotcut from Python
//!
//! The Python package `hotcut`, built by maturin from this crate with PyO3 against the
//! stable ABI of CPython ≥ 3.9 (`abi3`), so one wheel serves Rhino 8 (CPython 3.9),
//! Grasshopper's Python 3 component, compas and current Pythons. A thin layer: every
//! number comes from the workspace's crates; this crate only converts Python values to
//! their types and back, and turns their errors into Python exceptions.
//!
//! Without its `python` feature the crate is empty, so `cargo test --workspace` builds on
//! a machine without Python; maturin turns the feature on (`pyproject.toml`). The Python
//! API is documented in `python/hotcut/__init__.pyi` and the README's "From Python".
//!
//! Modules (all behind the `python` feature):
//! - `convert`: points and numbers between Python (lists, tuples, numpy arrays, Rhino and
//!   compas points) and Rust; arrays out as numpy when it is installed.
//! - `guard`: every call caught, so a Rust panic becomes `RuntimeError`, never an abort.
//! - `jobs`: `run` and `validate` of job files, RON text or dicts; `JobError`; the run on a
//!   worker thread with the GIL released and Ctrl-C honoured.
//! - `curves`: `hotcut.elastica`: the `Elastica` class, `fit`, `between`, `Elliptic`.
//! - `checks`: `check_section` and `bezier_to_elastica`, the checks made while dragging.

#[cfg(feature = "python")]
mod checks;
#[cfg(feature = "python")]
mod convert;
#[cfg(feature = "python")]
mod curves;
#[cfg(feature = "python")]
mod guard;
#[cfg(feature = "python")]
mod jobs;

#[cfg(feature = "python")]
use pyo3::prelude::*;

/// The native module `hotcut._native`; `hotcut/__init__.py` re-exports it.
#[cfg(feature = "python")]
#[pymodule(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    jobs::register(m)?;
    curves::register(m)?;
    checks::register(m)?;
    convert::register(m)?;
    guard::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
