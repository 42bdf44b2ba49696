//! The report a `FitCurves` run writes as `report.json`; its JSON Schema is
//! `schemas/fit-curves-report.schema.json`.

use elastica::fit::describe::{CurveFit, FitSummary};
use schemars::JsonSchema;
use serde::Serialize;

use super::curves::InputCurve;
use crate::spec::Units;

/// The result of the `FitCurves` task (`report.json`; schema
/// `schemas/fit-curves-report.schema.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FitCurvesReport {
    /// Job name.
    pub job: String,
    /// Task name, `FitCurves`.
    pub task: String,
    /// Length unit of every coordinate and length; curvatures in 1/unit.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// Where the curves came from: `file <path>` or `sections of the <kind> surface`.
    pub source: String,
    /// The boundary constraint every fit honours.
    pub constraint: crate::spec::FitConstraintSpec,
    /// The method.
    pub method: super::FitMethod,
    /// Totals.
    pub summary: FitSummary,
    /// One entry per curve, in input order (sections: by plane, then piece).
    pub curves: Vec<CurveFit>,
    /// With `NumericalSpline`: one entry per curve, in input order.
    pub numerical: Option<Vec<NumericalCurve>>,
}

/// The numerical spline approach on one curve ("Hot Blade Cuttings" §5.2, eq. 13).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NumericalCurve {
    /// The curve's id.
    pub id: String,
    /// Why it failed, if it did (then every other field is 0).
    pub error: Option<String>,
    /// Control points of the refined spline.
    pub control_points: usize,
    /// Whether some constraint is active: if none is, the result is an energy minimum
    /// within ε of the input (up to the spline's discretization).
    pub constraint_active: bool,
    /// How many control points sit on their ε bound.
    pub active_constraints: usize,
    /// Largest distance of a control point from the input spline's (≤ ε).
    pub max_control_offset: f64,
    /// Largest distance of an input point from the input spline (refinement error).
    pub input_fit_distance: f64,
    /// Largest distance of an input point from the result (≤ ε + `input_fit_distance`).
    pub max_distance: f64,
    /// Bending energy ½∫κ² ds times the length (dimensionless), before and after.
    pub energy_before: f64,
    /// See `energy_before`.
    pub energy_after: f64,
    /// Length of the input spline and of the result.
    pub input_length: f64,
    /// See `input_length`.
    pub length: f64,
    /// The eq. (11) residual of the result: how far it is from an elastica (0 for one).
    pub eq11_residual: f64,
    /// Largest distance of the result from the analytic fit (`null` when that failed).
    pub distance_to_analytic: Option<f64>,
    /// Whether the solver reached the optimality (KKT) conditions, its active-set Newton
    /// end game settled (else the result is the SQP's last feasible iterate).
    pub converged: bool,
}

/// Largest distance from the points `a` to the polyline `b`.
fn distance_to_polyline(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .map(|p| geom::polyline::distance_to_polyline(*p, b))
        .fold(0.0, f64::max)
}

impl NumericalCurve {
    /// The entry of curve `id` from its result `r`, compared with the analytic `fit`.
    pub fn new(
        id: &str,
        r: &Result<design::numerical::NumericalResult, String>,
        fit: Option<&elastica::fit::FitResult>,
    ) -> Self {
        match r {
            Ok(r) => Self {
                id: id.into(),
                error: None,
                control_points: r.control.len(),
                constraint_active: r.active_constraints > 0,
                active_constraints: r.active_constraints,
                max_control_offset: r.max_control_offset,
                input_fit_distance: r.input_fit_distance,
                max_distance: r.max_distance,
                energy_before: r.energy_before,
                energy_after: r.energy_after,
                input_length: r.input_length,
                length: r.length,
                eq11_residual: r.eq11_residual,
                distance_to_analytic: fit
                    .and_then(|f| f.segment.sample(2000).ok())
                    .map(|s| distance_to_polyline(&r.samples, &s)),
                converged: r.converged,
            },
            Err(e) => Self {
                id: id.into(),
                error: Some(e.clone()),
                control_points: 0,
                constraint_active: false,
                active_constraints: 0,
                max_control_offset: 0.0,
                input_fit_distance: 0.0,
                max_distance: 0.0,
                energy_before: 0.0,
                energy_after: 0.0,
                input_length: 0.0,
                length: 0.0,
                eq11_residual: 0.0,
                distance_to_analytic: None,
                converged: false,
            },
        }
    }
}

/// Length of a curve: its arc length when known, else its polyline's.
pub(super) fn input_length(c: &InputCurve) -> f64 {
    match &c.arc_length {
        Some(s) => s[s.len() - 1] - s[0],
        None => geom::polyline::length(&c.points),
    }
}
