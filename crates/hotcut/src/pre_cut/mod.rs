//! The `PreCut` task (thesis ch. 2): hot-wire cuts that remove the bulk of a block above
//! the design surface before milling, never cutting into it, by [`ruled::pre_cut`].
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // jobs/precut-bump.ron:
//! //   surface: HeightField(z: "...", x: (-0.5, 0.5), y: (-0.5, 0.5)),
//! //   block: Block(size: (1.0, 1.0, 0.6)),
//! //   task: PreCut(legs: 4, directions: [X]),
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/precut-bump.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{:?}", outcome.files);
//! # Ok(()) }
//! ```

/// Its files: `precut.json`, `sections.svg`, `precut.obj`, `model.gltf`, wire G-code with
/// its preview, and CSV.
mod outputs;
/// What `report.html` shows of it.
mod page;

/// `precut.json` (schema `schemas/precut.schema.json`).
#[derive(Debug, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PreCutFile<'a> {
    /// Length unit of every coordinate.
    pub units: Units,
    /// Per direction the polygons of rulings and the legs' B-splines.
    pub directions: &'a [ruled::DirectionCut],
}
/// The drawing of one wire program: both towers' paths, the block, the travel.
mod preview;

use crate::wire_machine as machine;
pub use crate::wire_machine::{machine, wire_params};

use geom::surface::Surface;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::Estimate;
use crate::progress::Progress;
use crate::spec::{OutputKind, OutputSpec, Units};
use crate::task::{Output, Task};

/// Hot-wire pre-cuts before milling (thesis ch. 2): per cutting direction, `legs`
/// straight wire cuts across the block whose lower envelope stays on or above the
/// design surface (never cutting into it) while leaving as little material as
/// possible for milling. The design surface's outward normal is roughly +z; the block
/// is `block` (origin defaults to the surface's bounding-box minimum). Write
/// `PreCut(legs: 4, directions: [X])`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PreCut {
    /// Cuts per direction (the moving polygon's legs), 1–32. Default: 4.
    #[serde(default = "default_legs")]
    #[schemars(range(min = 1, max = 32))]
    pub legs: u32,
    /// Cutting directions in the xy plane: a list of `X`, `Y`, `Degrees(a)` (from +x
    /// towards +y) or `Vector(dx, dy)`, or `Auto(n)` to try `n` directions evenly over
    /// the half turn and keep the one that leaves the least material. Default: `[X]`.
    #[serde(default = "default_cut_directions")]
    pub directions: Directions,
    /// B-spline degree of the cuts along the cutting direction (thesis p), 1–5.
    /// Default: 3.
    #[serde(default = "default_cut_degree")]
    #[schemars(range(min = 1, max = 5))]
    pub degree: u32,
    /// Control values per cut along the cutting direction (thesis k), degree + 1 to
    /// 64. Default: 8.
    #[serde(default = "default_cut_controls")]
    #[schemars(range(min = 2, max = 64))]
    pub controls: u32,
    /// Section planes along the cut (thesis N), ≥ 2. Default: 30.
    #[serde(default = "default_cut_samples")]
    #[schemars(range(min = 2, max = 500))]
    pub sections: u32,
    /// Samples per section across the block (thesis M), ≥ 2. Default: 30.
    #[serde(default = "default_cut_samples")]
    #[schemars(range(min = 2, max = 500))]
    pub samples: u32,
    /// Most assignment rounds of the optimizer. Default: 40.
    #[serde(default = "default_cut_rounds")]
    #[schemars(range(min = 1, max = 10000))]
    pub max_rounds: u32,
}

