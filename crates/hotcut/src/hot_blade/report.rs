//! The report a `HotBlade` run writes as `report.json`; its JSON Schema is
//! `schemas/hot-blade-report.schema.json`. Lengths in the job's units, angles in radians,
//! positions in the job's frame. The grid, blocks, splits and totals are the
//! [`hotblade`] pipeline's.

use hotblade::result::{BlockReport, GridInfo, HotBladeSummary, SplitInfo};
use schemars::JsonSchema;
use serde::Serialize;

use crate::report::SurfaceInfo;
use crate::robot_cell::report::CellReport;
use crate::spec::{Continuity, FitConstraintSpec, Units};

/// The result of the `HotBlade` task.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct HotBladeReport {
    /// Job name.
    pub job: String,
    /// Task name, `HotBlade`.
    pub task: String,
    /// Length unit.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The box of what `model.gltf` shows (blocks and rationalized surfaces).
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// The settings used (defaults filled in).
    pub settings: HotBladeSettings,
    /// The block grid.
    pub grid: GridInfo,
    /// Totals over all blocks and the verdict.
    pub summary: HotBladeSummary,
    /// Columns of blocks halved because their fit broke the tolerance.
    pub splits: Vec<SplitInfo>,
    /// One entry per block, by row then by position across the cut.
    pub blocks: Vec<BlockReport>,
    /// The robot cell: robots, holders, fixture, and per block what the robots reach
    /// (present when the job writes robot files).
    pub cell: Option<CellReport>,
}

/// Settings of the run.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct HotBladeSettings {
    /// Poses (and fitted sections) per block.
    pub targets_per_block: usize,
    /// What every fit keeps of its section.
    pub constraint: FitConstraintSpec,
    /// Continuity across block faces.
    pub continuity: Continuity,
    /// Largest number of halvings of a column.
    pub split_depth: u32,
    /// Fit samples per section.
    pub samples: usize,
    /// Planes between two targets on the deviation grid.
    pub refine: usize,
    /// `Parallel` or `Curve` (planes following a cutting-direction curve).
    pub planes: String,
    /// Blade length.
    pub blade_length: f64,
    /// Largest |curvature| the blade takes.
    pub max_curvature: f64,
    /// Most inflections on a blade.
    pub max_inflections: u32,
    /// RMS fit tolerance.
    pub tolerance_rms: f64,
    /// Largest-distance fit tolerance.
    pub tolerance_max: f64,
    /// Flat-blade limit: angle between the cutting plane and the surface normal.
    pub max_plane_angle: f64,
    /// Cutting speed, units per second.
    pub speed: f64,
    /// Approach and retreat distance along the cut.
    pub approach: f64,
    /// The blade's kerf the run compensated for (absent without `kerf`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kerf: Option<crate::context::KerfReport>,
}
