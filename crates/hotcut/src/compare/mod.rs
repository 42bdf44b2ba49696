//! The `Compare` task (thesis ch. 6, "Discussion": let an architect see a design "for
//! different price categories (with different production methods) … both considering
//! price and style"): one design, several processes, each run by its own task.
//!
//! Every process that applies to the design runs the task that makes it (`PreCut`,
//! `RuledBlocks`, `HotBlade`, `FacadeSegmentation`, `BlockSegmentation` for milling
//! stock) through the [`Task`] trait — its own parameters, run, report and writers, so its
//! numbers ([`Task::figures`]) and its files (in a folder of the output) are the ones the
//! task gives on its own — in parallel (rayon, results in the job's order). Milling is
//! measured on the stock ([`stock`](crate::compare::stock)), and [`cost`](crate::compare::cost) turns the figures into hours and cost
//! and asks which rate change flips the ranking. This module imports no task module: the
//! job's process list ([`crate::job::Process`]) hands each task over as its own type.
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/compare-mould.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{}", outcome.report["winner"]);
//! # Ok(()) }
//! ```

/// Hours, cost, ranking and the rate that flips it.
pub mod cost;
/// What `report.html` shows, and the cost-versus-deviation chart.
mod page;
/// `report.json`.
pub mod report;
/// Milling the job's blocks as bought.
pub mod stock;

use geom::surface::Surface;
use rayon::prelude::*;
use schemars::JsonSchema;
use serde::{de::DeserializeOwned, Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::Estimate;
use crate::output::Files;
use crate::process::ProcessFigures;
use crate::progress::{NoProgress, Progress};
use crate::render::MemoryRun;
use crate::spec::compare::{RatesSpec, ToolSpec, RATE_DEFAULTS, STEPOVER_MM, TOOL_DIAMETER_MM};
use crate::spec::{BlockSpec, OutputKind, OutputSpec, SurfaceSpec};
use crate::task::{output_kinds, Output, Task, Visit};
use cost::{Rates, Tool};
pub use report::CompareReport;

/// The `Compare` task (thesis ch. 6): one design, the processes to make it with, each with
/// its own task's settings, and the rates that price them. Every process that applies to
/// the design runs its own task (its files go to a folder of the output); one that cannot
/// apply is reported with the reason. Write
/// `Compare(processes: [Milling(), HotWireRuled(sections: 24)], rates: Rates(eps_per_m3: 70))`.
/// `P` is the job's list of processes ([`crate::job::Process`]), which names the tasks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Compare<P> {
    /// The processes, in the order the report lists them (at least one, at most 12).
    pub processes: Vec<P>,
    /// Prices, machine rates and speeds. Default: every rate's documented default.
    #[serde(default)]
    pub rates: RatesSpec,
}

/// The kind of a process.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Milling the job's blocks as bought.
    Milling,
    /// Milling the blocks of a block segmentation.
    MillingSegmented,
    /// Hot-wire pre-cuts, then milling.
    PreCutThenMilling,
    /// Ruled rationalization cut by a hot wire.
    HotWireRuled,
    /// The hot blade on a grid of blocks.
    HotBlade,
    /// Facade segmentation for the hot blade.
    FacadeSegmentation,
}

impl Kind {
    /// The process's name as job files write it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Milling | Self::MillingSegmented => "Milling",
            Self::PreCutThenMilling => "PreCutThenMilling",
            Self::HotWireRuled => "HotWireRuled",
            Self::HotBlade => "HotBlade",
            Self::FacadeSegmentation => "FacadeSegmentation",
        }
    }

    /// Its name in the report (and its folder's).
    pub fn id(self) -> &'static str {
        match self {
            Self::Milling => "milling",
            Self::MillingSegmented => "milling_segmented",
            Self::PreCutThenMilling => "precut_milling",
            Self::HotWireRuled => "hot_wire",
            Self::HotBlade => "hot_blade",
            Self::FacadeSegmentation => "facade_segmentation",
        }
    }

    /// Where its task's fields are, under the process.
    fn inner(self) -> &'static str {
        match self {
            Self::MillingSegmented => "/stock/BlockSegmentation",
            Self::PreCutThenMilling => "/pre_cut",
            _ => "",
        }
    }

    /// Whether it cuts with the hot blade (its robot program is planned).
    pub fn blade(self) -> bool {
        matches!(self, Self::HotBlade | Self::FacadeSegmentation)
    }
}

