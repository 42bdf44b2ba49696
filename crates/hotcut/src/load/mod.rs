//! Reading a job file in three layers, then resolving it into checked geometry.
//!
//! 1. **Syntax and structure** ([`parse_job`](crate::load::parse_job)): RON parsed straight into
//!    [`Job`](crate::job::Job).
//! 2. **Schema** ([`validate_schema`](crate::load::validate_schema)): the value ranges the JSON Schema carries.
//! 3. **Semantics** ([`resolve`](crate::load::resolve)): what a schema cannot say (the mesh file exists and is a
//!    valid mesh, the expression parses, the direction is non-zero, the task has what it
//!    needs and writes the outputs asked for). The task's own checks come through
//!    [`TaskSpec::visit`](crate::job::TaskSpec::visit); this module names no task.
//!
//! Entry points: [`load_job`](crate::load::load_job), [`ResolvedJob`](crate::load::ResolvedJob).

use std::path::Path;

use nalgebra::Vector3;

use crate::context::{blade_of, Context, JobFields};
use crate::error::JobError;
use crate::job::{Job, TaskSpec};
use crate::limits::Limits;
use crate::spec::OutputSpec;
use crate::task::{Check, Resolved};

/// Layer 1: RON syntax and structure.
mod parse;
/// Layer 2: the JSON Schema.
mod schema;
/// Loading the surface.
mod surface;
/// `task: Analyze` read as `task: Analyze()` (the unit form of struct variants).
mod unit_form;

pub use parse::{parse_job, parse_job_json};
pub use schema::{job_schema, validate_schema};

/// A job whose every field was checked, with its surface loaded.
#[derive(Debug, Clone)]
pub struct ResolvedJob {
    /// The common fields, resolved: what the task's run sees.
    pub context: Context,
    /// The task and its fields.
    pub task: TaskSpec,
    /// Files to write.
    pub outputs: Vec<OutputSpec>,
    /// What the run will take, as checked against the limits.
    pub estimate: crate::limits::Estimate,
}

impl ResolvedJob {
    /// The job file.
    pub fn path(&self) -> &Path {
        &self.context.path
    }
}

/// The unit cutting direction: the chord of `cutting.curve` when it has one (the task
/// that follows the curve checks it), else `cutting.direction` (+x when that is zero,
/// which is reported).
fn direction(path: &Path, job: &Job, errors: &mut Vec<JobError>) -> Vector3<f64> {
    let (dx, dy, dz) = job.cutting.direction;
    let direction = Vector3::new(dx, dy, dz);
    // a vector whose norm overflows or underflows, e.g. (1e200, 0, 0), is scaled by its
    // largest component first
    let largest = dx.abs().max(dy.abs()).max(dz.abs());
    let norm = direction.norm();
    let mut unit = if norm > 0.0 && norm.is_finite() {
        direction.normalize()
    } else if largest > 0.0 && largest.is_finite() {
        (direction / largest).normalize()
    } else {
        errors.push(JobError::semantic(
            path,
            "/cutting/direction",
            "the cutting direction must be a non-zero vector",
        ));
        Vector3::x()
    };
    if let Some(Ok(chord)) = job.cutting.curve.as_deref().map(hotblade::curve_chord) {
        unit = chord;
    }
    unit
}

/// Layer 3 and resolution: checks what the schema cannot and loads the surface.
///
/// # Errors
/// Every semantic problem found, each with its JSON pointer.
pub fn resolve(path: &Path, job: Job) -> Result<ResolvedJob, Vec<JobError>> {
    resolve_with(path, job, &Limits::default())
}

