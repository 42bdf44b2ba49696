//! `hotcut.run` and `hotcut.validate`: a job given as a path, RON text or a dict, loaded
//! and run by the `hotcut` crate exactly as the CLI does. The run goes on a worker thread
//! with the GIL released; the calling thread wakes every 50 ms to pass on progress and to
//! look for Ctrl-C, which stops the run (its next progress call unwinds it, and a run that
//! finished meanwhile is not put in place), so the earlier output stays whole.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use hotcut::limits::Limits;
use hotcut::load::ResolvedJob;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

use crate::convert::to_json;
use crate::guard::{guarded, panic_error};

create_exception!(
    hotcut,
    HotcutError,
    PyException,
    "Base class of the errors hotcut raises."
);
create_exception!(
    hotcut,
    JobError,
    HotcutError,
    "A job that is not valid: `message`, `pointer` (JSON pointer of the field), `line` and `col` (RON text), `path`, and `errors` (every problem found, as dicts). Nothing was written."
);
create_exception!(
    hotcut,
    RunError,
    HotcutError,
    "A valid job whose run failed, or cut nothing (then `report` holds its report when the run was in memory)."
);

/// Where a job comes from.
enum Source {
    /// A job file.
    File(PathBuf),
    /// RON text, named by a path whose folder holds its relative files.
    Ron(PathBuf, String),
    /// A dict job as JSON.
    Json(PathBuf, String),
}

impl Source {
    fn load(self, limits: &Limits) -> Result<ResolvedJob, Vec<hotcut::JobError>> {
        match self {
            Source::File(p) => hotcut::load::load_job_with(&p, limits),
            Source::Ron(p, text) => hotcut::load::load_job_text(&p, text, limits),
            Source::Json(p, json) => hotcut::load::load_job_json(&p, &json, limits),
        }
    }
}

/// The job argument read: a dict, a path (`str` without `(`, or path-like), or RON text.
fn source(job: &Bound<'_, PyAny>, base: Option<PathBuf>) -> PyResult<Source> {
    let base = base.unwrap_or_default();
    if job.cast::<PyDict>().is_ok() {
        let label = base.join("<job dict>");
        let json = to_json(job, "", 0).map_err(|(pointer, message)| {
            let e = hotcut::JobError::Schema {
                path: label.clone(),
                pointer,
                message,
            };
            job_error(job.py(), &[e])
        })?;
        return Ok(Source::Json(label, json.to_string()));
    }
    if let Ok(s) = job.cast::<PyString>() {
        let s = s.to_string();
        // RON text holds parentheses; a file that exists is a path even if its name does
        if s.contains('(') && !base.join(&s).is_file() {
            return Ok(Source::Ron(base.join("<job text>"), s));
        }
        return Ok(Source::File(base.join(s)));
    }
    if job.hasattr("__fspath__")? {
        let p: PathBuf = job.extract()?;
        return Ok(Source::File(base.join(p)));
    }
    Err(PyTypeError::new_err(
        "job: expected a path, RON text or a dict with the job file's fields",
    ))
}

/// The fields of one job error: (message, path, pointer, line, col).
type Fields = (String, String, Option<String>, Option<usize>, Option<usize>);

fn fields(e: &hotcut::JobError) -> Fields {
    use hotcut::JobError as E;
    let p = |p: &Path| p.display().to_string();
    match e {
        E::Read { path, message } => (message.clone(), p(path), None, None, None),
        E::Syntax {
            path,
            line,
            col,
            message,
        } => (message.clone(), p(path), None, Some(*line), Some(*col)),
        E::Structure {
            path,
            line,
            col,
            pointer,
            message,
        } => (
            message.clone(),
            p(path),
            Some(pointer.clone()),
            Some(*line),
            Some(*col),
        ),
        E::Schema {
            path,
            pointer,
            message,
        }
        | E::Semantic {
            path,
            pointer,
            message,
        } => (message.clone(), p(path), Some(pointer.clone()), None, None),
        other => (other.to_string(), String::new(), None, None, None),
    }
}

