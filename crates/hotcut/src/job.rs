//! The job file as the user writes it (RON): raw serde types with `deny_unknown_fields`.
//! Their doc comments become the descriptions in `schemas/job.schema.json`.
//!
//! Every omitted field has the default documented on it. Lengths are in the job's
//! [`Units`](crate::job::Units); curvatures in 1/length; angles in radians.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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
    /// The surface to cut. Required by `Analyze`, and by `FitCurves` without `input`.
    #[serde(default)]
    pub surface: Option<SurfaceSpec>,
    /// The foam block. When omitted, the block-size constraint is not checked.
    #[serde(default)]
    pub block: Option<BlockSpec>,
    /// The hot blade. Default: `Blade(length: 1000 mm, max_curvature: 0.011 /mm, max_inflections: 2)`
    /// (converted when `units: Metre`).
    #[serde(default)]
    pub blade: Option<BladeSpec>,
    /// The hot-wire machine (PreCut's `GCode` and `Csv` outputs need it).
    #[serde(default)]
    pub wire: Option<WireSpec>,
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
        /// Require a closed (watertight) mesh. Default: `false` (a facade is an open sheet).
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

/// A 4-axis hot-wire machine: two towers `tower_distance` apart across the block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Wire")]
pub struct WireSpec {
    /// Distance between the tower planes (> the block's width across the cut).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub tower_distance: f64,
    /// Kerf width (≥ 0): the wire's cut is offset by half of it into the removed material.
    #[schemars(range(min = 0))]
    pub kerf: f64,
    /// Wire speed through the foam, job units per minute (> 0). Default: 300 mm/min.
    #[serde(default)]
    pub speed: Option<f64>,
    /// Lead-in and lead-out along the cut outside the block (≥ 0). Default: 20 mm.
    #[serde(default)]
    pub lead: Option<f64>,
    /// Clearance above the block for rapid moves (> 0). Default: 50 mm.
    #[serde(default)]
    pub clearance: Option<f64>,
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
    /// RMS distance allowed between the surface and what is cut (> 0). Default: 0.5 mm.
    #[serde(default = "default_rms")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub rms: f64,
    /// Largest distance allowed between the surface and what is cut (> 0). Default: 2 mm.
    #[serde(default = "default_max")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub max: f64,
    /// Largest deviation allowed when a polyline section (mesh, spline surface) is replaced
    /// by a smoothing spline before curvature is taken (≥ 0). For meshes, a point may also
    /// deviate by its chordal sagitta (how far a facet can be from the true surface there).
    /// Default: 0.05 mm.
    #[serde(default = "default_smoothing")]
    #[schemars(range(min = 0))]
    pub smoothing: f64,
    /// Inflections are located by bisection to within this arc length (> 0). Default: 1e-6 mm.
    #[serde(default = "default_bisection")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub bisection: f64,
    /// A stretch between inflections that turns the tangent by less than this many radians
    /// is noise, and its inflections are dropped (≥ 0). Default: 0.002.
    #[serde(default = "default_min_turning")]
    #[schemars(range(min = 0))]
    pub min_turning: f64,
}

fn default_rms() -> f64 {
    0.5
}
fn default_max() -> f64 {
    2.0
}
fn default_smoothing() -> f64 {
    0.05
}
fn default_bisection() -> f64 {
    1e-6
}
fn default_min_turning() -> f64 {
    0.002
}

impl Default for ToleranceSpec {
    fn default() -> Self {
        Self {
            rms: default_rms(),
            max: default_max(),
            smoothing: default_smoothing(),
            bisection: default_bisection(),
            min_turning: default_min_turning(),
        }
    }
}

