//! The job-file types every task shares: units, surface, block, blade, wire, cell, cutting,
//! tolerances, fit constraints and the output files. Raw serde types with
//! `deny_unknown_fields`; their doc comments become the descriptions in
//! `schemas/job.schema.json`. Each task's own fields live in its module.
//!
//! Every omitted field has the default documented on it. Lengths are in the job's
//! [`Units`](crate::spec::Units); curvatures in 1/length; angles in radians.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The robot cell of the hot blade: `Cell(..)`, its robots, holders, fixture and heat.
mod cell;
/// The `Compare` task's rates and milling tool.
pub mod compare;
/// The hot-wire machine: `Wire(..)` and its controller profile.
mod wire;

pub use cell::{
    CarrierSpec, CellSpec, CustomModel, FrameSpec, HeatSpec, HolderSpec, ModelSpec, RobotSpec,
};

pub use wire::{FluidNcAxes, MachineSpec, TravelSpec, WireSpec};

/// Length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
pub enum Units {
    /// Millimetres (the default).
    #[default]
    Millimetre,
    /// Metres.
    Metre,
}

impl Units {
    /// Name as written in job files: `Millimetre` or `Metre`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Millimetre => "Millimetre",
            Self::Metre => "Metre",
        }
    }

    /// Short symbol for messages: `mm` or `m`.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Millimetre => "mm",
            Self::Metre => "m",
        }
    }

    /// How many job units one millimetre is.
    pub fn per_mm(self) -> f64 {
        match self {
            Self::Millimetre => 1.0,
            Self::Metre => 1e-3,
        }
    }
}

/// Where the surface comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum SurfaceSpec {
    /// `z = f(x, y)` over a rectangle, sectioned exactly. Operators `+ - * / ^`, unary minus,
    /// parentheses, `sin cos tan exp ln sqrt abs`, constants `pi` and `e`, variables `x`, `y`
    /// in job units.
    HeightField {
        /// The expression for `z`.
        #[schemars(length(min = 1))]
        z: String,
        /// `(min, max)` of `x`.
        x: (f64, f64),
        /// `(min, max)` of `y`.
        y: (f64, f64),
    },
    /// A triangle mesh from a Wavefront OBJ file (path relative to the job file).
    Mesh {
        /// Path of the `.obj` file, relative to the job file.
        #[schemars(length(min = 1))]
        path: String,
        /// Require a closed (watertight) mesh. Default: `false` (a facade is an open sheet;
        /// `BlockSegmentation` checks that its mesh is closed whatever this says).
        #[serde(default)]
        closed: bool,
    },
    /// A tensor-product B-spline surface from a JSON control-grid file (path relative to
    /// the job file); see the README for the format.
    Spline {
        /// Path of the control-grid `.json` file, relative to the job file.
        #[schemars(length(min = 1))]
        path: String,
    },
}

/// The foam block, an axis-aligned box in the job's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Block")]
pub struct BlockSpec {
    /// Edge lengths `(x, y, z)`, each > 0.
    pub size: (f64, f64, f64),
    /// Minimum corner `(x, y, z)`; when given, the surface must also lie inside the placed
    /// block. Default: not placed (only the size is checked).
    #[serde(default)]
    pub origin: Option<(f64, f64, f64)>,
}

