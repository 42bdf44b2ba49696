//! The `FacadeSegmentation` task (thesis ch. 5): the job's sections handed to one of the
//! [`facade_seg`] algorithms, then every piece rationalized
//! ([`facade_seg::rationalize`]: an elastica per section part, warm-started sweeps,
//! extended to the blade, posed for the robots that hold it), and the report, drawings and robot
//! files.
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
//! let hotcut::job::TaskSpec::FacadeSegmentation(task) = &job.task else { unreachable!() };
//! let out = hotcut::run::run_task(task, &job.context, &job.outputs, dir.path(), &hotcut::NoProgress)
//!     .unwrap();
//! // every part of every piece holds at most two inflections
//! assert!(out.report.pieces.iter().all(|p| p.verdicts.shape));
//! assert_eq!(out.report.counts.pieces, out.run.segmentation.pieces.len());
//! ```

/// Its files: `segmentation.svg`, `model.gltf`, `segmentation.obj`, `sections.csv`, robot
/// files.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// Its report.
pub mod report;

use elastica::clearance::Clearance;
use facade_seg::inflection::{inflection_points, InflectionParams};
use facade_seg::longest::{longest_elastica, LongestParams};
use facade_seg::rationalize::{pose_pieces, PosedPiece, RationalizeParams};
use facade_seg::trace::{trace, TraceParams};
use facade_seg::{Constraints, Facade, Segmentation};
use geom::surface::SectionParams;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::{blocks_spanned, section_cost, Estimate};
use crate::progress::Progress;
use crate::report::SurfaceInfo;
use crate::robot_cell::{self, CellPlan};
use crate::spec::defaults::{APPROACH_MM, BLADE_SPEED_MM_PER_S};
use crate::spec::{keep_length, FitConstraintSpec, OutputKind, OutputSpec};
use crate::task::{Output, Task};
use export::robot::Motion;
use report::{SegmentationReport, SegmentationSettings};

/// Facade segmentation for hot-blade cutting (thesis ch. 5): the sections of
/// `cutting` are split into pieces, each cut from one block, so that every part of a
/// section in a piece meets the production constraints (§5.1: blade length and block,
/// approximation, shape, blade strain); then each piece is rationalized (an elastica
/// per section part, extended to the blade, with its robot pose). Needs `block`. Write
/// `FacadeSegmentation(algorithm: Inflection(symmetric: false))`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FacadeSegmentation {
    /// The algorithm.
    pub algorithm: SegAlgorithmSpec,
    /// Points each section part is sampled at for its checks and fits (≥ 8).
    /// Default: 64.
    #[serde(default = "default_seg_samples")]
    #[schemars(range(min = 8, max = 100000))]
    pub samples: u32,
    /// Fit every piece's section parts by elastica and pose the blade on them (needed
    /// by `RobotTargets` and `Rapid`). Default: `true`.
    #[serde(default = "default_true")]
    pub rationalize: bool,
    /// What each piece's fitted elastica keeps of its section part: `EndPoints`, or
    /// `EndPointsAndLength`. Default: `EndPointsAndLength`.
    #[serde(default = "keep_length")]
    pub constraint: FitConstraintSpec,
    /// Cutting speed of the blade (> 0), job units per second. Default: 7 mm/s.
    #[serde(default)]
    pub speed: Option<f64>,
    /// Approach and retreat distance of the blade along the cut (≥ 0). Default: 50 mm.
    #[serde(default)]
    pub approach: Option<f64>,
    /// After the algorithm, pieces breaking a constraint that smaller pieces could meet
    /// are split (along their sections, at the worst place) until they meet it; no split
    /// leaves a section part shorter than this (> 0, job units). Default: a tenth of the
    /// smaller of the blade's length and the block's width across the cut.
    #[serde(default)]
    pub min_piece: Option<f64>,
}

/// How a facade is segmented (thesis ch. 5). With all fields at their defaults the
/// parentheses may be left out: `algorithm: Trace`.
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

/// The default `min_piece`: a tenth of the smaller of the blade's length and the block's
/// width across the cut (in the job's units, as both are).
fn default_min_piece(blade_length: f64, block_across: f64) -> f64 {
    0.1 * blade_length.min(block_across)
}

/// Most pieces refinement may leave (each is a block to cut).
const MAX_PIECES: usize = 20_000;

