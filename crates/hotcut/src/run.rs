//! The runner: runs a resolved job's task and writes its outputs as a whole.
//!
//! Outputs are rendered one file at a time and written into a temporary folder inside the
//! output directory (`.<name>.tmp-<pid>-…`), which takes the place of `<out>/<job name>/`
//! only when every file is written: renamed there when there is no earlier output, else
//! swapped with the earlier output in one atomic step (Linux `renameat2` with
//! `RENAME_EXCHANGE`; elsewhere the earlier folder is moved aside first), and the earlier
//! output is then deleted. So a kill at any instant leaves `<out>/<name>` holding one whole
//! run, old or new, and two runs of one job into one folder both end with a whole folder.
//! A run with nothing to cut fails and writes no file, except for a task that reports it
//! ([`Task::REPORTS_NOTHING_TO_CUT`](crate::task::Task::REPORTS_NOTHING_TO_CUT)): its
//! `report.json` and `report.html` (when the job lists them) replace the earlier output
//! as a whole, so no earlier program survives beside a report that refuses to cut.
//! A failed run leaves no partial folder; temporary folders of runs that were killed
//! (their process is gone) are deleted by the next run of the job, and
//! [`remove_temporaries`](crate::run::remove_temporaries) deletes this process's own on
//! SIGINT/SIGTERM (the CLI installs it).
//!
//! Entry points: [`run_job`](crate::run::run_job) for any job,
//! [`run_task`](crate::run::run_task) for a task of a known type with its typed results.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use crate::context::Context;
use crate::error::{HotcutError, Result};
use crate::load::ResolvedJob;
use crate::output::Files;
use crate::progress::Progress;
use crate::render::{own_outputs, render, summary, to_write};
use crate::spec::OutputSpec;
use crate::task::{Finished, Task, Visit};

/// What a run of any task produced.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The output folder, `<out>/<job name>`.
    pub dir: PathBuf,
    /// Files written, relative to `dir`, in order.
    pub files: Vec<String>,
    /// The report, as `report.json` holds it (before rounding).
    pub report: serde_json::Value,
    /// What the CLI prints about the run.
    pub summary: String,
}

/// What a run of task `T` produced, typed.
pub struct TaskOutcome<T: Task> {
    /// The output folder, `<out>/<job name>`.
    pub dir: PathBuf,
    /// Files written, relative to `dir`, in order.
    pub files: Vec<String>,
    /// The parameters it ran with.
    pub params: T::Params,
    /// What it produced.
    pub run: T::Run,
    /// Its report.
    pub report: T::Report,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> HotcutError + '_ {
    move |source| HotcutError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs a resolved job and writes its outputs to `<out>/<name>/`, replacing an earlier
/// run's folder.
///
/// # Errors
/// Failures of the task; I/O failures writing the outputs.
pub fn run_job(job: &ResolvedJob, out: &Path, progress: &dyn Progress) -> Result<RunOutcome> {
    job.task.visit(Runner { job, out, progress })
}

/// Runs a resolved job without writing a file: its report (and nothing else, unless
/// `outputs` names files, which are rendered into memory). A run with nothing to cut is
/// no error here: [`MemoryRun::nothing_to_cut`](crate::render::MemoryRun::nothing_to_cut)
/// says why. The Python bindings' `run(job)` without a folder.
///
/// # Errors
/// Failures of the task or of a writer; [`HotcutError::Cancelled`] when `progress` asked
/// for it.
pub fn run_in_memory(
    job: &ResolvedJob,
    outputs: &[OutputSpec],
    progress: &dyn Progress,
) -> Result<crate::render::MemoryRun> {
    struct InMemory<'a> {
        job: &'a ResolvedJob,
        outputs: &'a [OutputSpec],
        progress: &'a dyn Progress,
    }
    impl Visit for InMemory<'_> {
        type Output = Result<crate::render::MemoryRun>;
        fn visit<T: Task>(self, task: &T) -> Self::Output {
            let r = crate::render::in_memory(task, &self.job.context, self.outputs, self.progress)?;
            if self.progress.cancelled() {
                return Err(HotcutError::Cancelled);
            }
            Ok(r)
        }
    }
    job.task.visit(InMemory {
        job,
        outputs,
        progress,
    })
}