/// The hot blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Blade")]
pub struct BladeSpec {
    /// Blade length (> 0): sections longer than this need segmentation.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub length: f64,
    /// Largest |curvature| the blade takes without permanent deformation (> 0), 1/length.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub max_curvature: f64,
    /// Most inflection points a blade shape may have. Default: 2 (thesis §5.1.3).
    #[serde(default = "default_max_inflections")]
    pub max_inflections: u32,
    /// The width the heated blade melts (≥ 0, job units; thesis §5.1.5: "compensate for
    /// the width of the blade"). `HotBlade`, `FacadeSegmentation` and `Design` then fit
    /// the blade to the design moved half of it towards the material they remove (up,
    /// the side the design's normal points to), so the surface left is the design. Default:
    /// none (the blade's centre line on the design).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kerf: Option<f64>,
    /// Kerf by blade speed, `[(speed, kerf), ..]`: speeds (job units per second) strictly
    /// increasing, at most 64 rows; the task's cutting speed picks the kerf, interpolated
    /// linearly and held beyond the table's ends (a slower blade melts wider). Default:
    /// none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kerf_table: Option<Vec<(f64, f64)>>,
    /// Most inflections the whole held blade may have, its extension beyond the cut
    /// included, in every task (> 0). `max_inflections` limits the whole blade in
    /// `HotBlade` and `Design` and each section part in `FacadeSegmentation` (§5.1.3);
    /// this limits the whole blade everywhere. Default: none (the blade's stability,
    /// checked always, is what the inflection count stood for).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1))]
    pub max_blade_inflections: Option<u32>,
    /// Thickness of the blade strip in the cutting plane (> 0, job units): with `width`
    /// and `youngs_modulus` it gives the bending stiffness the forces and moments on the
    /// holders are reported with. Default: 1 mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub thickness: Option<f64>,
    /// Width of the blade strip along the cut (> 0, job units). Default: 25 mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub width: Option<f64>,
    /// Young's modulus of the blade at its working temperature, GPa (> 0). Default: 200
    /// (spring steel).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub youngs_modulus: Option<f64>,
    /// Least stability margin every posed blade keeps (0–1): the smallest eigenvalue of
    /// the held blade's second variation over a straight blade's; below it a pose is
    /// marginal and the plan avoids it. Default: 0.05.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub min_margin: Option<f64>,
}

fn default_max_inflections() -> u32 {
    2
}

/// How the surface is cut into sections.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Cutting")]
pub struct CuttingSpec {
    /// Cutting direction, the normal of the section planes. Default: `(1, 0, 0)`. Height
    /// fields need a horizontal direction (z = 0).
    #[serde(default = "default_direction")]
    pub direction: (f64, f64, f64),
    /// Number of section planes, at the centres of equal slabs of the surface's extent
    /// along the direction (≥ 1). Default: 26. `HotBlade` places its own planes per block
    /// (`targets_per_block`) and does not use this.
    #[serde(default = "default_sections")]
    #[schemars(range(min = 1, max = 100000))]
    pub sections: u32,
    /// `HotBlade` only: a cutting-direction curve, as plan points `[(x, y), ...]` (at least
    /// 2, strictly advancing from the first towards the last). The section planes then
    /// follow it (thesis §5.1.5, eq. 5.4): each plane is vertical, through a point of the
    /// curve, with the curve's horizontal tangent as its normal; the block grid is aligned
    /// with the chord from the first to the last point, which replaces `direction`.
    /// Default: none (parallel planes normal to `direction`).
    #[serde(default)]
    pub curve: Option<Vec<(f64, f64)>>,
}

fn default_direction() -> (f64, f64, f64) {
    (1.0, 0.0, 0.0)
}

fn default_sections() -> u32 {
    26
}

impl Default for CuttingSpec {
    fn default() -> Self {
        Self {
            direction: default_direction(),
            sections: default_sections(),
            curve: None,
        }
    }
}

/// Tolerances, in job units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Tolerance")]
pub struct ToleranceSpec {
    /// RMS distance allowed between the surface and what is cut (> 0). Default: 0.5 mm
    /// (converted when `units: Metre`).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub rms: Option<f64>,
    /// Largest distance allowed between the surface and what is cut (> 0). Default: 2 mm.
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub max: Option<f64>,
    /// Largest deviation allowed when a polyline section (mesh, spline surface) is replaced
    /// by a smoothing spline before curvature is taken (≥ 0). For meshes, a point may also
    /// deviate by its chordal sagitta (how far a facet can be from the true surface there).
    /// Default: 0.05 mm.
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub smoothing: Option<f64>,
    /// Inflections are located by bisection to within this arc length (> 0). Default: 1e-6 mm.
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub bisection: Option<f64>,
    /// A stretch between inflections that turns the tangent by less than this many radians
    /// is noise, and its inflections are dropped (≥ 0). Default: 0.002.
    #[serde(default = "default_min_turning")]
    #[schemars(range(min = 0))]
    pub min_turning: f64,
}