/// Parameters of a `FacadeSegmentation` run.
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
    /// Cutting speed and approach distance of the robot programs.
    pub motion: Motion,
    /// The production constraints of §5.1.
    pub constraints: Constraints,
    /// The blade.
    pub blade: hotblade::BladeLimits,
    /// Sectioning of the facade.
    pub sectioning: SectionParams,
    /// How the sections' inflections are found (the job's bisection and least turning).
    pub analysis: geom::analysis::CurveAnalysisParams,
    /// Precision of the longest-elastica search when the job leaves it out (1 mm).
    pub default_precision: f64,
    /// The refinement after the algorithm.
    pub refine: facade_seg::refine::RefineParams,
}

/// The result of a `FacadeSegmentation` run.
#[derive(Debug, Clone)]
pub struct SegmentationRun {
    /// The prepared sections.
    pub facade: Facade,
    /// What the algorithm returned, refined.
    pub segmentation: Segmentation,
    /// What the refinement did.
    pub refinement: facade_seg::refine::RefineReport,
    /// Rationalized pieces (empty when `rationalize` is off), in piece order.
    pub posed: Vec<PosedPiece>,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The robot cell's plan (when the job writes robot files and a piece has poses).
    pub cell: Option<CellPlan>,
}

const PTR: &str = "/task/FacadeSegmentation";

