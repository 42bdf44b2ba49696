//! The run, step by step: plane layout, sectioning, fitting columns (halving those over
//! tolerance), building blocks, measuring the faces neighbouring blocks share.

use geom::normals::SurfaceNormals;
use geom::slice::PlaneFrame;
use geom::surface::{Section, Surface};
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::block::build_block;
use crate::fit::fit_part;
use crate::grid::{CurvePlanes, Grid, Plane, Planes};
use crate::result::{BlockResult, FittedSection, HotBladeSummary, Rationalization, SplitInfo};
use crate::{HotBladeError, Params, Progress, ProgressFn};

/// A column part: a range across the cut, halved `level` times from column `column`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Part {
    pub column: usize,
    pub level: u32,
    pub range: (f64, f64),
}

/// A part fitted on every target plane.
pub(crate) struct FittedPart {
    pub part: Part,
    /// Per global target plane.
    pub fits: Vec<Option<FittedSection>>,
}

/// Everything the per-part work needs.
pub(crate) struct Context<'a> {
    pub params: &'a Params,
    pub grid: &'a Grid,
    pub planes: &'a [Plane],
    /// Per target plane, the grid `d` range of the row(s) it is a target of.
    pub plane_rows: &'a [(f64, f64)],
    pub sections: &'a [Vec<Section>],
    pub normals: &'a SurfaceNormals<'a>,
}

/// Where the planes are: every plane's position along the grid's `d`, targets first.
struct Layout {
    /// The grid.
    grid: Grid,
    /// Whether the planes follow a curve.
    follows_curve: bool,
    /// Every plane: the target planes (shared faces once), then the deviation planes.
    planes: Vec<Plane>,
    /// Number of target planes (they come first in `planes`).
    targets: usize,
    /// Per row, its target planes in cutting order.
    row_targets: Vec<Vec<usize>>,
    /// Per target plane, the grid `d` range of the row(s) it is a target of (both rows'
    /// at a shared face).
    plane_rows: Vec<(f64, f64)>,
    /// Per target plane, the deviation planes towards the next target of its row, with
    /// their share `t` of the way.
    between: Vec<Vec<(usize, f64)>>,
}

fn geom_err(context: &'static str) -> impl FnOnce(geom::GeomError) -> HotBladeError {
    move |source| HotBladeError::Geom { context, source }
}

/// Runs the pipeline on `surface` (see the [crate] documentation).
///
/// # Errors
/// [`HotBladeError::Invalid`] for parameters out of range ([`Params::problems`]);
/// [`HotBladeError::Geom`] when sectioning fails;
/// [`HotBladeError::Fit`] when a section cannot be fitted; [`HotBladeError::Blade`] when a
/// fit cannot be extended to the blade.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use hotblade::{rationalize, HotBladeError, Params};
///
/// // a circular cylinder of radius 2000 mm, axis along the cut: every section is the same
/// // arc, which an elastica (a circle is one, λ = 0) fits exactly
/// let z = Expr::parse("sqrt(4000000 - (y - 250)^2) - 2000")?;
/// let surface = Surface::HeightField(HeightField::try_new(z, (0.0, 600.0), (0.0, 500.0))?);
/// let params = Params { block: [600.0, 600.0, 400.0], origin: Some([0.0, 0.0, -200.0]), targets: 3, ..Params::default() };
/// let cut = rationalize(&surface, &params, &|_| {})?;
/// assert_eq!((cut.blocks.len(), cut.summary.sections), (1, 3));
/// assert!(cut.summary.max_fit_distance < 1e-6);
/// for s in &cut.blocks[0].sections {
///     // the blade's curvature is the cylinder's, 1/2000 mm⁻¹, and it never inflects
///     assert!((s.blade.max_abs_curvature - 1.0 / 2000.0).abs() < 1e-9);
///     assert_eq!(s.blade.inflections, 0);
/// }
/// // parameters out of range are refused before anything runs
/// let bad = Params { targets: 0, ..params };
/// assert!(matches!(rationalize(&surface, &bad, &|_| {}), Err(HotBladeError::Invalid { field: "targets", .. })));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn rationalize(
    surface: &Surface,
    params: &Params,
    progress: &ProgressFn<'_>,
) -> Result<Rationalization, HotBladeError> {
    if let Some(p) = params.problems().into_iter().next() {
        return Err(HotBladeError::Invalid {
            field: p.field,
            message: p.message,
        });
    }
    let size = run_size(surface, params)?;
    if !(size.rows * size.cols <= MAX_BLOCKS && size.planes <= MAX_PLANES) {
        return Err(HotBladeError::Invalid {
            field: "block",
            message: format!(
                "is far smaller than the surface: {:.3e} × {:.3e} blocks on {:.3e} planes (at most {MAX_BLOCKS:.0e} blocks and {MAX_PLANES:.0e} planes)",
                size.rows, size.cols, size.planes
            ),
        });
    }
    let layout = layout(surface, params)?;
    let sections = section(surface, &layout.planes, params, progress)?;
    let normals = SurfaceNormals::new(surface, 200).map_err(geom_err("surface normals"))?;
    let ctx = Context {
        params,
        grid: &layout.grid,
        planes: &layout.planes,
        plane_rows: &layout.plane_rows,
        sections: &sections,
        normals: &normals,
    };
    let (done, splits) = fit_columns(&ctx, layout.targets, progress)?;
    let blocks = build_blocks(&ctx, &layout, &done, progress);
    let summary = HotBladeSummary::of(&blocks, face_joints(&done));
    Ok(Rationalization {
        planes: layout.planes,
        grid: layout.grid,
        follows_curve: layout.follows_curve,
        blocks,
        splits,
        summary,
    })
}

