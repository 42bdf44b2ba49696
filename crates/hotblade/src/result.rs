//! The result of [`rationalize`](crate::rationalize): the blocks with their fitted sections
//! and swept surfaces, and the report entries (`report.json` of the `HotBlade` task embeds
//! them). Lengths in the surface's unit, angles in radians, positions in its frame.

use elastica::blade::Blade;
use elastica::fit::FitResult;
use elastica::sweep::BladePose;
use geom::mesh::TriMesh;
use nalgebra::Vector3;

use crate::grid::{Clipped, Grid, Plane};

/// The result of a run.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Rationalization {
    /// Every plane the run used: targets first (by row), then the deviation planes.
    pub planes: Vec<Plane>,
    /// The grid.
    pub grid: Grid,
    /// Whether the planes follow a cutting-direction curve (else they are parallel).
    pub follows_curve: bool,
    /// Blocks with surface, by row then across the cut, numbered from 1.
    pub blocks: Vec<BlockResult>,
    /// Columns of blocks halved because their fit broke the tolerance.
    pub splits: Vec<SplitInfo>,
    /// Totals over all blocks and the verdict.
    pub summary: HotBladeSummary,
}

/// One fitted section of a block.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FittedSection {
    /// Index of the target plane in the run's plane list.
    pub plane: usize,
    /// The design part inside the block.
    pub design: Clipped,
    /// The fit.
    pub fit: FitResult,
    /// The blade: the fit extended to the blade length (or the fit itself when the section
    /// is longer than the blade).
    pub blade: Blade,
    /// The 3D pose.
    pub pose: BladePose,
    /// Largest angle between the plane and the surface normal along the section.
    pub plane_angle: f64,
    /// With `C1`: whether the fit keeps the design's end tangents (false: the end-point fit
    /// was kept because the tangent solve failed).
    pub tangents_kept: bool,
    /// The blade outside the section against the block (planes parallel to the grid's;
    /// `None` on planes that follow a curve).
    pub clearance: Option<elastica::clearance::Clearance>,
}

/// A vertex of the rationalized surface mesh with its deviation from the design.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SurfaceVertex {
    /// World position.
    #[cfg_attr(feature = "serde", serde(serialize_with = "crate::ser::vec3"))]
    pub position: Vector3<f64>,
    /// Distance to the design section in its plane.
    pub deviation: f64,
}

/// One block's result.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BlockResult {
    /// Report entry.
    pub report: BlockReport,
    /// Rotation `[w, x, y, z]` of the block axes (the work object's orientation).
    pub rotation: [f64; 4],
    /// The fitted sections, in cutting order (targets where the block holds no surface are
    /// left out).
    pub sections: Vec<FittedSection>,
    /// The rationalized surface: one row of vertices per grid plane, in cutting order.
    pub surface: Vec<Vec<SurfaceVertex>>,
}

impl BlockResult {
    /// The rationalized surface as a triangle mesh: consecutive grid rows of equal length
    /// joined by triangles. `None` for a degenerate grid.
    pub fn surface_mesh(&self) -> Option<TriMesh> {
        let (verts, faces) = self.surface_grid();
        TriMesh::try_new(verts, faces).ok()
    }

    /// The rationalized surface's vertices (row after row, as [`Self::surface`] holds them)
    /// and the triangles joining consecutive rows of equal length.
    pub fn surface_grid(&self) -> (Vec<Vector3<f64>>, Vec<[u32; 3]>) {
        let mut verts = Vec::new();
        let mut faces = Vec::new();
        let mut prev: Option<(u32, usize)> = None;
        for row in &self.surface {
            let start = verts.len() as u32;
            verts.extend(row.iter().map(|v| v.position));
            if let Some((p0, len)) = prev {
                if len == row.len() {
                    for i in 0..len.saturating_sub(1) as u32 {
                        let (a, bb) = (p0 + i, p0 + i + 1);
                        let (c, d) = (start + i, start + i + 1);
                        faces.push([a, c, bb]);
                        faces.push([bb, c, d]);
                    }
                }
            }
            prev = Some((start, row.len()));
        }
        (verts, faces)
    }
}

/// The block grid.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct GridInfo {
    /// Block axis along the cut (the cutting direction or the curve's chord).
    pub axis_d: [f64; 3],
    /// Block axis across the cut, horizontal.
    pub axis_u: [f64; 3],
    /// Third block axis (up for a horizontal cut).
    pub axis_v: [f64; 3],
    /// Block edge lengths along `axis_d`, `axis_u`, `axis_v`.
    pub size: [f64; 3],
    /// World position of the grid's min corner.
    pub origin: [f64; 3],
    /// Rows of blocks along the cut.
    pub rows: usize,
    /// Columns of blocks across the cut (before splits).
    pub columns: usize,
}