/// A process as the job lists it: its kind, its milling tool, and the task it runs
/// handed to a [`Visit`] as its own type (`None` for milling the job's blocks).
pub trait ProcessSpec: Clone + std::fmt::Debug + Send + Sync + 'static {
    /// Its kind.
    fn kind(&self) -> Kind;
    /// Its milling tool (processes that mill).
    fn tool(&self) -> Option<&ToolSpec>;
    /// Calls `v` with the task it runs.
    fn visit<V: Visit>(&self, v: V) -> Option<V::Output>;
}

/// Where the task's fields are.
const PTR: &str = "/task/Compare";
/// Most processes in one comparison.
pub const MAX_PROCESSES: usize = 12;

/// A process as planned: what it runs, where its files go, and whether it applies.
#[derive(Debug, Clone)]
pub struct Planned<P> {
    /// The process as the job writes it.
    pub process: P,
    /// Its kind.
    pub kind: Kind,
    /// Its name in the report (`milling`, `milling_segmented`, `precut_milling`,
    /// `hot_wire`, `hot_blade`, `facade_segmentation`; `_2`, `_3` … when a kind is listed
    /// again).
    pub id: String,
    /// Its folder in the output (`None`: milling the job's blocks, which writes none).
    pub folder: Option<String>,
    /// Its milling tool, resolved (processes that mill).
    pub tool: Option<Tool>,
    /// Why it does not apply to the design, when it does not.
    pub not_applicable: Option<String>,
}

/// The parameters of a run.
#[derive(Debug, Clone)]
pub struct CompareParams<P> {
    /// The processes, in the job's order.
    pub processes: Vec<Planned<P>>,
    /// The rates in job units.
    pub rates: Rates,
    /// The rates as the job writes them.
    pub written: [Option<f64>; 10],
    /// `tolerance.max`.
    pub tolerance: f64,
    /// `tolerance.rms`.
    pub tolerance_rms: f64,
    /// The design's kind.
    pub design: &'static str,
}

/// One process's run.
#[derive(Debug, Clone, Default)]
pub struct Outcome {
    /// What it measured (`None`: not applicable, or its run failed).
    pub figures: Option<ProcessFigures>,
    /// Why its run failed, when it did.
    pub failed: Option<String>,
    /// Its files, named with its folder.
    pub files: Vec<(String, Vec<u8>)>,
    /// Its preview drawing: the first drawing its task writes.
    pub preview: Option<(String, Vec<u8>)>,
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct CompareRun {
    /// Per process, in the job's order.
    pub outcomes: Vec<Outcome>,
    /// The comparison (the report without the job's name and version).
    pub report: CompareReport,
}

impl<P> Task for Compare<P>
where
    P: ProcessSpec + PartialEq + Serialize + DeserializeOwned + JsonSchema,
{
    const NAME: &'static str = "Compare";
    const REPORT_SCHEMA: &'static str = "compare-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[Output::new(OutputKind::Svg, page::svg::<P>)];
    const REPORTS_NOTHING_TO_CUT: bool = true;
    const TABLES_FIRST: bool = true;
    type Params = CompareParams<P>;
    type Run = CompareRun;
    type Report = CompareReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        if self.processes.is_empty() || self.processes.len() > MAX_PROCESSES {
            errors.push(job.error(
                &format!("{PTR}/processes"),
                format!(
                    "list 1 to {MAX_PROCESSES} processes (Milling, PreCutThenMilling, HotWireRuled, HotBlade, FacadeSegmentation); it lists {}",
                    self.processes.len()
                ),
            ));
        }
        check_rates(self, job, errors);
        check_outputs(self, job, errors);
        // the ruled task places its blocks itself: it runs with the block's size only
        let unplaced = job.block.map(|b| BlockSpec {
            origin: None,
            ..b.clone()
        });
        for (i, p) in self.processes.iter().enumerate() {
            let kind = p.kind();
            let at = format!("{PTR}/processes/{i}/{}", kind.name());
            if let Some(t) = p.tool() {
                check_tool(t, &format!("{at}/tool"), job, errors);
            }
            if not_applicable_by_spec(kind, job.surface) {
                // reported NotApplicable, with its reason, once the surface is loaded
                continue;
            }
            match kind {
                Kind::Milling if job.block.is_none() => {
                    errors.push(job.error(
                        "/block",
                        format!("{at}: milling the job's blocks needs `block` (its size)"),
                    ));
                }
                Kind::PreCutThenMilling | Kind::HotWireRuled if job.wire.is_none() => {
                    errors.push(job.error(
                        "/wire",
                        format!("{at}: a hot-wire process needs `wire` (its cut lengths come from the wire programs)"),
                    ));
                }
                _ => {}
            }
            let fields = match kind {
                Kind::HotWireRuled => JobFields {
                    block: unplaced.as_ref(),
                    ..*job
                },
                _ => *job,
            };
            p.visit(SubCheck {
                job: fields,
                errors: &mut *errors,
                prefix: format!("{at}{}", kind.inner()),
            });
        }
    }

