//! `report.json` of a `RuledBlocks` run (schema `schemas/ruled-blocks-report.schema.json`).

use schemars::JsonSchema;
use serde::Serialize;

use super::{outputs, RuledBlocksParams, RuledBlocksRun};
use crate::context::Context;
use crate::spec::Units;

/// The report of a `RuledBlocks` run.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RuledBlocksReport {
    /// Job name.
    pub job: String,
    /// Task name, `RuledBlocks`.
    pub task: String,
    /// Length unit of every length.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The strategy cut (`blocks`, `deviation`, `rationalized` and the programs are its).
    pub strategy: super::Strategy,
    /// Why the run cut nothing (it failed with exit 1, and wrote only this report and
    /// `report.html`: no program, mesh or drawing), or `null` when it cut.
    pub nothing_to_cut: Option<String>,
    /// Both strategies side by side: whole model, then per block.
    pub comparison: Vec<StrategyReport>,
    /// The model as a closed solid (a height field closed into its slab).
    pub model: Solid,
    /// The rationalized model.
    pub rationalized: Solid,
    /// The box of what `model.gltf` shows.
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// `tolerance.max`: the largest deviation allowed.
    pub tolerance: f64,
    /// The axis the sections are normal to (`cutting.direction`, unit).
    pub axis: [f64; 3],
    /// Sections, the refined ones included.
    pub sections: usize,
    /// Deviation of the rationalized surface from the model, at the model's samples (its
    /// vertices and a barycentric lattice on each face, README): the distance from each
    /// to the rationalized surface.
    pub deviation: DeviationReport,
    /// The whole model's regions, each a piecewise ruled surface.
    pub regions: Vec<RegionReport>,
    /// The block segmentation (ch. 3) of the rationalized model (`WholeModel`) or of the
    /// model (`PerBlock`).
    pub segmentation: SegmentationSummary,
    /// Every block.
    pub blocks: Vec<BlockReport>,
    /// Sums over the blocks.
    pub totals: Totals,
}

/// One strategy's figures (§4.1): across every pair of blocks that meet, at the model's
/// samples both hold, the gap between their surfaces and the angle between their rulings.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StrategyReport {
    /// The strategy.
    pub strategy: super::Strategy,
    /// Pairs of blocks that meet.
    pub seams: usize,
    /// Model samples both blocks of a pair hold, summed.
    pub seam_samples: usize,
    /// Largest C⁰ gap between two blocks' surfaces.
    pub max_gap: f64,
    /// RMS gap.
    pub rms_gap: f64,
    /// Largest ruling-direction jump, degrees.
    pub max_jump_deg: f64,
    /// Median jump, degrees.
    pub median_jump_deg: f64,
    /// Deviation from the model.
    pub deviation: DeviationReport,
    /// Material the hulls add.
    pub added_volume: f64,
    /// Cuts.
    pub cuts: usize,
    /// Blocks.
    pub blocks: usize,
    /// Blocks cut by their strips.
    pub cuttable: usize,
}

/// A closed solid's size.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Solid {
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub faces: usize,
    /// Enclosed volume.
    pub volume: f64,
    /// Bounding-box diagonal.
    pub diagonal: f64,
}

/// A deviation, in job units and as a share of the model's bounding-box diagonal.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DeviationReport {
    /// Samples measured.
    pub samples: usize,
    /// Root mean square distance.
    pub rms: f64,
    /// Largest distance.
    pub max: f64,
    /// `rms` / diagonal.
    pub rms_fraction: f64,
    /// `max` / diagonal.
    pub max_fraction: f64,
    /// Whether `max` ≤ the tolerance.
    pub within_tolerance: bool,
}

impl DeviationReport {
    fn of(d: &::ruled_blocks::Deviation, diagonal: f64, tolerance: f64) -> Self {
        Self {
            samples: d.samples,
            rms: d.rms,
            max: d.max,
            rms_fraction: d.rms / diagonal,
            max_fraction: d.max / diagonal,
            within_tolerance: d.max <= tolerance,
        }
    }
}

/// One region.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RegionReport {
    /// Index (1-based, as drawings and programs name it).
    pub index: usize,
    /// Its sections.
    pub sections: usize,
    /// Offset of its first and last section along the axis.
    pub along: (f64, f64),
    /// Ruled strips around it.
    pub strips: usize,
    /// Strips per side (between the model's sharp edges).
    pub side_strips: Vec<usize>,
    /// Control points per rail.
    pub controls: usize,
    /// The fit's RMS and largest residual at its samples (eq. 4.1's terms: each sample's
    /// distance to the surface point of its own parameters).
    pub fit: (f64, f64),
    /// Deviation of the model samples closest to it.
    pub deviation: DeviationReport,
}