/// The blade's own checks: its length within a robot cell's, its section and least
/// margin in range.
fn check_blade(path: &Path, job: &Job, errors: &mut Vec<JobError>) {
    let Some(b) = &job.blade else { return };
    let most = MAX_BLADE_MM * job.units.per_mm();
    if !(b.length <= most) {
        errors.push(JobError::semantic(
            path,
            "/blade/length",
            format!(
                "a blade of {:e} is longer than any a robot cell holds: at most {most:e} ({} m)",
                b.length,
                MAX_BLADE_MM / 1e3
            ),
        ));
    }
    let u = job.units.per_mm();
    let section = [
        ("thickness", b.thickness, 50.0 * u, "50 mm"),
        ("width", b.width, 500.0 * u, "500 mm"),
        ("youngs_modulus", b.youngs_modulus, 1000.0, "1000 GPa"),
    ];
    for (field, v, most, said) in section {
        if let Some(v) = v.filter(|v| !(*v > 0.0 && *v <= most)) {
            errors.push(JobError::semantic(
                path,
                &format!("/blade/{field}"),
                format!("must be positive and at most {most} ({said}), got {v:?}"),
            ));
        }
    }
    if b.min_margin.is_some_and(|m| !(0.0..=1.0).contains(&m)) {
        errors.push(JobError::semantic(
            path,
            "/blade/min_margin",
            "the least stability margin must be 0–1 (a straight, unloaded blade's is 1)",
        ));
    }
}

/// [`resolve`], with the run's estimated work and memory checked against `limits`.
///
/// # Errors
/// As [`resolve`]; a run that would take more than `limits` (naming the field to change).
pub fn resolve_with(path: &Path, job: Job, limits: &Limits) -> Result<ResolvedJob, Vec<JobError>> {
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    let base = path.parent().unwrap_or(Path::new("."));
    let direction = direction(path, &job, &mut errors);
    if let Some(b) = &job.block {
        for (i, v) in [b.size.0, b.size.1, b.size.2].into_iter().enumerate() {
            if !(v > 0.0) {
                errors.push(JobError::semantic(
                    path,
                    &format!("/block/size/{i}"),
                    format!("block edge lengths must be > 0, got {v:?}"),
                ));
            }
        }
    }
    check_blade(path, &job, &mut errors);
    let surface = job
        .surface
        .as_ref()
        .and_then(|spec| surface::load(path, base, spec, &direction, &mut errors, &mut warnings));
    if let Some(s) = &surface {
        // every output is drawn in single precision (glTF) and every program holds
        // bounded numbers: a surface must lie within reach of the origin
        let far = MAX_SURFACE_MM * job.units.per_mm();
        let b = s.aabb();
        if let Some(v) = b.min.iter().chain(b.max.iter()).find(|v| !(v.abs() <= far)) {
            errors.push(JobError::semantic(
                path,
                "/surface",
                format!(
                    "the surface reaches {v:e}: it must lie within ±{far:e} (10 km) of the origin"
                ),
            ));
        }
    }
    let fields = JobFields {
        path,
        base,
        surface: job.surface.as_ref(),
        block: job.block.as_ref(),
        blade: job.blade.as_ref(),
        wire: job.wire.as_ref(),
        cell: job.cell.as_ref(),
        units: job.units,
        cutting: &job.cutting,
        outputs: &job.outputs,
    };
    job.task.visit(Check {
        job: fields,
        has_curve: job.cutting.curve.is_some(),
        errors: &mut errors,
    });
    if !errors.is_empty() {
        return Err(errors);
    }
    let job_ron = pretty_job(&job);
    let context = Context {
        job_ron,
        job_file: None,
        path: path.to_path_buf(),
        blade: blade_of(job.blade.as_ref(), job.units),
        stiffness: elastica::Stiffness::of(
            &crate::context::blade_section(job.blade.as_ref(), job.units),
            1e-3 / job.units.per_mm(),
        ),
        kerf: crate::context::Kerf::of(job.blade.as_ref()),
        name: job.name,
        units: job.units,
        surface,
        warnings,
        block: job.block,
        wire: job.wire,
        cell: job.cell,
        rapid: job.outputs.iter().any(|o| matches!(o, OutputSpec::Rapid)),
        outputs: job.outputs.clone(),
        cutting: job.cutting,
        direction,
        tolerance: job.tolerance.resolve(job.units),
        seed: job.seed,
    };
    let estimate = job.task.visit(Resolved {
        job: &context,
        limits,
    })?;
    Ok(ResolvedJob {
        context,
        task: job.task,
        outputs: job.outputs,
        estimate,
    })
}

/// Longest blade, mm: 100 m.
pub const MAX_BLADE_MM: f64 = 1e5;

/// Farthest a surface may reach from the origin, mm: 10 km.
pub const MAX_SURFACE_MM: f64 = 1e7;