/// The cutting directions of a `PreCut`: a list, or a search.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(
    untagged,
    expecting = "a list of cutting directions such as [X, Degrees(30)], or Auto(n)"
)]
pub enum Directions {
    /// These directions (1–8), each cut in turn, e.g. `[X, Degrees(30)]`.
    List(#[schemars(length(min = 1, max = 8))] Vec<CutDirection>),
    /// `Auto(n)`: see [`SearchDirections`].
    Search(SearchDirections),
}

/// A search over cutting directions (thesis §2.4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum SearchDirections {
    /// `n` directions (1–36) at `i · 180° / n` from +x, each cut on its own; the one that
    /// leaves the least material for milling is kept, and every candidate is reported.
    Auto(#[schemars(range(min = 1, max = 36))] u32),
}

/// A cutting direction in the xy plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum CutDirection {
    /// Along +x.
    X,
    /// Along +y.
    Y,
    /// At this angle from +x towards +y, degrees.
    Degrees(f64),
    /// Along `(dx, dy)` (normalised; must not be zero).
    Vector(f64, f64),
}

impl CutDirection {
    /// The direction as an `[x, y]` vector (not normalised for `Vector`).
    pub fn vector(&self) -> [f64; 2] {
        match *self {
            Self::X => [1.0, 0.0],
            Self::Y => [0.0, 1.0],
            Self::Degrees(a) => [a.to_radians().cos(), a.to_radians().sin()],
            Self::Vector(x, y) => [x, y],
        }
    }
}

fn default_legs() -> u32 {
    4
}
fn default_cut_directions() -> Directions {
    Directions::List(vec![CutDirection::X])
}
fn default_cut_degree() -> u32 {
    3
}
fn default_cut_controls() -> u32 {
    8
}
fn default_cut_samples() -> u32 {
    30
}
fn default_cut_rounds() -> u32 {
    40
}

/// The report of a `PreCut` run (`report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PreCutReport {
    /// Job name.
    pub job: String,
    /// Task name, `PreCut`.
    pub task: String,
    /// Length unit of every length.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The block: minimum and maximum corner.
    pub block: ruled::Block,
    /// The box of what `model.gltf` shows (design, cut surfaces, block).
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// The optimizer's parameters as run.
    pub params: ruled::Params,
    /// Table 2.1: volumes normalised by the block.
    pub volumes: ruled::Volumes,
    /// Per direction: rounds, QPs, constraint points, objective history, clearance.
    pub directions: Vec<DirectionSummary>,
    /// With `directions: Auto(n)`: every candidate direction and what it left; the one
    /// kept is `best` (and the report's `directions`).
    pub search: Option<ruled::search::DirectionSearch>,
    /// With `wire`: the controller profile the programs are written for.
    pub machine: Option<String>,
    /// With `wire`: every cut's program, its extents per axis and its cut time.
    pub programs: Vec<WireProgram>,
}

/// One cut's program in the report.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct WireProgram {
    /// The program's file: `wire_dD_cC.gcode`.
    pub file: String,
    /// What it makes the machine do.
    #[serde(flatten)]
    pub summary: ruled::wire::ProgramSummary,
}

/// What the optimizer did for one direction.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct DirectionSummary {
    /// Unit cutting direction.
    pub direction: [f64; 3],
    /// Assignment rounds.
    pub rounds: usize,
    /// QPs solved.
    pub qps: usize,
    /// Constraint points at the end.
    pub constraint_points: usize,
    /// Objective per round.
    pub objective_history: Vec<f64>,
    /// Least height of a cut above the design on the check grid (> 0).
    pub clearance: f64,
}

/// Parameters of a `PreCut` run.
#[derive(Debug, Clone, PartialEq)]
pub struct PreCutParams {
    /// The optimizer's.
    pub cut: ruled::Params,
    /// The block: its origin defaults to the surface's bounding-box minimum.
    pub block: ruled::Block,
    /// The wire machine, when the job has one (`GCode`, `Csv`), stepping once per section.
    pub wire: Option<ruled::wire::WireParams>,
    /// Its controller, with the job's `wire`.
    pub machine: Option<ruled::wire::Machine>,
    /// With `directions: Auto(n)`: `n` (the optimizer's `directions` are then ignored).
    pub search: Option<usize>,
}

