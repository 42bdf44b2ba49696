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

/// Building a block from its fitted sections: swept surface, deviation, flags.
mod block;
/// Fitting a part's sections: sweeps of warm-started fits, C¹ tangents, blades and poses.
pub(crate) mod fit;
/// Block grid, cutting planes, clipping a section to a block.
pub mod grid;
/// Rendering of the task's files.
pub mod outputs;
/// Report types.
pub mod report;

use elastica::blade::Blade;
use elastica::fit::FitResult;
use elastica::sweep::BladePose;
use geom::normals::SurfaceNormals;
use geom::slice::PlaneFrame;
use geom::surface::{Section, SectionParams};
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::analyze::AnalyzeParams;
use crate::error::{HotcutError, JobError, Result};
use crate::job::{Continuity, FitConstraintSpec, TaskSpec};
use crate::load::{Blade as BladeLimits, ResolvedJob};
use crate::report::SurfaceInfo;
use crate::Progress;
use block::build_block;
use fit::fit_part;
use grid::{Clipped, CurvePlanes, Grid, Plane, Planes};
use report::*;

/// Share of the largest-distance tolerance by which a parameter-interpolated curve of the
/// swept surface may stray from the pointwise blend of its two neighbouring fits before
/// the blend is refitted instead (see `swept_curve`).
pub const SWEEP_SHARE: f64 = 0.1;

/// Shortest design part fitted, as a share of the blade length: shorter parts (slivers
/// where a plane grazes the surface inside the block) get no blade pose and count as missing
/// sections, since extending a fit of a few millimetres to the whole blade is meaningless.
pub const SHORTEST_PART: f64 = 0.05;

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
