//! The report a `FacadeSegmentation` run writes as `report.json`; its JSON Schema is
//! `schemas/facade-segmentation-report.schema.json`. Lengths in the job's units, positions
//! in the job's frame. The pieces and counts are [`facade_seg::report`]'s.

use facade_seg::report::{PieceReport, SegmentationCounts};
use schemars::JsonSchema;
use serde::Serialize;

use super::SegAlgorithmSpec;
use crate::report::SurfaceInfo;
use crate::robot_cell::report::CellReport;
use crate::spec::{FitConstraintSpec, Units};

/// The result of the `FacadeSegmentation` task.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SegmentationReport {
    /// Job name.
    pub job: String,
    /// Task name, `FacadeSegmentation`.
    pub task: String,
    /// Length unit.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The box of what `model.gltf` shows (pieces and their blocks).
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// The settings used (defaults filled in).
    pub settings: SegmentationSettings,
    /// How many pieces and blocks, and how many break each constraint.
    pub counts: SegmentationCounts,
    /// The refinement after the algorithm: pieces and failing pieces before and after, the
    /// splits, and why each piece still failing cannot be made to hold.
    pub refinement: facade_seg::refine::RefineReport,
    /// The pieces, by band (from the facade's start edge across the cut) then by row.
    pub pieces: Vec<PieceReport>,
    /// Seams between bands, as 3D polylines (one point per section).
    pub seams: Vec<Vec<[f64; 3]>>,
    /// The robot cell: robots, holders, fixture, and per piece what the robots reach
    /// (present when the job writes robot files).
    pub cell: Option<CellReport>,
}

/// Settings of the run.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SegmentationSettings {
    /// The algorithm and its options as the job gives them.
    pub algorithm: SegAlgorithmSpec,
    /// Sections (planes) the facade was cut into.
    pub sections: usize,
    /// Points per section part for checks and fits.
    pub samples: usize,
    /// Block size along the cut, across it and up.
    pub block: [f64; 3],
    /// Blade length.
    pub blade_length: f64,
    /// Largest |curvature| the blade takes.
    pub max_curvature: f64,
    /// Most inflections a blade shape may have.
    pub max_inflections: u32,
    /// RMS tolerance of an elastica fit.
    pub tolerance_rms: f64,
    /// Largest-distance tolerance of an elastica fit.
    pub tolerance_max: f64,
    /// Whether the pieces were rationalized and posed.
    pub rationalized: bool,
    /// What each piece's fits keep.
    pub constraint: FitConstraintSpec,
    /// Cutting speed.
    pub speed: f64,
    /// Approach and retreat distance.
    pub approach: f64,
    /// The blade's kerf the run compensated for (absent without `kerf`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kerf: Option<crate::context::KerfReport>,
}

/// One line per piece refinement could not make hold, in the job's units: "piece 7,
/// section at 1.2 m along the cut (part 0.6 m): no elastica within 2 mm (its best: 3.1 mm);
/// its part's ... min_piece 0.06 m".
pub fn unresolved_lines(r: &SegmentationReport, units: &str) -> Vec<String> {
    r.refinement
        .unresolved
        .iter()
        .map(|u| {
            let what = match u.constraint.as_str() {
                "approximation" => format!(
                    "no elastica within {} {units} (its best: {:.4} {units})",
                    u.limit, u.measured
                ),
                "shape" => format!(
                    "{} inflections where the blade makes {}",
                    u.measured, u.limit
                ),
                "blade_strain" if u.reason.starts_with("the blade, extended") => format!(
                    "its blade bends beyond {} /{units} (the part itself bends up to {:.6} /{units})",
                    u.limit, u.measured
                ),
                "blade_strain" => format!(
                    "curvature {:.6} /{units} where the blade takes {} /{units}",
                    u.measured, u.limit
                ),
                _ => format!("{:.4} {units} where the blade is {} {units}", u.measured, u.limit),
            };
            let min = if u.reason.contains("min_piece") {
                format!(" ({} {units})", r.refinement.min_length)
            } else {
                String::new()
            };
            format!(
                "piece {}, section at {:.6} {units} along the cut (part {:.4} {units}): {what}; {}{min}",
                u.piece, u.offset, u.length, u.reason
            )
        })
        .collect()
}