/// A finished run.
#[derive(Debug, Clone)]
pub struct PreCutRun {
    /// The full result (polygons, legs).
    pub cut: ruled::PreCut,
    /// The design surface.
    pub surface: Surface,
    /// Per direction, the wire's path of every cut (none without a wire machine).
    pub wires: Vec<Vec<ruled::wire::WirePath>>,
    /// Per direction, every cut's program, checked against the machine's travel.
    pub programs: Vec<Vec<ruled::wire::Program>>,
    /// The direction search, with `directions: Auto(n)`.
    pub search: Option<ruled::search::DirectionSearch>,
}

const PTR: &str = "/task/PreCut";

impl Task for PreCut {
    const NAME: &'static str = "PreCut";
    const REPORT_SCHEMA: &'static str = "pre-cut-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::PreCut, outputs::precut_json),
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::GCode, outputs::wire),
        Output::new(OutputKind::Csv, outputs::wire),
        Output::new(OutputKind::Obj, outputs::obj),
        Output::new(OutputKind::Gltf, outputs::gltf),
    ];
    type Params = PreCutParams;
    type Run = PreCutRun;
    type Report = PreCutReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        job.require_surface_and_block(Self::NAME, "", "cuts are", errors);
        // the optimizer's own checks, on these fields
        let problems = self.optimizer().problems();
        let problems = problems.into_iter().map(|e| (e.field, e.index, e.message));
        let element = |i: usize| match &self.directions {
            Directions::List(list) => format!("{:?}", list[i]),
            Directions::Search(s) => format!("{s:?}"),
        };
        job.param_problems(PTR, problems, element, errors);
        if let Directions::Search(SearchDirections::Auto(n)) = self.directions {
            let max = ruled::search::MAX_CANDIDATES;
            if !(1..=max as u32).contains(&n) {
                errors.push(job.error(
                    &format!("{PTR}/directions"),
                    format!("Auto needs 1–{max} directions, got {n}"),
                ));
            }
        }
        for (i, o) in job.outputs.iter().enumerate() {
            if matches!(o, OutputSpec::GCode | OutputSpec::Csv) && job.wire.is_none() {
                errors.push(job.error(
                    &format!("/outputs/{i}"),
                    format!("{} writes wire programs: the job needs `wire: Wire(tower_distance: .., kerf: ..)`", o.name()),
                ));
            }
        }
        if let Some(w) = job.wire {
            machine::check(job, w, errors);
        }
    }

    fn params(&self, job: &Context) -> Result<PreCutParams> {
        let spec = job.block(Self::NAME)?;
        let origin = match spec.origin {
            Some(o) => [o.0, o.1, o.2],
            None => {
                let b = job.surface(Self::NAME)?.aabb();
                [b.min.x, b.min.y, b.min.z]
            }
        };
        let size = [spec.size.0, spec.size.1, spec.size.2];
        let block = ruled::Block {
            min: origin,
            max: [
                origin[0] + size[0],
                origin[1] + size[1],
                origin[2] + size[2],
            ],
        };
        let mut cut = self.optimizer();
        // the legs' lines stay over the table out to the towers
        cut.span = job.wire.as_ref().map(|w| w.tower_distance);
        let wire = wire_params(job).map(|w| ruled::wire::WireParams {
            steps: cut.sections + 1,
            ..w
        });
        Ok(PreCutParams {
            cut,
            block,
            wire,
            machine: machine(job),
            search: self.search(),
        })
    }

    fn estimate(p: &PreCutParams, _job: &Context) -> Estimate {
        let mut checks = Vec::new();
        // the wire's checks against the block, per direction, as the run makes them; with
        // `Auto(n)`, for every candidate the search may keep
        let candidates: Vec<[f64; 2]> = match p.search {
            Some(n) => ruled::search::candidates(n).iter().map(|c| c.1).collect(),
            None => p.cut.directions.clone(),
        };
        for (i, d) in candidates.iter().enumerate() {
            match ruled::CutFrame::new(*d, &p.block) {
                Err(e) => checks.push((format!("{PTR}/directions/{i}"), e.to_string())),
                Ok(frame) => {
                    if let (Some(w), Some(m)) = (&p.wire, &p.machine) {
                        let which = |(at, message): (String, String)| {
                            match p.search {
                            Some(_) => (
                                at,
                                format!("{message} (along the Auto candidate at {:.1}°: every candidate must fit)", d[1].atan2(d[0]).to_degrees()),
                            ),
                            None => (at, message),
                        }
                        };
                        checks.extend(wire_checks(&frame, &p.block, w, m).into_iter().map(which));
                    }
                }
            }
        }
        let mut seen = std::collections::HashSet::new();
        checks.retain(|c| seen.insert(c.clone()));
        let c = &p.cut;
        let dirs = p.search.unwrap_or(c.directions.len()) as f64;
        // the constraint points of one direction's program, each touching `degree + 1`
        // controls of every leg
        let points = (c.sections * c.samples * c.check_density.max(1)) as f64;
        let nnz = points * (c.legs * (c.degree + 1)) as f64;
        let vars = (c.legs * c.controls * 3) as f64;
        Estimate {
            checks,
            ..Estimate::new(
                nnz * 48.0
                    + vars * vars * 16.0
                    + (c.volume_grid * c.volume_grid) as f64 * 16.0
                    + 1e7,
                dirs * c.max_rounds as f64 * (nnz * 20.0 + vars * vars * 50.0),
                "/task/PreCut/samples",
                "lower the task's sections, samples, legs, controls or max_rounds",
            )
        }
    }

    fn run(params: &PreCutParams, job: &Context, progress: &dyn Progress) -> Result<PreCutRun> {
        let surface = job.surface(Self::NAME)?;
        let p = &params.cut;
        let dirs = params.search.unwrap_or(p.directions.len());
        progress.start("pre-cut", (dirs * p.max_rounds) as u64);
        let tick = |p: ruled::Progress| {
            progress.tick();
            progress.message(&format!(
                "direction {} · round {} · Σd² {:.4e}",
                p.direction + 1,
                p.round + 1,
                p.objective
            ));
        };
        let (cut, search) = match params.search {
            Some(n) => {
                let (cut, search) =
                    ruled::search::search_directions(surface, &params.block, p, n, &tick)
                        .map_err(|e| job.fail(e.to_string()))?;
                (cut, Some(search))
            }
            None => (
                ruled::pre_cut(surface, &params.block, p, &tick)
                    .map_err(|e| job.fail(e.to_string()))?,
                None,
            ),
        };
        progress.finish();
        // the wire's paths and programs now: bad machine settings and programs outside the
        // machine's travel fail the run, before any file is written
        let (wires, programs) = match (&params.wire, &params.machine) {
            (Some(w), Some(m)) => wire_programs(&cut, params, w, m, job)?,
            _ => (Vec::new(), Vec::new()),
        };
        Ok(PreCutRun {
            cut,
            surface: surface.clone(),
            wires,
            programs,
            search,
        })
    }

    fn nothing_to_cut(run: &PreCutRun) -> Option<String> {
        let legs: usize = run.cut.directions.iter().map(|d| d.legs.len()).sum();
        (legs == 0).then(|| "no cut in any direction".to_string())
    }

    fn figures(
        params: &PreCutParams,
        run: &PreCutRun,
        report: &PreCutReport,
        job: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let b = &params.block;
        let v = b.volume();
        let area = crate::process::area_over(
            &run.surface,
            [b.min[0], b.min[1]],
            [b.max[0], b.max[1]],
            crate::process::VOLUME_GRID,
        );
        let cut: f64 = report
            .programs
            .iter()
            .map(|p| p.summary.cut_length_mm)
            .sum();
        let minutes: f64 = report.programs.iter().map(|p| p.summary.cut_minutes).sum();
        // the pre-cut makes one block: a design wider than it is not made
        let d = run.surface.aabb();
        let slack = 1e-9 * (b.max[0] - b.min[0]).max(b.max[1] - b.min[1]);
        let outside = d.min.x < b.min[0] - slack
            || d.min.y < b.min[1] - slack
            || d.max.x > b.max[0] + slack
            || d.max.y > b.max[1] + slack;
        // a cut that does not clear the design cuts into it (the page's "not cuttable")
        let into = report
            .directions
            .iter()
            .find(|d| !(d.clearance > 0.0))
            .map(|d| (d.direction, d.clearance));
        let why_not = match (&area, report.programs.is_empty()) {
            _ if into.is_some() => into.map(|(d, c)| {
                format!(
                    "the cuts along ({:.3}, {:.3}, {:.3}) do not clear the design (clearance {c:.4}): they cut into it",
                    d[0], d[1], d[2]
                )
            }),
            _ if outside => Some(format!(
                "the pre-cut makes one block, x {}–{}, y {}–{}, and the design spans x {}–{}, y {}–{}: give a block that holds it",
                b.min[0], b.max[0], b.min[1], b.max[1], d.min.x, d.max.x, d.min.y, d.max.y
            )),
            (Err(e), _) => Some(format!("the design's area could not be measured: {e}")),
            (_, true) => Some("no wire program (the job gives no `wire`, or no cut)".into()),
            _ => None,
        };
        Some(crate::process::ProcessFigures {
            why_not,
            blocks: 1,
            stock_volume: v,
            part_volume: report.volumes.model * v,
            milling_volume: report.volumes.ruled * v,
            milled_area: area.unwrap_or(0.0),
            cutter: crate::process::Cutter::Wire,
            cut_length: cut * job.per_mm(),
            cut_speed: if minutes > 0.0 {
                cut * job.per_mm() / (60.0 * minutes)
            } else {
                0.0
            },
            dwell_s: report.programs.iter().map(|p| p.summary.preheat_s).sum(),
            // the block is turned once per direction
            setups: report.directions.len(),
            programs: report.programs.len(),
            deviation: None,
        })
    }

    fn report(params: &PreCutParams, run: &PreCutRun, job: &Context) -> PreCutReport {
        // the directions as run (a search's: the one kept)
        let directions = run
            .cut
            .directions
            .iter()
            .map(|d| [d.direction[0], d.direction[1]])
            .collect();
        PreCutReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            block: params.block,
            model_bounds: crate::report::ModelBounds::of(outputs::scene(run, &params.block)),
            params: ruled::Params {
                directions,
                ..params.cut.clone()
            },
            search: run.search.clone(),
            machine: params.machine.as_ref().map(|m| m.profile.clone()),
            programs: run
                .programs
                .iter()
                .flatten()
                .map(|p| WireProgram {
                    file: program_file(&p.summary, "gcode"),
                    summary: p.summary.clone(),
                })
                .collect(),
            volumes: run.cut.volumes,
            directions: run
                .cut
                .directions
                .iter()
                .map(|d| DirectionSummary {
                    direction: d.direction,
                    rounds: d.rounds,
                    qps: d.qps,
                    constraint_points: d.constraint_points,
                    objective_history: d.objective_history.clone(),
                    clearance: d.clearance,
                })
                .collect(),
        }
    }

    fn page(r: &PreCutReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &PreCutReport, job: &Context) -> String {
        let v = &r.volumes;
        let dirs = match &r.search {
            Some(s) => format!(
                "the best of {} directions ({:.1}°)",
                s.candidates.len(),
                s.candidates[s.best].degrees
            ),
            None => format!("{} direction(s)", r.directions.len()),
        };
        format!(
            "{} (PreCut): {dirs} × {} cut(s); left for milling {:.4} of the block (convex hull {:.4}, block {:.4}): {:.0} % more removed than the hull, {:.0} % more than the block; model {:.4}",
            job.name,
            r.params.legs,
            v.ruled,
            v.convex_hull,
            v.bounding_box,
            v.more_than_hull_percent,
            v.more_than_box_percent,
            v.model
        )
    }
}

