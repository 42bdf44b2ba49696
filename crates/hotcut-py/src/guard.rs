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

/// Adds the test hook.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_panic_for_test, m)?)
}
