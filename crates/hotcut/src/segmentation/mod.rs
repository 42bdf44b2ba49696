//! The `FacadeSegmentation` task (thesis ch. 5): the job's sections handed to one of the
//! `facade_seg` algorithms, then every piece rationalized with the `HotBlade` machinery
//! (an elastica per section part, warm-started sweeps, extended to the blade, posed for the
//! two robots), and the report, drawings and robot files.
//!
//! Entry points: [`SegmentationParams::from_job`](crate::segmentation::SegmentationParams::from_job)
//! and [`segment_facade`](crate::segmentation::segment_facade).
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("wavy.ron");
//! std::fs::write(&path, r#"Job(
//!     name: "wavy",
//!     surface: HeightField(z: "60*sin(y/150)", x: (0, 600), y: (0, 1800)),
//!     block: Block(size: (600, 600, 400)),
//!     blade: Blade(length: 800, max_curvature: 0.011),
//!     cutting: Cutting(sections: 6),
//!     task: FacadeSegmentation(algorithm: Inflection(symmetric: false), rationalize: false),
//! )"#).unwrap();
//! let job = hotcut::load::load_job(&path).unwrap();
//! let params = hotcut::segmentation::SegmentationParams::from_job(&job).unwrap();
//! let run = hotcut::segmentation::segment_facade(&job, &params, &hotcut::NoProgress).unwrap();
//! // every part of every piece holds at most two inflections
//! assert!(run.report.pieces.iter().all(|p| p.verdicts.shape));
//! assert_eq!(run.report.counts.pieces, run.segmentation.pieces.len());
//! ```

/// Rendering of the task's files.
pub mod outputs;
/// Report types.
pub mod report;

use elastica::blade::Blade;
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams, FitResult};
use elastica::sweep::{blade_pose, frame_quaternion, BladePose};
use facade_seg::inflection::{inflection_points, InflectionParams};
use facade_seg::longest::{longest_elastica, LongestParams};
use facade_seg::trace::{trace, TraceParams};
use facade_seg::{Constraints, Facade, Piece, Segmentation};
use geom::surface::SectionParams;
use rayon::prelude::*;

use crate::analyze::AnalyzeParams;
use crate::error::{HotcutError, JobError, Result};
use crate::hot_blade::fit::{make_blade, sweep_fits};
use crate::hot_blade::grid::Clipped;
use crate::hot_blade::outputs::{TargetsBlock, TargetsFile};
use crate::hot_blade::SHORTEST_PART;
use crate::job::{FitConstraintSpec, SegAlgorithmSpec, TaskSpec};
use crate::load::{Blade as BladeLimits, ResolvedJob};
use crate::Progress;
use report::*;

/// Parameters of [`segment_facade`], taken from the job.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentationParams {
    /// The algorithm and its options.
    pub algorithm: SegAlgorithmSpec,
    /// Points per section part for checks and fits.
    pub samples: usize,
    /// Whether pieces are rationalized and posed.
    pub rationalize: bool,
    /// What each piece's fits keep.
    pub constraint: FitConstraintSpec,
    /// Cutting speed (units/s).
    pub speed: f64,
    /// Approach distance along the cut.
    pub approach: f64,
    /// The production constraints of §5.1.
    pub constraints: Constraints,
    /// Blade limits as the job gives them.
    pub blade: BladeLimits,
    /// Sectioning of the facade.
    pub sectioning: SectionParams,
}

impl SegmentationParams {
    /// The parameters of a resolved `FacadeSegmentation` job (`None` for other tasks or
    /// without a block).
    pub fn from_job(job: &ResolvedJob) -> Option<Self> {
        let TaskSpec::FacadeSegmentation {
            algorithm,
            samples,
            rationalize,
            constraint,
            speed,
            approach,
        } = &job.job.task
        else {
            return None;
        };
        let block = job.job.block.as_ref()?;
        let per_mm = job.job.units.per_mm();
        Some(Self {
            algorithm: algorithm.clone(),
            samples: *samples as usize,
            rationalize: *rationalize,
            constraint: *constraint,
            speed: speed.unwrap_or(7.0 * per_mm),
            approach: approach.unwrap_or(50.0 * per_mm),
            constraints: Constraints {
                block: [block.size.0, block.size.1, block.size.2],
                blade_length: job.blade.length,
                max_curvature: job.blade.max_curvature,
                max_inflections: job.blade.max_inflections,
                tolerance_rms: job.job.tolerance.rms,
                tolerance_max: job.job.tolerance.max,
            },
            blade: job.blade.clone(),
            sectioning: AnalyzeParams::sectioning(job),
        })
    }
}