impl Task for FacadeSegmentation {
    const NAME: &'static str = "FacadeSegmentation";
    const REPORT_SCHEMA: &'static str = "facade-segmentation-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Obj, outputs::obj),
        Output::new(OutputKind::Gltf, outputs::gltf),
        Output::new(OutputKind::Csv, outputs::csv),
        Output::new(OutputKind::RobotTargets, outputs::robot),
        Output::new(OutputKind::Rapid, outputs::robot),
    ];
    type Params = SegmentationParams;
    type Run = SegmentationRun;
    type Report = SegmentationReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        job.require_surface_and_block(Self::NAME, " (the facade)", "pieces are", errors);
        if self.constraint == FitConstraintSpec::Free {
            errors.push(job.error(&format!("{PTR}/constraint"), "a piece's fits keep its parts' end points so that neighbouring pieces meet: use EndPoints or EndPointsAndLength"));
        }
        robot_cell::check(job, (PTR, self.speed, self.approach), errors);
        if job.blade.is_some_and(|b| b.max_inflections == 0) {
            errors.push(job.error("/blade/max_inflections", "FacadeSegmentation needs max_inflections ≥ 1: parts meet between inflections, never exactly on one, so a section with an inflection cannot be split into parts without any"));
        }
        self.algorithm.check(job, errors);
        if let Some(m) = self.min_piece {
            if !(m > 0.0 && m.is_finite()) {
                errors.push(job.error(
                    &format!("{PTR}/min_piece"),
                    format!("min_piece must be a positive length, got {m:?}"),
                ));
            }
        }
        for (i, o) in job.outputs.iter().enumerate() {
            let robot = matches!(o, OutputSpec::RobotTargets { .. } | OutputSpec::Rapid);
            if robot && !self.rationalize {
                errors.push(job.error(
                    &format!("/outputs/{i}"),
                    format!(
                        "output {} needs the pieces rationalized: set `rationalize: true`",
                        o.name()
                    ),
                ));
            }
            if let OutputSpec::RobotTargets { per_block: Some(_) } = o {
                errors.push(job.error(&format!("/outputs/{i}/RobotTargets/per_block"), "FacadeSegmentation poses the blade on every section a piece crosses: leave per_block out"));
            }
        }
    }

    fn params(&self, job: &Context) -> Result<SegmentationParams> {
        let block = job.block(Self::NAME)?;
        let per_mm = job.per_mm();
        let speed = self.speed.unwrap_or(BLADE_SPEED_MM_PER_S * per_mm);
        Ok(SegmentationParams {
            algorithm: self.algorithm.clone(),
            samples: self.samples as usize,
            rationalize: self.rationalize,
            constraint: self.constraint,
            motion: Motion {
                speed,
                approach: self.approach.unwrap_or(APPROACH_MM * per_mm),
            },
            constraints: Constraints {
                block: [block.size.0, block.size.1, block.size.2],
                blade_length: job.blade.length,
                max_curvature: job.blade.max_curvature,
                max_inflections: job.blade.max_inflections,
                tolerance_rms: job.tolerance.rms,
                tolerance_max: job.tolerance.max,
            },
            blade: job.blade,
            // the blade's path: the design moved half the kerf towards the removed side
            sectioning: SectionParams {
                offset: 0.5 * job.kerf.at(speed),
                ..job.sectioning()
            },
            analysis: geom::analysis::CurveAnalysisParams {
                bisection_tolerance: job.tolerance.bisection,
                min_lobe_turning: job.tolerance.min_turning,
                ..Default::default()
            },
            default_precision: crate::spec::defaults::PRECISION_MM * per_mm,
            refine: facade_seg::refine::RefineParams {
                min_length: self
                    .min_piece
                    .unwrap_or_else(|| default_min_piece(job.blade.length, block.size.1)),
                samples: self.samples as usize,
                max_pieces: MAX_PIECES,
            },
        })
    }

    fn estimate(p: &SegmentationParams, job: &Context) -> Estimate {
        let (cost, points) = section_cost(job.surface.as_ref());
        let n = p.sectioning.count as f64;
        let (rows, cols, blades) = blocks_spanned(job);
        let samples = p.samples as f64;
        // pieces: a few per block (or blade length) the facade spans; each holds its row's
        // sections
        let across = cols.max(blades);
        let pieces = 4.0 * rows * across;
        let parts = 4.0 * across * n;
        // each part's blade against its block: up to five places along the blade, each
        // sampled at elastica::clearance::SAMPLES points
        let clearance = 5.0 * elastica::clearance::SAMPLES as f64 * 20.0;
        Estimate::new(
            n * (2048.0 * 40.0 + 200.0 * points)
                + pieces * 2e3
                + parts * (samples * 48.0 + clearance)
                + 1e7,
            n * (cost + 1e3 * points + 2048.0 * 30.0) + parts * samples * 400.0,
            if blades > cols {
                "/blade/length"
            } else {
                "/block/size"
            },
            "enlarge block.size or blade.length, or lower cutting.sections or the task's samples",
        )
        // drawings, glTF, report and robot files: every part's samples and every section
        .with_output(parts * samples * 120.0 + n * points * 60.0 + pieces * 2e3 + 2e5)
    }

    fn run(
        params: &SegmentationParams,
        job: &Context,
        progress: &dyn Progress,
    ) -> Result<SegmentationRun> {
        let surface = job.surface(Self::NAME)?;
        progress.start("sectioning", params.sectioning.count as u64);
        let (frame, sections) = surface
            .sections(&params.sectioning, &|| progress.tick())
            .map_err(job.geom_err("sectioning the facade"))?;
        progress.finish();
        let facade = Facade::with_analysis(frame, &sections, &params.analysis)
            .map_err(|e| job.fail(e.to_string()))?;
        let first = segment(&facade, params, progress)
            .map_err(|e| job.fail(format!("segmentation failed: {e}")))?;
        progress.start("refining the pieces that fail", 0);
        // a rationalized run judges pieces by their blades, as its report does
        let rp = rationalize_params(params);
        let judge = |q: &facade_seg::Piece| {
            if params.rationalize {
                facade_seg::rationalize::pose_piece(&facade, q, &rp)
                    .map(|posed| facade_seg::report::judged(q, Some(&posed), &params.constraints))
                    .unwrap_or(q.verdicts)
            } else {
                q.verdicts
            }
        };
        let (mut segmentation, refinement) = facade_seg::refine::refine_judged(
            &facade,
            &params.constraints,
            &first,
            &params.refine,
            &judge,
            &|| progress.tick(),
        )
        .map_err(|e| job.fail(format!("refinement failed: {e}")))?;
        progress.finish();
        let posed = if params.rationalize {
            rationalize(&facade, &segmentation, params, progress)
                .map_err(|e| job.fail(e.to_string()))?
        } else {
            Vec::new()
        };
        facade_seg::rationalize::adopt_blocks(&mut segmentation, &posed);
        let mut run = SegmentationRun {
            facade,
            segmentation,
            refinement,
            posed,
            surface: SurfaceInfo::of(job, surface),
            cell: None,
        };
        let m = &params.motion;
        run.cell = robot_cell::program(
            job,
            (m.speed, m.approach),
            run.posed.iter().any(|p| !p.parts.is_empty()),
            || worst_clearance(&run.posed),
            || {
                outputs::targets(&run, params.blade.length, job.units, &job.stiffness)
                    .map_err(|e| job.fail(e.to_string()))
            },
        )?;
        Ok(run)
    }

    fn nothing_to_cut(run: &SegmentationRun) -> Option<String> {
        if run.segmentation.pieces.is_empty() {
            return Some("the segmentation made no piece".into());
        }
        let poses: usize = run.posed.iter().map(|p| p.parts.len()).sum();
        (!run.posed.is_empty() && poses == 0).then(|| {
            format!(
                "none of the {} pieces could be posed for the blade (fits over tolerance, or parts the blade cannot reach)",
                run.segmentation.pieces.len()
            )
        })
    }

    fn report(
        params: &SegmentationParams,
        run: &SegmentationRun,
        job: &Context,
    ) -> SegmentationReport {
        let c = &params.constraints;
        let pieces = facade_seg::report::summarize(
            &run.facade,
            &run.segmentation,
            &run.posed,
            params.rationalize,
            c,
            &job.stiffness,
        );
        SegmentationReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            surface: run.surface.clone(),
            model_bounds: crate::report::ModelBounds::of(Ok(outputs::scene(run))),
            settings: SegmentationSettings {
                algorithm: params.algorithm.clone(),
                sections: run.facade.sections.len(),
                samples: params.samples,
                block: c.block,
                blade_length: c.blade_length,
                max_curvature: c.max_curvature,
                max_inflections: c.max_inflections,
                tolerance_rms: c.tolerance_rms,
                tolerance_max: c.tolerance_max,
                rationalized: params.rationalize,
                constraint: params.constraint,
                speed: params.motion.speed,
                approach: params.motion.approach,
                kerf: job.kerf.report(params.motion.speed),
            },
            counts: pieces.counts,
            refinement: run.refinement.clone(),
            pieces: pieces.pieces,
            seams: run
                .segmentation
                .seams
                .iter()
                .map(|s| s.points.clone())
                .collect(),
            cell: run.cell.as_ref().map(|c| c.report.clone()),
        }
    }

    fn figures(
        _: &SegmentationParams,
        run: &SegmentationRun,
        r: &SegmentationReport,
        job: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let height = job
            .surface
            .as_ref()
            .and_then(|s| ruled::Height::new(s).ok());
        let mut part = 0.0;
        let mut stock = 0.0;
        let (mut sq, mut n, mut max) = (0.0, 0usize, 0.0f64);
        for p in &r.pieces {
            let b = &p.block;
            stock += b.size.iter().product::<f64>();
            let [w, x, y, z] = b.rotation;
            let q =
                nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            let axes = [
                q * nalgebra::Vector3::x(),
                q * nalgebra::Vector3::y(),
                q * nalgebra::Vector3::z(),
            ];
            if let Some(h) = &height {
                part +=
                    crate::process::solid_in_block(h, b.origin, axes, b.size, 100).unwrap_or(0.0);
            }
            for f in p.sections.iter().filter_map(|s| s.blade_fit.as_ref()) {
                sq += f.rms * f.rms;
                n += 1;
                max = max.max(f.max);
            }
        }
        let c = &r.counts;
        let why_not = (!c.all_ok).then(|| {
            format!(
                "{} of {} pieces break a constraint ({}), {} gouge(s), {} collision(s), {} part(s) without a pose",
                r.pieces.iter().filter(|p| !p.verdicts.all()).count(),
                c.pieces,
                crate::process::nonzero(&c.failing),
                c.gouges,
                c.collisions,
                c.unposed
            )
        });
        Some(crate::robot_cell::blade_figures(
            run.cell.as_ref(),
            why_not,
            (c.blocks, stock, part),
            (n > 0).then(|| crate::process::Deviation {
                rms: (sq / n as f64).sqrt(),
                max,
            }),
            job.per_mm(),
        ))
    }

    fn page(r: &SegmentationReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &SegmentationReport, job: &Context) -> String {
        let units = job.units.symbol();
        let c = &r.counts;
        let mut out = format!(
            "{} (FacadeSegmentation, {}): {} piece(s) from {} block(s), {} band(s) × {} row(s), {} section part(s)",
            r.job, r.settings.algorithm.name(), c.pieces, c.blocks, c.bands, c.rows, c.parts
        );
        if r.settings.rationalized {
            let worst = r
                .pieces
                .iter()
                .filter_map(|p| p.max_blade_fit)
                .fold(0.0, f64::max);
            out.push_str(&format!(
                "\n  {} blade pose(s), {} sliver(s) unposed; largest blade fit distance {:.4} {units}",
                c.poses, c.unposed, worst
            ));
        }
        let f = &c.failing;
        let broken = f.dimension + f.approximation + f.shape + f.blade_strain + f.stability;
        if broken > 0 {
            out.push_str(&format!(
                "\n  warning: pieces breaking a constraint — dimension {}, approximation {}, shape {}, blade strain {}, blade stability {}",
                f.dimension, f.approximation, f.shape, f.blade_strain, f.stability
            ));
        }
        if c.gouges + c.collisions > 0 {
            out.push_str(&format!(
                "\n  warning: blades outside their parts — {} piece(s) gouge what the block keeps, {} hold the blade within 1 % of its length of the block (pieces {}): trim those blocks across the cut to their pieces, or change blade.length; see report.json pieces[].sections[].blade_fit",
                c.gouges,
                c.collisions,
                clearance_ids(r)
            ));
        }
        let rf = &r.refinement;
        if rf.splits > 0 || !rf.unresolved.is_empty() {
            out.push_str(&format!(
                "\n  refinement: {} split(s); {} of {} piece(s) failed before, {} of {} after",
                rf.splits,
                rf.before.failing_pieces,
                rf.before.pieces,
                rf.after.failing_pieces,
                rf.after.pieces
            ));
        }
        for line in report::unresolved_lines(r, units) {
            out.push_str(&format!("\n  {line}"));
        }
        if let Some(cell) = &r.cell {
            out.push('\n');
            out.push_str(&cell.summary());
        }
        out
    }
}