/// The task to run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum TaskSpec {
    /// Section the surface and report, per section, its length, inflections, curvature
    /// maxima and the production constraints it breaks (thesis §5.1). Write `Analyze()`.
    Analyze {
        /// Curvature samples per section for the sign test of eq. (5.2) (≥ 8). Default: 2000.
        #[serde(default = "default_samples")]
        #[schemars(range(min = 8, max = 1000000))]
        samples: u32,
    },
    /// Fit every curve of `input` (or, without `input`, every section of the surface) by
    /// one elastica, line or arc — the shapes a hot blade takes ("Hot Blade Cuttings" §5.1).
    /// Writes `report.json` (per curve the segment, its distances to the curve and the
    /// fitted curve sampled at 400 points) and `fit.svg` (input and fit overlaid). Write
    /// `FitCurves(input: "curves.json", constraint: Free)`.
    FitCurves {
        /// Curves file, relative to the job file: JSON
        /// `{"curves": [{"id": "a", "points": [[x, y], ...]}, ...]}` (other fields are
        /// ignored) or CSV with a header `id,x,y` and one row per point, a curve's rows
        /// consecutive. Coordinates in job units. Default: the sections of `surface`.
        #[serde(default)]
        #[schemars(length(min = 1))]
        input: Option<String>,
        /// What the fitted segment must reproduce exactly. Default: `Free`.
        #[serde(default)]
        constraint: FitConstraintSpec,
        /// Points each surface section is sampled at, equally spaced in arc length (≥ 3;
        /// unused with `input`). Default: 200.
        #[serde(default = "default_fit_samples")]
        #[schemars(range(min = 3, max = 100000))]
        samples: u32,
    },
    /// Hot-blade rationalization ("Hot Blade Cuttings" §6–7, "Robotic Hot-Blade Cutting"
    /// §4): the surface inside a grid of blocks, every block's sections fitted by elastica,
    /// the swept surface between them, the blade poses for the two robots, and a RAPID
    /// program. Write `HotBlade(targets_per_block: 51)`.
    HotBlade {
        /// Blade poses per block (≥ 2), on planes equally spaced from the block's entry face
        /// to its exit face; a section is fitted on each. Default: 51 (the paper's cell).
        #[serde(default = "default_targets")]
        #[schemars(range(min = 2, max = 10000))]
        targets_per_block: u32,
        /// What each fitted elastica keeps of its section: `EndPoints`, or
        /// `EndPointsAndLength` (the skater ramp of "Hot Blade Cuttings" §7). End points are
        /// always kept, so neighbouring blocks meet. Default: `EndPointsAndLength`.
        #[serde(default = "default_blade_constraint")]
        constraint: FitConstraintSpec,
        /// Continuity where neighbouring blocks meet across a face along the cut: `C0`
        /// (shared end points) or `C1` (also shared end tangents, those of the design
        /// section). Default: `C0`.
        #[serde(default)]
        continuity: Continuity,
        /// How many times a column of blocks whose fit breaks the tolerance is halved along
        /// the cutting direction and refitted (0 = never). Default: 2.
        #[serde(default = "default_split_depth")]
        #[schemars(range(max = 8))]
        split_depth: u32,
        /// Points each section is sampled at for its fit (≥ 8). Default: 100.
        #[serde(default = "default_blade_samples")]
        #[schemars(range(min = 8, max = 100000))]
        samples: u32,
        /// Cutting speed of the blade through the block (> 0), job units per second.
        /// Default: 7 mm/s.
        #[serde(default)]
        speed: Option<f64>,
        /// Flat-blade restriction (§4): largest angle between the cutting plane and the
        /// surface normal, radians, in [0, π/2]. Default: π/6 (30°).
        #[serde(default = "default_plane_angle")]
        #[schemars(range(min = 0, max = 1.571))]
        max_plane_angle: f64,
        /// Approach and retreat distance of the blade before and after the block, along the
        /// cut (≥ 0). Default: 50 mm.
        #[serde(default)]
        approach: Option<f64>,
        /// Planes between two neighbouring targets on which the rationalized surface is
        /// compared with the design (and meshed). Default: 3.
        #[serde(default = "default_refine")]
        #[schemars(range(max = 100))]
        refine: u32,
    },
    /// Facade segmentation for hot-blade cutting (thesis ch. 5): the sections of
    /// `cutting` are split into pieces, each cut from one block, so that every part of a
    /// section in a piece meets the production constraints (§5.1: blade length and block,
    /// approximation, shape, blade strain); then each piece is rationalized (an elastica
    /// per section part, extended to the blade, with its robot pose). Needs `block`. Write
    /// `FacadeSegmentation(algorithm: Inflection(symmetric: false))`.
    FacadeSegmentation {
        /// The algorithm.
        algorithm: SegAlgorithmSpec,
        /// Points each section part is sampled at for its checks and fits (≥ 8).
        /// Default: 64.
        #[serde(default = "default_seg_samples")]
        #[schemars(range(min = 8, max = 100000))]
        samples: u32,
        /// Fit every piece's section parts by elastica and pose the blade on them (needed
        /// by `RobotTargets` and `Rapid`). Default: `true`.
        #[serde(default = "default_true")]
        rationalize: bool,
        /// What each piece's fitted elastica keeps of its section part: `EndPoints`, or
        /// `EndPointsAndLength`. Default: `EndPointsAndLength`.
        #[serde(default = "default_blade_constraint")]
        constraint: FitConstraintSpec,
        /// Cutting speed of the blade (> 0), job units per second. Default: 7 mm/s.
        #[serde(default)]
        speed: Option<f64>,
        /// Approach and retreat distance of the blade along the cut (≥ 0). Default: 50 mm.
        #[serde(default)]
        approach: Option<f64>,
    },
    /// Volumetric block segmentation (thesis ch. 3): cover a closed mesh
    /// (`surface: Mesh(path: .., closed: true)`) with as few freely translated and rotated
    /// blocks of `block.size` as possible, by the stochastic optimization of §3.3. The
    /// job's `seed` seeds it. Write `BlockSegmentation(restarts: 4, coverage: Solid)`.
    BlockSegmentation {
        /// Operations used: any of `Translate`, `Rotate`, `Align` (the ablation of
        /// Table 3.2). Default: all three.
        #[serde(default = "default_block_operations")]
        #[schemars(length(min = 1, max = 3))]
        operations: Vec<blocks::Operation>,
        /// `Solid`: the model's volume must lie in the union of blocks; `Surface`: only
        /// its surface. Default: `Solid`.
        #[serde(default)]
        coverage: blocks::Coverage,
        /// Exponent p of eq. 3.3 (≥ 1). Default: 2.
        #[serde(default = "default_block_p")]
        #[schemars(range(min = 1))]
        p: f64,
        /// ε of eq. 3.3 (> 0). Default: 1e-5.
        #[serde(default = "default_block_epsilon")]
        #[schemars(extend("exclusiveMinimum" = 0))]
        epsilon: f64,
        /// Independent runs in parallel, seeds derived from the job's `seed`; the run
        /// with the fewest blocks is kept. Default: 1.
        #[serde(default = "default_restarts")]
        #[schemars(range(min = 1, max = 256))]
        restarts: u32,
        /// Iteration cap per run (an iteration is one cycle over the blocks, of moves or
        /// of alignment). Default: 200.
        #[serde(default = "default_block_iterations")]
        #[schemars(range(min = 1))]
        max_iterations: u32,
        /// Wall-time cap per run, seconds (> 0). Results then depend on the machine's
        /// speed; prefer `max_iterations`. Default: none.
        #[serde(default)]
        time_limit: Option<f64>,
        /// Interior sample spacing as a fraction of the block's shortest edge, in
        /// (0, 0.25]; blocks are shrunk by this spacing (half of it for `Surface`) when
        /// testing coverage, so that covering the samples covers the model. Default: 0.05.
        #[serde(default = "default_sample_spacing")]
        #[schemars(extend("exclusiveMinimum" = 0), range(max = 0.25))]
        sample_spacing: f64,
    },
    /// Hot-wire pre-cuts before milling (thesis ch. 2): per cutting direction, `legs`
    /// straight wire cuts across the block whose lower envelope stays on or above the
    /// design surface (never cutting into it) while leaving as little material as
    /// possible for milling. The design surface's outward normal is roughly +z; the block
    /// is `block` (origin defaults to the surface's bounding-box minimum). Write
    /// `PreCut(legs: 4, directions: [X])`.
    PreCut {
        /// Cuts per direction (the moving polygon's legs), 1–32. Default: 4.
        #[serde(default = "default_legs")]
        #[schemars(range(min = 1, max = 32))]
        legs: u32,
        /// Cutting directions in the xy plane: `X`, `Y`, `Degrees(a)` (from +x towards
        /// +y) or `Vector(dx, dy)`. Default: `[X]`.
        #[serde(default = "default_cut_directions")]
        #[schemars(length(min = 1, max = 8))]
        directions: Vec<CutDirection>,
        /// B-spline degree of the cuts along the cutting direction (thesis p), 1–5.
        /// Default: 3.
        #[serde(default = "default_cut_degree")]
        #[schemars(range(min = 1, max = 5))]
        degree: u32,
        /// Control values per cut along the cutting direction (thesis k), degree + 1 to
        /// 64. Default: 8.
        #[serde(default = "default_cut_controls")]
        #[schemars(range(min = 2, max = 64))]
        controls: u32,
        /// Section planes along the cut (thesis N), ≥ 2. Default: 30.
        #[serde(default = "default_cut_samples")]
        #[schemars(range(min = 2, max = 500))]
        sections: u32,
        /// Samples per section across the block (thesis M), ≥ 2. Default: 30.
        #[serde(default = "default_cut_samples")]
        #[schemars(range(min = 2, max = 500))]
        samples: u32,
        /// Most assignment rounds of the optimizer. Default: 40.
        #[serde(default = "default_cut_rounds")]
        #[schemars(range(min = 1))]
        max_rounds: u32,
    },
}

