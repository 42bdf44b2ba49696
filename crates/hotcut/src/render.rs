//! Rendering a finished run's files: every output the job lists through the task's
//! declared writers, the attached files, and `report.html` last ([`render`](crate::render::render)); and a
//! whole run rendered into memory ([`in_memory`](crate::render::in_memory)), which `Compare` uses for its
//! processes. [`crate::run`] writes what is rendered into the output folder.

use std::path::PathBuf;

use export::html::{Drawing, Page};
use export::json::REPORT_DIGITS;

use crate::context::Context;
use crate::error::{HotcutError, Result};
use crate::output::Files;
use crate::progress::Progress;
use crate::spec::{OutputKind, OutputSpec};
use crate::task::{Finished, Task};

/// What the CLI prints after a run of `T`: the task's own lines, then the verdict of
/// `report.html` (the same [`Task::page`] call), so that the two cannot disagree.
pub fn summary<T: Task>(report: &T::Report, job: &Context) -> String {
    let verdict = T::page(report, job).verdict;
    let word = if verdict.ok { "verdict" } else { "warning" };
    format!("{}\n  {word}: {}", T::summary(report, job), verdict.text)
}

/// The outputs of `outputs` that `task` renders itself: the kinds it passes on to
/// [`Task::attached`] files (Compare's processes') are left out.
pub fn own_outputs<T: Task>(task: &T, outputs: &[OutputSpec]) -> Vec<OutputSpec> {
    let own = crate::task::output_kinds::<T>();
    let passed = task.passed_outputs();
    outputs
        .iter()
        .filter(|o| own.contains(&o.kind()) || !passed.contains(&o.kind()))
        .cloned()
        .collect()
}

/// What a run of `T` leaves to write: the outputs to render (only the report and page
/// when the run refused, for a task that reports it), or the error of a refusal.
pub fn to_write<T: Task>(
    job: &Context,
    outputs: Vec<OutputSpec>,
    refused: &Option<String>,
) -> Result<Vec<OutputSpec>> {
    let Some(why) = refused else {
        return Ok(outputs);
    };
    // a task that reports it writes its report and page, nothing else
    let reports_only: Vec<OutputSpec> = outputs
        .into_iter()
        .filter(|_| T::REPORTS_NOTHING_TO_CUT)
        .filter(|o| matches!(o.kind(), OutputKind::Report | OutputKind::Html))
        .collect();
    if reports_only.is_empty() {
        return Err(job.fail(format!("nothing to cut, no file written: {why}")));
    }
    Ok(reports_only)
}

/// A run of a task rendered into memory ([`in_memory`]).
#[derive(Debug, Clone)]
pub struct MemoryRun {
    /// Its files, (name, bytes), in the order a run into a folder writes them (none when
    /// it cut nothing and its task does not report that).
    pub files: Vec<(String, Vec<u8>)>,
    /// Its report, as `report.json` holds it (before rounding).
    pub report: serde_json::Value,
    /// The run measured as a process (`None`: the task is not one).
    pub figures: Option<crate::process::ProcessFigures>,
    /// Why it cut nothing, when it did not.
    pub nothing_to_cut: Option<String>,
    /// What the CLI would print about it.
    pub summary: String,
}

/// Runs task `task` on `job` and renders `outputs` into memory, each file as a run into a
/// folder writes it (Compare keeps its processes' files this way, one folder each). A run
/// with nothing to cut is not an error here: its files are the ones a run into a folder
/// would leave (none, or the report and page), and `nothing_to_cut` says why.
///
/// # Errors
/// Failures of the task, or of a writer.
pub fn in_memory<T: Task>(
    task: &T,
    job: &Context,
    outputs: &[OutputSpec],
    progress: &dyn Progress,
) -> Result<MemoryRun> {
    let start = std::time::Instant::now();
    let params = task.params(job)?;
    let run = T::run(&params, job, progress)?;
    let refused = T::nothing_to_cut(&run);
    // a refusal that writes no file is no error here: `nothing_to_cut` says why
    let outputs = to_write::<T>(job, own_outputs(task, outputs), &refused).unwrap_or_default();
    let report = T::report(&params, &run, job);
    let figures = T::figures(&params, &run, &report, job);
    let done = Finished::<T> {
        job,
        params: &params,
        run: &run,
        report: &report,
    };
    let mut files = Files::in_memory();
    render(&done, &outputs, &mut files, refused.is_none(), start).map_err(|(file, source)| {
        HotcutError::Export {
            path: PathBuf::from(file),
            source,
        }
    })?;
    let value = serde_json::to_value(&report).map_err(|e| HotcutError::Export {
        path: PathBuf::from("report.json"),
        source: e.into(),
    })?;
    Ok(MemoryRun {
        files: files.into_kept(),
        report: value,
        figures,
        summary: summary::<T>(&report, job),
        nothing_to_cut: refused,
    })
}