/// `JobError` carrying every problem: its text is what the CLI prints, its attributes
/// those of the first problem.
fn job_error(py: Python<'_>, errors: &[hotcut::JobError]) -> PyErr {
    let text = errors
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("\n");
    let err = JobError::new_err(text);
    let set = || -> PyResult<()> {
        let value = err.value(py);
        let list = PyList::empty(py);
        for e in errors {
            let (message, path, pointer, line, col) = fields(e);
            let d = PyDict::new(py);
            d.set_item("message", message)?;
            d.set_item("path", path)?;
            d.set_item("pointer", pointer)?;
            d.set_item("line", line)?;
            d.set_item("col", col)?;
            d.set_item("text", e.to_string())?;
            list.append(d)?;
        }
        let first = errors.first().map(fields).unwrap_or_default();
        value.setattr("message", first.0)?;
        value.setattr("path", first.1)?;
        value.setattr("pointer", first.2)?;
        value.setattr("line", first.3)?;
        value.setattr("col", first.4)?;
        value.setattr("errors", list)?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// The limits of a call: the CLI's defaults, or the ones given.
fn limits(
    max_work: Option<f64>,
    max_memory_gb: Option<f64>,
    max_output_mb: Option<f64>,
) -> PyResult<Limits> {
    let d = Limits::default();
    let mut l = d;
    for (v, slot, name) in [
        (max_work, &mut l.work, "max_work"),
        (max_memory_gb, &mut l.memory_gb, "max_memory_gb"),
        (max_output_mb, &mut l.output_mb, "max_output_mb"),
    ] {
        if let Some(v) = v {
            if !(v.is_finite() && v > 0.0) {
                return Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "{name} must be a positive number, got {v}"
                )));
            }
            *slot = v;
        }
    }
    Ok(l)
}

/// `validate(job, *, base=None, max_work=None, max_memory_gb=None, max_output_mb=None)`.
#[pyfunction]
#[pyo3(signature = (job, *, base=None, max_work=None, max_memory_gb=None, max_output_mb=None))]
fn validate(
    py: Python<'_>,
    job: &Bound<'_, PyAny>,
    base: Option<PathBuf>,
    max_work: Option<f64>,
    max_memory_gb: Option<f64>,
    max_output_mb: Option<f64>,
) -> PyResult<Py<PyAny>> {
    guarded(|| {
        let limits = limits(max_work, max_memory_gb, max_output_mb)?;
        let src = source(job, base)?;
        let loaded = py.detach(move || {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| src.load(&limits)))
        });
        let job = match loaded {
            Ok(Ok(j)) => j,
            Ok(Err(errors)) => return Err(job_error(py, &errors)),
            Err(p) => return Err(panic_error(p.as_ref())),
        };
        let d = PyDict::new(py);
        d.set_item("name", &job.context.name)?;
        d.set_item("task", job.task.name())?;
        d.set_item("estimate", job.estimate.summary())?;
        d.set_item("warnings", &job.context.warnings)?;
        Ok(d.into_any().unbind())
    })
}

/// Runs in progress (the tests check that a stopped run really stops).
static ACTIVE: AtomicUsize = AtomicUsize::new(0);

/// The unwinding payload of a stopped run.
struct Stopped;

/// A run's progress, shared between the worker and the waiting caller.
#[derive(Default)]
struct Shared {
    cancel: AtomicBool,
    done: AtomicU64,
    step: Mutex<(String, u64, String)>,
}