/// One section part of a piece, fitted and posed.
#[derive(Debug, Clone)]
pub struct PosedPart {
    /// Index of the part in the piece.
    pub part: usize,
    /// The design part (plane coordinates).
    pub design: Clipped,
    /// Its elastica.
    pub fit: FitResult,
    /// The blade: the fit extended to the blade length.
    pub blade: Blade,
    /// The 3D pose.
    pub pose: BladePose,
}

/// A rationalized piece.
#[derive(Debug, Clone)]
pub struct PosedPiece {
    /// Piece id.
    pub id: usize,
    /// Orientation `[w, x, y, z]` of the block axes (along the cut, across it, up).
    pub rotation: [f64; 4],
    /// Posed parts in cutting order (slivers shorter than [`SHORTEST_PART`] of the blade
    /// are left out).
    pub parts: Vec<PosedPart>,
}

/// The result of a `FacadeSegmentation` run.
#[derive(Debug, Clone)]
pub struct SegmentationRun {
    /// The prepared sections.
    pub facade: Facade,
    /// What the algorithm returned.
    pub segmentation: Segmentation,
    /// Rationalized pieces (empty when `rationalize` is off), in piece order.
    pub posed: Vec<PosedPiece>,
    /// Settings used.
    pub params: SegmentationParams,
    /// The report.
    pub report: SegmentationReport,
}

impl SegmentationRun {
    /// The robot targets: one "block" per posed piece, its poses in cutting order.
    pub fn targets(&self, units: crate::job::Units) -> TargetsFile {
        TargetsFile {
            units,
            blade_length: self.params.blade.length,
            blocks: self
                .posed
                .iter()
                .filter(|p| !p.parts.is_empty())
                .map(|p| TargetsBlock {
                    block: p.id,
                    origin: self.segmentation.pieces[p.id - 1].block.origin,
                    rotation: p.rotation,
                    poses: p.parts.iter().map(|q| q.pose).collect(),
                })
                .collect(),
        }
    }
}

/// Runs the task on a resolved job.
///
/// # Errors
/// [`HotcutError::Invalid`] when the job lacks a surface or block; [`HotcutError::Geom`]
/// when sectioning fails; [`HotcutError::Task`] when the algorithm cannot segment the
/// facade (e.g. a design curvature above the blade's) or a part cannot be fitted.
pub fn segment_facade(
    job: &ResolvedJob,
    params: &SegmentationParams,
    progress: &dyn Progress,
) -> Result<SegmentationRun> {
    let surface = job.surface.as_ref().ok_or_else(|| {
        HotcutError::Invalid(vec![JobError::Semantic {
            path: job.path.clone(),
            pointer: "/surface".into(),
            message: "task FacadeSegmentation needs a surface".into(),
        }])
    })?;
    let task_err = |message: String| HotcutError::Task {
        path: job.path.clone(),
        message,
    };
    progress.start("sectioning", params.sectioning.count as u64);
    let (frame, sections) = surface
        .sections(&params.sectioning, &|| progress.tick())
        .map_err(|source| HotcutError::Geom {
            path: job.path.clone(),
            context: "sectioning the facade".into(),
            source,
        })?;
    progress.finish();
    let facade = Facade::new(frame, &sections).map_err(|e| task_err(e.to_string()))?;
    let c = &params.constraints;
    let tick = || progress.tick();
    let samples = params.samples;
    let seg = match &params.algorithm {
        SegAlgorithmSpec::Inflection { symmetric } => {
            progress.start("inflection algorithm (rows)", 0);
            let p = InflectionParams {
                symmetric: *symmetric,
                samples,
                ..InflectionParams::default()
            };
            inflection_points(&facade, c, &p, &tick)
        }
        SegAlgorithmSpec::Trace {
            link_distance,
            merge_distance,
            min_sections,
        } => {
            progress.start("trace algorithm", 0);
            let p = TraceParams {
                link_distance: *link_distance,
                merge_distance: *merge_distance,
                min_sections: *min_sections as usize,
                samples,
            };
            trace(&facade, c, &p, &tick)
        }
        SegAlgorithmSpec::LongestElastica {
            precision,
            max_step,
        } => {
            progress.start("longest elastica (section parts)", 0);
            let p = LongestParams {
                precision: precision.unwrap_or(job.job.units.per_mm()),
                max_step: *max_step,
                samples,
                ..LongestParams::default()
            };
            longest_elastica(&facade, c, &p, &tick)
        }
    }
    .map_err(|e| task_err(format!("segmentation failed: {e}")))?;
    progress.finish();

    let posed = if params.rationalize {
        progress.start("rationalizing pieces", seg.pieces.len() as u64);
        let posed: Vec<Result<PosedPiece>> = seg
            .pieces
            .par_iter()
            .map(|piece| {
                let p = pose_piece(&facade, piece, params);
                progress.tick();
                p.map_err(|m| task_err(format!("piece {}: {m}", piece.id)))
            })
            .collect();
        progress.finish();
        posed.into_iter().collect::<Result<Vec<_>>>()?
    } else {
        Vec::new()
    };
    let report = SegmentationReport::new(job, surface, params, &facade, &seg, &posed);
    Ok(SegmentationRun {
        facade,
        segmentation: seg,
        posed,
        params: params.clone(),
        report,
    })
}