fn default_min_turning() -> f64 {
    0.002
}

impl Default for ToleranceSpec {
    fn default() -> Self {
        Self {
            rms: None,
            max: None,
            smoothing: None,
            bisection: None,
            min_turning: default_min_turning(),
        }
    }
}

/// The tolerances with their defaults applied, in job units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Tolerance {
    /// RMS distance allowed between the surface and what is cut.
    pub rms: f64,
    /// Largest distance allowed between the surface and what is cut.
    pub max: f64,
    /// Smoothing-spline deviation of polyline sections.
    pub smoothing: f64,
    /// Bisection tolerance of inflections, arc length.
    pub bisection: f64,
    /// Least tangent turning between inflections, radians.
    pub min_turning: f64,
}

impl ToleranceSpec {
    /// The tolerances in `units`, each omitted one from its millimetre default.
    pub fn resolve(&self, units: Units) -> Tolerance {
        let f = units.per_mm();
        Tolerance {
            rms: self.rms.unwrap_or(defaults::RMS_MM * f),
            max: self.max.unwrap_or(defaults::MAX_MM * f),
            smoothing: self.smoothing.unwrap_or(defaults::SMOOTHING_MM * f),
            bisection: self.bisection.unwrap_or(defaults::BISECTION_MM * f),
            min_turning: self.min_turning,
        }
    }
}

/// Boundary constraints of a fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
pub enum FitConstraintSpec {
    /// Nothing: the segment closest to the curve.
    #[default]
    Free,
    /// The segment starts and ends at the curve's end points.
    EndPoints,
    /// End points, and the segment is as long as the curve (the skater-ramp setting of the
    /// hot-blade paper §7: the blade keeps its length).
    EndPointsAndLength,
}

impl FitConstraintSpec {
    /// The `elastica` option.
    pub fn to_fit(self) -> elastica::fit::FitConstraint {
        match self {
            Self::Free => elastica::fit::FitConstraint::Free,
            Self::EndPoints => elastica::fit::FitConstraint::EndPoints,
            Self::EndPointsAndLength => elastica::fit::FitConstraint::EndPointsAndLength,
        }
    }
}

/// Continuity of the rationalized surface across block faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
pub enum Continuity {
    /// Neighbouring blades share their end points.
    #[default]
    C0,
    /// Neighbouring blades share their end points and end tangents.
    C1,
}

impl Continuity {
    /// The `hotblade` option.
    pub fn to_hotblade(self) -> hotblade::Continuity {
        match self {
            Self::C0 => hotblade::Continuity::C0,
            Self::C1 => hotblade::Continuity::C1,
        }
    }
}