/// Runs `job` with `T` and type-erases the outcome.
struct Runner<'a> {
    job: &'a ResolvedJob,
    out: &'a Path,
    progress: &'a dyn Progress,
}

impl Visit for Runner<'_> {
    type Output = Result<RunOutcome>;

    fn visit<T: Task>(self, task: &T) -> Result<RunOutcome> {
        let job = &self.job.context;
        let o = run_task(task, job, &self.job.outputs, self.out, self.progress)?;
        let report = serde_json::to_value(&o.report).map_err(|e| HotcutError::Export {
            path: o.dir.join("report.json"),
            source: e.into(),
        })?;
        Ok(RunOutcome {
            summary: summary::<T>(&o.report, job),
            dir: o.dir,
            files: o.files,
            report,
        })
    }
}

/// Runs task `task` on `job` and writes `outputs` to `<out>/<name>/` (see
/// [`run_job`]).
///
/// # Errors
/// Failures of the task; an output the task does not write; I/O failures.
pub fn run_task<T: Task>(
    task: &T,
    job: &Context,
    outputs: &[OutputSpec],
    out: &Path,
    progress: &dyn Progress,
) -> Result<TaskOutcome<T>> {
    let start = std::time::Instant::now();
    let params = task.params(job)?;
    let run = T::run(&params, job, progress)?;
    if progress.cancelled() {
        return Err(HotcutError::Cancelled);
    }
    let refused = T::nothing_to_cut(&run);
    let outputs = to_write::<T>(job, own_outputs(task, outputs), &refused)?;
    let report = T::report(&params, &run, job);
    let done = Finished::<T> {
        job,
        params: &params,
        run: &run,
        report: &report,
    };
    let dir = out.join(&job.name);
    std::fs::create_dir_all(out).map_err(io(out))?;
    remove_stale(out, &job.name, &dir);
    let prefix = format!(".{}.tmp-{}-", job.name, std::process::id());
    let kept = {
        // made and listed under the lock, so a signal finds it listed
        let mut list = in_progress();
        let tmp = tempfile::Builder::new()
            .prefix(&prefix)
            .tempdir_in(out)
            .map_err(io(out))?;
        let kept = Temporary(tmp.keep());
        list.push(kept.0.clone());
        kept
    };
    let mut files = Files::new(&kept.0);
    let rendered = render(&done, &outputs, &mut files, refused.is_none(), start);
    let placed = match rendered {
        Ok(()) => place(&kept.0, &dir, progress).map(|()| files.into_names()),
        Err((file, source)) => Err(HotcutError::Export {
            path: dir.join(file),
            source,
        }),
    };
    // whatever is left at the temporary path (a failed run's files, or the earlier output
    // swapped out) goes
    drop(kept);
    let files = match (placed, &refused) {
        (Ok(files), _) => files,
        (Err(e), None) => return Err(e),
        // the reason the run cut nothing outlives a failure to write its report
        (Err(e), Some(why)) => {
            return Err(job.fail(format!(
                "nothing to cut, and the report could not be written ({e}): {why}"
            )))
        }
    };
    if let Some(why) = refused {
        return Err(job.fail(format!(
            "nothing to cut, only {} written to {}: {why}",
            files.join(" and "),
            dir.display()
        )));
    }
    Ok(TaskOutcome {
        dir,
        files,
        params,
        run,
        report,
    })
}

/// A run's temporary folder: deleted and unlisted when dropped, also when the run
/// unwinds (a stopped run, a writer's panic), so no half-written folder is left behind.
struct Temporary(PathBuf);

impl Drop for Temporary {
    fn drop(&mut self) {
        let mut list = in_progress();
        remove_entry(&self.0);
        list.retain(|p| p != &self.0);
    }
}

/// Temporary folders of this process's runs in progress.
static IN_PROGRESS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The list of temporary folders in progress (a panic elsewhere does not poison it).
fn in_progress() -> MutexGuard<'static, Vec<PathBuf>> {
    IN_PROGRESS.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Deletes the temporary folders of this process's runs in progress, and keeps any other