/// How big a run on `surface` is, counted before anything is allocated (every count in
/// `f64`, so an absurd block size gives a huge number, not an overflow).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct RunSize {
    /// Blocks along the cut.
    pub rows: f64,
    /// Blocks across the cut.
    pub cols: f64,
    /// Planes the surface is sectioned on (targets and deviation planes).
    pub planes: f64,
    /// Section fits at most (every column halved `split_depth` times).
    pub fits: f64,
}

/// Most blocks, and most planes, a run may lay out: beyond these a grid is a mistake (a
/// block far smaller than the surface), whatever the machine.
pub const MAX_BLOCKS: f64 = 1e6;
/// See [`MAX_BLOCKS`].
pub const MAX_PLANES: f64 = 1e7;

/// The [`RunSize`] of a run of `params` on `surface`.
///
/// # Errors
/// [`HotBladeError::Geom`] for a cutting direction that spans no frame.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use hotblade::{run_size, Params};
/// // 1.8 m along the cut and 1 m across, in blocks of 600 mm: 3 rows of 2 columns
/// let surface = Surface::HeightField(HeightField::try_new(Expr::parse("0")?, (0.0, 1800.0), (0.0, 1000.0))?);
/// let size = run_size(&surface, &Params { block: [600.0, 600.0, 400.0], ..Params::default() })?;
/// assert_eq!((size.rows, size.cols), (3.0, 2.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run_size(surface: &Surface, params: &Params) -> Result<RunSize, HotBladeError> {
    let frame =
        PlaneFrame::from_direction(params.direction).map_err(geom_err("the cutting direction"))?;
    let span = |d: &Vector3<f64>, origin: Option<f64>| {
        let (lo, hi) = surface.extent_along(d);
        hi - origin.unwrap_or(lo)
    };
    let origin = params.origin.map(Vector3::from);
    let count = |d: &Vector3<f64>, size: f64| {
        let n = (span(d, origin.map(|o| d.dot(&o))) / size).ceil();
        if n.is_nan() {
            f64::INFINITY
        } else {
            n.max(1.0)
        }
    };
    let rows = count(&frame.normal, params.block[0]);
    let cols = count(&frame.u, params.block[1]);
    let t = params.targets as f64;
    let planes = rows * (t + (t - 1.0) * params.refine as f64);
    let fits = rows * cols * t * f64::from(1u32 << params.split_depth.min(16));
    Ok(RunSize {
        rows,
        cols,
        planes,
        fits,
    })
}

/// The grid over the surface and every plane: `targets` per block row (rows share their
/// face plane), then `refine` deviation planes between consecutive targets.
fn layout(surface: &Surface, params: &Params) -> Result<Layout, HotBladeError> {
    let frame =
        PlaneFrame::from_direction(params.direction).map_err(geom_err("the cutting direction"))?;
    let extent = [
        surface.extent_along(&frame.normal),
        surface.extent_along(&frame.u),
        surface.extent_along(&frame.v),
    ];
    let origin = params.origin.map(|o| {
        let o = Vector3::from(o);
        [frame.normal.dot(&o), frame.u.dot(&o), frame.v.dot(&o)]
    });
    let grid = Grid::new(frame, params.block, extent, origin);
    let family = match &params.curve {
        Some(points) => Planes::Curve(CurvePlanes::new(frame, points)),
        None => Planes::Parallel(frame),
    };

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
    let mut plane_rows = vec![(f64::INFINITY, f64::NEG_INFINITY); targets];
    for (r, ids) in row_targets.iter().enumerate() {
        let (lo, hi) = grid.row_range(r);
        for &id in ids {
            plane_rows[id] = (plane_rows[id].0.min(lo), plane_rows[id].1.max(hi));
        }
    }
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
    Ok(Layout {
        grid,
        follows_curve: matches!(family, Planes::Curve(_)),
        planes: positions.iter().map(|&a| family.at(a)).collect(),
        targets,
        row_targets,
        plane_rows,
        between,
    })
}

