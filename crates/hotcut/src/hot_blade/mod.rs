//! The `HotBlade` task: the surface inside a grid of blocks, every block's sections fitted
//! by elastica ("Hot Blade Cuttings" §6–7), the surface swept between them, the blade poses
//! for the two robots ("Robotic Hot-Blade Cutting" §4), and the checks of every production
//! constraint.
//!
//! The method, per column of blocks (blocks side by side across the cut):
//! 1. Target planes: `targets_per_block` per block, from its entry face to its exit face;
//!    neighbouring rows share the face plane (module `grid`).
//! 2. Every plane's section is clipped to the column's range across the cut and fitted by
//!    an elastica keeping its end points (and, by default, its length), warm-started from
//!    the previous plane's fit (§7). Neighbouring columns clip at the same point of the same
//!    section, so their blades share end points (C⁰); with `C1` the fits also keep the
//!    design's tangent there.
//! 3. When a block's fit breaks the tolerance, its column is halved along the cutting
//!    direction and refitted, up to `split_depth` times (§6); rows of a column are halved
//!    together so that they still share their face sections.
//! 4. Each fit is extended along its own elastica to the blade's length, centred on the
//!    section; its two ends give the robots' targets ([`elastica::sweep::blade_pose`]).
//! 5. The swept surface between targets interpolates the fits' parameters
//!    ([`elastica::sweep::interpolate`]); it is compared with the design on `refine` extra
//!    planes between targets, in each plane (an upper bound of the distance to the surface).

/// Block grid, cutting planes, clipping a section to a block.
pub mod grid;
/// Rendering of the task's files.
pub mod outputs;
/// Report types.
pub mod report;

use elastica::blade::{extend_to_blade, Blade, BladeError, BladeParams};
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitError, FitParams, FitResult};
use elastica::segment::Segment;
use elastica::sweep::{blade_pose, frame_quaternion, interpolate, BladePose};
use geom::normals::SurfaceNormals;
use geom::slice::PlaneFrame;
use geom::surface::{Section, SectionParams};
use nalgebra::{Vector2, Vector3};
use rayon::prelude::*;

use crate::analyze::AnalyzeParams;
use crate::error::{HotcutError, JobError, Result};
use crate::job::{Continuity, FitConstraintSpec, TaskSpec};
use crate::load::{Blade as BladeLimits, ResolvedJob};
use crate::report::SurfaceInfo;
use crate::Progress;
use grid::{clip, clip_polyline, Clipped, CurvePlanes, Grid, Plane, Planes};
use report::*;

/// Share of the largest-distance tolerance by which a parameter-interpolated curve of the
/// swept surface may stray from the pointwise blend of its two neighbouring fits before
/// the blend is refitted instead (see `swept_curve`).
pub const SWEEP_SHARE: f64 = 0.1;

/// Parameters of [`hot_blade`], taken from the job.
#[derive(Debug, Clone, PartialEq)]
pub struct HotBladeParams {
    /// Poses per block.
    pub targets: usize,
    /// What each fit keeps.
    pub constraint: FitConstraintSpec,
    /// Continuity across block faces.
    pub continuity: Continuity,
    /// Largest number of halvings.
    pub split_depth: u32,
    /// Fit samples per section.
    pub samples: usize,
    /// Cutting speed (units/s).
    pub speed: f64,
    /// Flat-blade limit (radians).
    pub max_plane_angle: f64,
    /// Approach distance along the cut.
    pub approach: f64,
    /// Extra planes between targets on the deviation grid.
    pub refine: usize,
    /// Points per curve on the deviation grid and in the meshes.
    pub grid_points: usize,
    /// Blade limits.
    pub blade: BladeLimits,
    /// RMS tolerance.
    pub tolerance_rms: f64,
    /// Largest-distance tolerance.
    pub tolerance_max: f64,
    /// Sectioning (smoothing of polyline sections).
    pub sectioning: SectionParams,
}