/// A file to write. Each task writes the kinds it declares; the files per task:
/// `Analyze` Report, Svg (`sections.svg`), Obj (`sections.obj`); `FitCurves` Report, Svg
/// (`fit.svg`); `HotBlade` Report, Svg (`block_NNN.svg`), Obj (`surface_block_NNN.obj`),
/// Gltf, Csv (`sections.csv`), RobotTargets, Rapid; `FacadeSegmentation` Report, Svg
/// (`segmentation.svg`), Obj (`segmentation.obj`), Gltf, Csv (`sections.csv`),
/// RobotTargets, Rapid; `BlockSegmentation` Report, Blocks, Svg (`progress.svg`), Obj
/// (`blocks.obj`), Gltf; `PreCut` Report, PreCut, Svg (`sections.svg`), Obj
/// (`precut.obj`), Gltf, GCode and Csv (`wire_dD_cC.gcode/.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum OutputSpec {
    /// `report.json`: the task's full result.
    Report,
    /// A drawing: the sections in plan and profile (Analyze), every curve with its fit
    /// (FitCurves), each block's worst section (HotBlade), the pieces in plan
    /// (FacadeSegmentation), blocks and E per iteration (BlockSegmentation), cross sections
    /// of the cuts (PreCut).
    Svg,
    /// Wavefront OBJ: the section curves (Analyze), each block's rationalized surface
    /// (HotBlade), every piece's section parts (FacadeSegmentation), the blocks as boxes
    /// (BlockSegmentation), the design, cut surfaces and block (PreCut). `Obj` alone is
    /// `Obj(axes: ZUp)`.
    Obj {
        /// Which axis is up in the file: `ZUp` (default; as computed, for Rhino and CAD)
        /// or `YUp` (for Blender's default OBJ import and three.js: (x, y, z) is written
        /// (x, z, −y), so the mesh lands with the job's `model.gltf`).
        #[serde(default)]
        axes: ObjAxes,
    },
    /// `model.gltf`: blocks as boxes and the rationalized surfaces coloured by deviation
    /// (HotBlade), the pieces in colours and their blocks (FacadeSegmentation), the model
    /// and its blocks (BlockSegmentation), the design, cut surfaces and block (PreCut).
    Gltf,
    /// CSV: one row per fitted section (HotBlade), per section part of a piece
    /// (FacadeSegmentation), per wire step of each cut (PreCut, `wire_dD_cC.csv`).
    Csv,
    /// `targets.json` and `targets.csv`: blade poses per block (HotBlade) or per piece
    /// (FacadeSegmentation: one pose per section the piece crosses).
    RobotTargets {
        /// HotBlade: targets per block; when given, must equal the task's
        /// `targets_per_block`. FacadeSegmentation: leave out. Default: none.
        #[serde(default)]
        #[schemars(range(min = 2))]
        per_block: Option<u32>,
    },
    /// ABB RAPID programs for a MultiMove cell, one module and `.pgf` per blade robot
    /// (HotBlade, FacadeSegmentation).
    Rapid,
    /// Hot-wire G-code, one file per cut (PreCut, `wire_dD_cC.gcode`).
    GCode,
    /// `blocks.json` (BlockSegmentation): every block's centre, rotation `[w, x, y, z]`
    /// (block axes to model axes) and size, in the mesh's coordinates.
    Blocks,
    /// `precut.json` (PreCut): per direction, per section along the cut, the polygon of
    /// rulings as 3D points, so anyone can re-check the cut.
    PreCut,
    /// `report.html` (every task): one self-contained page — the verdict first (can it be
    /// cut, with how many blocks, pieces or cuts), the constraints, the drawings inlined,
    /// the per-block/piece/curve tables with flagged rows highlighted, links to every other
    /// file written, the run time and the job. No script, no network needed.
    Html,
}

/// The up axis of an OBJ output.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum ObjAxes {
    /// +z up, as hotcut computes.
    #[default]
    ZUp,
    /// +y up: (x, y, z) written as (x, z, −y).
    YUp,
}

impl OutputSpec {
    /// The kind of file, without its options.
    pub fn kind(&self) -> OutputKind {
        match self {
            Self::Report => OutputKind::Report,
            Self::Svg => OutputKind::Svg,
            Self::Obj { .. } => OutputKind::Obj,
            Self::Gltf => OutputKind::Gltf,
            Self::Csv => OutputKind::Csv,
            Self::RobotTargets { .. } => OutputKind::RobotTargets,
            Self::Rapid => OutputKind::Rapid,
            Self::GCode => OutputKind::GCode,
            Self::Blocks => OutputKind::Blocks,
            Self::PreCut => OutputKind::PreCut,
            Self::Html => OutputKind::Html,
        }
    }