    fn params(&self, job: &Context) -> Result<CompareParams<P>> {
        let surface = job.surface(Self::NAME)?;
        let design = design_kind(surface);
        let mut bases: Vec<&'static str> = Vec::new();
        let processes = self
            .processes
            .iter()
            .map(|p| {
                let kind = p.kind();
                let base = kind.id();
                let n = bases.iter().filter(|b| **b == base).count();
                bases.push(base);
                let id = if n == 0 {
                    base.to_string()
                } else {
                    format!("{base}_{}", n + 1)
                };
                Planned {
                    tool: p.tool().map(|t| resolve_tool(t, job.per_mm())),
                    not_applicable: applies(kind, surface).err(),
                    folder: p.visit(crate::task::Name).map(|_| id.clone()),
                    id,
                    kind,
                    process: p.clone(),
                }
            })
            .collect();
        let written = self.rates.values();
        Ok(CompareParams {
            processes,
            rates: Rates::resolve(written, job.per_mm()),
            written,
            tolerance: job.tolerance.max,
            tolerance_rms: job.tolerance.rms,
            design,
        })
    }

    fn estimate(p: &CompareParams<P>, job: &Context) -> Estimate {
        let mut total = Estimate::new(1e6, 1e6, "/task/Compare/processes", "list fewer processes");
        let mut biggest = 0.0;
        for (i, planned) in p.processes.iter().enumerate() {
            if planned.not_applicable.is_some() {
                continue;
            }
            let at = format!("{PTR}/processes/{i}/{}", planned.kind.name());
            let e = match planned.kind {
                Kind::Milling => milling_estimate(job, &at),
                // as it runs: the blade processes plan their robot program
                _ => match planned.process.visit(SubEstimate {
                    job: &for_process(planned.kind, job),
                }) {
                    Some(Ok(e)) => e,
                    Some(Err(message)) => {
                        total.checks.push((at, message));
                        continue;
                    }
                    None => continue,
                },
            };
            // the task's pointers, moved to where the job has its fields: under the process
            let task_ptr = format!(
                "/task/{}",
                planned
                    .process
                    .visit(crate::task::Name)
                    .unwrap_or("Milling")
            );
            let inner = format!("{at}{}", planned.kind.inner());
            total.memory += e.memory;
            total.work += e.work;
            total.output += e.output;
            if e.work > biggest {
                biggest = e.work;
                total.pointer = remap(&e.pointer, &task_ptr, &inner).into();
                total.change = e.change;
            }
            total.checks.extend(e.checks.into_iter().map(|(ptr, m)| {
                (
                    remap(&ptr, &task_ptr, &inner),
                    format!("{}: {m}", planned.kind.name()),
                )
            }));
        }
        total
    }

