//! What reports share (the surface as loaded). Each task's report type lives in its module;
//! all are written as `report.json`, floats rounded to
//! [`REPORT_DIGITS`](export::json::REPORT_DIGITS) significant digits.

use geom::surface::Surface;
use schemars::JsonSchema;
use serde::Serialize;

use crate::context::Context;

/// What was loaded.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SurfaceInfo {
    /// `HeightField`, `Mesh` or `Spline`.
    pub kind: String,
    /// Minimum corner of the bounding box (height-field and spline heights are sampled).
    pub bbox_min: [f64; 3],
    /// Maximum corner of the bounding box.
    pub bbox_max: [f64; 3],
    /// Non-fatal findings while loading.
    pub warnings: Vec<String>,
}

impl SurfaceInfo {
    /// What a job loaded.
    pub fn of(job: &Context, surface: &Surface) -> Self {
        let b = surface.aabb();
        Self {
            kind: surface_kind(surface).into(),
            bbox_min: [b.min.x, b.min.y, b.min.z],
            bbox_max: [b.max.x, b.max.y, b.max.z],
            warnings: job.warnings.clone(),
        }
    }
}

/// The job's name for a surface kind: `HeightField`, `Mesh` or `Spline`.
pub fn surface_kind(surface: &Surface) -> &'static str {
    match surface {
        Surface::Mesh(_) => "Mesh",
        Surface::HeightField(_) => "HeightField",
        Surface::Spline(_) => "Spline",
    }
}
