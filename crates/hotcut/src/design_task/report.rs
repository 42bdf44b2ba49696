//! The report a `Design` run writes as `report.json`; its JSON Schema is
//! `schemas/design-report.schema.json`. Lengths in the job's units, angles in radians
//! unless named `_deg`, curvature per job unit.

use design::cut::{CurveResult, CutResult, Form};
use schemars::JsonSchema;
use serde::Serialize;

use crate::robot_cell::report::CellReport;
use crate::spec::Units;

use super::Resolution;
use design::assembly::Block;

/// The result of the `Design` task.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DesignReport {
    /// Job name.
    pub job: String,
    /// Task name, `Design`.
    pub task: String,
    /// Length unit.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The box of what `model.gltf` shows (blocks, design and elastica surfaces, tops).
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// The design file, as the job names it.
    pub design: String,
    /// The settings used (defaults filled in).
    pub settings: DesignSettings,
    /// The blocks.
    pub blocks: Vec<BlockInfo>,
    /// Per cut, in the design file's order.
    pub cuts: Vec<CutReport>,
    /// Totals and the verdict.
    pub summary: DesignSummary,
    /// The robot cell (present when the job writes robot files or gives a cell).
    pub cell: Option<CellReport>,
}

/// Settings of the run.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DesignSettings {
    /// `Design` (a quick look) or `Production` (what the robot files use).
    pub resolution: Resolution,
    /// Cutting planes per cut, entry to exit (each a blade pose).
    pub planes_per_block: usize,
    /// Points each curve is drawn and meshed with, per block.
    pub points_per_curve: usize,
    /// Blade length.
    pub blade_length: f64,
    /// Largest |curvature| the blade takes.
    pub max_curvature: f64,
    /// Most inflections on a blade.
    pub max_inflections: u32,
    /// Cutting speed, units per second.
    pub speed: f64,
    /// Approach and retreat distance along the cut.
    pub approach: f64,
    /// The blade's kerf the run compensated for (absent without `kerf`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kerf: Option<crate::context::KerfReport>,
}

/// A block.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockInfo {
    /// Its name.
    pub id: String,
    /// Smallest corner.
    pub min: [f64; 3],
    /// Largest corner.
    pub max: [f64; 3],
    /// The cuts through it, in priority order (the primary, closest to the block's base,
    /// first), dropped ones last.
    pub cuts: Vec<BlockCut>,
    /// With several cuts: the block's top, their lower envelope.
    pub envelope: Option<EnvelopeReport>,
}

/// One cut through a block.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockCut {
    /// The cut.
    pub cut: String,
    /// Its number in the robot files (each (cut, block) pair is one placement of the
    /// block), `null` when dropped.
    pub number: Option<usize>,
    /// Why it was dropped, if it was.
    pub note: Option<String>,
}

/// The lower envelope of a block's cuts ("Designing for Robotic Hot-Blade Cutting" §3.1,
/// figs. 4/5).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeReport {
    /// Grid points per side over the block's footprint.
    pub grid: usize,
    /// Largest height difference of the envelope, elastica against design.
    pub max_deviation: f64,
    /// How far the crease (where the lowest cut changes) of the elastica's envelope lies
    /// from the design's: the larger of the two one-sided largest distances; `null`
    /// without a crease.
    pub crease_deviation: Option<f64>,
    /// Crease points found on the grid, design and elastica.
    pub crease_points: [usize; 2],
}

/// One cut.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CutReport {
    /// Its name.
    pub id: String,
    /// `Bezier` (G¹) or `Spline` (C²).
    pub form: String,
    /// Its blocks, across the cut.
    pub blocks: Vec<String>,
    /// The blocks' faces across the cut.
    pub faces: Vec<f64>,
    /// Per station and block: the design curve against its elastica.
    pub curves: Vec<CurveReport>,
    /// Per station and interior face: how the neighbouring elastica meet.
    pub joints: Vec<JointReport>,
    /// Over every cutting plane: the worst of each measure.
    pub planes: PlanesReport,
}