    fn run(p: &CompareParams<P>, job: &Context, progress: &dyn Progress) -> Result<CompareRun> {
        progress.start("processes", p.processes.len() as u64);
        let outputs = job_outputs(job);
        let outcomes: Vec<Outcome> = p
            .processes
            .par_iter()
            .map(|planned| {
                let o = run_process(planned, job, &outputs);
                progress.tick();
                o
            })
            .collect();
        progress.finish();
        let report = page::compare(p, &outcomes, job);
        Ok(CompareRun { outcomes, report })
    }

    fn nothing_to_cut(run: &CompareRun) -> Option<String> {
        run.report.winner.is_none().then(|| {
            let why: Vec<String> = run
                .report
                .processes
                .iter()
                .map(|r| format!("{}: {}", r.process, r.reason.as_deref().unwrap_or("?")))
                .collect();
            format!(
                "no process makes the design within the tolerance ({})",
                why.join("; ")
            )
        })
    }

    fn passed_outputs(&self) -> Vec<OutputKind> {
        vec![
            OutputKind::Obj,
            OutputKind::Gltf,
            OutputKind::Csv,
            OutputKind::RobotTargets,
            OutputKind::Rapid,
            OutputKind::GCode,
            OutputKind::Blocks,
            OutputKind::PreCut,
        ]
    }

    fn attached(run: &CompareRun) -> Vec<(&str, &[u8])> {
        run.outcomes
            .iter()
            .flat_map(|o| o.files.iter().map(|(n, b)| (n.as_str(), b.as_slice())))
            .collect()
    }

    fn report(_: &CompareParams<P>, run: &CompareRun, _: &Context) -> CompareReport {
        run.report.clone()
    }

    fn summary(r: &CompareReport, job: &Context) -> String {
        page::summary(r, job)
    }

    fn page(r: &CompareReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }
}

/// The job's outputs the processes write: every one but the report, page and drawing
/// (which each process writes anyway).
fn job_outputs(job: &Context) -> Vec<OutputSpec> {
    job.outputs
        .iter()
        .filter(|o| {
            !matches!(
                o.kind(),
                OutputKind::Report | OutputKind::Html | OutputKind::Svg
            )
        })
        .cloned()
        .collect()
}

/// `design` of the report: the surface's kind, `ClosedMesh` for a closed mesh.
pub fn design_kind(surface: &Surface) -> &'static str {
    match surface {
        Surface::Mesh(m) if m.topology().boundary_edges == 0 => "ClosedMesh",
        other => crate::report::surface_kind(other),
    }
}

/// The job as a process of `kind` runs it: the blade processes plan their robot program
/// (their cut path is measured there), the ruled task places its blocks itself (the
/// block's `origin` left out).
fn for_process(kind: Kind, job: &Context) -> Context {
    let mut sub = job.clone();
    sub.rapid = kind.blade();
    if kind == Kind::HotWireRuled {
        if let Some(b) = sub.block.as_mut() {
            b.origin = None;
        }
    }
    sub
}

/// Whether the job's surface, as written, already tells that a process of `kind` does
/// not apply (a height field or B-spline is never a closed mesh; a mesh the job requires
/// closed is one): its checks are left out then, and the run reports it.
fn not_applicable_by_spec(kind: Kind, surface: Option<&SurfaceSpec>) -> bool {
    match surface {
        Some(SurfaceSpec::HeightField { .. } | SurfaceSpec::Spline { .. }) => {
            kind == Kind::MillingSegmented
        }
        Some(SurfaceSpec::Mesh { closed: true, .. }) => matches!(
            kind,
            Kind::PreCutThenMilling | Kind::HotBlade | Kind::FacadeSegmentation
        ),
        _ => false,
    }
}

