//! Loading the surface a job names: a height field (expression parsed and checked), a
//! triangle mesh (OBJ, validated) or a B-spline surface (control-grid JSON).

use std::path::Path;

use geom::expr::Expr;
use geom::heightfield::HeightField;
use geom::mesh::{MeshWarning, TriMesh};
use geom::surface::Surface;
use geom::surface_spline::BSplineSurface;
use nalgebra::Vector3;
use serde::Deserialize;

use crate::error::JobError;
use crate::spec::SurfaceSpec;

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

/// Largest spline control-grid file, bytes.
const MAX_SPLINE_BYTES: u64 = 64 << 20;

fn load_spline(file: &Path) -> Result<BSplineSurface, String> {
    let text = crate::input::read_text(file, MAX_SPLINE_BYTES, "spline file")?;
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
    // degrees the grid supports, said rather than clamped (a spline of degree ≥ its point
    // count is a mistake in the file)
    for (name, degree, n) in [("degree_u", f.degree_u, nu), ("degree_v", f.degree_v, nv)] {
        if !(1..n).contains(&degree) || degree > 7 {
            return Err(format!(
                "{}: {name} must be 1–{} for {n} rows of points (and at most 7), got {degree}",
                file.display(),
                (n - 1).clamp(1, 7)
            ));
        }
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

/// Loads the surface of `spec` (relative paths from `base`), pushing every problem to
/// `errors` and every non-fatal finding to `warnings`. `direction` is the unit cutting
/// direction: a height field is sectioned exactly only by vertical planes.
pub(super) fn load(
    path: &Path,
    base: &Path,
    spec: &SurfaceSpec,
    direction: &Vector3<f64>,
    errors: &mut Vec<JobError>,
    warnings: &mut Vec<String>,
) -> Option<Surface> {
    let fail = |errors: &mut Vec<JobError>, pointer: &str, message: String| {
        errors.push(JobError::semantic(path, pointer, message));
        None
    };
    match spec {
        SurfaceSpec::HeightField { z, x, y } => {
            height_field(path, z, *x, *y, direction, errors).map(Surface::HeightField)
        }
        SurfaceSpec::Mesh { path: rel, closed } => {
            let ptr = "/surface/Mesh/path";
            let file = base.join(rel);
            if let Err(m) = crate::input::regular(&file, u64::MAX, "mesh file") {
                return fail(errors, ptr, m);
            }
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
                Err(e) => fail(errors, ptr, format!("{}: {e}", file.display())),
            }
        }
        SurfaceSpec::Spline { path: rel } => match load_spline(&base.join(rel)) {
            Ok(s) => Some(Surface::Spline(s)),
            Err(m) => fail(errors, "/surface/Spline/path", m),
        },
    }
}

/// A height field `z` over `x × y`, with its checks.
fn height_field(
    path: &Path,
    z: &str,
    x: (f64, f64),
    y: (f64, f64),
    direction: &Vector3<f64>,
    errors: &mut Vec<JobError>,
) -> Option<HeightField> {
    let ptr = "/surface/HeightField";
    let mut ok = true;
    for (name, r) in [("x", x), ("y", y)] {
        if !(r.1 > r.0) {
            errors.push(JobError::semantic(
                path,
                &format!("{ptr}/{name}"),
                format!("range ({}, {}) must have min < max", r.0, r.1),
            ));
            ok = false;
        }
    }
    if direction.z.abs() > 1e-12 {
        errors.push(JobError::semantic(path, "/cutting/direction", "a HeightField is sectioned exactly only for a horizontal cutting direction (z component 0)"));
    }
    let at_z = format!("{ptr}/z");
    match Expr::parse(z) {
        Err(geom::GeomError::Expression { column, message }) => {
            errors.push(JobError::semantic(
                path,
                &at_z,
                format!("column {column}: {message}"),
            ));
            None
        }
        Err(e) => {
            errors.push(JobError::semantic(path, &at_z, e.to_string()));
            None
        }
        Ok(expr) if ok => match HeightField::try_new(expr, x, y) {
            Ok(h) => Some(h),
            Err(e) => {
                errors.push(JobError::semantic(path, &at_z, e.to_string()));
                None
            }
        },
        Ok(_) => None,
    }
}