/// A cutting direction in the xy plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum CutDirection {
    /// Along +x.
    X,
    /// Along +y.
    Y,
    /// At this angle from +x towards +y, degrees.
    Degrees(f64),
    /// Along `(dx, dy)` (normalised; must not be zero).
    Vector(f64, f64),
}

impl CutDirection {
    /// The direction as an `[x, y]` vector (not normalised for `Vector`).
    pub fn vector(&self) -> [f64; 2] {
        match *self {
            Self::X => [1.0, 0.0],
            Self::Y => [0.0, 1.0],
            Self::Degrees(a) => [a.to_radians().cos(), a.to_radians().sin()],
            Self::Vector(x, y) => [x, y],
        }
    }
}

fn default_legs() -> u32 {
    4
}
fn default_cut_directions() -> Vec<CutDirection> {
    vec![CutDirection::X]
}
fn default_cut_degree() -> u32 {
    3
}
fn default_cut_controls() -> u32 {
    8
}
fn default_cut_samples() -> u32 {
    30
}
fn default_cut_rounds() -> u32 {
    40
}

fn default_block_operations() -> Vec<blocks::Operation> {
    vec![
        blocks::Operation::Translate,
        blocks::Operation::Rotate,
        blocks::Operation::Align,
    ]
}
fn default_block_p() -> f64 {
    2.0
}
fn default_block_epsilon() -> f64 {
    1e-5
}
fn default_restarts() -> u32 {
    1
}
fn default_block_iterations() -> u32 {
    200
}
fn default_sample_spacing() -> f64 {
    0.05
}

