//! The blade poses as robot data: `targets.json` (the [`Targets`](crate::robot::Targets)
//! serialized) and `targets.csv` (one row per pose and held end). The RAPID programs are
//! written by [`crate::rapid`] from the cell's plan.

use schemars::JsonSchema;
use serde::Serialize;

use crate::csv::Table;

/// Significant digits of `targets.json` (finer than a report: robot data).
pub const TARGET_DIGITS: usize = 12;

/// One held end of the blade.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
pub struct EndPose {
    /// Position.
    pub position: [f64; 3],
    /// Unit tangent of the blade there, from its first end to its second.
    pub tangent: [f64; 3],
    /// Tool orientation `[w, x, y, z]`: x-axis = `tangent`, z-axis = the plane normal.
    pub rotation: [f64; 4],
}

/// A blade pose: the cutting plane's normal and both held ends, the blade's start first,
/// and the blade planned between them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
pub struct Pose {
    /// Unit normal of the cutting plane.
    pub plane_normal: [f64; 3],
    /// The two ends.
    pub ends: [EndPose; 2],
    /// The blade between them: its planned shape, its stability and its loads.
    pub blade: PoseBlade,
}

/// Stations of [`PoseBlade::shape`]: every sixteenth of the blade, both ends included.
pub const SHAPE_STATIONS: usize = 17;

/// The blade a pose plans: which of the equilibria its held ends allow it means, whether
/// that equilibrium holds, and what the holders carry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
pub struct PoseBlade {
    /// The blade's tangent angle against its chord (from the first end to the second),
    /// turning positive about `plane_normal`, at 17 equally spaced stations along it,
    /// radians: the planned shape (the same ends often hold several).
    pub shape: [f64; SHAPE_STATIONS],
    /// Total turning from the first end to the second, radians.
    pub turning: f64,
    /// The blade's length less the distance between its ends (job units): a nearly taut
    /// blade's shape and stability hang on fractions of a millimetre of it.
    pub slack: f64,
    /// Inflections of the whole blade.
    pub inflections: usize,
    /// Stability margin: the smallest eigenvalue of the held blade's second variation over
    /// a straight blade's (`4π²/L²`); unit-free, 1 for a straight unloaded blade, ≤ 0
    /// where it buckles out of the shape.
    pub margin: f64,
    /// `Stable`, `Marginal` (below the job's `blade.min_margin`) or `Unstable`.
    pub stability: &'static str,
    /// The force on either holder, N.
    pub force_n: f64,
    /// The blade's tension at the first and the second end, N (positive pulls the holder
    /// in along the blade).
    pub tension_n: [f64; 2],
    /// The bending moment at the first and the second end, N·m.
    pub moment_nm: [f64; 2],
}

/// The poses of a run, `targets.json`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Targets {
    /// Length unit of every position, as the job names it (`Millimetre`, `Metre`).
    pub units: String,
    /// How many of those units one millimetre is.
    #[serde(skip)]
    pub per_mm: f64,
    /// The unit's symbol (`mm`, `m`).
    #[serde(skip)]
    #[schemars(skip)]
    pub unit_symbol: &'static str,
    /// Physical blade length.
    pub blade_length: f64,
    /// Blocks in cutting order.
    pub blocks: Vec<TargetsBlock>,
}

/// One block (or piece) of `targets.json`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct TargetsBlock {
    /// Block number.
    pub block: usize,
    /// The work object's origin, in job coordinates: the block's corner that is least in
    /// the block's own frame (`rotation`: x along the cut, y across it, z up). It is the
    /// block's min corner in world coordinates only when the cut runs along +x; for a cut
    /// along y or an oblique one it is another corner.
    pub origin: [f64; 3],
    /// Orientation `[w, x, y, z]` of the block axes (work object frame).
    pub rotation: [f64; 4],
    /// Poses in cutting order, positions in job coordinates.
    pub poses: Vec<Pose>,
}

/// Blade motion settings of a RAPID program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Cutting speed, job units per second.
    pub speed: f64,
    /// Approach and retreat distance along the cut.
    pub approach: f64,
}

/// `targets.csv`: one row per pose and held end.
pub fn targets_csv(targets: &Targets) -> String {
    let mut t = Table::new(
        "block,pose,end,x,y,z,tangent_x,tangent_y,tangent_z,q_w,q_x,q_y,q_z,normal_x,normal_y,normal_z",
    );
    let f = Table::num;
    for b in &targets.blocks {
        for (k, pose) in b.poses.iter().enumerate() {
            for (e, end) in pose.ends.iter().enumerate() {
                let mut row = vec![
                    b.block.to_string(),
                    (k + 1).to_string(),
                    (e + 1).to_string(),
                ];
                row.extend(end.position.iter().map(|v| f(*v)));
                row.extend(end.tangent.iter().map(|v| f(*v)));
                row.extend(end.rotation.iter().map(|v| f(*v)));
                row.extend(pose.plane_normal.iter().map(|v| f(*v)));
                t.row(&row);
            }
        }
    }
    t.finish()
}
