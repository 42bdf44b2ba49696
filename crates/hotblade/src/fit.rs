//! Fitting a part's sections: the design part of each plane, sweeps of warm-started fits,
//! the C¹ end-tangent fits and the blades with their poses.

use elastica::blade::{extend_to_blade, Blade, BladeError, BladeParams};
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitError, FitParams, FitResult};
use elastica::segment::Segment;
use elastica::sweep::blade_pose;
use nalgebra::{Vector2, Vector3};

use crate::grid::{clip, clip_polyline, Clipped};
use crate::pipeline::{Context, FittedPart, Part};
use crate::result::FittedSection;
use crate::{BladeLimits, Continuity, HotBladeError, Progress, ProgressFn, SHORTEST_PART};

/// The longest clipped part of a plane's section pieces as a dense polyline (for the
/// deviation grid; see [`clip_polyline`]).
pub(crate) fn design_polyline(
    ctx: &Context<'_>,
    plane: usize,
    range: (f64, f64),
    n: usize,
) -> Option<Vec<[f64; 2]>> {
    let length = geom::polyline::length;
    ctx.sections[plane]
        .iter()
        .filter_map(|s| clip_polyline(s, &ctx.planes[plane], &ctx.grid.frame.u, range, n))
        .map(|p| (length(&p), p))
        .fold(None, |best: Option<(f64, Vec<[f64; 2]>)>, c| match best {
            Some(b) if b.0 >= c.0 => Some(b),
            _ => Some(c),
        })
        .map(|(_, p)| p)
}

/// The longest clipped part of a plane's section pieces.
fn design_part(ctx: &Context<'_>, plane: usize, range: (f64, f64), n: usize) -> Option<Clipped> {
    ctx.sections[plane]
        .iter()
        .filter_map(|s| clip(s, &ctx.planes[plane], &ctx.grid.frame.u, range, n))
        .fold(None, |best: Option<Clipped>, c| match best {
            Some(b) if b.length >= c.length => Some(b),
            _ => Some(c),
        })
}

/// A section part of [`sweep_fits`] that no elastica could be fitted to.
#[derive(Debug, thiserror::Error)]
#[error("plane {plane}: {source}")]
pub struct SweepError {
    /// Index of the part in the sweep.
    pub plane: usize,
    /// The fit's error.
    #[source]
    pub source: FitError,
}