impl TaskSpec {
    /// Name as written in job files.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Analyze { .. } => "Analyze",
            Self::FitCurves { .. } => "FitCurves",
            Self::HotBlade { .. } => "HotBlade",
            Self::FacadeSegmentation { .. } => "FacadeSegmentation",
            Self::BlockSegmentation { .. } => "BlockSegmentation",
            Self::PreCut { .. } => "PreCut",
        }
    }
}

/// How a facade is segmented (thesis ch. 5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum SegAlgorithmSpec {
    /// §5.2: a grid of blocks per row along the cut; blocks are translated along their
    /// row (or a translated copy inserted) until no block holds a section part with more
    /// than `max_inflections` inflections; in overlaps the seam runs through curvature
    /// maxima. Write `Inflection(symmetric: false)`.
    Inflection {
        /// Apply every move to all rows alike (one arrangement for the whole facade).
        /// Default: `false`.
        #[serde(default)]
        symmetric: bool,
    },
    /// §5.3: curvature maxima between inflections linked across sections into traces,
    /// extended, merged and completed by middle traces; pieces are the bands between
    /// traces. Write `Trace()`.
    Trace {
        /// Farthest (across the cut) a maximum may be from a trace's last point to continue
        /// it (> 0). Default: a quarter of the block's width.
        #[serde(default)]
        link_distance: Option<f64>,
        /// Traces closer than this anywhere are merged (≥ 0). Default: 2 % of the block's
        /// width.
        #[serde(default)]
        merge_distance: Option<f64>,
        /// Traces over fewer sections are dropped (the stand-in for the thesis' smoothing
        /// step, ≥ 1). Default: 2.
        #[serde(default = "default_min_sections")]
        #[schemars(range(min = 1, max = 100000))]
        min_sections: u32,
    },
    /// §5.4: per section the longest part from the current seam an elastica fits within
    /// tolerance (halving search), seams evened out, repeated until the facade is covered;
    /// shape and blade strain enforced too. Write `LongestElastica(precision: 1.0)`.
    LongestElastica {
        /// Precision of the halving search (> 0), job units. Default: 1 mm.
        #[serde(default)]
        precision: Option<f64>,
        /// Most a part may be longer than its neighbour's (> 0). Default: the spacing of
        /// the sections.
        #[serde(default)]
        max_step: Option<f64>,
    },
}