impl Shared {
    /// A stopped run unwinds from its next progress call (the caught payload is
    /// [`Stopped`]; no panic message is printed).
    fn check(&self) {
        if self.cancel.load(Ordering::Relaxed) {
            std::panic::resume_unwind(Box::new(Stopped));
        }
    }
    fn step(&self) -> std::sync::MutexGuard<'_, (String, u64, String)> {
        self.step.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl hotcut::Progress for Shared {
    fn start(&self, label: &str, total: u64) {
        self.check();
        *self.step() = (label.to_string(), total, String::new());
        self.done.store(0, Ordering::Relaxed);
    }
    fn tick(&self) {
        self.check();
        self.done.fetch_add(1, Ordering::Relaxed);
    }
    fn finish(&self) {
        self.check();
    }
    fn message(&self, status: &str) {
        self.check();
        self.step().2 = status.to_string();
    }
    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// What the worker thread hands back.
enum Outcome {
    Invalid(Vec<hotcut::JobError>),
    /// The report as `report.json` holds it.
    Done(String),
    /// Nothing to cut: why, and the report.
    NothingToCut(String, String),
    Failed(String),
    Stopped,
    Panicked(String),
}

/// The report rounded as `report.json` is written.
fn report_text(v: &serde_json::Value) -> Result<String, String> {
    export::json::to_json_string(v, export::json::REPORT_DIGITS).map_err(|e| e.to_string())
}

/// Loads and runs the job (on the worker thread).
fn work(src: Source, limits: &Limits, out: Option<&Path>, progress: &Shared) -> Outcome {
    let job = match src.load(limits) {
        Ok(j) => j,
        Err(e) => return Outcome::Invalid(e),
    };
    let result = match out {
        Some(dir) => hotcut::run::run_job(&job, dir, progress).map(|o| (o.report, None)),
        None => {
            hotcut::run::run_in_memory(&job, &[], progress).map(|m| (m.report, m.nothing_to_cut))
        }
    };
    match result {
        Ok((report, why)) => match (report_text(&report), why) {
            (Ok(text), None) => Outcome::Done(text),
            (Ok(text), Some(why)) => Outcome::NothingToCut(why, text),
            (Err(e), _) => Outcome::Failed(e),
        },
        Err(hotcut::HotcutError::Cancelled) => Outcome::Stopped,
        Err(e) => Outcome::Failed(e.to_string()),
    }
}

/// Counts a run as active while it lives.
struct Active;
impl Active {
    fn new() -> Self {
        ACTIVE.fetch_add(1, Ordering::SeqCst);
        Active
    }
}
impl Drop for Active {
    fn drop(&mut self) {
        ACTIVE.fetch_sub(1, Ordering::SeqCst);
    }
}

/// How often the caller wakes while the run goes on.
const POLL: Duration = Duration::from_millis(50);
/// How long a stopped run is given to unwind before the caller returns anyway.
const STOP_WAIT: Duration = Duration::from_millis(700);

/// `run(job, out=None, *, progress=None, base=None, max_work=None, ...)`.
#[pyfunction]
#[pyo3(signature = (job, out=None, *, progress=None, base=None, max_work=None, max_memory_gb=None, max_output_mb=None))]
#[allow(clippy::too_many_arguments)]
fn run(
    py: Python<'_>,
    job: &Bound<'_, PyAny>,
    out: Option<PathBuf>,
    progress: Option<Bound<'_, PyAny>>,
    base: Option<PathBuf>,
    max_work: Option<f64>,
    max_memory_gb: Option<f64>,
    max_output_mb: Option<f64>,
) -> PyResult<Py<PyAny>> {
    guarded(|| {
        let limits = limits(max_work, max_memory_gb, max_output_mb)?;
        if let Some(cb) = &progress {
            if !cb.is_callable() {
                return Err(PyTypeError::new_err(
                    "progress: expected a callable progress(label, done, total)",
                ));
            }
        }
        if let Some(dir) = &out {
            if dir.as_os_str().is_empty() {
                return Err(pyo3::exceptions::PyValueError::new_err(
                    "out: an empty path; give a folder (\".\" for the current one)",
                ));
            }
            if dir.exists() && !dir.is_dir() {
                return Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "out: {} exists and is not a folder",
                    dir.display()
                )));
            }
        }
        let src = source(job, base)?;
        let shared = Arc::new(Shared::default());
        let (tx, rx) = channel::<Outcome>();
        // shared with the GIL-free waits (a receiver alone is not `Sync`)
        let rx = Mutex::new(rx);
        let recv = |d: Duration| {
            rx.lock()
                .unwrap_or_else(PoisonError::into_inner)
                .recv_timeout(d)
        };
        let worker = Arc::clone(&shared);
        std::thread::Builder::new()
            .name("hotcut-run".into())
            .spawn(move || {
                let _active = Active::new();
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    work(src, &limits, out.as_deref(), &worker)
                }));
                let outcome = match r {
                    Ok(o) => o,
                    Err(p) if p.is::<Stopped>() => Outcome::Stopped,
                    Err(p) => Outcome::Panicked(crate::guard::panic_message(p.as_ref())),
                };
                let _ = tx.send(outcome);
            })
            .map_err(|e| pyo3::exceptions::PyOSError::new_err(e.to_string()))?;
        let mut seen = (String::new(), u64::MAX, u64::MAX, String::new());
        let outcome = loop {
            match py.detach(|| recv(POLL)) {
                Ok(o) => break o,
                Err(RecvTimeoutError::Disconnected) => {
                    break Outcome::Panicked("the run's thread ended without a result".into())
                }
                Err(RecvTimeoutError::Timeout) => {}
            }
            let polled = py.check_signals().and_then(|()| match &progress {
                Some(cb) => report_progress(cb, &shared, &mut seen),
                None => Ok(()),
            });
            if let Err(e) = polled {
                // Ctrl-C, or the callback raised: the run stops, the earlier output stays
                shared.cancel.store(true, Ordering::SeqCst);
                // a run that got past the last check before the flag was set puts its new
                // output in place: say so rather than claim the earlier one stayed
                let late = py.detach(|| recv(STOP_WAIT));
                if matches!(late, Ok(Outcome::Done(_)))
                    && e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py)
                {
                    return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
                        "the run had finished before it could stop: its new output is in place",
                    ));
                }
                return Err(e);
            }
        };
        outcome_to_py(py, outcome)
    })
}