/// The block segmentation in brief (`blocks` has every block).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SegmentationSummary {
    /// Blocks of the initial grid.
    pub initial_blocks: usize,
    /// Blocks at the end.
    pub final_blocks: usize,
    /// ⌈volume / block volume⌉.
    pub lower_bound: usize,
    /// The job's seed.
    pub seed: u64,
}

/// One block.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockReport {
    /// Index (1-based).
    pub index: usize,
    /// Centre, rotation `[w, x, y, z]` (block axes to model axes) and edge lengths; the
    /// block's axes `x`, `y`, `z` are the ones the programs' mounting lines name.
    pub placement: blocks::Placement,
    /// `PerBlock`: the block axis its own sections are normal to (`+x`, `+y`, `+z`).
    pub axis: Option<String>,
    /// Whether its strips cut it (else: its convex hull).
    pub cuttable: bool,
    /// Why not.
    pub reason: Option<String>,
    /// Deepest a strip's wire would enter what it keeps.
    pub deepest: f64,
    /// Volume of the rationalized model in it (lattice estimate).
    pub kept_volume: f64,
    /// Material its hull adds beyond the rationalized model (lattice estimate; 0 when its
    /// strips cut it).
    pub added_volume: f64,
    /// Largest depth of that material.
    pub added_depth: f64,
    /// Its share of overlaps with neighbours: the half-spaces `normal · x ≤ offset` what it
    /// keeps lies in (empty: all of the rationalized model in it).
    pub keeps: Vec<HalfSpace>,
    /// Its cuts, in order.
    pub cuts: Vec<CutReport>,
}

/// A half-space `normal · x ≤ offset`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HalfSpace {
    /// Unit normal, pointing out of the share.
    pub normal: [f64; 3],
    /// Offset.
    pub offset: f64,
}

/// Sharing the blocks' overlaps (fig. 4.4).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SharingReport {
    /// Overlaps split between two blocks.
    pub splits: usize,
    /// Material the hulls add with no overlap shared.
    pub added_before: f64,
    /// With the overlaps shared.
    pub added_after: f64,
    /// `added_before − added_after`.
    pub saved: f64,
}

/// One cut.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CutReport {
    /// `Strip` (a ruled strip of `region`) or `Plane` (a face of the block's hull).
    pub kind: String,
    /// The strip's region (1-based).
    pub region: Option<usize>,
    /// The strip (1-based around the region).
    pub strip: Option<usize>,
    /// The block's axes along the cut, towards tower B and up (`+x`, `-z`, …).
    pub mount: [String; 3],
    /// Wire positions, the lead-in and lead-out included.
    pub positions: usize,
    /// Its program, when G-code is written.
    pub program: Option<String>,
    /// The faster tower's path while cutting, mm (0 without a program).
    pub cut_length_mm: f64,
    /// Cutting time at the set speed, minutes (0 without a program).
    pub cut_minutes: f64,
}

/// Sums.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Totals {
    /// Blocks their strips cut.
    pub cuttable: usize,
    /// Cuts.
    pub cuts: usize,
    /// Material added by hulls.
    pub added_volume: f64,
    /// Largest added depth.
    pub added_depth: f64,
    /// Cutting minutes.
    pub cut_minutes: f64,
    /// `WholeModel`: what sharing the overlaps saved (`PerBlock` shares none).
    pub sharing: Option<SharingReport>,
}