/// A design curve's piece in one block, against its elastica.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CurveReport {
    /// Station number (from 0).
    pub station: usize,
    /// Offset of the station's plane along the cut.
    pub offset: f64,
    /// The block.
    pub block: String,
    /// Length of the design piece (and of its elastica).
    pub length: f64,
    /// Largest distance design vs elastica at equal arc length.
    pub max_deviation: f64,
    /// L² (root mean square over arc length) of that distance.
    pub rms_deviation: f64,
    /// The largest distance as a percentage of the length.
    pub max_deviation_percent: f64,
    /// The elastica's length against the design's, relative.
    pub relative_length_error: f64,
    /// Distance between the elastica's and the design's end points.
    pub end_point_error: f64,
    /// Difference of their end tangent angles.
    pub end_angle_error: f64,
    /// The elastica's largest |κ|.
    pub max_curvature: f64,
    /// The elastica's inflections.
    pub inflections: usize,
    /// RMS residual of κ ≈ λ₂x − λ₁y + α fitted on the design ("Hot Blade Cuttings"
    /// eq. 11), times the length: a cheap predictor of the deviation (0 for an elastica).
    pub eq11_residual: f64,
    /// Interior angles of the control polygon, degrees.
    pub polygon_angles_deg: [f64; 2],
    /// The discrete elastica (64 segments) against the closed form: largest distance.
    pub discrete_distance: f64,
    /// The blade (the elastica extended to the blade's length): largest |κ|.
    pub blade_max_curvature: f64,
    /// The blade's inflections.
    pub blade_inflections: usize,
    /// The blade's curvature breaks the limit (strain).
    pub strain_flag: bool,
    /// The blade has more inflections than allowed.
    pub inflection_flag: bool,
    /// The held blade's stability margin (unit-free; `elastica::stability`).
    pub blade_margin: f64,
    /// The blade does not hold its shape: an unstable or marginal equilibrium.
    pub stability_flag: bool,
}

/// How two neighbouring elastica meet on a face.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JointReport {
    /// Station number (from 0).
    pub station: usize,
    /// The face, between blocks `face − 1` and `face` of the cut.
    pub face: usize,
    /// Distance between the ends.
    pub gap: f64,
    /// Tangent jump, radians.
    pub tangent_jump: f64,
    /// Curvature jump (the next block's minus the previous').
    pub curvature_jump: f64,
}

/// The worst over a cut's cutting planes.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlanesReport {
    /// Planes.
    pub planes: usize,
    /// Largest distance design vs elastica.
    pub max_deviation: f64,
    /// The same, as a percentage of the piece's length.
    pub max_deviation_percent: f64,
    /// Largest |κ| of a blade.
    pub blade_max_curvature: f64,
    /// Most inflections on a blade.
    pub blade_inflections: usize,
    /// Largest gap between neighbouring elastica.
    pub max_gap: f64,
    /// Largest |tangent jump| between neighbouring elastica, radians.
    pub max_tangent_jump: f64,
    /// Largest |curvature jump| between neighbouring elastica.
    pub max_curvature_jump: f64,
    /// Planes on which a blade breaks the curvature limit.
    pub strain_flags: usize,
    /// Planes on which a blade has too many inflections.
    pub inflection_flags: usize,
    /// Planes on which a blade does not hold its shape (unstable or marginal), or is
    /// carried from the plane before without keeping it (a snap).
    pub stability_flags: usize,
    /// The least stability margin of a blade over the planes (`None` without planes).
    pub min_margin: Option<f64>,
    /// Deepest the blade outside its piece runs into material a block keeps, over the
    /// planes (0: nowhere).
    pub max_gouge_depth: f64,
    /// Planes on which the blade outside a piece runs into kept material.
    pub gouge_flags: usize,
    /// Smallest distance of a held blade end from its block (negative: inside it).
    pub min_holder_clearance: f64,
    /// Planes on which a held blade end lies inside its block or closer to it than 1 % of
    /// the blade's length (`elastica::clearance::HOLDER_MARGIN`).
    pub collision_flags: usize,
    /// Per plane and block: the blade outside the piece against the block.
    pub clearance: Vec<PlaneClearance>,
}

/// The blade outside its piece against the block, on one plane (issue 37).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaneClearance {
    /// The plane (0 at the entry face).
    pub plane: usize,
    /// The block.
    pub block: String,
    /// How deep the blade outside the piece runs into what the block keeps (0: clean).
    pub gouge_depth: f64,
    /// How much of the blade outside the piece lies in it.
    pub gouge_length: f64,
    /// The smaller distance of the blade's held ends from the block (negative: inside).
    pub holder_clearance: f64,
    /// Both held ends at least 1 % of the blade's length from the block.
    pub holders_clear: bool,
    /// The blade's length before the piece: where along the blade the planner put the
    /// piece to keep the blade out of the block (half the extension unless that gouges).
    pub lead_in: f64,
}

