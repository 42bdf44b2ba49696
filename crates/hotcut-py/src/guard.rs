//! Every call into Rust is caught: a panic (a bug) becomes Python's `RuntimeError` with its
//! message, never a `PanicException` that slips past `except Exception`, never an abort.

use std::any::Any;
use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// The message a panic carried.
pub fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".to_string()
    }
}

/// The `RuntimeError` of a panic.
pub fn panic_error(payload: &(dyn Any + Send)) -> PyErr {
    PyRuntimeError::new_err(format!(
        "hotcut: internal error (a bug, please report it with the input): {}",
        panic_message(payload)
    ))
}

/// Runs `f`, turning a panic into `RuntimeError`.
pub fn guarded<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|p| Err(panic_error(p.as_ref())))
}

/// Test hook: panics inside the guard with `message` (the tests check that it arrives as
/// `RuntimeError`).
#[pyfunction]
fn _panic_for_test(message: &str) -> PyResult<()> {
    guarded(|| panic!("{message}"))
}

/// Adds the test and benchmark hooks.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_panic_for_test, m)?)?;
    m.add_function(wrap_pyfunction!(_rust_fit_seconds, m)?)
}

/// Benchmark hook (`python/bench/overhead.py`): seconds per call of the Rust work behind
/// `hotcut.elastica.fit(points)` (chord lengths, the fit, its polish) on 2-D `points`,
/// timed over `repeats` calls inside Rust — the baseline the bindings' overhead is
/// measured against, in the same process and build.
#[pyfunction]
fn _rust_fit_seconds(points: Vec<[f64; 2]>, repeats: usize) -> PyResult<f64> {
    guarded(|| {
        let params = elastica::FitParams::default();
        let s = geom::polyline::chord_lengths(&points);
        let start = std::time::Instant::now();
        for _ in 0..repeats.max(1) {
            let f = elastica::fit_points_with_arclength(&points, &s, &params)
                .and_then(|f| elastica::polish(&points, &s, &f, &params))
                .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
            std::hint::black_box(f);
        }
        Ok(start.elapsed().as_secs_f64() / repeats.max(1) as f64)
    })
}