/// The report of a run.
pub fn make(p: &RuledBlocksParams, run: &RuledBlocksRun, job: &Context) -> RuledBlocksReport {
    let r = &run.whole;
    let tol = p.plan.tolerance;
    let diag = r.diagonal;
    let solid = |m: &geom::TriMesh| Solid {
        vertices: m.vertices().len(),
        faces: m.faces().len(),
        volume: m.volume(),
        diagonal: m.aabb().size().norm(),
    };
    let regions = r
        .regions
        .iter()
        .enumerate()
        .map(|(i, g)| RegionReport {
            index: i + 1,
            sections: g.region.offsets.len(),
            along: (
                g.region.offsets[0],
                g.region.offsets[g.region.offsets.len() - 1],
            ),
            strips: g.region.strips,
            side_strips: g.region.side_strips.clone(),
            controls: g.region.controls,
            fit: (g.region.fit_rms, g.region.fit_max),
            deviation: DeviationReport::of(&g.deviation, diag, tol),
        })
        .collect();
    let blocks = block_reports(run);
    let totals = Totals {
        cuttable: blocks.iter().filter(|b| b.cuttable).count(),
        cuts: blocks.iter().map(|b| b.cuts.len()).sum(),
        added_volume: blocks.iter().map(|b| b.added_volume).sum(),
        added_depth: blocks.iter().map(|b| b.added_depth).fold(0.0, f64::max),
        sharing: match run.strategy {
            super::Strategy::WholeModel => {
                let x = &r.sharing;
                Some(SharingReport {
                    splits: x.splits,
                    added_before: x.added_before,
                    added_after: x.added_after,
                    saved: x.added_before - x.added_after,
                })
            }
            super::Strategy::PerBlock => None,
        },
        cut_minutes: blocks
            .iter()
            .flat_map(|b| &b.cuts)
            .map(|c| c.cut_minutes)
            .sum(),
    };
    RuledBlocksReport {
        job: job.name.clone(),
        task: "RuledBlocks".into(),
        units: job.units,
        hotcut_version: crate::report::VERSION.into(),
        strategy: run.strategy,
        nothing_to_cut: super::refusal(run),
        comparison: comparison(run, diag, tol),
        model: solid(&run.model),
        rationalized: solid(&run.mesh),
        model_bounds: crate::report::ModelBounds::of(outputs::scene(run)),
        tolerance: tol,
        axis: r.solid.axis.into(),
        sections: r.sections,
        deviation: DeviationReport::of(&run.deviation, diag, tol),
        regions,
        segmentation: {
            let seg = match run.strategy {
                super::Strategy::WholeModel => &r.segmentation,
                super::Strategy::PerBlock => &run.per_block.segmentation,
            };
            SegmentationSummary {
                initial_blocks: seg.initial_blocks,
                final_blocks: seg.final_blocks,
                lower_bound: seg.lower_bound,
                seed: seg.seed,
            }
        },
        blocks,
        totals,
    }
}

/// Every block's report.
fn block_reports(run: &RuledBlocksRun) -> Vec<BlockReport> {
    run.blocks
        .iter()
        .enumerate()
        .map(|(i, b)| BlockReport {
            index: i + 1,
            axis: match run.strategy {
                super::Strategy::WholeModel => None,
                super::Strategy::PerBlock => run.per_block.rational[i]
                    .as_ref()
                    .map(|x| ::ruled_blocks::machine::axis_name((x.axis, 1.0))),
            },
            placement: blocks::Placement::of(&b.block),
            cuttable: b.cuttable,
            reason: b.reason.clone(),
            deepest: b.deepest,
            kept_volume: b.kept_volume,
            added_volume: b.added_volume,
            added_depth: b.added_depth,
            keeps: b
                .keeps
                .iter()
                .map(|h| HalfSpace {
                    normal: h.n.into(),
                    offset: h.c,
                })
                .collect(),
            cuts: b
                .cuts
                .iter()
                .enumerate()
                .map(|(k, c)| {
                    let prog = run.programs.get(i).and_then(|v| v.get(k));
                    let (region, strip) = match c.kind {
                        ::ruled_blocks::cuts::CutKind::Strip { region, strip } => {
                            (Some(region + 1), Some(strip + 1))
                        }
                        ::ruled_blocks::cuts::CutKind::Plane => (None, None),
                    };
                    CutReport {
                        kind: if region.is_some() { "Strip" } else { "Plane" }.into(),
                        region,
                        strip,
                        mount: [c.mount.along, c.mount.across, c.mount.up]
                            .map(::ruled_blocks::machine::axis_name),
                        positions: c.lines.len(),
                        program: prog.map(|_| outputs::program_file(i, k)),
                        cut_length_mm: prog.map_or(0.0, |p| p.summary.cut_length_mm),
                        cut_minutes: prog.map_or(0.0, |p| p.summary.cut_minutes),
                    }
                })
                .collect(),
        })
        .collect()
}

/// Both strategies' figures.
fn comparison(run: &RuledBlocksRun, diag: f64, tol: f64) -> Vec<StrategyReport> {
    [super::Strategy::WholeModel, super::Strategy::PerBlock]
        .iter()
        .zip(&run.figures)
        .map(|(&strategy, f)| StrategyReport {
            strategy,
            seams: f.seams,
            seam_samples: f.seam_samples,
            max_gap: f.max_gap,
            rms_gap: f.rms_gap,
            max_jump_deg: f.max_jump_deg,
            median_jump_deg: f.median_jump_deg,
            deviation: DeviationReport::of(&f.deviation, diag, tol),
            added_volume: f.added_volume,
            cuts: f.cuts,
            blocks: f.blocks,
            cuttable: f.cuttable,
        })
        .collect()
}
