//! Building one block from its fitted sections: the swept surface between them, its
//! deviation from the design on a dense grid, overlaps and every constraint's flag.

use elastica::fit::{FitConstraint, FitError, FitParams};
use elastica::segment::Segment;
use elastica::sweep::{frame_quaternion, interpolate};
use geom::polyline::distance_to_polyline;
use nalgebra::Vector2;

use crate::fit::design_polyline;
use crate::grid::Plane;
use crate::pipeline::{Context, FittedPart};
use crate::result::{
    BlockReport, BlockResult, FittedSection, Flags, SectionClearance, Stats, SurfaceVertex,
};
use crate::SWEEP_SHARE;

/// Block `row` of column part `part`: its fitted sections (the row's targets), the swept
/// surface with its deviation from the design, the overlaps and the flags. `None` when the
/// block holds no surface.
pub(crate) fn build_block(
    ctx: &Context<'_>,
    part: &FittedPart,
    row: usize,
    row_targets: &[usize],
    between: &[Vec<(usize, f64)>],
) -> Option<BlockResult> {
    let grid = ctx.grid;
    let sections: Vec<FittedSection> = row_targets
        .iter()
        .filter_map(|&i| part.fits[i].clone())
        .collect();
    if sections.is_empty() {
        return None;
    }
    let (d_lo, _) = grid.row_range(row);
    let origin = grid.world([d_lo, part.part.range.0, grid.origin[2]]);
    let swept = swept_surface(ctx, part, row_targets, between);
    let overlaps = overlaps(ctx, &sections);
    let report = BlockReport {
        block: 0,
        row,
        column: part.part.column,
        split_level: part.part.level,
        origin: [origin.x, origin.y, origin.z],
        size: [
            grid.size[0],
            part.part.range.1 - part.part.range.0,
            grid.size[2],
        ],
        sections: sections.len(),
        missing_sections: row_targets.len() - sections.len(),
        l2: Stats::of(sections.iter().map(|s| s.fit.l2)),
        max_rms: fold(&sections, |s| s.fit.rms),
        max_fit_distance: fold(&sections, |s| s.fit.max),
        max_deviation: swept.max_deviation,
        section_length: Stats::of(sections.iter().map(|s| s.design.length)),
        max_abs_curvature: fold(&sections, |s| s.blade.max_abs_curvature),
        max_inflections: sections
            .iter()
            .map(|s| s.blade.inflections)
            .max()
            .unwrap_or(0),
        min_margin: sections
            .iter()
            .map(|s| s.blade.stability.margin)
            .reduce(f64::min),
        max_plane_angle: fold(&sections, |s| s.plane_angle),
        worst_section: worst_section(&sections),
        blended_planes: swept.blended,
        tangent_failures: sections.iter().filter(|s| !s.tangents_kept).count(),
        flags: Flags::default(),
        overlaps,
        clearance: sections
            .iter()
            .enumerate()
            .filter_map(|(i, s)| {
                s.clearance.map(|c| SectionClearance {
                    section: i,
                    gouge_depth: c.gouge_depth,
                    gouge_length: c.gouge_length,
                    holder_clearance: c.holder_clearance,
                    lead_in: s.blade.lead_in,
                })
            })
            .collect(),
        max_gouge_depth: fold(&sections, |s| s.clearance.map_or(0.0, |c| c.gouge_depth)),
    };
    let flags = flags(ctx, &report, &sections);
    Some(BlockResult {
        report: BlockReport { flags, ..report },
        rotation: frame_quaternion(&grid.frame.normal, &grid.frame.v),
        sections,
        surface: swept.rows,
    })
}

/// The largest of `f` over the sections (0 for none).
fn fold(sections: &[FittedSection], f: impl Fn(&FittedSection) -> f64) -> f64 {
    sections.iter().map(f).fold(0.0, f64::max)
}

/// Index of the section with the largest L2 distance: the first of those within 10⁻⁶ of
/// the largest, so that sections equal but for rounding (mirror images on a symmetric
/// surface) give the same answer in any unit.
fn worst_section(sections: &[FittedSection]) -> usize {
    let max = fold(sections, |s| s.fit.l2);
    sections
        .iter()
        .position(|s| s.fit.l2 >= max * (1.0 - 1e-6))
        .unwrap_or(0)
}

/// Which production constraints the block breaks.
fn flags(ctx: &Context<'_>, r: &BlockReport, sections: &[FittedSection]) -> Flags {
    let (p, grid) = (ctx.params, ctx.grid);
    let v_range = (grid.origin[2], grid.origin[2] + grid.size[2]);
    let block_height = sections.iter().any(|s| {
        let pl = &ctx.planes[s.plane];
        s.design.points.iter().any(|q| {
            let v = grid
                .frame
                .v
                .dot(&pl.frame.to_world(pl.offset, &Vector2::new(q[0], q[1])));
            v < v_range.0 - 1e-9 * grid.size[2] || v > v_range.1 + 1e-9 * grid.size[2]
        })
    });
    Flags {
        approximation: r.max_rms > p.tolerance_rms || r.max_fit_distance > p.tolerance_max,
        blade_strain: sections.iter().any(|s| !s.blade.curvature_ok),
        shape: sections.iter().any(|s| !s.blade.inflections_ok),
        stability: sections.iter().any(|s| !s.blade.stability_ok) || {
            let blades: Vec<elastica::Blade> = sections.iter().map(|s| s.blade.clone()).collect();
            elastica::clearance::snapping_moves(&blades) > 0
        },
        blade_length: sections.iter().any(|s| s.design.length > p.blade.length),
        flat_blade: r.max_plane_angle > p.max_plane_angle,
        block_height,
        overlap: !r.overlaps.is_empty(),
        // a section longer than the blade has no blade outside it (flag `blade_length`)
        gouge: sections.iter().any(|s| {
            s.design.length <= p.blade.length && s.clearance.is_some_and(|c| !c.is_clean())
        }),
    }
}