/// Whether a process of `kind` can apply to `surface`; else why not.
fn applies(kind: Kind, surface: &Surface) -> std::result::Result<(), String> {
    let closed = design_kind(surface) == "ClosedMesh";
    let open_mesh = matches!(surface, Surface::Mesh(_)) && !closed;
    match kind {
        Kind::MillingSegmented if !closed => Err(
            "a block segmentation (thesis ch. 3) covers a closed mesh; the design is an open surface: mill the job's blocks (`stock: Blocks`)".into(),
        ),
        Kind::PreCutThenMilling if closed => Err(
            "pre-cuts remove the material above a design surface (thesis ch. 2); a closed model has material to remove under it too".into(),
        ),
        Kind::HotWireRuled if open_mesh => Err(
            "the ruled rationalization (thesis ch. 4) takes a closed mesh or a height field or B-spline surface (closed into a slab); the design is an open mesh".into(),
        ),
        Kind::HotBlade | Kind::FacadeSegmentation if closed => Err(
            "the hot blade sweeps one open facade surface through a block from one side (thesis ch. 5); a closed model needs cuts from every side".into(),
        ),
        _ => Ok(()),
    }
}

/// `ptr` with the task's prefix `from` replaced by `to`.
fn remap(ptr: &str, from: &str, to: &str) -> String {
    match ptr.strip_prefix(from) {
        Some(rest) => format!("{to}{rest}"),
        None => ptr.to_string(),
    }
}

/// A milling tool in job units.
fn resolve_tool(t: &ToolSpec, per_mm: f64) -> Tool {
    Tool {
        diameter: t.diameter.unwrap_or(TOOL_DIAMETER_MM * per_mm),
        stepover: t.stepover.unwrap_or(STEPOVER_MM * per_mm),
        feed: t.feed,
        removal_rate: t.removal_rate,
    }
}

/// The estimate of milling the job's blocks: a midpoint lattice per block column.
fn milling_estimate(job: &Context, at: &str) -> Estimate {
    let mut e = Estimate::new(1e6, 1e6, "/block/size", "make `block.size` larger");
    if let (Some(s), Some(b)) = (&job.surface, &job.block) {
        let n = stock::grid_blocks(s, arr(b.size), b.origin.map(arr));
        if n > stock::MAX_GRID_BLOCKS - 1.0 {
            e.checks.push((
                "/block/size".into(),
                format!("{at}: the job's blocks would tile the design {n} times or more (fewer than {} allowed); make `block.size` larger", stock::MAX_GRID_BLOCKS),
            ));
        }
        let lattice = (crate::process::VOLUME_GRID * crate::process::VOLUME_GRID) as f64;
        e.work = n * lattice * 50.0;
    }
    e
}

/// Runs one process (not applicable: nothing).
fn run_process<P: ProcessSpec>(
    planned: &Planned<P>,
    job: &Context,
    outputs: &[OutputSpec],
) -> Outcome {
    if planned.not_applicable.is_some() {
        return Outcome::default();
    }
    {
        if planned.kind == Kind::Milling {
            let measured = match (&job.surface, &job.block) {
                (Some(s), Some(b)) => stock::figures(s, arr(b.size), b.origin.map(arr)),
                _ => Err("milling the job's blocks needs a surface and `block`".into()),
            };
            return match measured {
                Ok(f) => Outcome {
                    figures: Some(f),
                    ..Outcome::default()
                },
                Err(e) => Outcome {
                    failed: Some(e),
                    ..Outcome::default()
                },
            };
        }
    }
    let sub = for_process(planned.kind, job);
    let ran = planned.process.visit(SubRun { job: &sub, outputs });
    let folder = planned.folder.clone().unwrap_or_default();
    match ran {
        Some(Ok(m)) => outcome(m, &folder),
        Some(Err(e)) => Outcome {
            failed: Some(e.to_string()),
            ..Outcome::default()
        },
        None => Outcome::default(),
    }
}

