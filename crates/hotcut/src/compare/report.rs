//! `report.json` of a `Compare` run.

use schemars::JsonSchema;
use serde::Serialize;

use super::cost::{Cost, Hours, Tool};
use crate::process::{Deviation, ProcessFigures};
use crate::spec::Units;

/// The report of a `Compare` run (`report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CompareReport {
    /// Job name.
    pub job: String,
    /// Task name, `Compare`.
    pub task: String,
    /// Length unit of every length (volumes in its cube, areas in its square).
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The design: `HeightField`, `Spline`, `Mesh` (open) or `ClosedMesh`.
    pub design: String,
    /// The tolerance every process is held to (`tolerance.max`).
    pub tolerance: f64,
    /// The RMS a milled surface's scallop is held to (`tolerance.rms`; the thermal
    /// processes' own tasks apply theirs).
    pub tolerance_rms: f64,
    /// Every rate used, its unit, whether the job set it, and its source.
    pub rates: Vec<RateRow>,
    /// Every process, in the job's order.
    pub processes: Vec<ProcessRow>,
    /// The feasible processes, cheapest first (by `id`; equal costs to 9 significant
    /// digits keep the job's order).
    pub ranking: Vec<String>,
    /// The cheapest feasible process, `None` when no process is feasible.
    pub winner: Option<String>,
    /// How much dearer the second cheapest feasible process is than the winner, percent
    /// (`None` with fewer than two).
    pub margin_percent: Option<f64>,
    /// Every rate halved and raised by half: the winner then.
    pub sensitivity: Vec<Sensitivity>,
    /// The seed's claims, measured on this design where they apply (plausibility, not
    /// inputs).
    pub plausibility: Plausibility,
}

/// One rate.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct RateRow {
    /// Its field in `rates:`.
    pub field: String,
    /// The value used, in job units.
    pub value: f64,
    /// Its unit.
    pub unit: String,
    /// Whether the job set it (else the default).
    pub set_by_job: bool,
    /// Whether the default has no published source.
    pub assumed: bool,
    /// The default's source.
    pub source: String,
}

/// Whether a process can make the design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, JsonSchema)]
pub enum Status {
    /// It makes the design within the tolerance.
    Feasible,
    /// It ran, and misses the design: `reason` says where.
    Infeasible,
    /// It does not apply to this design (`reason`); nothing was run.
    NotApplicable,
}

/// One process.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ProcessRow {
    /// Its name in this report: `milling`, `milling_segmented`, `precut_milling`,
    /// `hot_wire`, `hot_blade`, `facade_segmentation` (`_2`, … for a kind listed again).
    pub id: String,
    /// The process as the job names it.
    pub process: String,
    /// Its folder in the output (its own task's files), `None` without one.
    pub folder: Option<String>,
    /// Whether it can make the design.
    pub status: Status,
    /// Why not, for an infeasible or not applicable process.
    pub reason: Option<String>,
    /// What its run measured (`None` when not applicable).
    pub figures: Option<ProcessFigures>,
    /// Its milling tool, for the processes that mill.
    pub tool: Option<Tool>,
    /// The fidelity: the milling tool's scallop where milling finishes, else the cut
    /// surface's deviation.
    pub deviation: Option<Deviation>,
    /// EPS bought, m³.
    pub eps_m3: Option<f64>,
    /// EPS that ends as waste (bought minus kept), m³.
    pub waste_m3: Option<f64>,
    /// Hours per machine.
    pub hours: Option<Hours>,
    /// The cutting speed its thermal cuts are timed at, job units per second: its
    /// programs' own, or the job's `rates.wire_speed`/`blade_speed` when it sets one.
    pub cut_speed: Option<f64>,
    /// Cost, split.
    pub cost: Option<Cost>,
    /// Its place among the feasible processes, cheapest 1.
    pub rank: Option<usize>,
}

/// The winner with one rate scaled.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Sensitivity {
    /// The rate.
    pub rate: String,
    /// The winner with the rate halved.
    pub halved: Option<String>,
    /// The winner with the rate raised by half.
    pub raised: Option<String>,
    /// Whether either changes the winner.
    pub flips: bool,
    /// The feasible processes cheapest first with the rate halved.
    pub ranking_halved: Vec<String>,
    /// The same with the rate raised by half.
    pub ranking_raised: Vec<String>,
    /// Whether either changes the ranking (not only the winner).
    pub ranking_changes: bool,
    /// The factor nearest to 1 below it at which the winner changes (`None`: not above
    /// 1/100).
    pub flip_below: Option<f64>,
    /// The factor nearest to 1 above it at which the winner changes (`None`: not below
    /// 100).
    pub flip_above: Option<f64>,
}

/// The seed's claims on this design.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Plausibility {
    /// Milling's machine hours ÷ the hot blade's (the seed: "more than a hundred times
    /// faster", "up to 126 times"), when both ran (feasible or not).
    pub blade_speedup: Option<f64>,
    /// How much of milling's machine time pre-cuts save, percent (the seed, ch. 2:
    /// 69–72 % on a roughing-dominated mould).
    pub precut_saving_percent: Option<f64>,
    /// How much of milling's roughing time the pre-cuts save, their own wire time
    /// counted, percent (the seed's figure is for a job that was roughing only, ~92 % of
    /// its machine hours).
    pub precut_roughing_saving_percent: Option<f64>,
    /// Blocks of a block segmentation and of the job's block grid, when both milled
    /// (thesis ch. 3: fewer blocks).
    pub blocks_segmented_vs_grid: Option<[usize; 2]>,
}
