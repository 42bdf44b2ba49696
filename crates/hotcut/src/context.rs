//! What a task sees of its job: the common fields as written ([`JobFields`](crate::context::JobFields), for the
//! task's checks while the job is validated) and resolved ([`Context`](crate::context::Context), with the surface
//! loaded and defaults applied, for its run).
//!
//! Tasks never see the job enum: they get these two views, which is what keeps the
//! modules free of circles (`job` → tasks → `context`).

use std::path::{Path, PathBuf};

use geom::fit::SmoothingParams;
use geom::surface::{SectionParams, Surface};
use hotblade::BladeLimits;
use nalgebra::Vector3;

use crate::error::{HotcutError, JobError};
use crate::spec::{defaults, BladeSpec, BlockSpec, CuttingSpec, OutputSpec, SurfaceSpec};
use crate::spec::{CellSpec, Tolerance, Units, WireSpec};

/// The job's blade, or the default blade (1000 mm, 0.011 /mm, 2 inflections) converted to
/// `units`.
pub fn blade_of(spec: Option<&BladeSpec>, units: Units) -> BladeLimits {
    match spec {
        Some(b) => BladeLimits {
            max_blade_inflections: b.max_blade_inflections,
            min_margin: b.min_margin.unwrap_or(elastica::stability::MARGINAL),
            ..BladeLimits::new(b.length, b.max_curvature, b.max_inflections)
        },
        None => {
            let f = units.per_mm();
            BladeLimits::new(
                defaults::BLADE_LENGTH_MM * f,
                defaults::BLADE_MAX_CURVATURE_PER_MM / f,
                2,
            )
        }
    }
}

/// Young's modulus of the default blade, GPa (spring steel).
pub const BLADE_YOUNGS_MODULUS_GPA: f64 = 200.0;

/// The blade's section in job units (its modulus in pascals), defaults applied.
pub fn blade_section(spec: Option<&BladeSpec>, units: Units) -> elastica::BladeSection {
    let f = units.per_mm();
    elastica::BladeSection {
        thickness: spec
            .and_then(|b| b.thickness)
            .unwrap_or(defaults::BLADE_THICKNESS_MM * f),
        width: spec
            .and_then(|b| b.width)
            .unwrap_or(defaults::BLADE_WIDTH_MM * f),
        youngs_modulus: spec
            .and_then(|b| b.youngs_modulus)
            .unwrap_or(BLADE_YOUNGS_MODULUS_GPA)
            * 1e9,
    }
}

/// The hot blade's kerf as the job gives it: a width, a table by speed, or none.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Kerf {
    /// The width, when given as one.
    pub width: Option<f64>,
    /// `(speed, kerf)` rows, when given as a table.
    pub table: Vec<(f64, f64)>,
}

impl Kerf {
    /// The blade's kerf of `spec`.
    pub fn of(spec: Option<&BladeSpec>) -> Self {
        Self {
            width: spec.and_then(|b| b.kerf),
            table: spec.and_then(|b| b.kerf_table.clone()).unwrap_or_default(),
        }
    }

    /// Whether the job gives a kerf.
    pub fn given(&self) -> bool {
        self.width.is_some() || !self.table.is_empty()
    }

    /// The kerf at blade speed `speed` (0 without one).
    pub fn at(&self, speed: f64) -> f64 {
        ruled::wire::kerf_from_table(&self.table, speed).unwrap_or(self.width.unwrap_or(0.0))
    }

    /// What a report says of the kerf at `speed`, `None` without one.
    pub fn report(&self, speed: f64) -> Option<KerfReport> {
        self.given().then(|| {
            let kerf = self.at(speed);
            KerfReport {
                kerf,
                offset: 0.5 * kerf,
                speed,
                from_table: !self.table.is_empty(),
            }
        })
    }
}

/// The hot blade's kerf a run compensated for: every section the blade is fitted to was
/// moved `offset` (half the kerf) along its normal towards the material removed (up, the
/// side the design's normal points to), so the surface the kerf leaves is the design.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, schemars::JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct KerfReport {
    /// The width the blade melts, job units.
    pub kerf: f64,
    /// How far the blade's path lies off the design: half the kerf.
    pub offset: f64,
    /// The blade speed it was read at, job units per second.
    pub speed: f64,
    /// Whether it came from `kerf_table` (else `kerf`).
    pub from_table: bool,
}

