//! The runner: runs a resolved job's task and writes its outputs as a whole.
//!
//! Outputs are rendered one file at a time and written into a temporary folder inside the
//! output directory, which is renamed to `<out>/<job name>/` only when every file is
//! written (an earlier run's folder is moved aside first, and put back if the rename
//! fails), so a failed run leaves no partial output folder.
//!
//! Entry points: [`run_job`](crate::run::run_job) for any job,
//! [`run_task`](crate::run::run_task) for a task of a known type with its typed results.

use std::path::{Path, PathBuf};

use export::json::REPORT_DIGITS;

use crate::context::Context;
use crate::error::{HotcutError, Result};
use crate::load::ResolvedJob;
use crate::output::Files;
use crate::progress::Progress;
use crate::spec::{OutputKind, OutputSpec};
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
            summary: T::summary(&o.report, job),
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
    let params = task.params(job)?;
    let run = T::run(&params, job, progress)?;
    if let Some(why) = T::nothing_to_cut(&run) {
        return Err(job.fail(format!("nothing to cut, no file written: {why}")));
    }
    let report = T::report(&params, &run, job);
    let done = Finished::<T> {
        job,
        params: &params,
        run: &run,
        report: &report,
    };
    let dir = out.join(&job.name);
    std::fs::create_dir_all(out).map_err(io(out))?;
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".{}.tmp-", job.name))
        .tempdir_in(out)
        .map_err(io(out))?;
    let files =
        render(&done, outputs, tmp.path()).map_err(|(file, source)| HotcutError::Export {
            path: dir.join(file),
            source,
        })?;
    move_into_place(tmp, &dir)?;
    Ok(TaskOutcome {
        dir,
        files,
        params,
        run,
        report,
    })
}

/// A file that could not be rendered, and why.
type FileError = (String, export::ExportError);

/// Writes every output into `dir`, in the job's order, through the task's declared
/// writers; an output the task does not declare is an error (validation rejects it first).
/// Returns the file names in order.
fn render<T: Task>(
    done: &Finished<'_, T>,
    outputs: &[OutputSpec],
    dir: &Path,
) -> std::result::Result<Vec<String>, FileError> {
    let mut files = Files::new(dir);
    for o in outputs {
        let before = files.len();
        let result = if o.kind() == OutputKind::Report {
            files.json("report.json", done.report, REPORT_DIGITS)
        } else {
            match T::OUTPUTS.iter().find(|w| w.kind == o.kind()) {
                Some(w) => (w.write)(done, o, &mut files),
                None => Err(export::ExportError::Data(format!(
                    "task {} does not write {} files",
                    T::NAME,
                    o.name()
                ))),
            }
        };
        // the file that failed: the last one the writer named, else the output itself
        let failed = |files: &Files| match files.last_name() {
            Some(name) if files.len() > before => name.to_string(),
            _ => o.name().to_string(),
        };
        result.map_err(|e| (failed(&files), e))?;
    }
    Ok(files.into_names())
}

/// Renames the finished temporary folder to `dir`. An earlier run's folder is first moved
/// aside (renamed within `out`), then the new one moved into place, then the old one
/// deleted; if the new one cannot be moved, the old one is put back. So `dir` always holds
/// one whole run, old or new.
fn move_into_place(tmp: tempfile::TempDir, dir: &Path) -> Result<()> {
    let kept = tmp.keep();
    let parent = dir.parent().unwrap_or(Path::new("."));
    let name = dir.file_name().map(|n| n.to_string_lossy().into_owned());
    let aside = dir.exists().then(|| {
        // a fresh name beside it: the temporary folder's own name with a suffix
        let stem = kept.file_name().map(|n| n.to_string_lossy().into_owned());
        parent.join(format!(
            "{}.old-{}",
            stem.unwrap_or_default(),
            name.unwrap_or_default()
        ))
    });
    if let Some(old) = &aside {
        if let Err(e) = std::fs::rename(dir, old) {
            let _ = std::fs::remove_dir_all(&kept);
            return Err(io(dir)(e));
        }
    }
    if let Err(e) = std::fs::rename(&kept, dir) {
        let _ = std::fs::remove_dir_all(&kept);
        if let Some(old) = &aside {
            let _ = std::fs::rename(old, dir);
        }
        return Err(io(dir)(e));
    }
    if let Some(old) = aside {
        let _ = std::fs::remove_dir_all(old);
    }
    Ok(())
}