/// A block's rationalized surface on the deviation grid.
struct Swept {
    /// One row of vertices per grid plane, in cutting order.
    rows: Vec<Vec<SurfaceVertex>>,
    /// Deviation planes whose curve is the elastica fitted to the blend.
    blended: usize,
    /// Largest deviation from the design.
    max_deviation: f64,
}

/// The swept surface of a block: each target plane's fit, then its `refine` planes
/// towards the next target, each compared with the design there.
fn swept_surface(
    ctx: &Context<'_>,
    part: &FittedPart,
    row_targets: &[usize],
    between: &[Vec<(usize, f64)>],
) -> Swept {
    let p = ctx.params;
    let m = p.grid_points.max(2);
    let mut swept = Swept {
        rows: Vec::new(),
        blended: 0,
        max_deviation: 0.0,
    };
    for (k, &t) in row_targets.iter().enumerate() {
        let Some(a) = &part.fits[t] else { continue };
        let mut rows: Vec<(usize, Vec<[f64; 2]>)> =
            vec![(t, sample_blend(&a.fit.segment, None, 0.0, m))];
        if let Some(b) = row_targets
            .get(k + 1)
            .and_then(|&next| part.fits[next].as_ref())
        {
            for &(plane, w) in &between[t] {
                let tolerance = SWEEP_SHARE * p.tolerance_max;
                let (pts, refit) = swept_curve(&a.fit.segment, &b.fit.segment, w, m, tolerance);
                swept.blended += usize::from(refit);
                rows.push((plane, pts));
            }
        }
        for (plane, pts) in rows {
            let Some(design) = design_polyline(ctx, plane, part.part.range, 8 * p.samples) else {
                continue;
            };
            let pl = &ctx.planes[plane];
            let verts: Vec<SurfaceVertex> = pts
                .iter()
                .map(|q| {
                    let deviation = distance_to_polyline(*q, &design);
                    swept.max_deviation = swept.max_deviation.max(deviation);
                    SurfaceVertex {
                        position: pl.frame.to_world(pl.offset, &Vector2::new(q[0], q[1])),
                        deviation,
                    }
                })
                .collect();
            swept.rows.push(verts);
        }
    }
    swept
}

/// Pairs of consecutive sections (indices among the block's) whose planes cross inside
/// the block: each plane's section must lie strictly ahead of the previous plane.
fn overlaps(ctx: &Context<'_>, sections: &[FittedSection]) -> Vec<[usize; 2]> {
    let side = |pl: &Plane, sec: &FittedSection| {
        let own = &ctx.planes[sec.plane];
        sec.design
            .points
            .iter()
            .map(|q| {
                pl.frame
                    .normal
                    .dot(&own.frame.to_world(own.offset, &Vector2::new(q[0], q[1])))
                    - pl.offset
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    };
    let mut overlaps = Vec::new();
    for (k, w) in sections.windows(2).enumerate() {
        let (pa, pb) = (&ctx.planes[w[0].plane], &ctx.planes[w[1].plane]);
        if pa.frame == pb.frame {
            continue;
        }
        let ahead = side(pa, &w[1]).0 > 0.0;
        let behind = side(pb, &w[0]).1 < 0.0;
        if !(ahead && behind) {
            overlaps.push([k, k + 1]);
        }
    }
    overlaps
}

/// `m` points of the swept surface's curve a fraction `w` of the way from fit `a` to fit
/// `b`: the parameter interpolation of [`interpolate`] when it stays within `tolerance` of
/// the pointwise blend of the two curves; otherwise (kinds differ, or the shapes lie on
/// different branches) the elastica fitted to that blend through its end points. The flag
/// says whether the fallback was taken.
fn swept_curve(
    a: &Segment,
    b: &Segment,
    w: f64,
    m: usize,
    tolerance: f64,
) -> (Vec<[f64; 2]>, bool) {
    let blend = sample_blend(a, Some(b), w, m);
    if let Some(s) = interpolate(a, b, w) {
        let pts = s.sample(m).unwrap_or_default();
        let far = pts
            .iter()
            .zip(&blend)
            .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(0.0, f64::max);
        if pts.len() == blend.len() && far <= tolerance {
            return (pts, false);
        }
    }
    let params = FitParams {
        constraint: FitConstraint::EndPoints,
        warm_start: Some(*a),
        ..FitParams::default()
    };
    match elastica::fit::fit_points(&blend, &params).and_then(|f| {
        f.segment
            .sample(m)
            .map_err(|e| FitError::Failed(e.to_string()))
    }) {
        Ok(pts) => (pts, true),
        Err(_) => (blend, true),
    }
}

/// `m` points of `seg` on t ∈ [0, 1], or of the pointwise blend towards `other` by `w`.
fn sample_blend(seg: &Segment, other: Option<&Segment>, w: f64, m: usize) -> Vec<[f64; 2]> {
    let a = seg.sample(m).unwrap_or_default();
    match other.map(|o| o.sample(m)) {
        Some(Ok(b)) if b.len() == a.len() => a
            .iter()
            .zip(&b)
            .map(|(p, q)| [p[0] + (q[0] - p[0]) * w, p[1] + (q[1] - p[1]) * w])
            .collect(),
        _ => a,
    }
}