    /// Name as written in job files.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }
}

/// The kinds of output file, as [`OutputSpec`] names them without their options. Each task
/// declares the kinds it writes once ([`crate::task::Task::OUTPUTS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// `report.json`, written by every task.
    Report,
    /// A drawing.
    Svg,
    /// Wavefront OBJ.
    Obj,
    /// glTF 2.0.
    Gltf,
    /// CSV tables.
    Csv,
    /// `targets.json` and `targets.csv`.
    RobotTargets,
    /// ABB RAPID modules.
    Rapid,
    /// Hot-wire G-code.
    GCode,
    /// `blocks.json`.
    Blocks,
    /// `precut.json`.
    PreCut,
    /// `report.html`, written by every task.
    Html,
}

impl OutputKind {
    /// Name as written in job files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Report => "Report",
            Self::Svg => "Svg",
            Self::Obj => "Obj",
            Self::Gltf => "Gltf",
            Self::Csv => "Csv",
            Self::RobotTargets => "RobotTargets",
            Self::Rapid => "Rapid",
            Self::GCode => "GCode",
            Self::Blocks => "Blocks",
            Self::PreCut => "PreCut",
            Self::Html => "Html",
        }
    }
}

/// Every length default of a job, stated once, in millimetres. They are applied only
/// through [`Units::per_mm`] (lengths multiplied, curvatures divided), so a job in metres
/// gets the same physical defaults as one in millimetres.
pub mod defaults {
    /// `tolerance.rms`, mm.
    pub const RMS_MM: f64 = 0.5;
    /// `tolerance.max`, mm.
    pub const MAX_MM: f64 = 2.0;
    /// `tolerance.smoothing`, mm.
    pub const SMOOTHING_MM: f64 = 0.05;
    /// `tolerance.bisection`, mm.
    pub const BISECTION_MM: f64 = 1e-6;
    /// `blade.length`, mm.
    pub const BLADE_LENGTH_MM: f64 = 1000.0;
    /// `blade.max_curvature`, 1/mm.
    pub const BLADE_MAX_CURVATURE_PER_MM: f64 = 0.011;
    /// `blade.thickness`, mm: a spring-steel hot blade strip.
    pub const BLADE_THICKNESS_MM: f64 = 1.0;
    /// `blade.width`, mm.
    pub const BLADE_WIDTH_MM: f64 = 25.0;
    /// Cutting speed of the blade (`speed` of `HotBlade` and `FacadeSegmentation`), mm/s.
    pub const BLADE_SPEED_MM_PER_S: f64 = 7.0;
    /// Approach and retreat distance of the blade along the cut (`approach`), mm.
    pub const APPROACH_MM: f64 = 50.0;
    /// `wire.speed`, mm/min.
    pub const WIRE_SPEED_MM_PER_MIN: f64 = 300.0;
    /// `wire.lead`, mm.
    pub const WIRE_LEAD_MM: f64 = 20.0;
    /// `wire.clearance`, mm.
    pub const WIRE_CLEARANCE_MM: f64 = 50.0;
    /// `wire.power`, the `S` word of the heat-on command (no unit: the controller's).
    pub const WIRE_POWER: f64 = 1000.0;
    /// `wire.preheat_s`, seconds.
    pub const WIRE_PREHEAT_S: f64 = 2.0;
    /// `LongestElastica(precision)`, mm.
    pub const PRECISION_MM: f64 = 1.0;
    /// `RuledBlocks(floor)`: depth of the slab under a height field below its lowest
    /// point, mm.
    pub const RULED_FLOOR_MM: f64 = 50.0;
}

/// The fit constraint of a blade that keeps its length: the default of the tasks that
/// pose the blade.
pub(crate) fn keep_length() -> FitConstraintSpec {
    FitConstraintSpec::EndPointsAndLength
}