/// A file that could not be rendered, and why.
pub type FileError = (String, export::ExportError);

/// Writes every output into `dir`, in the job's order, through the task's declared
/// writers; an output the task does not declare is an error (validation rejects it first).
/// `report.html` comes last, whatever its place in the list, so it can link every other
/// file and give the run time since `start`. Returns the file names in order.
pub fn render<T: Task>(
    done: &Finished<'_, T>,
    outputs: &[OutputSpec],
    files: &mut Files,
    attach: bool,
    start: std::time::Instant,
) -> std::result::Result<(), FileError> {
    let html = outputs.iter().any(|o| o.kind() == OutputKind::Html);
    for o in outputs.iter().filter(|o| o.kind() != OutputKind::Html) {
        let before = files.len();
        let result = if o.kind() == OutputKind::Report {
            files.json("report.json", done.report, REPORT_DIGITS)
        } else {
            match T::OUTPUTS.iter().find(|w| w.kind == o.kind()) {
                Some(w) => (w.write)(done, o, files),
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
        result.map_err(|e| (failed(files), e))?;
    }
    if attach {
        for (name, bytes) in T::attached(done.run) {
            files
                .add(name, |buf| {
                    buf.extend_from_slice(bytes);
                    Ok(())
                })
                .map_err(|e| (name.to_string(), e))?;
        }
    }
    if html {
        write_page::<T>(done, files, start.elapsed()).map_err(|e| (PAGE.to_string(), e))?;
    }
    Ok(())
}

/// The page's file name.
const PAGE: &str = "report.html";

/// Writes `report.html` of a finished run into `files`, after every other file: the
/// drawings are rendered again into memory through the task's `Svg` writer (so the page
/// has them whether or not the job writes `Svg`), followed by any other drawing the run
/// wrote (PreCut's G-code previews); the files listed are the ones in `files`.
///
/// # Errors
/// The drawing writer's, or the file system's.
fn write_page<T: Task>(
    done: &Finished<'_, T>,
    files: &mut Files,
    elapsed: std::time::Duration,
) -> export::Result<()> {
    let mut drawings = Vec::new();
    if let Some(w) = T::OUTPUTS.iter().find(|w| w.kind == OutputKind::Svg) {
        let mut memory = Files::in_memory();
        (w.write)(done, &OutputSpec::Svg, &mut memory)?;
        drawings = memory
            .into_kept()
            .into_iter()
            .map(|(name, svg)| Drawing { name, svg })
            .collect();
    }
    // drawings other outputs wrote (PreCut's G-code previews); not the ones in folders
    // (a Compare's processes', which their own pages show)
    for name in files
        .names()
        .iter()
        .filter(|n| n.ends_with(".svg") && !n.contains('/'))
    {
        if drawings.iter().any(|d| &d.name == name) {
            continue;
        }
        if let Some(svg) = files.bytes(name) {
            drawings.push(Drawing {
                name: name.clone(),
                svg,
            });
        }
    }
    let listed = files
        .names()
        .iter()
        .map(|name| (name.clone(), files.size(name)))
        .collect();
    let job = done.job;
    let page = Page {
        title: job.name.clone(),
        subtitle: format!(
            "{} · units {} · hotcut {} · job file {}",
            T::NAME,
            job.units.name(),
            crate::report::VERSION,
            job.path.file_name().map_or_else(
                || job.path.display().to_string(),
                |f| f.to_string_lossy().into_owned()
            )
        ),
        body: T::page(done.report, job),
        drawings,
        tables_first: T::TABLES_FIRST,
        files: listed,
        run_time: format!("{:.2} s", elapsed.as_secs_f64()),
        job: job.job_ron.clone(),
        job_as_written: job.job_file.clone(),
    };
    files.text(PAGE, export::html::render(&page))
}
