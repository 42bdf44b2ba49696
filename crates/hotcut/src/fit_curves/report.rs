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
    /// Where the curves came from: `file <path>` or `sections of the <kind> surface`.
    pub source: String,
    /// The boundary constraint every fit honours.
    pub constraint: crate::spec::FitConstraintSpec,
    /// Totals.
    pub summary: FitSummary,
    /// One entry per curve, in input order (sections: by plane, then piece).
    pub curves: Vec<CurveFit>,
}

/// Length of a curve: its arc length when known, else its polyline's.
pub(super) fn input_length(c: &InputCurve) -> f64 {
    match &c.arc_length {
        Some(s) => s[s.len() - 1] - s[0],
        None => c
            .points
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum(),
    }
}