impl HotBladeParams {
    /// The parameters of a resolved `HotBlade` job (`None` for other tasks).
    pub fn from_job(job: &ResolvedJob) -> Option<Self> {
        let TaskSpec::HotBlade {
            targets_per_block,
            constraint,
            continuity,
            split_depth,
            samples,
            speed,
            max_plane_angle,
            approach,
            refine,
        } = &job.job.task
        else {
            return None;
        };
        let per_mm = job.job.units.per_mm();
        Some(Self {
            targets: *targets_per_block as usize,
            constraint: *constraint,
            continuity: *continuity,
            split_depth: *split_depth,
            samples: *samples as usize,
            speed: speed.unwrap_or(7.0 * per_mm),
            max_plane_angle: *max_plane_angle,
            approach: approach.unwrap_or(50.0 * per_mm),
            refine: *refine as usize,
            grid_points: 60,
            blade: job.blade.clone(),
            tolerance_rms: job.job.tolerance.rms,
            tolerance_max: job.job.tolerance.max,
            sectioning: AnalyzeParams::sectioning(job),
        })
    }
}

/// One fitted section of a block.
#[derive(Debug, Clone)]
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
}

/// A vertex of the rationalized surface mesh with its deviation from the design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceVertex {
    /// World position.
    pub position: Vector3<f64>,
    /// Distance to the design section in its plane.
    pub deviation: f64,
}

/// One block's result.
#[derive(Debug, Clone)]
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

/// The result of a `HotBlade` run.
#[derive(Debug, Clone)]
pub struct HotBladeRun {
    /// Every plane the run used: targets first (by row), then the deviation planes.
    pub planes: Vec<Plane>,
    /// The grid.
    pub grid: Grid,
    /// Blocks, in report order.
    pub blocks: Vec<BlockResult>,
    /// Settings used.
    pub params: HotBladeParams,
    /// The report.
    pub report: HotBladeReport,
}

fn arr(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// A column part: a range across the cut, halved `level` times from column `column`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Part {
    column: usize,
    level: u32,
    range: (f64, f64),
}

/// A part fitted on every target plane.
struct FittedPart {
    part: Part,
    /// Per global target plane.
    fits: Vec<Option<FittedSection>>,
}

/// Everything the per-part work needs.
struct Context<'a> {
    params: &'a HotBladeParams,
    grid: &'a Grid,
    planes: &'a [Plane],
    sections: &'a [Vec<Section>],
    normals: &'a SurfaceNormals<'a>,
    path: &'a std::path::Path,
}

