//! Reading a job file in three layers, then resolving it into checked geometry.
//!
//! 1. **Syntax and structure**: RON is parsed straight into [`crate::job::Job`] with
//!    `deny_unknown_fields`; syntax errors carry `file:line:column`, structural errors
//!    (unknown field, wrong type) also the JSON pointer of the field.
//! 2. **Schema**: the parsed job, as JSON, is validated against the job's JSON Schema
//!    (`jsonschema`), which carries the value ranges (positive lengths, at least one
//!    section, …); errors carry the JSON pointer. NaN and infinities fail here.
//! 3. **Semantics**: what a schema cannot say (the mesh file exists and is a valid mesh, the
//!    expression parses and is finite, the direction is non-zero, the task has what it
//!    needs, the outputs exist for the task).
//!
//! Entry points: [`parse_job`](crate::load::parse_job), [`validate_schema`](crate::load::validate_schema), [`load_job`](crate::load::load_job), [`ResolvedJob`](crate::load::ResolvedJob).

use std::path::{Path, PathBuf};

use geom::expr::Expr;
use geom::heightfield::HeightField;
use geom::mesh::{MeshWarning, TriMesh};
use geom::surface::Surface;
use geom::surface_spline::BSplineSurface;
use nalgebra::Vector3;
use serde::Deserialize;

use crate::error::JobError;
use crate::job::{BladeSpec, Job, SurfaceSpec, TaskSpec, Units};

/// Per-task checks and the outputs each task writes.
mod tasks;

/// Turns a `serde_path_to_error` path into a JSON pointer.
fn pointer_of(path: &serde_path_to_error::Path) -> String {
    let mut s = String::new();
    for seg in path.iter() {
        use serde_path_to_error::Segment;
        let part = match seg {
            Segment::Seq { index } => index.to_string(),
            Segment::Map { key } => key.clone(),
            Segment::Enum { variant } => variant.clone(),
            Segment::Unknown => continue,
        };
        s.push('/');
        s.push_str(&part.replace('~', "~0").replace('/', "~1"));
    }
    if s.is_empty() {
        s.push('/');
    }
    s
}

/// Layer 1: parses RON text into a [`Job`].
///
/// # Errors
/// [`JobError::Syntax`] or [`JobError::Structure`], with line and column.
pub fn parse_job(path: &Path, text: &str) -> Result<Job, JobError> {
    let syntax = |e: ron::error::SpannedError| JobError::Syntax {
        path: path.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: e.code.to_string(),
    };
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let mut de = ron::de::Deserializer::from_str_with_options(text, &options).map_err(syntax)?;
    let mut track = serde_path_to_error::Track::new();
    let result = Job::deserialize(serde_path_to_error::Deserializer::new(&mut de, &mut track));
    match result {
        Ok(job) => {
            de.end().map_err(|e| syntax(de.span_error(e)))?;
            Ok(job)
        }
        Err(e) => {
            let spanned = de.span_error(e);
            let pointer = pointer_of(&track.path());
            // well-formed RON of the wrong shape or type: report the field's pointer too
            let is_syntax = !matches!(
                spanned.code,
                ron::Error::NoSuchStructField { .. }
                    | ron::Error::NoSuchEnumVariant { .. }
                    | ron::Error::MissingStructField { .. }
                    | ron::Error::DuplicateStructField { .. }
                    | ron::Error::InvalidValueForType { .. }
                    | ron::Error::ExpectedDifferentLength { .. }
                    | ron::Error::ExpectedDifferentStructName { .. }
                    | ron::Error::ExpectedBoolean
                    | ron::Error::ExpectedFloat
                    | ron::Error::ExpectedInteger
                    | ron::Error::ExpectedString
                    | ron::Error::ExpectedChar
                    | ron::Error::ExpectedUnit
                    | ron::Error::ExpectedOption
                    | ron::Error::ExpectedArray
                    | ron::Error::ExpectedMap
                    | ron::Error::ExpectedStructLike
                    | ron::Error::ExpectedNamedStructLike(_)
                    | ron::Error::IntegerOutOfBounds
                    | ron::Error::Message(_)
            );
            if is_syntax {
                return Err(syntax(spanned));
            }
            Err(JobError::Structure {
                path: path.to_path_buf(),
                line: spanned.span.start.line,
                col: spanned.span.start.col,
                pointer,
                message: spanned.code.to_string(),
            })
        }
    }
}