/// Most bytes a job file may have (a job is a page of text; this stops `/dev/zero`).
pub const MAX_JOB_BYTES: u64 = 1 << 20;

/// The text of a job file, a regular file of at most [`MAX_JOB_BYTES`].
fn read_job_text(path: &Path) -> std::result::Result<String, String> {
    crate::input::read_text(path, MAX_JOB_BYTES, "job file")
}

/// Reads, validates (all three layers) and resolves one job file.
///
/// # Errors
/// Every problem found, in layer order; a later layer runs only when the earlier ones pass.
///
/// # Example
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("demo.ron");
/// std::fs::write(&path, r#"Job(name: "demo", surface: HeightField(z: "x*y", x: (0, 1), y: (0, 1)), task: Analyze())"#).unwrap();
/// let job = hotcut::load::load_job(&path).unwrap();
/// assert_eq!(job.context.cutting.sections, 26);
/// ```
pub fn load_job(path: &Path) -> Result<ResolvedJob, Vec<JobError>> {
    load_job_with(path, &Limits::default())
}

/// [`load_job`], with the run's estimated work and memory checked against `limits`.
///
/// # Errors
/// As [`load_job`].
pub fn load_job_with(path: &Path, limits: &Limits) -> Result<ResolvedJob, Vec<JobError>> {
    let text = read_job_text(path).map_err(|message| {
        vec![JobError::Read {
            path: path.to_path_buf(),
            message,
        }]
    })?;
    load_job_text(path, text, limits)
}

/// [`load_job_with`] for job text that is not read from `path`: `path` names the job in
/// messages and its folder is where relative file names (meshes, curve files) are looked
/// up. The Python bindings load a job given as RON text this way.
///
/// # Errors
/// As [`load_job`].
///
/// # Example
/// ```
/// let text = r#"Job(name: "t", surface: HeightField(z: "x*y", x: (0, 1), y: (0, 1)), task: Analyze())"#;
/// let job = hotcut::load::load_job_text(std::path::Path::new("<text>"), text.into(), &Default::default()).unwrap();
/// assert_eq!(job.context.name, "t");
/// ```
pub fn load_job_text(
    path: &Path,
    text: String,
    limits: &Limits,
) -> Result<ResolvedJob, Vec<JobError>> {
    within_size(path, text.len(), "")?;
    let job = parse_job(path, &text).map_err(|e| vec![e])?;
    validate_schema(path, &job)?;
    let mut resolved = resolve_with(path, job, limits)?;
    resolved.context.job_file = Some(text);
    Ok(resolved)
}

/// A job given as text of `len` bytes is refused above [`MAX_JOB_BYTES`], as a job file
/// is.
fn within_size(path: &Path, len: usize, form: &str) -> Result<(), Vec<JobError>> {
    if len as u64 <= MAX_JOB_BYTES {
        return Ok(());
    }
    Err(vec![JobError::Read {
        path: path.to_path_buf(),
        message: format!(
            "{}: the job is {len} bytes{form}, more than a job may have ({MAX_JOB_BYTES})",
            path.display()
        ),
    }])
}

/// [`load_job_text`] for a job in its JSON form (see [`parse_job_json`]): the Python
/// bindings turn a `dict` job into it. The job is echoed in `report.html` as RON, every
/// default filled in.
///
/// # Errors
/// As [`load_job`]; a field that does not fit is named by its JSON pointer.
pub fn load_job_json(
    path: &Path,
    json: &str,
    limits: &Limits,
) -> Result<ResolvedJob, Vec<JobError>> {
    within_size(path, json.len(), " of JSON")?;
    let job = parse_job_json(path, json).map_err(|e| vec![e])?;
    validate_schema(path, &job)?;
    let text = pretty_job(&job);
    let mut resolved = resolve_with(path, job, limits)?;
    resolved.context.job_file = Some(text);
    Ok(resolved)
}

/// The job as RON, pretty-printed with struct names and every default filled in.
fn pretty_job(job: &Job) -> String {
    let config = ron::ser::PrettyConfig::new()
        .struct_names(true)
        .indentor("    ".to_string());
    ron::ser::to_string_pretty(job, config).unwrap_or_else(|e| format!("(not printable: {e})"))
}
