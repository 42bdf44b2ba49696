//! The [`Task`](crate::task::Task) trait every task implements, the [`Output`](crate::task::Output) table through which it
//! declares and writes its files, and [`Visit`](crate::task::Visit), the way code that works for any task (the
//! checks, the runner) is handed the job's task as its own type.
//!
//! A task is its job-file struct (`HotBlade { targets_per_block, .. }`); the trait turns
//! it into parameters, runs it, makes its report and writes its files.

use schemars::JsonSchema;
use serde::Serialize;

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::{Estimate, Limits};
use crate::output::Files;
use crate::progress::Progress;
use crate::spec::{OutputKind, OutputSpec};

/// One task of a job file.
pub trait Task: Sized + 'static {
    /// The task's name as job files write it (`HotBlade`).
    const NAME: &'static str;
    /// File name of its report's JSON Schema in `schemas/`.
    const REPORT_SCHEMA: &'static str;
    /// The files it writes besides `report.json`, each kind once with its writer.
    /// Validation accepts exactly these kinds (and `Report`); the runner writes through them.
    const OUTPUTS: &'static [Output<Self>];
    /// Whether the task follows a cutting-direction curve (`cutting.curve`). Default: no.
    const CUTTING_CURVE: bool = false;
    /// Whether a run with nothing to cut ([`Task::nothing_to_cut`]) still writes the job's
    /// `report.json` and `report.html` (saying why, with numbers) before it fails; its
    /// other files (machine programs, meshes, drawings) are never written. Default: no
    /// (the run fails with no file).
    const REPORTS_NOTHING_TO_CUT: bool = false;
    /// Whether `report.html` shows the task's tables before its drawings (Compare opens
    /// on its comparison table). Default: no.
    const TABLES_FIRST: bool = false;

    /// Parameters of a run, built from the resolved job.
    type Params: 'static;
    /// What a run produces, kept for the report and the writers.
    type Run: 'static;
    /// `report.json`.
    type Report: Serialize + JsonSchema + 'static;

    /// Layer-3 checks of the task's own fields and of the common fields it needs: every
    /// problem is pushed to `errors`, with its JSON pointer.
    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>);

    /// The parameters for a resolved job.
    ///
    /// # Errors
    /// What validation would have reported, should the job lack something.
    fn params(&self, job: &Context) -> Result<Self::Params>;

    /// How much work and memory a run with `params` will take, and the checks that need
    /// the resolved job (the surface loaded); made at validation, before any geometry
    /// work, and checked against [`crate::limits::Limits`].
    fn estimate(params: &Self::Params, job: &Context) -> Estimate;

    /// Runs the task.
    ///
    /// # Errors
    /// Failures of the geometry or of the algorithm on valid input.
    fn run(params: &Self::Params, job: &Context, progress: &dyn Progress) -> Result<Self::Run>;

    /// Why a run produced nothing to cut (no block, piece, pose or cut), or `None` when
    /// it did. A run with nothing to cut fails and writes no file (but its report and page
    /// when [`Task::REPORTS_NOTHING_TO_CUT`]). Default: `None` (tasks that write no machine
    /// file).
    fn nothing_to_cut(run: &Self::Run) -> Option<String> {
        let _ = run;
        None
    }

    /// The run measured as a production process ([`crate::process`]), for `Compare`;
    /// `None` for a task that is not one (the default).
    fn figures(
        params: &Self::Params,
        run: &Self::Run,
        report: &Self::Report,
        job: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let _ = (params, run, report, job);
        None
    }

    /// Output kinds a job of this task may list besides [`Task::OUTPUTS`], written by
    /// [`Task::attached`] (Compare: the kinds its processes write). Default: none.
    fn passed_outputs(&self) -> Vec<OutputKind> {
        Vec::new()
    }

    /// Files of a finished run written as they are, after its outputs (`name` may hold a
    /// folder: Compare's processes' files, each in its folder). Default: none.
    fn attached(run: &Self::Run) -> Vec<(&str, &[u8])> {
        let _ = run;
        Vec::new()
    }

    /// The report of a run.
    fn report(params: &Self::Params, run: &Self::Run, job: &Context) -> Self::Report;

    /// What the CLI prints after a run: lines without a trailing newline.
    fn summary(report: &Self::Report, job: &Context) -> String;

    /// What `report.html` shows of a run: the verdict, counts, constraints, notes and
    /// tables (the runner adds the drawings, files, run time and job).
    fn page(report: &Self::Report, job: &Context) -> export::html::Body;
}

