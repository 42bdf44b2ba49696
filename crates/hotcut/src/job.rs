//! The job file as the user writes it (RON): raw serde types with `deny_unknown_fields`,
//! whose doc comments become the descriptions in `schemas/job.schema.json`.
//!
//! [`TaskSpec`](crate::job::TaskSpec) is the one list of every task: each variant holds
//! the task's own struct, defined in the task's module;
//! [`TaskSpec::visit`](crate::job::TaskSpec::visit) hands the job's task to code that
//! works for any task (checks, runner), and [`TaskSpec::each`](crate::job::TaskSpec::each)
//! visits every task type (report schemas). The fields every task shares are in
//! [`crate::spec`].

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::analyze::Analyze;
use crate::block_segmentation::BlockSegmentation;
use crate::compare::{Compare, Kind, ProcessSpec};
use crate::design_task::Design;
use crate::facade_segmentation::FacadeSegmentation;
use crate::fit_curves::FitCurves;
use crate::hot_blade::HotBlade;
use crate::pre_cut::PreCut;
use crate::ruled_blocks::RuledBlocks;
use crate::spec::compare::ToolSpec;
use crate::spec::{BladeSpec, BlockSpec, CuttingSpec, OutputSpec, SurfaceSpec, ToleranceSpec};
use crate::spec::{CellSpec, Units, WireSpec};
use crate::task::{Name, Visit, VisitType};

/// A hotcut job: what to cut, with which tool and constraints, which task to run and which
/// files to write.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// Name of the job; outputs go to `<out>/<name>/`. Letters, digits, `.`, `_` and `-`.
    #[schemars(
        regex(pattern = r"^[A-Za-z0-9][A-Za-z0-9._-]*$"),
        length(min = 1, max = 100)
    )]
    pub name: String,
    /// Length unit of every length in the job and its outputs. Default: `Millimetre`.
    #[serde(default)]
    pub units: Units,
    /// The surface to cut. Required by every task but `FitCurves` with an `input` file.
    #[serde(default)]
    pub surface: Option<SurfaceSpec>,
    /// The foam block. Required by `HotBlade`, `FacadeSegmentation`, `BlockSegmentation` and
    /// `PreCut`; optional for `Analyze` (when omitted, the block-size constraint is not
    /// checked).
    #[serde(default)]
    pub block: Option<BlockSpec>,
    /// The hot blade. Default: `Blade(length: 1000 mm, max_curvature: 0.011 /mm, max_inflections: 2)`
    /// (converted when `units: Metre`).
    #[serde(default)]
    pub blade: Option<BladeSpec>,
    /// The hot-wire machine (PreCut's `GCode` and `Csv` outputs need it).
    #[serde(default)]
    pub wire: Option<WireSpec>,
    /// The robot cell of the hot blade (`HotBlade` and `FacadeSegmentation` robot files).
    /// Default: the default cell (README, "The robot cell").
    #[serde(default)]
    pub cell: Option<CellSpec>,
    /// Cutting direction and number of sections. Default: `Cutting(direction: (1, 0, 0), sections: 26)`.
    #[serde(default)]
    pub cutting: CuttingSpec,
    /// Tolerances. Default: see each field.
    #[serde(default)]
    pub tolerance: ToleranceSpec,
    /// The task to run.
    pub task: TaskSpec,
    /// Files to write. Default: `[Report, Svg]`.
    #[serde(default = "default_outputs")]
    pub outputs: Vec<OutputSpec>,
    /// Seed of every random choice a task makes. Default: 0.
    #[serde(default)]
    pub seed: u64,
}

fn default_outputs() -> Vec<OutputSpec> {
    vec![OutputSpec::Report, OutputSpec::Svg]
}

/// The task to run: its name, and in parentheses its fields, e.g.
/// `HotBlade(targets_per_block: 51)`; with all fields at their defaults, `Analyze()` or
/// just `Analyze`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum TaskSpec {
    /// Section the surface and check every section against the production constraints.
    Analyze(Analyze),
    /// Fit curves, or the surface's sections, by one elastica, line or arc each.
    FitCurves(FitCurves),
    /// Hot-blade rationalization of a grid of blocks, with robot data.
    HotBlade(HotBlade),
    /// Facade segmentation into pieces a hot blade can cut, each rationalized.
    FacadeSegmentation(FacadeSegmentation),
    /// Cover a closed mesh with few freely placed blocks.
    BlockSegmentation(BlockSegmentation),
    /// Hot-wire pre-cuts removing the bulk above a design surface.
    PreCut(PreCut),
    /// A surface designed for the hot blade: design curves per block, their elastica.
    Design(Design),
    /// A model rationalized by piecewise ruled strips, segmented into blocks a hot wire cuts.
    RuledBlocks(RuledBlocks),
    /// One design made by several processes (milling, pre-cut + milling, hot wire, hot
    /// blade), set side by side: material, time, fidelity and cost.
    Compare(Compare<Process>),
}