impl SegAlgorithmSpec {
    /// Name as written in job files.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Inflection { .. } => "Inflection",
            Self::Trace { .. } => "Trace",
            Self::LongestElastica { .. } => "LongestElastica",
        }
    }
}

fn default_min_sections() -> u32 {
    2
}
fn default_true() -> bool {
    true
}
fn default_seg_samples() -> u32 {
    64
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

fn default_targets() -> u32 {
    51
}
fn default_blade_constraint() -> FitConstraintSpec {
    FitConstraintSpec::EndPointsAndLength
}
fn default_split_depth() -> u32 {
    2
}
fn default_blade_samples() -> u32 {
    100
}
fn default_plane_angle() -> f64 {
    std::f64::consts::FRAC_PI_6
}
fn default_refine() -> u32 {
    3
}

fn default_samples() -> u32 {
    2000
}

fn default_fit_samples() -> u32 {
    200
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

/// A file to write.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum OutputSpec {
    /// `report.json`: the task's full result.
    Report,
    /// `sections.svg` (Analyze): plan and profile drawing of the sections; `fit.svg`
    /// (FitCurves): every curve with its fit overlaid; `segmentation.svg`
    /// (FacadeSegmentation): plan view of the pieces, sections, inflections and seams;
    /// `progress.svg` (BlockSegmentation): blocks and E per iteration.
    Svg,
    /// `sections.obj`: the section curves as 3D polylines (BlockSegmentation:
    /// `blocks.obj`, the blocks as boxes).
    Obj,
    /// `model.gltf` (HotBlade: blocks as boxes, the rationalized surfaces coloured by
    /// deviation; FacadeSegmentation: the pieces in colours, and their blocks;
    /// BlockSegmentation: the model and its blocks).
    Gltf,
    /// `sections.csv` (HotBlade: one row per fitted section; FacadeSegmentation: one row
    /// per section part of a piece).
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
    /// ABB RAPID program for a MultiMove cell, one module and `.pgf` per blade robot
    /// (HotBlade).
    Rapid,
    /// Hot-wire G-code (pre-cut task).
    GCode,
    /// `blocks.json` (BlockSegmentation): every block's centre, rotation `[w, x, y, z]`
    /// (block axes to model axes) and size, in the mesh's coordinates.
    Blocks,
    /// `precut.json` (PreCut): per direction, per section along the cut, the polygon of
    /// rulings as 3D points, so anyone can re-check the cut.
    PreCut,
}

impl OutputSpec {
    /// Name as written in job files.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Report => "Report",
            Self::Svg => "Svg",
            Self::Obj => "Obj",
            Self::Gltf => "Gltf",
            Self::Csv => "Csv",
            Self::RobotTargets { .. } => "RobotTargets",
            Self::Rapid => "Rapid",
            Self::GCode => "GCode",
            Self::Blocks => "Blocks",
            Self::PreCut => "PreCut",
        }
    }
}