/// A job's common fields, resolved: what every task's run gets.
#[derive(Debug, Clone)]
pub struct Context {
    /// The job file.
    pub path: PathBuf,
    /// The job's name (its output folder).
    pub name: String,
    /// Length unit of every length.
    pub units: Units,
    /// The loaded surface, if the job has one.
    pub surface: Option<Surface>,
    /// Non-fatal findings while loading (e.g. an open mesh).
    pub warnings: Vec<String>,
    /// The block, as written.
    pub block: Option<BlockSpec>,
    /// Blade constraints (defaults applied, in job units).
    pub blade: BladeLimits,
    /// The blade's bending stiffness, for the loads on its holders.
    pub stiffness: elastica::Stiffness,
    /// The blade's kerf, as written.
    pub kerf: Kerf,
    /// The hot-wire machine, as written.
    pub wire: Option<WireSpec>,
    /// The robot cell, as written.
    pub cell: Option<CellSpec>,
    /// Whether the job writes robot programs (`Rapid`): the robot cell is planned then, or
    /// when the job gives a `cell:`.
    pub rapid: bool,
    /// The outputs the job lists (`Compare` hands them to its processes).
    pub outputs: Vec<OutputSpec>,
    /// Cutting direction, sections and curve, as written.
    pub cutting: CuttingSpec,
    /// Unit cutting direction (the curve's chord when the job gives a curve).
    pub direction: Vector3<f64>,
    /// Tolerances (defaults applied, in job units).
    pub tolerance: Tolerance,
    /// Seed of every random choice.
    pub seed: u64,
    /// The job as read, pretty-printed RON with every default filled in (`report.html`
    /// shows it).
    pub job_ron: String,
    /// The job file's text as written, when the job was read from a file.
    pub job_file: Option<String>,
}

impl Context {
    /// How many job units one millimetre is.
    pub fn per_mm(&self) -> f64 {
        self.units.per_mm()
    }

    /// How the job's `cutting` and `tolerance` section the surface (shared by the tasks
    /// that work on sections).
    pub fn sectioning(&self) -> SectionParams {
        SectionParams {
            direction: self.direction,
            count: self.cutting.sections as usize,
            smoothing: SmoothingParams {
                degree: 3,
                tolerance: self.tolerance.smoothing,
                max_control: 400,
                chordal: false,
            },
            spline_grid: 200,
            offset: 0.0,
        }
    }

    /// A task's failure on this job.
    pub fn fail(&self, message: impl Into<String>) -> HotcutError {
        HotcutError::Task {
            path: self.path.clone(),
            message: message.into(),
        }
    }

    /// A geometry failure while doing `context`.
    pub fn geom_err(&self, context: &str) -> impl FnOnce(geom::GeomError) -> HotcutError {
        let (path, context) = (self.path.clone(), context.to_string());
        move |source| HotcutError::Geom {
            path,
            context,
            source,
        }
    }

    /// The surface; validation made sure a task that needs one has it.
    ///
    /// # Errors
    /// [`HotcutError::Invalid`] naming `/surface` when there is none.
    pub fn surface(&self, task: &str) -> Result<&Surface, HotcutError> {
        self.surface.as_ref().ok_or_else(|| {
            JobError::semantic(
                &self.path,
                "/surface",
                format!("task {task} needs a surface"),
            )
            .into()
        })
    }

    /// The block; validation made sure a task that needs one has it.
    ///
    /// # Errors
    /// [`HotcutError::Invalid`] naming `/block` when there is none.
    pub fn block(&self, task: &str) -> Result<&BlockSpec, HotcutError> {
        self.block.as_ref().ok_or_else(|| {
            JobError::semantic(&self.path, "/block", format!("task {task} needs a block")).into()
        })
    }
}

/// A job's common fields as written, for the checks of its task while the job is
/// validated (the surface may not have loaded).
#[derive(Debug, Clone, Copy)]
pub struct JobFields<'a> {
    /// The job file.
    pub path: &'a Path,
    /// The folder relative paths start from.
    pub base: &'a Path,
    /// The surface.
    pub surface: Option<&'a SurfaceSpec>,
    /// The block.
    pub block: Option<&'a BlockSpec>,
    /// The blade.
    pub blade: Option<&'a BladeSpec>,
    /// The hot-wire machine.
    pub wire: Option<&'a WireSpec>,
    /// The robot cell.
    pub cell: Option<&'a CellSpec>,
    /// Length unit of the job.
    pub units: Units,
    /// Cutting direction, sections and curve.
    pub cutting: &'a CuttingSpec,
    /// Files to write.
    pub outputs: &'a [OutputSpec],
}

