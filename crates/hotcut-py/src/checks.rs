//! The checks a designer makes while dragging: `check_section` (one section against the
//! §5.1 production constraints and its elastica, [`facade_seg::check::check_section`])
//! and `bezier_to_elastica` (a cubic design curve against the elastica with its end data,
//! [`design::proxy`], and whether the blade bends to it, [`elastica::extend_to_blade`]).
//! Lengths are in the caller's units; `units` only picks the millimetre defaults' scale,
//! as a job's `units` does.

use facade_seg::check::{CheckParams, SectionCheck};
use facade_seg::survey::SurveyParams;
use geom::analysis::CurveAnalysisParams;
use hotcut::spec::{BladeSpec, ToleranceSpec, Units};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{json_to_py, points, row, to_json};
use crate::curves::{elastica_object, planar, to_caller, Plane};
use crate::guard::guarded;

/// `"mm"`/`"Millimetre"` or `"m"`/`"Metre"`.
fn units(name: &str) -> PyResult<Units> {
    match name {
        "mm" | "Millimetre" | "millimetre" => Ok(Units::Millimetre),
        "m" | "Metre" | "metre" => Ok(Units::Metre),
        other => Err(PyValueError::new_err(format!(
            "units: expected \"mm\" or \"m\", got {other:?}"
        ))),
    }
}

/// A job-file struct (`Blade(..)`, `Tolerance(..)`) from a dict with its fields.
fn spec<T: serde::de::DeserializeOwned>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<T> {
    let v =
        to_json(obj, "", 0).map_err(|(p, m)| PyValueError::new_err(format!("{what}{p}: {m}")))?;
    serde_json::from_value(v).map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

/// `ValueError` unless `v` is a finite number above 0 (or at 0, when `zero_ok`).
pub fn positive(what: &str, v: f64, zero_ok: bool) -> PyResult<()> {
    if v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0)) {
        return Ok(());
    }
    let want = if zero_ok {
        "a number ≥ 0"
    } else {
        "a number > 0"
    };
    Err(PyValueError::new_err(format!(
        "{what}: must be {want}, got {v:?}"
    )))
}

/// The ranges a job's schema gives the blade's fields.
fn check_blade(b: &BladeSpec) -> PyResult<()> {
    positive("blade/length", b.length, false)?;
    positive("blade/max_curvature", b.max_curvature, false)?;
    if let Some(k) = b.kerf {
        positive("blade/kerf", k, true)?;
    }
    Ok(())
}

/// The ranges a job's schema gives the tolerances.
fn check_tolerance(t: &hotcut::spec::Tolerance) -> PyResult<()> {
    positive("tolerance/rms", t.rms, false)?;
    positive("tolerance/max", t.max, false)?;
    positive("tolerance/smoothing", t.smoothing, true)?;
    positive("tolerance/bisection", t.bisection, false)?;
    positive("tolerance/min_turning", t.min_turning, true)
}

/// A dict of the serializable `v`, with `extra` entries set after.
fn dict_of<'py>(py: Python<'py>, v: &impl serde::Serialize) -> PyResult<Bound<'py, PyDict>> {
    let v = serde_json::to_value(v).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(json_to_py(py, &v)?.into_bound(py).cast_into::<PyDict>()?)
}

/// A 2-D point of the section's plane in the caller's coordinates.
fn out_point(py: Python<'_>, plane: &Option<Plane>, q: [f64; 2]) -> PyResult<Py<PyAny>> {
    row(py, &to_caller(plane, q))
}