/// The file of a cut's program or CSV: `wire_dD_cC.{ext}`, 1-based.
pub fn program_file(s: &ruled::wire::ProgramSummary, ext: &str) -> String {
    format!("wire_d{}_c{}.{ext}", s.direction + 1, s.cut + 1)
}

/// The wire's checks for one direction's frame, as the run makes them: the settings
/// against the block's width, the dialect, and the block with its lead and clearance
/// within the machine's travel. `(pointer, message)` pairs.
fn wire_checks(
    frame: &ruled::CutFrame,
    block: &ruled::Block,
    w: &ruled::wire::WireParams,
    m: &ruled::wire::Machine,
) -> Vec<(String, String)> {
    let width = frame.w.1 - frame.w.0;
    let length = frame.u.1 - frame.u.0;
    let height = block.max[2] - block.min[2];
    let dialect = m.check();
    // the fit only with a valid dialect (its travel ordered)
    let fit = match dialect {
        Ok(()) => ruled::wire::check_fit(length, height, w, m),
        Err(_) => Ok(()),
    };
    let results = [ruled::wire::check(width, w), dialect, fit];
    results
        .into_iter()
        .filter_map(|r| match r {
            Err(ruled::PreCutError::InvalidParameter { name, reason }) => {
                Some((machine::pointer(name), format!("{name} {reason}")))
            }
            Err(e @ ruled::PreCutError::OutOfTravel { .. }) => Some((
                "/wire/travel".into(),
                format!("{e}: the block does not fit the machine; place it with `wire.origin`, or shorten `wire.lead` or `wire.clearance`"),
            )),
            Err(e) => Some(("/wire".into(), e.to_string())),
            Ok(()) => None,
        })
        .collect()
}