/// Totals.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DesignSummary {
    /// Cuts.
    pub cuts: usize,
    /// Curves reported (stations × blocks).
    pub curves: usize,
    /// Blade poses the robots get: planes of every (cut, block) pair not dropped.
    pub poses: usize,
    /// Largest deviation design vs elastica anywhere, % of the piece's length.
    pub max_deviation_percent: f64,
    /// Largest eq. (11) residual of a station curve.
    pub max_eq11_residual: f64,
    /// Largest |κ| of a blade.
    pub blade_max_curvature: f64,
    /// Planes or stations whose blade breaks the curvature limit.
    pub strain_flags: usize,
    /// Planes or stations whose blade has too many inflections.
    pub inflection_flags: usize,
    /// Planes whose blade does not hold its shape, or snaps from the plane before.
    pub stability_flags: usize,
    /// Deepest gouge of a blade outside its piece into kept material (0: none).
    pub max_gouge_depth: f64,
    /// Planes on which a blade outside its piece gouges kept material.
    pub gouge_flags: usize,
    /// Planes on which a held blade end lies inside its block.
    pub collision_flags: usize,
    /// Every blade within its limits, out of what the blocks keep, its held ends outside.
    pub all_ok: bool,
}

fn percent(dev: f64, length: f64) -> f64 {
    if length > 0.0 {
        100.0 * dev / length
    } else {
        0.0
    }
}

/// The curve rows of `station`.
fn curves(station: usize, c: &CurveResult, names: &[String]) -> Vec<CurveReport> {
    c.pieces
        .iter()
        .zip(names)
        .map(|(p, name)| {
            let x = &p.proxy;
            CurveReport {
                station,
                offset: c.offset,
                block: name.clone(),
                length: x.length,
                max_deviation: x.max_deviation,
                rms_deviation: x.rms_deviation,
                max_deviation_percent: percent(x.max_deviation, x.length),
                relative_length_error: x.relative_length_error,
                end_point_error: x.end_point_error,
                end_angle_error: x.end_angle_error,
                max_curvature: x.max_curvature,
                inflections: x.inflections,
                eq11_residual: x.eq11_residual,
                polygon_angles_deg: x.polygon_angles_deg,
                discrete_distance: x.discrete_distance,
                blade_max_curvature: p.blade.max_abs_curvature,
                blade_inflections: p.blade.inflections,
                strain_flag: !p.blade.curvature_ok,
                inflection_flag: !p.blade.inflections_ok,
                blade_margin: p.blade.stability.margin,
                stability_flag: !p.blade.stability_ok,
            }
        })
        .collect()
}

fn planes(r: &CutResult, names: &[String]) -> PlanesReport {
    let mut out = PlanesReport {
        planes: r.planes.len(),
        max_deviation: 0.0,
        max_deviation_percent: 0.0,
        blade_max_curvature: 0.0,
        blade_inflections: 0,
        max_gap: 0.0,
        max_tangent_jump: 0.0,
        max_curvature_jump: 0.0,
        strain_flags: 0,
        inflection_flags: 0,
        stability_flags: 0,
        min_margin: None,
        max_gouge_depth: 0.0,
        gouge_flags: 0,
        min_holder_clearance: 0.0,
        collision_flags: 0,
        clearance: Vec::new(),
    };
    let mut least = f64::INFINITY;
    for (j, c) in r.planes.iter().enumerate() {
        let (mut gouge, mut collision) = (false, false);
        for (p, name) in c.pieces.iter().zip(names) {
            let Some(k) = p.clearance else { continue };
            out.max_gouge_depth = out.max_gouge_depth.max(k.gouge_depth);
            least = least.min(k.holder_clearance);
            gouge |= k.gouge_depth > 0.0;
            collision |= !k.holders_clear;
            out.clearance.push(PlaneClearance {
                plane: j,
                block: name.clone(),
                gouge_depth: k.gouge_depth,
                gouge_length: k.gouge_length,
                holder_clearance: k.holder_clearance,
                holders_clear: k.holders_clear,
                lead_in: p.blade.lead_in,
            });
        }
        out.gouge_flags += usize::from(gouge);
        out.collision_flags += usize::from(collision);
    }
    if least.is_finite() {
        out.min_holder_clearance = least;
    }
    // a plane fails stability where a blade is unstable or marginal, or the move into it
    // from the plane before (the same block's blade) snaps
    let pieces = r.planes.first().map_or(0, |c| c.pieces.len());
    let mut snapping = vec![false; r.planes.len()];
    for k in 0..pieces {
        for (j, pair) in r.planes.windows(2).enumerate() {
            let (Some(a), Some(b)) = (pair[0].pieces.get(k), pair[1].pieces.get(k)) else {
                continue;
            };
            if elastica::clearance::snapping_moves(&[a.blade.clone(), b.blade.clone()]) > 0 {
                snapping[j + 1] = true;
            }
        }
    }
    for (j, c) in r.planes.iter().enumerate() {
        out.stability_flags +=
            usize::from(snapping[j] || c.pieces.iter().any(|p| !p.blade.stability_ok));
    }
    for c in &r.planes {
        for p in &c.pieces {
            out.max_deviation = out.max_deviation.max(p.proxy.max_deviation);
            out.max_deviation_percent = out
                .max_deviation_percent
                .max(percent(p.proxy.max_deviation, p.proxy.length));
            out.blade_max_curvature = out.blade_max_curvature.max(p.blade.max_abs_curvature);
            out.blade_inflections = out.blade_inflections.max(p.blade.inflections);
        }
        out.strain_flags += usize::from(c.pieces.iter().any(|p| !p.blade.curvature_ok));
        out.inflection_flags += usize::from(c.pieces.iter().any(|p| !p.blade.inflections_ok));
        for p in &c.pieces {
            let m = p.blade.stability.margin;
            out.min_margin = Some(out.min_margin.map_or(m, |v: f64| v.min(m)));
        }
        for j in &c.joints {
            out.max_gap = out.max_gap.max(j.gap);
            out.max_tangent_jump = out.max_tangent_jump.max(j.tangent_jump.abs());
            out.max_curvature_jump = out.max_curvature_jump.max(j.curvature_jump.abs());
        }
    }
    out
}