/// The surface's sections on every plane, grouped by plane.
fn section(
    surface: &Surface,
    planes: &[Plane],
    params: &Params,
    progress: &ProgressFn<'_>,
) -> Result<Vec<Vec<Section>>, HotBladeError> {
    progress(Progress::Start {
        step: "sectioning",
        total: planes.len() as u64,
    });
    let frames: Vec<(PlaneFrame, f64)> = planes.iter().map(|p| (p.frame, p.offset)).collect();
    let all = surface
        .sections_at(&frames, &params.sectioning, &|| progress(Progress::Tick))
        .map_err(geom_err("sectioning the surface"))?;
    progress(Progress::Finish);
    let mut sections: Vec<Vec<Section>> = vec![Vec::new(); planes.len()];
    for s in all {
        let i = s.index;
        sections[i].push(s);
    }
    Ok(sections)
}

/// Fits every column on every target plane; a column whose fits break the tolerance is
/// halved and refitted, up to `split_depth` times. Returns the parts sorted across the
/// cut, and the halvings made.
fn fit_columns(
    ctx: &Context<'_>,
    targets: usize,
    progress: &ProgressFn<'_>,
) -> Result<(Vec<FittedPart>, Vec<SplitInfo>), HotBladeError> {
    let params = ctx.params;
    let mut pending: Vec<Part> = (0..ctx.grid.cols)
        .map(|c| Part {
            column: c,
            level: 0,
            range: ctx.grid.col_range(c),
        })
        .collect();
    let mut done: Vec<FittedPart> = Vec::new();
    let mut splits: Vec<SplitInfo> = Vec::new();
    // each round halves every part it keeps, so at most split_depth + 1 rounds
    while !pending.is_empty() {
        progress(Progress::Start {
            step: "fitting sections",
            total: (pending.len() * targets) as u64,
        });
        let fitted: Vec<Result<FittedPart, HotBladeError>> = pending
            .par_iter()
            .map(|part| fit_part(ctx, *part, targets, progress))
            .collect();
        progress(Progress::Finish);
        let mut next = Vec::new();
        for f in fitted {
            let f = f?;
            let fits = || f.fits.iter().flatten();
            let over = fits()
                .any(|s| s.fit.rms > params.tolerance_rms || s.fit.max > params.tolerance_max);
            if !(over && f.part.level < params.split_depth) {
                done.push(f);
                continue;
            }
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
                max_fit_distance: fits().map(|s| s.fit.max).fold(0.0, f64::max),
            });
            for half in [(range.0, mid), (mid, range.1)] {
                next.push(Part {
                    column,
                    level: level + 1,
                    range: half,
                });
            }
        }
        pending = next;
    }
    done.sort_by(|a, b| a.part.range.0.total_cmp(&b.part.range.0));
    Ok((done, splits))
}

/// Every block with surface, by row then across the cut, numbered from 1.
fn build_blocks(
    ctx: &Context<'_>,
    layout: &Layout,
    done: &[FittedPart],
    progress: &ProgressFn<'_>,
) -> Vec<BlockResult> {
    let rows = ctx.grid.rows;
    progress(Progress::Start {
        step: "blocks",
        total: (rows * done.len()) as u64,
    });
    let work: Vec<(usize, usize)> = (0..rows)
        .flat_map(|r| (0..done.len()).map(move |p| (r, p)))
        .collect();
    let built: Vec<Option<BlockResult>> = work
        .par_iter()
        .map(|&(r, p)| {
            let b = build_block(ctx, &done[p], r, &layout.row_targets[r], &layout.between);
            progress(Progress::Tick);
            b
        })
        .collect();
    progress(Progress::Finish);
    let mut blocks: Vec<BlockResult> = built.into_iter().flatten().collect();
    for (i, b) in blocks.iter_mut().enumerate() {
        b.report.block = i + 1;
    }
    blocks
}

/// The largest gap and tangent angle between the shared ends of neighbouring parts' fits.
fn face_joints(done: &[FittedPart]) -> (f64, f64) {
    let (mut gap, mut angle) = (0.0f64, 0.0f64);
    for w in done.windows(2) {
        if w[0].part.range.1 != w[1].part.range.0 {
            continue;
        }
        for (l, r) in w[0].fits.iter().zip(&w[1].fits) {
            let (Some(l), Some(r)) = (l, r) else { continue };
            let (Ok(el), Ok(er)) = (l.fit.segment.eval(1.0), r.fit.segment.eval(0.0)) else {
                continue;
            };
            gap = gap.max((el.p[0] - er.p[0]).hypot(el.p[1] - er.p[1]));
            let d = (el.tangent[0] * er.tangent[1] - el.tangent[1] * er.tangent[0])
                .atan2(el.tangent[0] * er.tangent[0] + el.tangent[1] * er.tangent[1]);
            angle = angle.max(d.abs());
        }
    }
    (gap, angle)
}