impl JobFields<'_> {
    /// A semantic error at JSON pointer `pointer` of this job.
    pub fn error(&self, pointer: &str, message: impl Into<String>) -> JobError {
        JobError::semantic(self.path, pointer, message)
    }

    /// A task that cuts a surface from blocks needs both: reports each missing one. `what`
    /// says what the surface is (may be empty), `cut` what is cut from the blocks, with its
    /// verb ("surface is").
    pub fn require_surface_and_block(
        &self,
        task: &str,
        what: &str,
        cut: &str,
        errors: &mut Vec<JobError>,
    ) {
        if self.surface.is_none() {
            errors.push(self.error("/surface", format!("task {task} needs a surface{what}")));
        }
        if self.block.is_none() {
            errors.push(self.error(
                "/block",
                format!("task {task} needs `block` (the size of the blocks the {cut} cut from)"),
            ));
        }
    }

    /// Reports the problems an algorithm crate finds in its parameters, each as
    /// `(field, index of a list element, what is wrong)`, at `{ptr}/{field}[/{index}]`.
    /// `element(i)` names list element `i` as the job writes it.
    pub fn param_problems(
        &self,
        ptr: &str,
        problems: impl IntoIterator<Item = (&'static str, Option<usize>, String)>,
        element: impl Fn(usize) -> String,
        errors: &mut Vec<JobError>,
    ) {
        for (field, index, message) in problems {
            let (at, message) = match index {
                Some(i) => (
                    format!("{ptr}/{field}/{i}"),
                    format!("{} {message}", element(i)),
                ),
                None => (format!("{ptr}/{field}"), format!("{field} {message}")),
            };
            errors.push(self.error(&at, message));
        }
    }

    /// Checks the blade's `kerf` and `kerf_table` (a task that cuts with the blade calls
    /// it): a width ≥ 0, or a table of 1–64 rows with speeds > 0 strictly increasing and
    /// kerfs ≥ 0, not both; and half of every kerf at most half the radius of the blade's
    /// tightest bend (`kerf · max_curvature < 1`: the moved design has no cusp where the
    /// blade can bend at all).
    pub fn check_kerf(&self, errors: &mut Vec<JobError>) {
        let Some(b) = self.blade else {
            return;
        };
        let kerfs: Vec<f64> = match (b.kerf, &b.kerf_table) {
            (Some(_), Some(_)) => {
                errors.push(self.error(
                    "/blade/kerf",
                    "give kerf or kerf_table, not both (the table sets the kerf at every speed)",
                ));
                return;
            }
            (Some(k), None) => vec![k],
            (None, Some(t)) => {
                if t.is_empty() || t.len() > 64 {
                    errors.push(self.error(
                        "/blade/kerf_table",
                        format!("kerf_table needs 1–64 rows, got {}", t.len()),
                    ));
                    return;
                }
                for (i, w) in t.windows(2).enumerate() {
                    if !(w[1].0 > w[0].0) {
                        errors.push(self.error(
                            &format!("/blade/kerf_table/{}/0", i + 1),
                            "speeds must increase strictly",
                        ));
                    }
                }
                for (i, &(v, _)) in t.iter().enumerate() {
                    if !(v > 0.0 && v.is_finite()) {
                        errors.push(self.error(
                            &format!("/blade/kerf_table/{i}/0"),
                            format!("a speed must be a positive number, got {v:?}"),
                        ));
                    }
                }
                t.iter().map(|r| r.1).collect()
            }
            (None, None) => return,
        };
        for k in kerfs {
            let ptr = if b.kerf.is_some() {
                "/blade/kerf"
            } else {
                "/blade/kerf_table"
            };
            if !(k >= 0.0 && k.is_finite()) {
                errors.push(self.error(ptr, format!("a kerf must be a number ≥ 0, got {k:?}")));
            } else if !(k * b.max_curvature < 1.0) {
                errors.push(self.error(
                    ptr,
                    format!(
                        "a kerf of {k} is wider than the blade's tightest bend allows (radius {}): moving the design half of it would fold it; check the kerf's unit",
                        1.0 / b.max_curvature
                    ),
                ));
            }
        }
    }

    /// Checks a task's cutting speed (> 0) and approach distance (≥ 0), when given; `ptr`
    /// is the task's pointer.
    pub fn check_motion(
        &self,
        ptr: &str,
        speed: Option<f64>,
        approach: Option<f64>,
        errors: &mut Vec<JobError>,
    ) {
        if let Some(v) = speed {
            if !(v > 0.0) || !v.is_finite() {
                errors.push(self.error(
                    &format!("{ptr}/speed"),
                    format!("the cutting speed must be a positive number, got {v:?}"),
                ));
            }
        }
        if let Some(v) = approach {
            if !(v >= 0.0) || !v.is_finite() {
                errors.push(self.error(
                    &format!("{ptr}/approach"),
                    format!("the approach distance must be ≥ 0, got {v:?}"),
                ));
            }
        }
    }
}