/// Fits every part of a piece (warm-started sweeps along the cut, as `HotBlade` does per
/// block), extends each fit to the blade and poses it.
fn pose_piece(
    facade: &Facade,
    piece: &Piece,
    params: &SegmentationParams,
) -> std::result::Result<PosedPiece, String> {
    let constraint = match params.constraint {
        FitConstraintSpec::EndPointsAndLength => FitConstraint::EndPointsAndLength,
        _ => FitConstraint::EndPoints,
    };
    let shortest = SHORTEST_PART * params.blade.length;
    let designs: Vec<Option<Clipped>> = piece
        .parts
        .iter()
        .map(|part| {
            let sec = facade.sections.iter().find(|s| s.index == part.plane)?;
            let (points, s) = sec.samples(part.s[0], part.s[1], params.samples);
            let length = part.s[1] - part.s[0];
            let angle = |a: [f64; 2], b: [f64; 2]| (b[1] - a[1]).atan2(b[0] - a[0]);
            let n = points.len();
            (length >= shortest && n >= 2).then(|| Clipped {
                end_angles: [
                    angle(points[0], points[1]),
                    angle(points[n - 2], points[n - 1]),
                ],
                points,
                s,
                length,
            })
        })
        .collect();
    let mut fits = sweep_fits(&designs, constraint)
        .map_err(|(k, e)| format!("section {}: {e}", piece.parts[k].plane))?;
    // a length-keeping fit over tolerance may sit in a poor local minimum that neither a
    // cold start nor its neighbours escape (a part with an inflection near one end): start
    // it again from the end-point fit, which has no length to keep
    if constraint == FitConstraint::EndPointsAndLength {
        for (design, fit) in designs.iter().zip(fits.iter_mut()) {
            let (Some(design), Some(f)) = (design, fit.as_mut()) else {
                continue;
            };
            if f.max <= params.constraints.tolerance_max {
                continue;
            }
            let run = |constraint, warm_start| {
                let fp = FitParams {
                    constraint,
                    warm_start,
                    ..FitParams::default()
                };
                fit_points_with_arclength(&design.points, &design.s, &fp).ok()
            };
            let better = run(FitConstraint::EndPoints, None)
                .and_then(|e| run(FitConstraint::EndPointsAndLength, Some(e.segment)));
            if let Some(b) = better.filter(|b| b.l2 < f.l2) {
                *f = b;
            }
        }
    }
    let mut parts = Vec::new();
    for (k, (design, fit)) in designs.into_iter().zip(fits).enumerate() {
        let (Some(design), Some(fit)) = (design, fit) else {
            continue;
        };
        let blade = make_blade(&fit.segment, &params.blade)
            .map_err(|e| format!("section {}: {e}", piece.parts[k].plane))?;
        let pose = blade_pose(&facade.frame, piece.parts[k].offset, &blade);
        parts.push(PosedPart {
            part: k,
            design,
            fit,
            blade,
            pose,
        });
    }
    Ok(PosedPiece {
        id: piece.id,
        rotation: frame_quaternion(&facade.frame.normal, &facade.frame.v),
        parts,
    })
}