/// Sweeps of warm-started fits over a part's planes (§7: each section starts from its
/// neighbour's fit). Forward, each plane keeps the better of a cold fit and one warm-started
/// from the plane before; then backward and forward again with warm starts from the plane
/// after / before, a fit replaced only when the new one is better, until a sweep changes
/// nothing (at most `MAX_SWEEPS`). On long, nearly straight sections any single start
/// lands in a poor local minimum now and then (an arc 0.6 mm off where an elastica fits
/// to 0.003 mm); a good fit found anywhere then spreads to its neighbours.
pub fn sweep_fits(
    designs: &[Option<Clipped>],
    constraint: FitConstraint,
) -> Result<Vec<Option<FitResult>>, SweepError> {
    const MAX_SWEEPS: usize = 4;
    let fit_from = |design: &Clipped, warm_start: Option<Segment>| {
        let fit_params = FitParams {
            constraint,
            warm_start,
            ..FitParams::default()
        };
        fit_points_with_arclength(&design.points, &design.s, &fit_params)
    };
    let better = |a: &FitResult, b: &FitResult| a.l2 < b.l2 * (1.0 - 1e-9);
    let mut fits: Vec<Option<FitResult>> = Vec::with_capacity(designs.len());
    for (plane, design) in designs.iter().enumerate() {
        let Some(design) = design else {
            fits.push(None);
            continue;
        };
        let warm = fits.last().and_then(|f| f.as_ref()).map(|f| f.segment);
        let cold = fit_from(design, None);
        let fit = match (warm.map(|w| fit_from(design, Some(w))), cold) {
            (Some(Ok(w)), Ok(c)) => {
                if better(&c, &w) {
                    c
                } else {
                    w
                }
            }
            (Some(Ok(w)), Err(_)) => w,
            (_, c) => c.map_err(|source| SweepError { plane, source })?,
        };
        fits.push(Some(fit));
    }
    for sweep in 0..MAX_SWEEPS {
        let backward = sweep % 2 == 0;
        let mut changed = false;
        let order: Vec<usize> = if backward {
            (0..designs.len()).rev().collect()
        } else {
            (0..designs.len()).collect()
        };
        for w in order.windows(2) {
            let (from, to) = (w[0], w[1]);
            let (Some(design), Some(Some(source))) = (&designs[to], fits.get(from)) else {
                continue;
            };
            let Ok(f) = fit_from(design, Some(source.segment)) else {
                continue;
            };
            if fits[to].as_ref().is_none_or(|cur| better(&f, cur)) {
                fits[to] = Some(f);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    Ok(fits)
}

/// Fits part `part` on every target plane: the design parts (slivers left out), the
/// warm-started sweeps, with `C1` the tangent-keeping refits, and the blades with their
/// poses.
pub(crate) fn fit_part(
    ctx: &Context<'_>,
    part: Part,
    targets: usize,
    progress: &ProgressFn<'_>,
) -> Result<FittedPart, HotBladeError> {
    let p = ctx.params;
    let constraint = p.constraint.with_end_points();
    // a plane that only grazes the block's surface (a corner of a rotated plane, the edge
    // of a surface) gives a sliver no blade pose can be extrapolated from: left out
    let shortest = SHORTEST_PART * p.blade.length;
    let designs: Vec<Option<Clipped>> = (0..targets)
        .map(|plane| {
            design_part(ctx, plane, part.range, p.samples).filter(|d| d.length >= shortest)
        })
        .collect();
    let c0 = sweep_fits(&designs, constraint).map_err(|e| HotBladeError::Fit {
        column: part.column,
        range: part.range,
        plane: e.plane,
        source: e.source,
    })?;
    let mut fitted: Vec<Option<(Clipped, FitResult, bool)>> = designs
        .into_iter()
        .zip(c0)
        .map(|(d, f)| d.zip(f).map(|(d, f)| (d, f, true)))
        .collect();
    if p.continuity == Continuity::C1 {
        keep_tangents(ctx, part, constraint, &mut fitted);
    }
    let mut fits = Vec::with_capacity(targets);
    for (plane, slot) in fitted.into_iter().enumerate() {
        progress(Progress::Tick);
        // a failed C¹ fit keeps its C⁰ fit; the block reports it and the face angle shows it
        fits.push(match slot {
            Some((design, fit, tangents_kept)) => Some(pose_section(
                ctx,
                plane,
                part.range,
                design,
                fit,
                tangents_kept,
            )?),
            None => None,
        });
    }
    Ok(FittedPart { part, fits })
}

/// C¹: each fit refitted to keep the design's tangents at shared faces, started from the
/// plane before; those that fail are retried backwards from the plane after. A fit that
/// still fails keeps its C⁰ fit and is marked (`false`).
fn keep_tangents(
    ctx: &Context<'_>,
    part: Part,
    constraint: FitConstraint,
    fitted: &mut [Option<(Clipped, FitResult, bool)>],
) {
    let keep = |plane: usize, design: &Clipped, fit: &FitResult, warm: Option<&Segment>| {
        let (t0, t1) = design_tangents(ctx, plane, design, part.range);
        elastica::fit::fit_with_end_tangents(
            &design.points,
            &design.s,
            fit,
            warm,
            t0,
            t1,
            constraint,
        )
        .ok()
    };
    let mut warm: Option<Segment> = None;
    for (plane, slot) in fitted.iter_mut().enumerate() {
        let Some((design, fit, kept)) = slot else {
            continue;
        };
        match keep(plane, design, fit, warm.as_ref()) {
            Some(f) => *fit = f,
            None => *kept = false,
        }
        warm = Some(fit.segment);
    }
    for plane in (0..fitted.len().saturating_sub(1)).rev() {
        let next = match &fitted[plane + 1] {
            Some((_, f, true)) => f.segment,
            _ => continue,
        };
        if let Some((design, fit, kept @ false)) = &mut fitted[plane] {
            if let Some(f) = keep(plane, design, fit, Some(&next)) {
                *fit = f;
                *kept = true;
            }
        }
    }
}

/// A fitted section with its blade, pose and largest plane angle.
fn pose_section(
    ctx: &Context<'_>,
    plane: usize,
    range: (f64, f64),
    design: Clipped,
    fit: FitResult,
    tangents_kept: bool,
) -> Result<FittedSection, HotBladeError> {
    let plane_ref = &ctx.planes[plane];
    // the block where the surface covers it: a section shorter than its block (at the
    // surface's edge) leaves the rest of the block's width to no design
    let covered = design
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
            (lo.min(q[0]), hi.max(q[0]))
        });
    let (blade, clearance) = match block_section(ctx, plane, covered, range) {
        Some(section) => {
            let bp = blade_params(&fit.segment, &ctx.params.blade);
            let tolerance = 1e-6 * bp.length;
            let (b, c) = elastica::clearance::place(&fit.segment, &bp, &section, tolerance)
                .map_err(|source| HotBladeError::Blade { plane, source })?;
            (b, Some(c))
        }
        None => (
            make_blade(&fit.segment, &ctx.params.blade)
                .map_err(|source| HotBladeError::Blade { plane, source })?,
            None,
        ),
    };
    let pose = blade_pose(&plane_ref.frame, plane_ref.offset, &blade);
    let world: Vec<Vector3<f64>> = design
        .points
        .iter()
        .map(|q| {
            plane_ref
                .frame
                .to_world(plane_ref.offset, &Vector2::new(q[0], q[1]))
        })
        .collect();
    let plane_angle = ctx
        .normals
        .normals_near(&world)
        .iter()
        .map(|n| n.dot(&plane_ref.frame.normal).abs().min(1.0).asin())
        .fold(0.0, f64::max);
    Ok(FittedSection {
        plane,
        design,
        fit,
        blade,
        pose,
        plane_angle,
        tangents_kept,
        clearance,
    })
}

/// The design's unit tangent angles that a C¹ fit keeps at its ends: only where the end is
/// on a face shared with a neighbouring part (not at the surface's own edge).
fn design_tangents(
    ctx: &Context<'_>,
    plane: usize,
    design: &Clipped,
    range: (f64, f64),
) -> (Option<f64>, Option<f64>) {
    let n = design.points.len();
    let grid_u = |q: [f64; 2]| {
        let pl = &ctx.planes[plane];
        ctx.grid
            .frame
            .u
            .dot(&pl.frame.to_world(pl.offset, &Vector2::new(q[0], q[1])))
    };
    let on_face = |u: f64, face: f64| (u - face).abs() <= 1e-9 * (range.1 - range.0);
    let u0 = grid_u(design.points[0]);
    let u1 = grid_u(design.points[n - 1]);
    let faces = (
        ctx.grid.origin[1],
        ctx.grid.origin[1] + ctx.grid.cols as f64 * ctx.grid.size[1],
    );
    let inner = |u: f64| !on_face(u, faces.0) && !on_face(u, faces.1);
    let t0 = (on_face(u0, range.0) && inner(u0)).then_some(design.end_angles[0]);
    let t1 = (on_face(u1, range.1) && inner(u1)).then_some(design.end_angles[1]);
    (t0, t1)
}

/// The block's section on target plane `index` in the plane's coordinates: up, the grid's
/// height; across, where the plane crosses the block — the part's column (grid `u` in
/// `range`) within the row(s) the plane is a target of (grid `d`) — which the held ends must keep
/// out of, and of that, where the design covers it (`covered`, plane `u`), where kept
/// material is sought. For the grid's parallel planes this is the block's rectangle; a
/// plane that follows a curve stands vertical, as the grid's `v` does, so it cuts the
/// block in a rectangle too. `None` when the plane is not vertical to the grid, or misses
/// the block (a curve's end plane can leave its row's block within the column: its section
/// is then not checked). The block keeps what lies below the surface.
fn block_section(
    ctx: &Context<'_>,
    index: usize,
    covered: (f64, f64),
    range: (f64, f64),
) -> Option<elastica::clearance::Section> {
    let plane = &ctx.planes[index];
    let (f, g) = (&plane.frame, &ctx.grid.frame);
    if (f.v - g.v).norm() > 1e-12 {
        return None;
    }
    // grid u and d of the plane's point (u_p, v) are c + a·u_p (the plane's v is the
    // grid's): the u_p where each lies in its range
    let o = f.normal * plane.offset;
    let within = |axis: &nalgebra::Vector3<f64>, (lo, hi): (f64, f64)| -> Option<(f64, f64)> {
        let (a, c) = (axis.dot(&f.u), axis.dot(&o));
        if a.abs() > 1e-12 {
            let (x, y) = ((lo - c) / a, (hi - c) / a);
            Some((x.min(y), x.max(y)))
        } else {
            // the plane runs along this axis: all of it, or none
            (c >= lo && c <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY))
        }
    };
    let (u_lo, u_hi) = within(&g.u, range)?;
    let (d_lo, d_hi) = within(&g.normal, *ctx.plane_rows.get(index)?)?;
    let (u0, u1) = (u_lo.max(d_lo), u_hi.min(d_hi));
    let v = (ctx.grid.origin[2], ctx.grid.origin[2] + ctx.grid.size[2]);
    let (lo, hi) = (covered.0.max(u0), covered.1.min(u1));
    (u1.is_finite() && u0.is_finite() && hi > lo).then_some(elastica::clearance::Section {
        rect: [[lo, v.0], [hi, v.1]],
        block: [[u0, v.0], [u1, v.1]],
        keeps_below: true,
    })
}

/// The blade's parameters for `segment`: the limits' length (or the segment's own when
/// it is longer: its block is flagged), half the extension before the piece.
pub fn blade_params(segment: &Segment, limits: &BladeLimits) -> BladeParams {
    blade_params_over(segment.length(), limits)
}

/// [`blade_params`] for sections up to `longest` long: the limits' length, or `longest`
/// when that is longer.
pub fn blade_params_over(longest: f64, limits: &BladeLimits) -> BladeParams {
    let whole = limits.max_blade_inflections.unwrap_or(u32::MAX);
    BladeParams {
        length: limits.length.max(longest),
        lead_in_share: 0.5,
        max_curvature: Some(limits.max_curvature),
        max_inflections: Some(limits.max_inflections.min(whole) as usize),
        stability: elastica::StabilityParams {
            marginal: limits.min_margin,
            ..elastica::StabilityParams::default()
        },
    }
}

/// The fit extended to the blade's length ([`blade_params`]).
pub fn make_blade(
    segment: &Segment,
    limits: &BladeLimits,
) -> std::result::Result<Blade, BladeError> {
    extend_to_blade(segment, &blade_params(segment, limits))
}