/// Runs the task on a resolved job.
///
/// # Errors
/// [`HotcutError::Invalid`] when the job is not a `HotBlade` job or lacks a surface or
/// block; [`HotcutError::Geom`] when sectioning fails; [`HotcutError::Task`] when a
/// section cannot be fitted.
pub fn hot_blade(
    job: &ResolvedJob,
    params: &HotBladeParams,
    progress: &dyn Progress,
) -> Result<HotBladeRun> {
    let invalid = |pointer: &str, message: &str| {
        HotcutError::Invalid(vec![JobError::Semantic {
            path: job.path.clone(),
            pointer: pointer.into(),
            message: message.into(),
        }])
    };
    let surface = job
        .surface
        .as_ref()
        .ok_or_else(|| invalid("/surface", "task HotBlade needs a surface"))?;
    let block = job
        .job
        .block
        .as_ref()
        .ok_or_else(|| invalid("/block", "task HotBlade needs a block"))?;
    let geom_err = |context: &str| {
        let path = job.path.clone();
        let context = context.to_string();
        move |source| HotcutError::Geom {
            path,
            context,
            source,
        }
    };
    let frame =
        PlaneFrame::from_direction(job.direction).map_err(geom_err("the cutting direction"))?;
    let extent = [
        surface.extent_along(&frame.normal),
        surface.extent_along(&frame.u),
        surface.extent_along(&frame.v),
    ];
    let origin = block.origin.map(|o| {
        let o = Vector3::new(o.0, o.1, o.2);
        [frame.normal.dot(&o), frame.u.dot(&o), frame.v.dot(&o)]
    });
    let grid = Grid::new(
        frame,
        [block.size.0, block.size.1, block.size.2],
        extent,
        origin,
    );
    let plane_family = match &job.job.cutting.curve {
        Some(points) => Planes::Curve(CurvePlanes::new(frame, points)),
        None => Planes::Parallel(frame),
    };

    // target planes (shared faces once), then the deviation planes between targets
    let mut positions: Vec<f64> = Vec::new();
    let mut row_targets: Vec<Vec<usize>> = Vec::with_capacity(grid.rows);
    for r in 0..grid.rows {
        let mut ids = Vec::with_capacity(params.targets);
        for a in grid.row_planes(r, params.targets) {
            let id = match positions.last() {
                Some(&last) if last == a => positions.len() - 1,
                _ => {
                    positions.push(a);
                    positions.len() - 1
                }
            };
            ids.push(id);
        }
        row_targets.push(ids);
    }
    let targets = positions.len();
    // deviation planes: for target pair (j, j+1) of a row, `refine` planes in between
    let mut between: Vec<Vec<(usize, f64)>> = vec![Vec::new(); targets];
    for ids in &row_targets {
        for w in ids.windows(2) {
            let (a, b) = (positions[w[0]], positions[w[1]]);
            for k in 1..=params.refine {
                let t = k as f64 / (params.refine + 1) as f64;
                positions.push(a + (b - a) * t);
                between[w[0]].push((positions.len() - 1, t));
            }
        }
    }
    let planes: Vec<Plane> = positions.iter().map(|&a| plane_family.at(a)).collect();

    progress.start("sectioning", planes.len() as u64);
    let frames: Vec<(PlaneFrame, f64)> = planes.iter().map(|p| (p.frame, p.offset)).collect();
    let all = surface
        .sections_at(&frames, &params.sectioning, &|| progress.tick())
        .map_err(geom_err("sectioning the surface"))?;
    progress.finish();
    let mut sections: Vec<Vec<Section>> = vec![Vec::new(); planes.len()];
    for s in all {
        let i = s.index;
        sections[i].push(s);
    }
    let normals = SurfaceNormals::new(surface, 200).map_err(geom_err("surface normals"))?;
    let ctx = Context {
        params,
        grid: &grid,
        planes: &planes,
        sections: &sections,
        normals: &normals,
        path: &job.path,
    };

    // fit columns, halving those over tolerance
    let mut pending: Vec<Part> = (0..grid.cols)
        .map(|c| Part {
            column: c,
            level: 0,
            range: grid.col_range(c),
        })
        .collect();
    let mut done: Vec<FittedPart> = Vec::new();
    let mut splits: Vec<SplitInfo> = Vec::new();
    while !pending.is_empty() {
        progress.start("fitting sections", (pending.len() * targets) as u64);
        let fitted: Vec<Result<FittedPart>> = pending
            .par_iter()
            .map(|part| fit_part(&ctx, *part, targets, progress))
            .collect();
        progress.finish();
        let mut next = Vec::new();
        for f in fitted {
            let f = f?;
            let worst = f
                .fits
                .iter()
                .flatten()
                .map(|s| s.fit.max)
                .fold(0.0, f64::max);
            let over = f
                .fits
                .iter()
                .flatten()
                .any(|s| s.fit.rms > params.tolerance_rms || s.fit.max > params.tolerance_max);
            if over && f.part.level < params.split_depth {
                let Part {
                    column,
                    level,
                    range,
                } = f.part;
                let mid = 0.5 * (range.0 + range.1);
                splits.push(SplitInfo {
                    column,
                    level: level + 1,
                    range: [range.0, range.1],
                    max_fit_distance: worst,
                });
                next.push(Part {
                    column,
                    level: level + 1,
                    range: (range.0, mid),
                });
                next.push(Part {
                    column,
                    level: level + 1,
                    range: (mid, range.1),
                });
            } else {
                done.push(f);
            }
        }
        pending = next;
    }
    done.sort_by(|a, b| a.part.range.0.total_cmp(&b.part.range.0));

    // blocks: by row, then across the cut
    progress.start("blocks", (grid.rows * done.len()) as u64);
    let work: Vec<(usize, usize)> = (0..grid.rows)
        .flat_map(|r| (0..done.len()).map(move |p| (r, p)))
        .collect();
    let built: Vec<Option<BlockResult>> = work
        .par_iter()
        .map(|&(r, p)| {
            let b = build_block(&ctx, &done[p], r, &row_targets[r], &between);
            progress.tick();
            b
        })
        .collect();
    progress.finish();
    let mut blocks: Vec<BlockResult> = built.into_iter().flatten().collect();
    for (i, b) in blocks.iter_mut().enumerate() {
        b.report.block = i + 1;
    }

    // what neighbouring blades share across faces
    let (mut gap, mut angle) = (0.0f64, 0.0f64);
    for w in done.windows(2) {
        if w[0].part.range.1 != w[1].part.range.0 {
            continue;
        }
        for (l, r) in w[0].fits.iter().zip(&w[1].fits) {
            if let (Some(l), Some(r)) = (l, r) {
                let (Ok(el), Ok(er)) = (l.fit.segment.eval(1.0), r.fit.segment.eval(0.0)) else {
                    continue;
                };
                gap = gap.max((el.p[0] - er.p[0]).hypot(el.p[1] - er.p[1]));
                let d = (el.tangent[0] * er.tangent[1] - el.tangent[1] * er.tangent[0])
                    .atan2(el.tangent[0] * er.tangent[0] + el.tangent[1] * er.tangent[1]);
                angle = angle.max(d.abs());
            }
        }
    }

    let reports: Vec<BlockReport> = blocks.iter().map(|b| b.report.clone()).collect();
    let flagged = FlagCounts::of(&reports);
    let fold = |f: &dyn Fn(&BlockReport) -> f64| reports.iter().map(f).fold(0.0, f64::max);
    let summary = HotBladeSummary {
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
        max_face_gap: gap,
        max_face_angle: angle,
        tangent_failures: reports.iter().map(|b| b.tangent_failures).sum(),
        all_ok: reports.iter().all(|b| !b.flags.any()),
        flagged,
    };
    let report = HotBladeReport {
        job: job.job.name.clone(),
        task: "HotBlade".into(),
        units: job.job.units,
        surface: SurfaceInfo::of(job, surface),
        settings: HotBladeSettings {
            targets_per_block: params.targets,
            constraint: params.constraint,
            continuity: params.continuity,
            split_depth: params.split_depth,
            samples: params.samples,
            refine: params.refine,
            planes: match plane_family {
                Planes::Parallel(_) => "Parallel".into(),
                Planes::Curve(_) => "Curve".into(),
            },
            blade_length: params.blade.length,
            max_curvature: params.blade.max_curvature,
            max_inflections: params.blade.max_inflections,
            tolerance_rms: params.tolerance_rms,
            tolerance_max: params.tolerance_max,
            max_plane_angle: params.max_plane_angle,
            speed: params.speed,
            approach: params.approach,
        },
        grid: GridInfo {
            axis_d: arr(&frame.normal),
            axis_u: arr(&frame.u),
            axis_v: arr(&frame.v),
            size: grid.size,
            origin: arr(&grid.world(grid.origin)),
            rows: grid.rows,
            columns: grid.cols,
        },
        summary,
        splits,
        blocks: reports,
    };
    Ok(HotBladeRun {
        planes,
        grid,
        blocks: blocks.into_iter().collect(),
        params: params.clone(),
        report,
    })
}

