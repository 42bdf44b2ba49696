//! What reports share (the surface as loaded). Each task's report type lives in its module;
//! all are written as `report.json`, floats rounded to
//! [`REPORT_DIGITS`](export::json::REPORT_DIGITS) significant digits.

use geom::surface::Surface;
use schemars::JsonSchema;
use serde::Serialize;

use crate::context::Context;

/// The hotcut version every report carries (`hotcut_version`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The bounding box of what `model.gltf` shows, in job units and double precision (the
/// glTF holds the same box in metres, turned y up, rounded to single precision as its
/// positions are).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ModelBounds {
    /// Minimum corner.
    pub min: [f64; 3],
    /// Maximum corner.
    pub max: [f64; 3],
}

impl ModelBounds {
    /// The box of a glTF scene's meshes (`None` for an empty scene or one that could not
    /// be built).
    pub fn of(scene: export::Result<Vec<export::gltf::Mesh>>) -> Option<Self> {
        let meshes = scene.ok()?;
        export::gltf::bounds(&meshes).map(|(min, max)| Self { min, max })
    }
}

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