/// Min, max and average of a quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Stats {
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Mean value.
    pub avg: f64,
}

impl Stats {
    /// Statistics of `values` (zeros when empty).
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let (mut min, mut max, mut sum, mut n) = (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0usize);
        for v in values {
            min = min.min(v);
            max = max.max(v);
            sum += v;
            n += 1;
        }
        if n == 0 {
            return Self {
                min: 0.0,
                max: 0.0,
                avg: 0.0,
            };
        }
        Self {
            min,
            max,
            avg: sum / n as f64,
        }
    }
}

/// Which production constraints a block breaks (true = broken).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Flags {
    /// A fit's RMS or largest distance exceeds the tolerance (thesis §5.1.2).
    pub approximation: bool,
    /// The blade bends beyond its largest |curvature| (§5.1.4).
    pub blade_strain: bool,
    /// The blade has more inflections than allowed (§5.1.3).
    pub shape: bool,
    /// A section is longer than the blade (§5.1.1).
    pub blade_length: bool,
    /// A cutting plane leans from the surface normal by more than the limit ("Hot Blade
    /// Cuttings" §4, flat blade).
    pub flat_blade: bool,
    /// The surface leaves the block's height (§5.1.1).
    pub block_height: bool,
    /// Two cutting planes cross inside the block, so material would be cut twice (§5.1.5).
    pub overlap: bool,
    /// The blade outside a section runs into what the block keeps, or a held end lies
    /// inside the block (issue 37).
    pub gouge: bool,
    /// A blade does not hold its shape: an unstable or marginal equilibrium
    /// ([`elastica::stability()`]), or one that snaps to another shape as the robots carry
    /// it to the next plane's.
    pub stability: bool,
}

impl Flags {
    /// Whether any constraint is broken.
    pub fn any(&self) -> bool {
        self.approximation
            || self.blade_strain
            || self.shape
            || self.blade_length
            || self.flat_blade
            || self.block_height
            || self.overlap
            || self.gouge
            || self.stability
    }
}

/// One block.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct BlockReport {
    /// Block number (the `block` of `targets.json` and the RAPID work object).
    pub block: usize,
    /// Row along the cut.
    pub row: usize,
    /// Column across the cut (of the grid before splits).
    pub column: usize,
    /// How many times the column was halved for this block.
    pub split_level: u32,
    /// World position of the work object's origin: the block's corner least along the
    /// grid axes (along the cut, across it, up); the world min corner only when the cut
    /// runs along +x.
    pub origin: [f64; 3],
    /// Block edge lengths along the grid axes.
    pub size: [f64; 3],
    /// Fitted sections (= poses).
    pub sections: usize,
    /// Target planes on which the block holds no surface, or only a sliver shorter than
    /// 5 % of the blade ([`super::SHORTEST_PART`]): no blade pose for those.
    pub missing_sections: usize,
    /// L2 distance of eq. (9) per section (the paper's Table 1 columns).
    pub l2: Stats,
    /// Largest RMS distance of a fit.
    pub max_rms: f64,
    /// Largest distance between a section point and its fit.
    pub max_fit_distance: f64,
    /// Largest distance between the rationalized and the design surface on the dense grid.
    pub max_deviation: f64,
    /// Section lengths.
    pub section_length: Stats,
    /// Largest |curvature| on a blade (extended to its full length).
    pub max_abs_curvature: f64,
    /// Most inflections on a blade.
    pub max_inflections: usize,
    /// The least stability margin of a blade (unit-free; [`elastica::stability()`]; `None`
    /// without sections).
    pub min_margin: Option<f64>,
    /// Largest angle between a cutting plane and the surface normal.
    pub max_plane_angle: f64,
    /// Index (among the block's targets) of the section with the largest L2 distance.
    pub worst_section: usize,
    /// Deviation planes where interpolating the neighbouring fits' parameters strayed from
    /// their pointwise blend by more than the tolerance (different kinds or branches), so
    /// the swept curve there is the elastica fitted to the blend.
    pub blended_planes: usize,
    /// With `C1`: sections whose fit could not keep the design's end tangents (their
    /// end-point fit is used; the joint there is only C⁰).
    pub tangent_failures: usize,
    /// Pairs of target indices whose planes cross inside the block.
    pub overlaps: Vec<[usize; 2]>,
    /// The blade outside each section against the block, in cutting order (empty where
    /// the planes follow a curve: not checked).
    pub clearance: Vec<SectionClearance>,
    /// Deepest the blade outside a section runs into what the block keeps (0: nowhere).
    pub max_gouge_depth: f64,
    /// Broken constraints.
    pub flags: Flags,
}