/// A finished run, as the writers see it.
pub struct Finished<'a, T: Task> {
    /// The job.
    pub job: &'a Context,
    /// The parameters it ran with.
    pub params: &'a T::Params,
    /// What it produced.
    pub run: &'a T::Run,
    /// Its report.
    pub report: &'a T::Report,
}

/// Writes the files of one output (`spec` carries its options) into `files`.
pub type Writer<T> = fn(&Finished<'_, T>, &OutputSpec, &mut Files) -> export::Result<()>;

/// An output kind a task writes, and its writer.
pub struct Output<T: Task> {
    /// The kind, as job files name it.
    pub kind: OutputKind,
    /// Its writer.
    pub write: Writer<T>,
}

impl<T: Task> Output<T> {
    /// Kind `kind`, written by `write`.
    pub const fn new(kind: OutputKind, write: Writer<T>) -> Self {
        Self { kind, write }
    }
}

/// The output kinds `T` writes, `Report` and `Html` (every task's) first.
pub fn output_kinds<T: Task>() -> Vec<OutputKind> {
    [OutputKind::Report, OutputKind::Html]
        .into_iter()
        .chain(T::OUTPUTS.iter().map(|o| o.kind))
        .collect()
}

/// Code that works for any task: [`crate::job::TaskSpec::visit`] calls
/// [`visit`](Visit::visit) with the job's task as its own type.
pub trait Visit {
    /// What the visit returns.
    type Output;
    /// Does the work for task `task` of type `T`.
    fn visit<T: Task>(self, task: &T) -> Self::Output;
}

/// Code that works for every task type, without a task value (the schema list):
/// [`crate::job::TaskSpec::each`] calls [`visit`](VisitType::visit) once per task type.
pub trait VisitType {
    /// Does the work for task type `T`.
    fn visit<T: Task>(&mut self);
}

/// The checks every task gets: its own ([`Task::check`]), that it writes every output the
/// job asks for, and that only a task that follows a cutting-direction curve is given one.
pub struct Check<'a, 'e> {
    /// The job's common fields.
    pub job: JobFields<'a>,
    /// Whether the job gives `cutting.curve`.
    pub has_curve: bool,
    /// Where problems go.
    pub errors: &'e mut Vec<JobError>,
}

impl Visit for Check<'_, '_> {
    type Output = ();

    fn visit<T: Task>(self, task: &T) {
        let Check {
            job,
            has_curve,
            errors,
        } = self;
        if has_curve && !T::CUTTING_CURVE {
            errors.push(job.error(
                "/cutting/curve",
                format!("a cutting-direction curve is not used by task {}", T::NAME),
            ));
        }
        task.check(&job, errors);
        let mut kinds = output_kinds::<T>();
        kinds.extend(task.passed_outputs());
        for (i, o) in job.outputs.iter().enumerate() {
            if job.outputs[..i].iter().any(|p| p.kind() == o.kind()) {
                errors.push(job.error(
                    &format!("/outputs/{i}"),
                    format!("output {} is listed twice", o.name()),
                ));
            }
            if !kinds.contains(&o.kind()) {
                let names: Vec<&str> = kinds.iter().map(|k| k.name()).collect();
                errors.push(job.error(
                    &format!("/outputs/{i}"),
                    format!(
                        "output {} is not produced by task {} (it writes {})",
                        o.name(),
                        T::NAME,
                        names.join(", ")
                    ),
                ));
            }
        }
    }
}

/// The task's name.
pub struct Name;

impl Visit for Name {
    type Output = &'static str;

    fn visit<T: Task>(self, _: &T) -> &'static str {
        T::NAME
    }
}

/// The checks of a resolved job: its parameters built, and the task's [`Task::estimate`]
/// checked against the limits. Every problem, with its JSON pointer.
pub struct Resolved<'a> {
    /// The resolved job.
    pub job: &'a Context,
    /// The limits.
    pub limits: &'a Limits,
}

impl Visit for Resolved<'_> {
    type Output = std::result::Result<Estimate, Vec<JobError>>;

    fn visit<T: Task>(self, task: &T) -> Self::Output {
        let job = self.job;
        let params = match task.params(job) {
            Ok(p) => p,
            Err(e) => return Err(vec![JobError::semantic(&job.path, "", e.to_string())]),
        };
        let e = T::estimate(&params, job);
        let mut out: Vec<JobError> = e
            .checks
            .iter()
            .map(|(pointer, message)| JobError::semantic(&job.path, pointer, message.clone()))
            .collect();
        out.extend(e.problems(&job.path, T::NAME, self.limits));
        if out.is_empty() {
            Ok(e)
        } else {
            Err(out)
        }
    }
}
