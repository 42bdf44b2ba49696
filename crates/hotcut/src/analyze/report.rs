//! The report an `Analyze` run writes as `report.json`; its JSON Schema is
//! `schemas/report.schema.json`. Lengths are in the job's units, curvatures in 1/unit,
//! positions in the job's frame; floats are rounded to
//! [`export::json::REPORT_DIGITS`](export::json::REPORT_DIGITS) significant digits when written.

use facade_seg::survey::{SectionReport, Summary};
use schemars::JsonSchema;
use serde::Serialize;

use crate::report::SurfaceInfo;
use crate::spec::Units;

/// The result of the `Analyze` task.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct AnalyzeReport {
    /// Job name.
    pub job: String,
    /// Task name, `Analyze`.
    pub task: String,
    /// Length unit.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The section planes.
    pub cutting: CuttingInfo,
    /// The constraints checked.
    pub constraints: ConstraintsInfo,
    /// Totals and the verdict.
    pub summary: Summary,
    /// One entry per section piece, by plane then piece.
    pub sections: Vec<SectionReport>,
}

/// The plane family.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CuttingInfo {
    /// Unit cutting direction (plane normal).
    pub direction: [f64; 3],
    /// First in-plane axis: section coordinates are `(u, v)`.
    pub plane_u: [f64; 3],
    /// Second in-plane axis.
    pub plane_v: [f64; 3],
    /// Number of planes.
    pub planes: usize,
    /// Extent of the surface along the direction, `[min, max]`.
    pub extent: [f64; 2],
}

/// The production constraints checked (thesis §5.1).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ConstraintsInfo {
    /// Blade length.
    pub blade_length: f64,
    /// Largest allowed |curvature|.
    pub max_curvature: f64,
    /// Most inflections allowed per section.
    pub max_inflections: u32,
    /// Block size, if given.
    pub block_size: Option<[f64; 3]>,
}