/// The longest clipped part of a plane's section pieces as a dense polyline (for the
/// deviation grid; see [`grid::clip_polyline`]).
fn design_polyline(
    ctx: &Context<'_>,
    plane: usize,
    range: (f64, f64),
    n: usize,
) -> Option<Vec<[f64; 2]>> {
    let length = |p: &[[f64; 2]]| {
        p.windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum::<f64>()
    };
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

/// Sweeps of warm-started fits over a part's planes (§7: each section starts from its
/// neighbour's fit). Forward, each plane keeps the better of a cold fit and one warm-started
/// from the plane before; then backward and forward again with warm starts from the plane
/// after / before, a fit replaced only when the new one is better, until a sweep changes
/// nothing (at most `MAX_SWEEPS`). On long, nearly straight sections any single start
/// lands in a poor local minimum now and then (an arc 0.6 mm off where an elastica fits
/// to 0.003 mm); a good fit found anywhere then spreads to its neighbours.
fn sweep_fits(
    designs: &[Option<Clipped>],
    constraint: FitConstraint,
) -> std::result::Result<Vec<Option<FitResult>>, (usize, FitError)> {
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
            (_, c) => c.map_err(|e| (plane, e))?,
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

fn fit_part(
    ctx: &Context<'_>,
    part: Part,
    targets: usize,
    progress: &dyn Progress,
) -> Result<FittedPart> {
    let p = ctx.params;
    let constraint = match p.constraint {
        FitConstraintSpec::EndPointsAndLength => FitConstraint::EndPointsAndLength,
        _ => FitConstraint::EndPoints,
    };
    let task_err = |message: String| HotcutError::Task {
        path: ctx.path.to_path_buf(),
        message,
    };
    let designs: Vec<Option<Clipped>> = (0..targets)
        .map(|plane| design_part(ctx, plane, part.range, p.samples))
        .collect();
    let c0 = sweep_fits(&designs, constraint).map_err(|(plane, e)| {
        task_err(format!(
            "column {} (range {:.6}..{:.6}), plane {plane}: {e}",
            part.column, part.range.0, part.range.1
        ))
    })?;
    let mut fits = Vec::with_capacity(targets);
    let mut warm: Option<Segment> = None;
    for (plane, (design, fit)) in designs.into_iter().zip(c0).enumerate() {
        progress.tick();
        let (Some(design), Some(mut fit)) = (design, fit) else {
            fits.push(None);
            continue;
        };
        let mut tangents_kept = true;
        if p.continuity == Continuity::C1 {
            let (t0, t1) = design_tangents(ctx, plane, &design, part.range);
            match elastica::fit::fit_with_end_tangents(
                &design.points,
                &design.s,
                &fit,
                warm.as_ref(),
                t0,
                t1,
                constraint,
            ) {
                Ok(f) => fit = f,
                // keep the C⁰ fit; the block reports it and the face angle shows it
                Err(_) => tangents_kept = false,
            }
        }
        warm = Some(fit.segment);
        let blade = make_blade(&fit.segment, &p.blade)
            .map_err(|e| task_err(format!("plane {plane}: {e}")))?;
        let plane_ref = &ctx.planes[plane];
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
        fits.push(Some(FittedSection {
            plane,
            design,
            fit,
            blade,
            pose,
            plane_angle,
            tangents_kept,
        }));
    }
    Ok(FittedPart { part, fits })
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

/// The fit extended to the blade's length; a section longer than the blade keeps its own
/// length (and its block is flagged).
fn make_blade(segment: &Segment, limits: &BladeLimits) -> std::result::Result<Blade, BladeError> {
    let bp = BladeParams {
        length: limits.length.max(segment.length()),
        lead_in_share: 0.5,
        max_curvature: Some(limits.max_curvature),
        max_inflections: Some(limits.max_inflections as usize),
    };
    extend_to_blade(segment, &bp)
}

fn build_block(
    ctx: &Context<'_>,
    part: &FittedPart,
    row: usize,
    row_targets: &[usize],
    between: &[Vec<(usize, f64)>],
) -> Option<BlockResult> {
    let p = ctx.params;
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
    let size = [
        grid.size[0],
        part.part.range.1 - part.part.range.0,
        grid.size[2],
    ];

    // deviation grid and mesh: each target plane, then its `refine` planes towards the next
    let m = p.grid_points.max(2);
    let mut surface: Vec<Vec<SurfaceVertex>> = Vec::new();
    let mut blended = 0usize;
    let mut max_dev = 0.0f64;
    for (k, &t) in row_targets.iter().enumerate() {
        let Some(a) = &part.fits[t] else { continue };
        let mut rows: Vec<(usize, Vec<[f64; 2]>)> =
            vec![(t, sample_blend(&a.fit.segment, None, 0.0, m))];
        if let Some(&next) = row_targets.get(k + 1) {
            if let Some(b) = &part.fits[next] {
                for &(plane, w) in &between[t] {
                    let (pts, refit) = swept_curve(
                        &a.fit.segment,
                        &b.fit.segment,
                        w,
                        m,
                        SWEEP_SHARE * p.tolerance_max,
                    );
                    blended += usize::from(refit);
                    rows.push((plane, pts));
                }
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
                    max_dev = max_dev.max(deviation);
                    SurfaceVertex {
                        position: pl.frame.to_world(pl.offset, &Vector2::new(q[0], q[1])),
                        deviation,
                    }
                })
                .collect();
            surface.push(verts);
        }
    }

    // overlaps: each plane's section must lie strictly ahead of the previous plane
    let mut overlaps = Vec::new();
    for (k, w) in sections.windows(2).enumerate() {
        let (pa, pb) = (&ctx.planes[w[0].plane], &ctx.planes[w[1].plane]);
        if pa.frame == pb.frame {
            continue;
        }
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
        let ahead = side(pa, &w[1]).0 > 0.0;
        let behind = side(pb, &w[0]).1 < 0.0;
        if !(ahead && behind) {
            overlaps.push([k, k + 1]);
        }
    }

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
    let worst_section = sections
        .iter()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |(bi, bv), (i, s)| {
            if s.fit.l2 > bv {
                (i, s.fit.l2)
            } else {
                (bi, bv)
            }
        })
        .0;
    let fold = |f: &dyn Fn(&FittedSection) -> f64| sections.iter().map(f).fold(0.0, f64::max);
    let max_rms = fold(&|s| s.fit.rms);
    let max_fit = fold(&|s| s.fit.max);
    let max_k = fold(&|s| s.blade.max_abs_curvature);
    let max_angle = fold(&|s| s.plane_angle);
    let max_infl = sections
        .iter()
        .map(|s| s.blade.inflections)
        .max()
        .unwrap_or(0);
    let flags = Flags {
        approximation: max_rms > p.tolerance_rms || max_fit > p.tolerance_max,
        blade_strain: sections.iter().any(|s| !s.blade.curvature_ok),
        shape: sections.iter().any(|s| !s.blade.inflections_ok),
        blade_length: sections.iter().any(|s| s.design.length > p.blade.length),
        flat_blade: max_angle > p.max_plane_angle,
        block_height,
        overlap: !overlaps.is_empty(),
    };
    let report = BlockReport {
        block: 0,
        row,
        column: part.part.column,
        split_level: part.part.level,
        origin: arr(&origin),
        size,
        sections: sections.len(),
        missing_sections: row_targets.len() - sections.len(),
        l2: Stats::of(sections.iter().map(|s| s.fit.l2)),
        max_rms,
        max_fit_distance: max_fit,
        max_deviation: max_dev,
        section_length: Stats::of(sections.iter().map(|s| s.design.length)),
        max_abs_curvature: max_k,
        max_inflections: max_infl,
        max_plane_angle: max_angle,
        worst_section,
        blended_planes: blended,
        tangent_failures: sections.iter().filter(|s| !s.tangents_kept).count(),
        overlaps,
        flags,
    };
    Some(BlockResult {
        report,
        rotation: frame_quaternion(&grid.frame.normal, &grid.frame.v),
        sections,
        surface,
    })
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

/// Distance from `q` to a polyline.
pub(crate) fn distance_to_polyline(q: [f64; 2], poly: &[[f64; 2]]) -> f64 {
    let mut best = f64::INFINITY;
    for w in poly.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = (q[0] - a[0] - t * dx).hypot(q[1] - a[1] - t * dy);
        best = best.min(d);
    }
    if poly.len() == 1 {
        best = (q[0] - poly[0][0]).hypot(q[1] - poly[0][1]);
    }
    best
}