/// `check_section(points, blade, tolerance=None, *, units="mm", samples=None,
/// plane_tolerance=None)`.
#[pyfunction]
#[pyo3(signature = (points, blade, tolerance=None, *, units="mm", samples=None, plane_tolerance=None))]
fn check_section(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    blade: &Bound<'_, PyAny>,
    tolerance: Option<&Bound<'_, PyAny>>,
    units: &str,
    samples: Option<i64>,
    plane_tolerance: Option<f64>,
) -> PyResult<Py<PyAny>> {
    guarded(|| {
        let pts = crate::convert::points(points, "points", 3)?;
        let samples = match samples {
            None => facade_seg::check::default_samples(pts.xyz.len()),
            Some(n) if (8..=1_000_000).contains(&n) => n as usize,
            Some(n) => {
                return Err(PyValueError::new_err(format!(
                    "samples: expected 8 to 10⁶, got {n}"
                )))
            }
        };
        let u = self::units(units)?;
        let blade: BladeSpec = spec(blade, "blade")?;
        check_blade(&blade)?;
        let tol: ToleranceSpec = match tolerance {
            Some(t) => spec(t, "tolerance")?,
            None => ToleranceSpec::default(),
        };
        let tol = tol.resolve(u);
        check_tolerance(&tol)?;
        let (xy, plane) = planar(&pts, plane_tolerance)?;
        let params = CheckParams {
            survey: SurveyParams {
                curve: CurveAnalysisParams {
                    samples,
                    bisection_tolerance: tol.bisection,
                    min_lobe_turning: tol.min_turning,
                    ..Default::default()
                },
                blade_length: blade.length,
                max_curvature: blade.max_curvature,
                max_inflections: blade.max_inflections,
                block: None,
            },
            smoothing: tol.smoothing,
            rms: tol.rms,
            max: tol.max,
            min_margin: blade.min_margin.unwrap_or(elastica::stability::MARGINAL),
        };
        let c = facade_seg::check::check_section(&xy, &params)
            .map_err(|e| PyValueError::new_err(format!("check_section: {e}")))?;
        let stiffness = elastica::Stiffness::of(
            &hotcut::context::blade_section(Some(&blade), u),
            1e-3 / u.per_mm(),
        );
        section_dict(py, c, &plane, &tol, &stiffness)
    })
}

/// The result of `check_section` as a dict.
fn section_dict(
    py: Python<'_>,
    c: SectionCheck,
    plane: &Option<Plane>,
    tol: &hotcut::spec::Tolerance,
    stiffness: &elastica::Stiffness,
) -> PyResult<Py<PyAny>> {
    let d = PyDict::new(py);
    d.set_item("cuttable", c.cuttable)?;
    match &c.blade {
        Some(b) => {
            let e = PyDict::new(py);
            let s = &b.stability;
            let loads = s.loads.held(stiffness);
            e.set_item("margin", s.margin)?;
            e.set_item("stability", format!("{:?}", s.class))?;
            e.set_item("inflections", b.inflections)?;
            e.set_item("turning", s.turning)?;
            e.set_item("lead_in", b.lead_in)?;
            e.set_item("force_n", loads.force_n)?;
            e.set_item("tension_n", loads.tension_n.to_vec())?;
            e.set_item("moment_nm", loads.moment_nm.to_vec())?;
            d.set_item("blade", e)?;
        }
        None => d.set_item("blade", py.None())?,
    }
    d.set_item("fit_ok", c.fit_ok)?;
    d.set_item("length", c.length)?;
    let point = |p: &facade_seg::check::CheckPoint| -> PyResult<Bound<'_, PyDict>> {
        let e = PyDict::new(py);
        e.set_item("s", p.s)?;
        e.set_item("point", out_point(py, plane, p.point)?)?;
        e.set_item("curvature", p.curvature)?;
        Ok(e)
    };
    let infl = PyList::empty(py);
    for p in &c.inflections {
        infl.append(point(p)?)?;
    }
    d.set_item("inflections", infl)?;
    d.set_item("max_abs_curvature", point(&c.max_abs_curvature)?)?;
    d.set_item("suppressed_inflections", c.suppressed_inflections)?;
    d.set_item("smoothing_rms", c.smoothing_rms)?;
    let v = PyList::empty(py);
    for x in &c.violations {
        v.append(dict_of(py, x)?)?;
    }
    d.set_item("violations", v)?;
    d.set_item("tolerance", (tol.rms, tol.max))?;
    match c.elastica {
        Ok(f) => {
            d.set_item("rms", f.rms)?;
            d.set_item("max", f.max)?;
            d.set_item("fit_error", py.None())?;
            d.set_item("elastica", elastica_object(py, f.segment, *plane, Some(f))?)?;
        }
        Err(e) => {
            d.set_item("rms", py.None())?;
            d.set_item("max", py.None())?;
            d.set_item("fit_error", e)?;
            d.set_item("elastica", py.None())?;
        }
    }
    Ok(d.into_any().unbind())
}