/// A process's outcome from its task's run in memory, its files put in `folder`.
fn outcome(m: MemoryRun, folder: &str) -> Outcome {
    let preview = m
        .files
        .iter()
        .find(|(n, _)| n.ends_with(".svg"))
        .map(|(n, b)| (format!("preview_{folder}_{n}"), b.clone()));
    let figures = m.figures.map(|mut f| {
        if f.why_not.is_none() {
            f.why_not = m.nothing_to_cut.clone();
        }
        f
    });
    Outcome {
        failed: figures.is_none().then(|| {
            m.nothing_to_cut
                .unwrap_or_else(|| "the task measures no process".into())
        }),
        figures,
        files: m
            .files
            .into_iter()
            .map(|(n, b)| (format!("{folder}/{n}"), b))
            .collect(),
        preview,
    }
}

/// Runs a process's task into memory, with the report, page and drawing and the job's
/// outputs that the task writes.
struct SubRun<'a> {
    job: &'a Context,
    outputs: &'a [OutputSpec],
}

impl Visit for SubRun<'_> {
    type Output = Result<MemoryRun>;

    fn visit<T: Task>(self, task: &T) -> Result<MemoryRun> {
        let kinds = output_kinds::<T>();
        let mut outs = vec![OutputSpec::Report, OutputSpec::Html];
        if kinds.contains(&OutputKind::Svg) {
            outs.push(OutputSpec::Svg);
        }
        for o in self.outputs {
            if kinds.contains(&o.kind()) && !outs.iter().any(|p| p.kind() == o.kind()) {
                outs.push(o.clone());
            }
        }
        crate::render::in_memory(task, self.job, &outs, &NoProgress)
    }
}

/// A process's task's own checks, its pointers moved under the process.
struct SubCheck<'a, 'e> {
    job: JobFields<'a>,
    errors: &'e mut Vec<JobError>,
    prefix: String,
}

impl Visit for SubCheck<'_, '_> {
    type Output = ();

    fn visit<T: Task>(self, task: &T) {
        let mut found = Vec::new();
        task.check(&self.job, &mut found);
        let from = format!("/task/{}", T::NAME);
        for e in found {
            self.errors.push(match e {
                JobError::Semantic {
                    path,
                    pointer,
                    message,
                } => JobError::Semantic {
                    path,
                    pointer: remap(&pointer, &from, &self.prefix),
                    message,
                },
                other => other,
            });
        }
    }
}

/// A process's task's parameters and estimate.
struct SubEstimate<'a> {
    job: &'a Context,
}

impl Visit for SubEstimate<'_> {
    type Output = std::result::Result<Estimate, String>;

    fn visit<T: Task>(self, task: &T) -> Self::Output {
        let params = task.params(self.job).map_err(|e| e.to_string())?;
        Ok(T::estimate(&params, self.job))
    }
}

/// A rate's unit in a job's length unit `unit`.
pub(crate) fn rate_unit(d: &crate::spec::compare::RateDefault, unit: &str) -> String {
    match d.length_power {
        3 => format!("{unit}³ per minute"),
        1 if d.field.ends_with("feed") => format!("{unit} per minute"),
        1 => format!("{unit} per second"),
        _ => d.unit.into(),
    }
}

/// The output kinds a task writes.
struct Kinds;

impl Visit for Kinds {
    type Output = Vec<OutputKind>;

    fn visit<T: Task>(self, _: &T) -> Vec<OutputKind> {
        output_kinds::<T>()
    }
}

/// Every output the job lists is written by the comparison or by one of its processes.
fn check_outputs<P: ProcessSpec>(c: &Compare<P>, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
    let written: Vec<OutputKind> = c
        .processes
        .iter()
        .filter_map(|p| p.visit(Kinds))
        .flatten()
        .chain([OutputKind::Report, OutputKind::Html, OutputKind::Svg])
        .collect();
    for (i, o) in job.outputs.iter().enumerate() {
        if !written.contains(&o.kind()) {
            errors.push(job.error(
                &format!("/outputs/{i}"),
                format!(
                    "output {} is written by none of the processes compared",
                    o.name()
                ),
            ));
        }
    }
}