impl TaskSpec {
    /// Calls `v` with the task as its own type: the one place that dispatches on the task.
    pub fn visit<V: Visit>(&self, v: V) -> V::Output {
        match self {
            Self::Analyze(t) => v.visit(t),
            Self::FitCurves(t) => v.visit(t),
            Self::HotBlade(t) => v.visit(t),
            Self::FacadeSegmentation(t) => v.visit(t),
            Self::BlockSegmentation(t) => v.visit(t),
            Self::PreCut(t) => v.visit(t),
            Self::Design(t) => v.visit(t),
            Self::RuledBlocks(t) => v.visit(t),
            Self::Compare(t) => v.visit(t),
        }
    }

    /// Calls `v` once per task type, in the order of the variants: the one list of task
    /// types for code that needs no task value (the report schemas).
    pub fn each<V: VisitType>(v: &mut V) {
        v.visit::<Analyze>();
        v.visit::<FitCurves>();
        v.visit::<HotBlade>();
        v.visit::<FacadeSegmentation>();
        v.visit::<BlockSegmentation>();
        v.visit::<PreCut>();
        v.visit::<Design>();
        v.visit::<RuledBlocks>();
        v.visit::<Compare<Process>>();
    }

    /// Name as written in job files.
    pub fn name(&self) -> &'static str {
        self.visit(Name)
    }
}

/// One way to make the design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum Process {
    /// CNC milling of the stock as bought: roughing by the removal rate, finishing by the
    /// tool's passes.
    Milling(Milling),
    /// Hot-wire pre-cuts (the `PreCut` task) remove the bulk, then milling finishes
    /// (thesis ch. 2). Needs `wire:` (the cut lengths come from its programs).
    PreCutThenMilling(PreCutThenMilling),
    /// A closed model (or a height field's slab) rationalized by ruled strips and cut by a
    /// hot wire block by block (the `RuledBlocks` task, thesis ch. 4). Needs `wire:`.
    HotWireRuled(RuledBlocks),
    /// A facade cut by the hot blade on a grid of blocks (the `HotBlade` task).
    HotBlade(HotBlade),
    /// A facade segmented into pieces one blade can cut (the `FacadeSegmentation` task,
    /// thesis ch. 5), when one blade across a block cannot.
    FacadeSegmentation(FacadeSegmentation),
}

/// Milling: the tool, and the stock it mills.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Milling {
    /// The tool. Default: `Tool()` (20 mm ball nose, 4 mm stepover, the rates' feeds).
    #[serde(default)]
    pub tool: ToolSpec,
    /// The stock. Default: `Blocks` (the job's `block` tiling the design).
    #[serde(default)]
    pub stock: MillingStock,
}

/// Pre-cut then milling: the `PreCut` task's settings, and the milling tool.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PreCutThenMilling {
    /// The pre-cut, as the `PreCut` task takes it. Default: `PreCut()`.
    #[serde(default = "default_pre_cut")]
    pub pre_cut: PreCut,
    /// The milling tool. Default: `Tool()`.
    #[serde(default)]
    pub tool: ToolSpec,
}

fn default_pre_cut() -> PreCut {
    // every field of PreCut has a default
    ron::from_str("()").expect("PreCut() is a valid task")
}

/// The stock a milling machine starts from.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum MillingStock {
    /// The job's `block` (its size, and its origin when given) repeated over the design's
    /// bounding box.
    #[default]
    Blocks,
    /// Freely placed blocks covering a closed mesh (the `BlockSegmentation` task,
    /// thesis ch. 3).
    BlockSegmentation(BlockSegmentation),
}

impl ProcessSpec for Process {
    fn kind(&self) -> Kind {
        match self {
            Self::Milling(Milling {
                stock: MillingStock::Blocks,
                ..
            }) => Kind::Milling,
            Self::Milling(_) => Kind::MillingSegmented,
            Self::PreCutThenMilling(_) => Kind::PreCutThenMilling,
            Self::HotWireRuled(_) => Kind::HotWireRuled,
            Self::HotBlade(_) => Kind::HotBlade,
            Self::FacadeSegmentation(_) => Kind::FacadeSegmentation,
        }
    }

    fn tool(&self) -> Option<&ToolSpec> {
        match self {
            Self::Milling(m) => Some(&m.tool),
            Self::PreCutThenMilling(p) => Some(&p.tool),
            _ => None,
        }
    }

    fn visit<V: Visit>(&self, v: V) -> Option<V::Output> {
        match self {
            Self::Milling(Milling {
                stock: MillingStock::BlockSegmentation(t),
                ..
            }) => Some(v.visit(t)),
            Self::Milling(_) => None,
            Self::PreCutThenMilling(p) => Some(v.visit(&p.pre_cut)),
            Self::HotWireRuled(t) => Some(v.visit(t)),
            Self::HotBlade(t) => Some(v.visit(t)),
            Self::FacadeSegmentation(t) => Some(v.visit(t)),
        }
    }
}