/// from starting to take its place: call it on SIGINT or SIGTERM, then exit. An output
/// being swapped into place finishes first (the swap holds the same lock), so
/// `<out>/<name>` keeps one whole run.
pub fn remove_temporaries() {
    let mut list = in_progress();
    for p in list.drain(..) {
        // the main thread may be writing a file into it: a few tries
        for _ in 0..20 {
            if std::fs::remove_dir_all(&p).is_ok() || !p.exists() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    }
    // the lock is held until the process exits
    std::mem::forget(list);
}

/// Deletes `<out>/.<name>.tmp-<pid>-…` folders of runs whose process is gone (killed
/// before they could clean up). An earlier output a killed two-step swap left aside
/// (`….old`, see [`exchange_in_two`]) is put back at `dir` when `dir` is missing, else
/// deleted. Only names of exactly that form are touched (a job named `a.tmp-x` is
/// another job).
fn remove_stale(out: &Path, name: &str, dir: &Path) {
    let prefix = format!(".{name}.tmp-");
    let Ok(entries) = std::fs::read_dir(out) else {
        return;
    };
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = file.strip_prefix(&prefix) else {
            continue;
        };
        let Some((pid, _)) = rest.split_once('-') else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if pid == std::process::id() || process_alive(pid) {
            continue;
        }
        if file.ends_with(".old") && !dir.exists() {
            let _ = std::fs::rename(e.path(), dir);
        } else {
            remove_entry(&e.path());
        }
    }
}

/// Deletes whatever is at `path`: a folder with its contents, or a file, symbolic link or
/// other entry (what `<out>/<name>` was before a run swapped it out may be any of them). A
/// symbolic link is removed, never followed.
fn remove_entry(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = std::fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// Whether process `pid` is running (on Linux: `/proc/<pid>` exists; elsewhere assumed,
/// so nothing is deleted that might be in use).
fn process_alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        Path::new(&format!("/proc/{pid}")).exists()
    } else {
        true
    }
}

/// Puts the finished folder `tmp` at `dir`: renamed there when `dir` does not exist,
/// else swapped with it atomically (after which `tmp` holds the earlier output, for the
/// caller to delete). Holds the in-progress lock, so a signal handler waits for it; a run
/// whose `progress` was cancelled is not placed.
fn place(tmp: &Path, dir: &Path, progress: &dyn Progress) -> Result<()> {
    let _guard = in_progress();
    // a caller that stopped the run keeps its earlier output (checked under the lock)
    if progress.cancelled() {
        return Err(HotcutError::Cancelled);
    }
    // a concurrent run may create or remove `dir` between the attempts: a few rounds
    let mut last = None;
    for _ in 0..4 {
        match std::fs::rename(tmp, dir) {
            Ok(()) => return Ok(()),
            // nothing there, not even a dangling link: try again
            Err(e) if std::fs::symlink_metadata(dir).is_err() => {
                last = Some(e);
                continue;
            }
            Err(_) => {}
        }
        match exchange(tmp, dir) {
            Ok(()) => return Ok(()),
            Err(e) => last = Some(e),
        }
    }
    Err(io(dir)(last.unwrap_or_else(|| {
        std::io::Error::other("the output folder kept changing under a concurrent run")
    })))
}

/// Swaps the folders at `a` and `b` in one step.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(()),
        // a file system without the exchange: the two-step fallback
        Err(rustix::io::Errno::INVAL) | Err(rustix::io::Errno::NOSYS) => exchange_in_two(a, b),
        Err(e) => Err(e.into()),
    }
}

/// Swaps the folders at `a` and `b`.
#[cfg(not(target_os = "linux"))]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    exchange_in_two(a, b)
}

/// Swaps `a` and `b` in two renames through a third name beside them: `b` is moved aside,
/// `a` moved to `b`, the old `b` moved to `a` (and put back if the second step fails).
/// A kill between the steps leaves the old output complete beside `b`.
fn exchange_in_two(a: &Path, b: &Path) -> std::io::Result<()> {
    let mut aside = a.as_os_str().to_owned();
    aside.push(".old");
    let aside = PathBuf::from(aside);
    std::fs::rename(b, &aside)?;
    if let Err(e) = std::fs::rename(a, b) {
        let _ = std::fs::rename(&aside, b);
        return Err(e);
    }
    std::fs::rename(&aside, a)
}