/// The JSON Schema of job files.
pub fn job_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Job)).unwrap_or(serde_json::Value::Null)
}

/// Layer 2: validates a parsed job against the job schema.
///
/// # Errors
/// Every schema violation, each with its JSON pointer.
pub fn validate_schema(path: &Path, job: &Job) -> Result<(), Vec<JobError>> {
    let schema = job_schema();
    let instance = serde_json::to_value(job).map_err(|e| {
        vec![JobError::Schema {
            path: path.to_path_buf(),
            pointer: "/".into(),
            message: e.to_string(),
        }]
    })?;
    let validator = jsonschema::validator_for(&schema).map_err(|e| {
        vec![JobError::Schema {
            path: path.to_path_buf(),
            pointer: "/".into(),
            message: format!("invalid job schema: {e}"),
        }]
    })?;
    let mut found = Vec::new();
    for e in validator.iter_errors(&instance) {
        leaf_errors(&e, &mut found);
    }
    let mut errors: Vec<JobError> = Vec::new();
    for (pointer, message) in found {
        let e = JobError::Schema {
            path: path.to_path_buf(),
            pointer,
            message,
        };
        if !errors.contains(&e) {
            errors.push(e);
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// The most specific errors under a schema error: for `anyOf`/`oneOf` (optional fields,
/// enum variants) the branch whose errors reach deepest into the instance is the one the
/// user meant, so its errors are reported instead of "not valid under any of the schemas".
fn leaf_errors(e: &jsonschema::ValidationError<'_>, out: &mut Vec<(String, String)>) {
    if let Some(branches) = branches_of(e) {
        if let Some(best) = branches
            .iter()
            .max_by_key(|b| b.iter().map(depth).max().unwrap_or(0))
        {
            if best.iter().map(depth).max().unwrap_or(0) > e.instance_path().to_string().len() {
                for x in best {
                    leaf_errors(x, out);
                }
                return;
            }
        }
    }
    let pointer = e.instance_path().to_string();
    let pointer = if pointer.is_empty() {
        "/".to_string()
    } else {
        pointer
    };
    // serde_json turns NaN and infinities into null; say what really happened
    let message = if e.instance().is_null() {
        "must be a finite number (NaN or infinity given)".to_string()
    } else {
        e.to_string()
    };
    out.push((pointer, message));
}

type Branches = Vec<Vec<jsonschema::ValidationError<'static>>>;

fn branches_of<'e>(e: &'e jsonschema::ValidationError<'_>) -> Option<&'e Branches> {
    use jsonschema::error::ValidationErrorKind as K;
    match e.kind() {
        K::AnyOf { context } | K::OneOfNotValid { context } => Some(context),
        _ => None,
    }
}

/// Length of the deepest instance path among an error and its branches.
fn depth(e: &jsonschema::ValidationError<'_>) -> usize {
    let own = e.instance_path().to_string().len();
    branches_of(e)
        .map(|bs| bs.iter().flatten().map(depth).max().unwrap_or(0))
        .unwrap_or(0)
        .max(own)
}

/// Blade constraints in job units.
#[derive(Debug, Clone, PartialEq)]
pub struct Blade {
    /// Blade length.
    pub length: f64,
    /// Largest allowed |curvature|.
    pub max_curvature: f64,
    /// Most inflections a blade shape may have.
    pub max_inflections: u32,
}

/// A job whose every field was checked, with its surface loaded.
#[derive(Debug, Clone)]
pub struct ResolvedJob {
    /// The job file.
    pub path: PathBuf,
    /// The job as written (with defaults filled in).
    pub job: Job,
    /// The loaded surface, if the job has one.
    pub surface: Option<Surface>,
    /// Non-fatal findings while loading (e.g. an open mesh).
    pub warnings: Vec<String>,
    /// Blade constraints (defaults applied, in job units).
    pub blade: Blade,
    /// Unit cutting direction.
    pub direction: Vector3<f64>,
}

pub(crate) fn semantic(path: &Path, pointer: &str, message: impl Into<String>) -> JobError {
    JobError::Semantic {
        path: path.to_path_buf(),
        pointer: pointer.into(),
        message: message.into(),
    }
}

/// The default blade of [`crate::job::Job::blade`], converted to `units`.
pub fn default_blade(units: Units) -> Blade {
    let f = units.per_mm();
    Blade {
        length: 1000.0 * f,
        max_curvature: 0.011 / f,
        max_inflections: 2,
    }
}

/// Checks a cutting-direction curve and returns its unit chord.
fn check_curve(curve: &[(f64, f64)]) -> Result<Vector3<f64>, String> {
    if curve.len() < 2 {
        return Err(format!("needs at least 2 points, got {}", curve.len()));
    }
    if let Some(i) = curve
        .iter()
        .position(|p| !p.0.is_finite() || !p.1.is_finite())
    {
        return Err(format!("point {i} is not finite"));
    }
    let (a, b) = (curve[0], curve[curve.len() - 1]);
    let chord = Vector3::new(b.0 - a.0, b.1 - a.1, 0.0);
    if !(chord.norm() > 0.0) {
        return Err("the first and last points coincide".into());
    }
    let d = chord.normalize();
    for i in 1..curve.len() {
        let step = (curve[i].0 - curve[i - 1].0) * d.x + (curve[i].1 - curve[i - 1].1) * d.y;
        if !(step > 0.0) {
            return Err(format!(
                "point {i} does not advance along the chord from the first to the last point (planes would cross)"
            ));
        }
    }
    Ok(d)
}

/// Layer 3 and resolution: checks what the schema cannot and loads the surface.
///
/// # Errors
/// Every semantic problem found, each with its JSON pointer.
pub fn resolve(path: &Path, job: Job) -> Result<ResolvedJob, Vec<JobError>> {
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    let base = path.parent().unwrap_or(Path::new("."));
    let (dx, dy, dz) = job.cutting.direction;
    let direction = Vector3::new(dx, dy, dz);
    if !(direction.norm() > 0.0) {
        errors.push(semantic(
            path,
            "/cutting/direction",
            "the cutting direction must be a non-zero vector",
        ));
    }
    let mut direction = if direction.norm() > 0.0 {
        direction.normalize()
    } else {
        Vector3::x()
    };
    if let Some(curve) = &job.cutting.curve {
        match check_curve(curve) {
            Ok(chord) => direction = chord,
            Err(m) => errors.push(semantic(path, "/cutting/curve", m)),
        }
        if !matches!(job.task, TaskSpec::HotBlade { .. }) {
            errors.push(semantic(
                path,
                "/cutting/curve",
                "a cutting-direction curve is used by task HotBlade only",
            ));
        }
    }

    if let Some(b) = &job.block {
        for (i, v) in [b.size.0, b.size.1, b.size.2].into_iter().enumerate() {
            if !(v > 0.0) {
                errors.push(semantic(
                    path,
                    &format!("/block/size/{i}"),
                    format!("block edge lengths must be > 0, got {v}"),
                ));
            }
        }
    }

    let surface = match &job.surface {
        None => None,
        Some(SurfaceSpec::HeightField { z, x, y }) => {
            let ptr = "/surface/HeightField";
            let mut ok = true;
            for (name, r) in [("x", x), ("y", y)] {
                if !(r.1 > r.0) {
                    errors.push(semantic(
                        path,
                        &format!("{ptr}/{name}"),
                        format!("range ({}, {}) must have min < max", r.0, r.1),
                    ));
                    ok = false;
                }
            }
            if direction.z.abs() > 1e-12 {
                errors.push(semantic(path, "/cutting/direction", "a HeightField is sectioned exactly only for a horizontal cutting direction (z component 0)"));
            }
            match Expr::parse(z) {
                Err(geom::GeomError::Expression { column, message }) => {
                    errors.push(semantic(
                        path,
                        &format!("{ptr}/z"),
                        format!("column {column}: {message}"),
                    ));
                    None
                }
                Err(e) => {
                    errors.push(semantic(path, &format!("{ptr}/z"), e.to_string()));
                    None
                }
                Ok(expr) if ok => match HeightField::try_new(expr, *x, *y) {
                    Ok(h) => Some(Surface::HeightField(h)),
                    Err(e) => {
                        errors.push(semantic(path, &format!("{ptr}/z"), e.to_string()));
                        None
                    }
                },
                Ok(_) => None,
            }
        }
        Some(SurfaceSpec::Mesh { path: rel, closed }) => {
            let ptr = "/surface/Mesh/path";
            let file = base.join(rel);
            if !file.is_file() {
                errors.push(semantic(
                    path,
                    ptr,
                    format!("mesh file not found: {}", file.display()),
                ));
                None
            } else {
                match TriMesh::load_obj(&file).and_then(|m| m.validate(*closed).map(|w| (m, w))) {
                    Ok((m, w)) => {
                        for warning in w {
                            // an open boundary is what a facade sheet has; say it only when it has holes
                            if let MeshWarning::Open {
                                boundary_loops: 1, ..
                            } = warning
                            {
                                continue;
                            }
                            warnings.push(format!("{}: {warning}", file.display()));
                        }
                        Some(Surface::Mesh(m))
                    }
                    Err(e) => {
                        errors.push(semantic(path, ptr, format!("{}: {e}", file.display())));
                        None
                    }
                }
            }
        }
        Some(SurfaceSpec::Spline { path: rel }) => {
            let ptr = "/surface/Spline/path";
            let file = base.join(rel);
            match load_spline(&file) {
                Ok(s) => Some(Surface::Spline(s)),
                Err(m) => {
                    errors.push(semantic(path, ptr, m));
                    None
                }
            }
        }
    };

    let allowed = tasks::check_task(path, &job, base, &mut errors);
    for (i, o) in job.outputs.iter().enumerate() {
        if !allowed.contains(&o.name()) {
            errors.push(semantic(
                path,
                &format!("/outputs/{i}"),
                format!(
                    "output {} is not produced by task {} (it writes {})",
                    o.name(),
                    job.task.name(),
                    allowed.join(", ")
                ),
            ));
        }
    }
    let blade = match &job.blade {
        Some(BladeSpec {
            length,
            max_curvature,
            max_inflections,
        }) => Blade {
            length: *length,
            max_curvature: *max_curvature,
            max_inflections: *max_inflections,
        },
        None => default_blade(job.units),
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(ResolvedJob {
        path: path.to_path_buf(),
        job,
        surface,
        warnings,
        blade,
        direction,
    })
}

/// The control-grid file of a `Spline` surface.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SplineFile {
    degree_u: usize,
    degree_v: usize,
    #[serde(default)]
    knots_u: Option<Vec<f64>>,
    #[serde(default)]
    knots_v: Option<Vec<f64>>,
    /// rows of points: `points[i][j] = [x, y, z]`
    points: Vec<Vec<[f64; 3]>>,
}

fn load_spline(file: &Path) -> Result<BSplineSurface, String> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| format!("cannot read spline file {}: {e}", file.display()))?;
    let f: SplineFile =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let nu = f.points.len();
    let nv = f.points.first().map_or(0, |r| r.len());
    if nu == 0 || nv == 0 || f.points.iter().any(|r| r.len() != nv) {
        return Err(format!(
            "{}: points must be a non-empty rectangular grid",
            file.display()
        ));
    }
    let control: Vec<Vector3<f64>> = f
        .points
        .iter()
        .flatten()
        .map(|p| Vector3::new(p[0], p[1], p[2]))
        .collect();
    let s = match (f.knots_u, f.knots_v) {
        (Some(ku), Some(kv)) => {
            BSplineSurface::try_new((f.degree_u, f.degree_v), ku, kv, (nu, nv), control)
        }
        (None, None) => {
            BSplineSurface::clamped_uniform((f.degree_u, f.degree_v), (nu, nv), control)
        }
        _ => {
            return Err(format!(
                "{}: give both knots_u and knots_v, or neither",
                file.display()
            ))
        }
    };
    s.map_err(|e| format!("{}: {e}", file.display()))
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
/// assert_eq!(job.job.cutting.sections, 26);
/// ```
pub fn load_job(path: &Path) -> Result<ResolvedJob, Vec<JobError>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        vec![JobError::Read {
            path: path.to_path_buf(),
            message: e.to_string(),
        }]
    })?;
    let job = parse_job(path, &text).map_err(|e| vec![e])?;
    validate_schema(path, &job)?;
    resolve(path, job)
}