/// The report of cut `id` through `blocks` (resolved) with result `r`.
pub fn cut_report(id: &str, blocks: &[&Block], faces: &[f64], r: &CutResult) -> CutReport {
    let names: Vec<String> = blocks.iter().map(|b| b.id.clone()).collect();
    CutReport {
        id: id.into(),
        form: match r.form {
            Form::Bezier => "Bezier",
            Form::Spline => "Spline",
        }
        .into(),
        blocks: names.clone(),
        faces: faces.to_vec(),
        curves: r
            .stations
            .iter()
            .enumerate()
            .flat_map(|(i, c)| curves(i, c, &names))
            .collect(),
        joints: r
            .stations
            .iter()
            .enumerate()
            .flat_map(|(i, c)| {
                c.joints.iter().map(move |j| JointReport {
                    station: i,
                    face: j.face,
                    gap: j.gap,
                    tangent_jump: j.tangent_jump,
                    curvature_jump: j.curvature_jump,
                })
            })
            .collect(),
        planes: planes(r, &names),
    }
}

/// The totals over `cuts`.
pub fn summary(cuts: &[CutReport]) -> DesignSummary {
    let mut s = DesignSummary {
        cuts: cuts.len(),
        curves: 0,
        poses: 0,
        max_deviation_percent: 0.0,
        max_eq11_residual: 0.0,
        blade_max_curvature: 0.0,
        strain_flags: 0,
        inflection_flags: 0,
        stability_flags: 0,
        max_gouge_depth: 0.0,
        gouge_flags: 0,
        collision_flags: 0,
        all_ok: true,
    };
    for c in cuts {
        s.curves += c.curves.len();
        s.poses += c.planes.planes * c.blocks.len();
        s.max_deviation_percent = s.max_deviation_percent.max(c.planes.max_deviation_percent);
        s.blade_max_curvature = s.blade_max_curvature.max(c.planes.blade_max_curvature);
        s.strain_flags += c.planes.strain_flags;
        s.inflection_flags += c.planes.inflection_flags;
        s.stability_flags += c.planes.stability_flags;
        s.max_gouge_depth = s.max_gouge_depth.max(c.planes.max_gouge_depth);
        s.gouge_flags += c.planes.gouge_flags;
        s.collision_flags += c.planes.collision_flags;
        for k in &c.curves {
            s.max_deviation_percent = s.max_deviation_percent.max(k.max_deviation_percent);
            s.max_eq11_residual = s.max_eq11_residual.max(k.eq11_residual);
            s.blade_max_curvature = s.blade_max_curvature.max(k.blade_max_curvature);
            s.strain_flags += usize::from(k.strain_flag);
            s.inflection_flags += usize::from(k.inflection_flag);
        }
    }
    s.all_ok = s.strain_flags == 0
        && s.inflection_flags == 0
        && s.stability_flags == 0
        && s.gouge_flags == 0
        && s.collision_flags == 0;
    s
}