/// How far from its default a rate or tool size may be, either way: 10⁶ (a rate further
/// off is a typo or a unit mistake, and its products overflow).
pub const RANGE: f64 = 1e6;

/// `v` for field `name` (at `at`): finite, positive (or, with `zero_ok`, 0 or more),
/// and within [`RANGE`] of `nominal` either way; else the error, naming the field.
fn bounded(v: f64, nominal: f64, zero_ok: bool, unit: &str) -> std::result::Result<(), String> {
    let (lo, hi) = (nominal / RANGE, nominal * RANGE);
    let ok = v.is_finite() && v <= hi && if zero_ok { v >= 0.0 } else { v >= lo };
    if ok {
        return Ok(());
    }
    Err(if zero_ok {
        format!("must be a finite number from 0 to {hi:e} ({unit}); it is {v}")
    } else {
        format!("must be a finite number from {lo:e} to {hi:e} ({unit}), above 0; it is {v}")
    })
}

/// Every rate finite, within [`RANGE`] of its default; prices and set-up 0 or more,
/// speeds, feeds and removal rates above 0.
fn check_rates<P>(c: &Compare<P>, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
    let per_mm = job.units.per_mm();
    for (v, d) in c.rates.values().iter().zip(RATE_DEFAULTS.iter()) {
        let Some(v) = v else { continue };
        let nominal = d.value * per_mm.powi(d.length_power);
        let unit = rate_unit(d, job.units.name());
        if let Err(m) = bounded(*v, nominal, d.length_power == 0, &unit) {
            errors.push(job.error(
                &format!("{PTR}/rates/{}", d.field),
                format!("{} {m}", d.field),
            ));
        }
    }
}

/// A milling tool: diameter, stepover and feeds finite, positive and within [`RANGE`] of
/// their defaults; the stepover within the diameter.
fn check_tool(t: &ToolSpec, at: &str, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
    let per_mm = job.units.per_mm();
    let rate = |k: usize| RATE_DEFAULTS[k].value * per_mm.powi(RATE_DEFAULTS[k].length_power);
    let fields = [
        ("diameter", t.diameter, TOOL_DIAMETER_MM * per_mm),
        ("stepover", t.stepover, STEPOVER_MM * per_mm),
        ("feed", t.feed, rate(cost::rate::FEED)),
        ("removal_rate", t.removal_rate, rate(cost::rate::REMOVAL)),
    ];
    let mut bad = false;
    for (name, v, nominal) in fields {
        if let Some(v) = v {
            if let Err(m) = bounded(v, nominal, false, job.units.name()) {
                bad = true;
                errors.push(job.error(&format!("{at}/{name}"), format!("{name} {m}")));
            }
        }
    }
    let d = t.diameter.unwrap_or(TOOL_DIAMETER_MM * per_mm);
    let s = t.stepover.unwrap_or(STEPOVER_MM * per_mm);
    if !bad && s > d {
        errors.push(job.error(
            &format!("{at}/stepover"),
            format!("the stepover ({s}) must not exceed the tool's diameter ({d})"),
        ));
    }
}

/// The drawings of a run: the chart, then every process's preview.
pub(crate) fn previews(run: &CompareRun) -> impl Iterator<Item = &(String, Vec<u8>)> {
    run.outcomes.iter().filter_map(|o| o.preview.as_ref())
}

/// Writes every process's preview drawing into `files`.
pub(crate) fn write_previews(run: &CompareRun, files: &mut Files) -> export::Result<()> {
    for (name, svg) in previews(run) {
        files.add(name.clone(), |buf| {
            buf.extend_from_slice(svg);
            Ok(())
        })?;
    }
    Ok(())
}

/// A triple as an array.
fn arr((x, y, z): (f64, f64, f64)) -> [f64; 3] {
    [x, y, z]
}