/// Paths and programs per direction.
type WirePrograms = (
    Vec<Vec<ruled::wire::WirePath>>,
    Vec<Vec<ruled::wire::Program>>,
);

/// Every cut's wire path and program; a program outside the machine's travel is an error
/// naming the cut and the axis.
fn wire_programs(
    cut: &ruled::PreCut,
    params: &PreCutParams,
    w: &ruled::wire::WireParams,
    m: &ruled::wire::Machine,
    job: &Context,
) -> Result<WirePrograms> {
    let b = &params.block;
    let fail = |e: ruled::PreCutError| {
        match e {
        ruled::PreCutError::OutOfTravel { .. } => job.fail(format!(
            "{e}: move the block on the machine (`wire.origin`), shorten `wire.clearance`, or give the machine's real `wire.travel`"
        )),
        e => job.fail(e.to_string()),
    }
    };
    let mut wires = Vec::new();
    let mut programs = Vec::new();
    for (i, d) in cut.directions.iter().enumerate() {
        let paths = ruled::wire::paths(d, i, b.min[2], w).map_err(fail)?;
        let progs = paths
            .iter()
            .map(|p| ruled::wire::program(p, w, m, b.max[2], b.min[2], &job.name))
            .collect::<std::result::Result<Vec<_>, _>>()
            .map_err(fail)?;
        wires.push(paths);
        programs.push(progs);
    }
    Ok((wires, programs))
}

impl PreCut {
    /// `n` of `directions: Auto(n)`.
    fn search(&self) -> Option<usize> {
        match self.directions {
            Directions::Search(SearchDirections::Auto(n)) => Some(n as usize),
            Directions::List(_) => None,
        }
    }

    /// The optimizer's parameters (with `Auto(n)`, +x stands for the candidates, which
    /// the search sets itself).
    fn optimizer(&self) -> ruled::Params {
        let directions = match &self.directions {
            Directions::List(list) => list.iter().map(|d| d.vector()).collect(),
            Directions::Search(_) => vec![[1.0, 0.0]],
        };
        ruled::Params {
            legs: self.legs as usize,
            directions,
            degree: self.degree as usize,
            controls: self.controls as usize,
            sections: self.sections as usize,
            samples: self.samples as usize,
            max_rounds: self.max_rounds as usize,
            ..ruled::Params::default()
        }
    }
}