/// `bezier_to_elastica(control_points, blade_length, *, max_curvature=None,
/// max_inflections=None, plane_tolerance=None)`.
#[pyfunction]
#[pyo3(signature = (control_points, blade_length, *, max_curvature=None, max_inflections=None, plane_tolerance=None))]
fn bezier_to_elastica(
    py: Python<'_>,
    control_points: &Bound<'_, PyAny>,
    blade_length: f64,
    max_curvature: Option<f64>,
    max_inflections: Option<i64>,
    plane_tolerance: Option<f64>,
) -> PyResult<Py<PyAny>> {
    guarded(|| {
        let pts = points(control_points, "control_points", 4)?;
        if pts.xyz.len() != 4 {
            return Err(PyValueError::new_err(format!(
                "control_points: a cubic Bézier has 4 control points, got {}",
                pts.xyz.len()
            )));
        }
        positive("blade_length", blade_length, false)?;
        let max_inflections = match max_inflections {
            None => None,
            Some(n) if (0..=i64::from(u32::MAX)).contains(&n) => Some(n as usize),
            Some(n) => {
                return Err(PyValueError::new_err(format!(
                    "max_inflections: expected 0 to {}, got {n}",
                    u32::MAX
                )))
            }
        };
        if let Some(k) = max_curvature {
            if !(k.is_finite() && k > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "max_curvature must be a positive number, got {k}"
                )));
            }
        }
        let (xy, plane) = planar(&pts, plane_tolerance)?;
        let b = design::Bezier {
            p: [xy[0], xy[1], xy[2], xy[3]],
        };
        let p = design::proxy(&b)
            .map_err(|e| PyValueError::new_err(format!("bezier_to_elastica: {e}")))?;
        let blade = elastica::extend_to_blade(
            &p.elastica,
            &elastica::BladeParams {
                length: blade_length,
                lead_in_share: 0.5,
                max_curvature,
                max_inflections,
                stability: elastica::StabilityParams::default(),
            },
        );
        let d = dict_of(py, &p)?;
        d.set_item("elastica", elastica_object(py, p.elastica, plane, None)?)?;
        let why_not = match &blade {
            Err(e) => Some(e.to_string()),
            Ok(b) if !b.curvature_ok => Some(format!(
                "the blade would bend to |κ| = {:.4e}, more than max_curvature = {:.4e}",
                b.max_abs_curvature,
                max_curvature.unwrap_or(f64::INFINITY)
            )),
            Ok(b) if !b.inflections_ok => Some(format!(
                "the blade would have {} inflections, more than max_inflections = {}",
                b.inflections,
                max_inflections.unwrap_or(usize::MAX)
            )),
            Ok(_) => None,
        };
        d.set_item("can_bend", why_not.is_none())?;
        d.set_item("why_not", why_not)?;
        match &blade {
            Ok(b) => {
                let bd = PyDict::new(py);
                let ends = PyList::empty(py);
                for e in &b.ends {
                    let ed = PyDict::new(py);
                    ed.set_item("position", out_point(py, &plane, e.position)?)?;
                    ed.set_item("angle", e.angle)?;
                    ends.append(ed)?;
                }
                bd.set_item("ends", ends)?;
                bd.set_item("lead_in", b.lead_in)?;
                bd.set_item("lead_out", b.lead_out)?;
                bd.set_item("max_abs_curvature", b.max_abs_curvature)?;
                bd.set_item("inflections", b.inflections)?;
                bd.set_item("elastica", elastica_object(py, b.segment, plane, None)?)?;
                d.set_item("blade", bd)?;
            }
            Err(_) => d.set_item("blade", py.None())?,
        }
        Ok(d.into_any().unbind())
    })
}

/// Adds `check_section` and `bezier_to_elastica`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check_section, m)?)?;
    m.add_function(wrap_pyfunction!(bezier_to_elastica, m)?)
}