/// The ids of the pieces whose blades gouge or whose holders touch their blocks (the
/// first 12).
fn clearance_ids(r: &SegmentationReport) -> String {
    let ids: Vec<String> = r
        .pieces
        .iter()
        .filter(|p| !p.is_clear())
        .map(|p| p.id.to_string())
        .collect();
    if ids.len() > 12 {
        format!("{}, … {} in all", ids[..12].join(", "), ids.len())
    } else {
        ids.join(", ")
    }
}

impl SegAlgorithmSpec {
    /// Checks the algorithm's own options.
    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        let mut positive = |field: &str, v: Option<f64>, zero_ok: bool| {
            let Some(v) = v else { return };
            if !(v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0))) {
                errors.push(job.error(
                    &format!("{PTR}/algorithm/{}/{field}", self.name()),
                    format!(
                        "{field} must be a {} number, got {v:?}",
                        if zero_ok { "non-negative" } else { "positive" }
                    ),
                ));
            }
        };
        match self {
            Self::Inflection { .. } => {}
            Self::Trace {
                link_distance,
                merge_distance,
                ..
            } => {
                positive("link_distance", *link_distance, false);
                positive("merge_distance", *merge_distance, true);
            }
            Self::LongestElastica {
                precision,
                max_step,
            } => {
                positive("precision", *precision, false);
                positive("max_step", *max_step, false);
            }
        }
    }
}