/// The blade outside one section against its block (issue 37).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SectionClearance {
    /// The section (index among the block's targets).
    pub section: usize,
    /// How deep the blade outside the section runs into what the block keeps (0: clean).
    pub gouge_depth: f64,
    /// How much of the blade outside the section lies in it.
    pub gouge_length: f64,
    /// The smaller distance of the blade's held ends from the block (negative: inside).
    pub holder_clearance: f64,
    /// The blade's length before the section: where the planner put it along the blade.
    pub lead_in: f64,
}

/// A column halving.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SplitInfo {
    /// Column of the grid.
    pub column: usize,
    /// Halving level (1 = first halving).
    pub level: u32,
    /// `[lo, hi]` along the grid's `u` axis of the part that was halved.
    pub range: [f64; 2],
    /// Largest fit distance in the part before halving.
    pub max_fit_distance: f64,
}

/// Totals.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct HotBladeSummary {
    /// Blocks with surface.
    pub blocks: usize,
    /// Fitted sections over all blocks (faces shared by two rows count once per block).
    pub sections: usize,
    /// L2 distance per section over all blocks.
    pub l2: Stats,
    /// Largest fit distance.
    pub max_fit_distance: f64,
    /// Largest deviation between rationalized and design surface.
    pub max_deviation: f64,
    /// Largest |curvature| of a blade.
    pub max_abs_curvature: f64,
    /// Most inflections on a blade.
    pub max_inflections: usize,
    /// Largest angle between a cutting plane and the surface normal.
    pub max_plane_angle: f64,
    /// Largest distance between the shared end points of neighbouring blocks' blades.
    pub max_face_gap: f64,
    /// Largest angle between the end tangents of neighbouring blocks' blades.
    pub max_face_angle: f64,
    /// With `C1`: sections that could keep only C⁰ (see the blocks).
    pub tangent_failures: usize,
    /// Blocks breaking each constraint.
    pub flagged: FlagCounts,
    /// Whether every block meets every constraint.
    pub all_ok: bool,
}

/// Blocks breaking each constraint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct FlagCounts {
    /// Approximation tolerance.
    pub approximation: usize,
    /// Blade strain.
    pub blade_strain: usize,
    /// Shape (inflections).
    pub shape: usize,
    /// Blade length.
    pub blade_length: usize,
    /// Flat blade.
    pub flat_blade: usize,
    /// Block height.
    pub block_height: usize,
    /// Overlapping planes.
    pub overlap: usize,
    /// The blade outside a section in what the block keeps, or a holder inside it.
    pub gouge: usize,
    /// A blade that does not hold its shape.
    pub stability: usize,
}

impl FlagCounts {
    /// Counts the flags of `blocks`.
    pub fn of<'a>(blocks: impl IntoIterator<Item = &'a BlockReport> + Clone) -> Self {
        let c =
            |f: &dyn Fn(&Flags) -> bool| blocks.clone().into_iter().filter(|b| f(&b.flags)).count();
        Self {
            approximation: c(&|f| f.approximation),
            blade_strain: c(&|f| f.blade_strain),
            shape: c(&|f| f.shape),
            blade_length: c(&|f| f.blade_length),
            flat_blade: c(&|f| f.flat_blade),
            block_height: c(&|f| f.block_height),
            overlap: c(&|f| f.overlap),
            gouge: c(&|f| f.gouge),
            stability: c(&|f| f.stability),
        }
    }
}

impl HotBladeSummary {
    /// Totals over `blocks`; `face` is the largest gap and tangent angle between the shared
    /// ends of neighbouring blocks' blades.
    pub fn of(blocks: &[BlockResult], face: (f64, f64)) -> Self {
        let reports: Vec<&BlockReport> = blocks.iter().map(|b| &b.report).collect();
        let fold =
            |f: &dyn Fn(&BlockReport) -> f64| reports.iter().map(|b| f(b)).fold(0.0, f64::max);
        Self {
            blocks: blocks.len(),
            sections: blocks.iter().map(|b| b.sections.len()).sum(),
            l2: Stats::of(
                blocks
                    .iter()
                    .flat_map(|b| b.sections.iter().map(|s| s.fit.l2)),
            ),
            max_fit_distance: fold(&|b| b.max_fit_distance),
            max_deviation: fold(&|b| b.max_deviation),
            max_abs_curvature: fold(&|b| b.max_abs_curvature),
            max_inflections: reports.iter().map(|b| b.max_inflections).max().unwrap_or(0),
            max_plane_angle: fold(&|b| b.max_plane_angle),
            max_face_gap: face.0,
            max_face_angle: face.1,
            tangent_failures: reports.iter().map(|b| b.tangent_failures).sum(),
            all_ok: reports.iter().all(|b| !b.flags.any()),
            flagged: FlagCounts::of(reports.iter().copied()),
        }
    }
}