/// Calls `cb(label, done, total)` when the step or its count changed.
fn report_progress(
    cb: &Bound<'_, PyAny>,
    shared: &Shared,
    seen: &mut (String, u64, u64, String),
) -> PyResult<()> {
    let (label, total, message) = shared.step().clone();
    let done = shared.done.load(Ordering::Relaxed);
    if label.is_empty()
        || (label == seen.0 && done == seen.1 && total == seen.2 && message == seen.3)
    {
        return Ok(());
    }
    let shown = if message.is_empty() {
        label.clone()
    } else {
        format!("{label}: {message}")
    };
    *seen = (label, done, total, message);
    cb.call1((shown, done, total))?;
    Ok(())
}

fn outcome_to_py(py: Python<'_>, outcome: Outcome) -> PyResult<Py<PyAny>> {
    let loads = |text: &str| -> PyResult<Py<PyAny>> {
        Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
    };
    match outcome {
        Outcome::Done(text) => loads(&text),
        Outcome::Invalid(errors) => Err(job_error(py, &errors)),
        Outcome::NothingToCut(why, text) => {
            let err = RunError::new_err(format!("nothing to cut: {why}"));
            err.value(py).setattr("report", loads(&text)?)?;
            Err(err)
        }
        Outcome::Failed(message) => {
            let err = RunError::new_err(message);
            err.value(py).setattr("report", py.None())?;
            Err(err)
        }
        Outcome::Stopped => Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
            "the run was stopped; the earlier output, if any, is unchanged",
        )),
        Outcome::Panicked(message) => Err(panic_error(&message)),
    }
}

/// Deletes the temporary folders of this process's runs that are still going (Python
/// calls it at exit, so a script that stops on Ctrl-C leaves no `.<name>.tmp-…` folder
/// behind on systems where the next run cannot tell a dead process's from a live one's).
#[pyfunction]
fn _remove_temporaries() {
    hotcut::run::remove_temporaries();
}

/// Test hook: how many runs are still going (a stopped run must reach 0 within a second).
#[pyfunction]
fn _active_runs() -> usize {
    ACTIVE.load(Ordering::SeqCst)
}

/// Adds `run`, `validate` and the exceptions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("HotcutError", py.get_type::<HotcutError>())?;
    m.add("JobError", py.get_type::<JobError>())?;
    m.add("RunError", py.get_type::<RunError>())?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    m.add_function(wrap_pyfunction!(_remove_temporaries, m)?)?;
    m.add_function(wrap_pyfunction!(_active_runs, m)?)
}