/// For `strict`: the worst part whose blade outside it enters what its block keeps, or
/// whose held end touches its block (the deepest gouge, then the smallest clearance).
fn worst_clearance(posed: &[PosedPiece]) -> Option<String> {
    let parts = posed
        .iter()
        .flat_map(|p| p.parts.iter().map(move |x| ((p.id, x.part), x.clearance)));
    let ((id, part), c) = Clearance::worst(parts)?;
    Some(format!(
        "runs {:.4e} deep into what block {id} keeps (holder clearance {:.4e}) at the piece's section {part} (report.json's index)",
        c.gouge_depth, c.holder_clearance
    ))
}

/// Runs the job's segmentation algorithm on the facade.
fn segment(
    facade: &Facade,
    params: &SegmentationParams,
    progress: &dyn Progress,
) -> std::result::Result<Segmentation, facade_seg::SegError> {
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
            inflection_points(facade, c, &p, &tick)
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
            trace(facade, c, &p, &tick)
        }
        SegAlgorithmSpec::LongestElastica {
            precision,
            max_step,
        } => {
            progress.start("longest elastica (section parts)", 0);
            let p = LongestParams {
                precision: precision.unwrap_or(params.default_precision),
                max_step: *max_step,
                samples,
                ..LongestParams::default()
            };
            longest_elastica(facade, c, &p, &tick)
        }
    };
    progress.finish();
    seg
}

/// How a run's pieces are rationalized.
fn rationalize_params(params: &SegmentationParams) -> RationalizeParams {
    RationalizeParams {
        constraint: params.constraint.to_fit().with_end_points(),
        samples: params.samples,
        blade: params.blade,
        tolerance_max: params.constraints.tolerance_max,
        tolerance_rms: params.constraints.tolerance_rms,
    }
}

fn rationalize(
    facade: &Facade,
    seg: &Segmentation,
    params: &SegmentationParams,
    progress: &dyn Progress,
) -> std::result::Result<Vec<PosedPiece>, facade_seg::SegError> {
    let rp = rationalize_params(params);
    progress.start("rationalizing pieces", seg.pieces.len() as u64);
    let posed = pose_pieces(facade, seg, &rp, &|| progress.tick());
    progress.finish();
    posed
}
