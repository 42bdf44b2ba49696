//! The `HotBlade` task: the surface inside a grid of blocks, every block's sections fitted
//! by elastica ("Hot Blade Cuttings" §6–7), the surface swept between them, the blade poses
//! for the robots that hold the blade ("Robotic Hot-Blade Cutting" §4), and the checks of every production
//! constraint — the [`hotblade`] pipeline, with the job's settings, report and files.

/// Its files: robot targets, RAPID, OBJ, glTF, SVG, CSV.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// Its report.
pub mod report;

use hotblade::Rationalization;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{HotcutError, JobError, Result};
use crate::limits::{section_cost, Estimate};
use crate::progress::Progress;
use crate::report::SurfaceInfo;
use crate::robot_cell::{self, CellPlan};
use crate::spec::defaults::{APPROACH_MM, BLADE_SPEED_MM_PER_S};
use crate::spec::{keep_length, Continuity, FitConstraintSpec, OutputKind, OutputSpec};
use crate::task::{Output, Task};
use export::robot::Motion;
use report::{HotBladeReport, HotBladeSettings};

/// Hot-blade rationalization ("Hot Blade Cuttings" §6–7, "Robotic Hot-Blade Cutting"
/// §4): the surface inside a grid of blocks, every block's sections fitted by elastica,
/// the swept surface between them, the blade poses for the robots that hold the blade,
/// and the cell's RAPID programs (two robots, or three when one carries the block). Write `HotBlade(targets_per_block: 51)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HotBlade {
    /// Blade poses per block (≥ 2), on planes equally spaced from the block's entry face
    /// to its exit face; a section is fitted on each. Default: 51 (the paper's cell).
    #[serde(default = "default_targets")]
    #[schemars(range(min = 2, max = 10000))]
    pub targets_per_block: u32,
    /// What each fitted elastica keeps of its section: `EndPoints`, or
    /// `EndPointsAndLength` (the skater ramp of "Hot Blade Cuttings" §7). End points are
    /// always kept, so neighbouring blocks meet. Default: `EndPointsAndLength`.
    #[serde(default = "keep_length")]
    pub constraint: FitConstraintSpec,
    /// Continuity where neighbouring blocks meet across a face along the cut: `C0`
    /// (shared end points) or `C1` (also shared end tangents, those of the design
    /// section). Default: `C0`.
    #[serde(default)]
    pub continuity: Continuity,
    /// How many times a column of blocks whose fit breaks the tolerance is halved along
    /// the cutting direction and refitted (0 = never). Default: 2.
    #[serde(default = "default_split_depth")]
    #[schemars(range(max = 8))]
    pub split_depth: u32,
    /// Points each section is sampled at for its fit (≥ 8). Default: 100.
    #[serde(default = "default_blade_samples")]
    #[schemars(range(min = 8, max = 100000))]
    pub samples: u32,
    /// Cutting speed of the blade through the block (> 0), job units per second.
    /// Default: 7 mm/s.
    #[serde(default)]
    pub speed: Option<f64>,
    /// Flat-blade restriction (§4): largest angle between the cutting plane and the
    /// surface normal, radians, in [0, π/2]. Default: π/6 (30°).
    #[serde(default = "default_plane_angle")]
    #[schemars(range(min = 0, max = std::f64::consts::FRAC_PI_2))]
    pub max_plane_angle: f64,
    /// Approach and retreat distance of the blade before and after the block, along the
    /// cut (≥ 0). Default: 50 mm.
    #[serde(default)]
    pub approach: Option<f64>,
    /// Planes between two neighbouring targets on which the rationalized surface is
    /// compared with the design (and meshed). Default: 3.
    #[serde(default = "default_refine")]
    #[schemars(range(max = 100))]
    pub refine: u32,
}

fn default_targets() -> u32 {
    51
}
fn default_split_depth() -> u32 {
    2
}
fn default_blade_samples() -> u32 {
    100
}
fn default_plane_angle() -> f64 {
    std::f64::consts::FRAC_PI_6
}
fn default_refine() -> u32 {
    3
}

/// Parameters of a `HotBlade` run.
#[derive(Debug, Clone, PartialEq)]
pub struct HotBladeParams {
    /// The pipeline's.
    pub pipeline: hotblade::Params,
    /// The fit constraint as the job writes it.
    pub constraint: FitConstraintSpec,
    /// The continuity as the job writes it.
    pub continuity: Continuity,
    /// Cutting speed and approach distance of the robot programs.
    pub motion: Motion,
}

/// What a `HotBlade` run produced: the rationalization and the surface as loaded.
#[derive(Debug, Clone)]
pub struct HotBladeRun {
    /// The pipeline's result.
    pub cut: Rationalization,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The robot cell's plan (when the job writes robot files or gives a cell, and a block has poses).
    pub cell: Option<CellPlan>,
}

const PTR: &str = "/task/HotBlade";

impl HotBlade {
    /// The pipeline's parameters this task's fields set (the job's block, direction,
    /// curve, blade, tolerances and sectioning left at their defaults).
    fn pipeline_fields(&self) -> hotblade::Params {
        hotblade::Params {
            targets: self.targets_per_block as usize,
            constraint: self.constraint.to_fit().with_end_points(),
            continuity: self.continuity.to_hotblade(),
            split_depth: self.split_depth,
            samples: self.samples as usize,
            max_plane_angle: self.max_plane_angle,
            refine: self.refine as usize,
            grid_points: 60,
            ..hotblade::Params::default()
        }
    }
}

impl Task for HotBlade {
    const NAME: &'static str = "HotBlade";
    const REPORT_SCHEMA: &'static str = "hot-blade-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Obj, outputs::obj),
        Output::new(OutputKind::Gltf, outputs::gltf),
        Output::new(OutputKind::Csv, outputs::csv),
        Output::new(OutputKind::RobotTargets, outputs::robot),
        Output::new(OutputKind::Rapid, outputs::robot),
    ];
    const CUTTING_CURVE: bool = true;
    type Params = HotBladeParams;
    type Run = HotBladeRun;
    type Report = HotBladeReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        job.require_surface_and_block(Self::NAME, "", "surface is", errors);
        if self.constraint == FitConstraintSpec::Free {
            errors.push(job.error(&format!("{PTR}/constraint"), "HotBlade fits keep the sections' end points so that neighbouring blocks meet: use EndPoints or EndPointsAndLength"));
        }
        robot_cell::check(job, (PTR, self.speed, self.approach), errors);
        // the pipeline's own checks of these fields and of the cutting curve
        let pipeline = hotblade::Params {
            curve: job.cutting.curve.clone(),
            ..self.pipeline_fields()
        };
        for p in pipeline.problems() {
            // the job's name of each field (block, direction, blade and tolerance are the
            // job's own, checked when it is loaded: here they are placeholders)
            let (pointer, field) = match p.field {
                "curve" => ("/cutting/curve".to_string(), None),
                "targets" => (
                    format!("{PTR}/targets_per_block"),
                    Some("targets_per_block"),
                ),
                "block" | "origin" => ("/block".to_string(), Some(p.field)),
                "direction" => ("/cutting/direction".to_string(), Some(p.field)),
                "blade" => ("/blade".to_string(), Some(p.field)),
                "tolerance" => ("/tolerance".to_string(), Some(p.field)),
                "grid_points" => (PTR.to_string(), Some(p.field)),
                field => (format!("{PTR}/{field}"), Some(field)),
            };
            let message = match field {
                Some(f) => format!("{f} {}", p.message),
                None => p.message,
            };
            errors.push(job.error(&pointer, message));
        }
        for (i, o) in job.outputs.iter().enumerate() {
            if let OutputSpec::RobotTargets {
                per_block: Some(per_block),
            } = o
            {
                if *per_block != self.targets_per_block {
                    errors.push(job.error(
                        &format!("/outputs/{i}/RobotTargets/per_block"),
                        format!(
                            "per_block ({per_block}) must equal the task's targets_per_block ({})",
                            self.targets_per_block
                        ),
                    ));
                }
            }
        }
    }

    fn params(&self, job: &Context) -> Result<HotBladeParams> {
        let block = job.block(Self::NAME)?;
        let per_mm = job.per_mm();
        let speed = self.speed.unwrap_or(BLADE_SPEED_MM_PER_S * per_mm);
        Ok(HotBladeParams {
            pipeline: hotblade::Params {
                block: [block.size.0, block.size.1, block.size.2],
                origin: block.origin.map(|o| [o.0, o.1, o.2]),
                direction: job.direction,
                curve: job.cutting.curve.clone(),
                blade: job.blade,
                tolerance_rms: job.tolerance.rms,
                tolerance_max: job.tolerance.max,
                // the blade's path: the design moved half the kerf towards the removed side
                sectioning: geom::surface::SectionParams {
                    offset: 0.5 * job.kerf.at(speed),
                    ..job.sectioning()
                },
                ..self.pipeline_fields()
            },
            constraint: self.constraint,
            continuity: self.continuity,
            motion: Motion {
                speed,
                approach: self.approach.unwrap_or(APPROACH_MM * per_mm),
            },
        })
    }

    fn estimate(p: &HotBladeParams, job: &Context) -> Estimate {
        let (cost, points) = section_cost(job.surface.as_ref());
        let pipeline = &p.pipeline;
        let (blocks, planes, fits) = match job
            .surface
            .as_ref()
            .map(|s| hotblade::run_size(s, pipeline))
        {
            Some(Ok(n)) => (n.rows * n.cols, n.planes, n.fits),
            _ => (1.0, 1.0, 1.0),
        };
        let samples = pipeline.samples as f64;
        let grid = (pipeline.grid_points * pipeline.grid_points) as f64;
        let per_block = (pipeline.targets * (pipeline.refine + 1)) as f64;
        let mut checks = Vec::new();
        // the pipeline's own bound on its grid, whatever the limits
        if !(blocks <= hotblade::MAX_BLOCKS && planes <= hotblade::MAX_PLANES) {
            checks.push((
                "/block/size".to_string(),
                format!(
                    "the block is far smaller than the surface: {blocks:.3e} blocks on {planes:.3e} planes (at most {:.0e} and {:.0e})",
                    hotblade::MAX_BLOCKS,
                    hotblade::MAX_PLANES
                ),
            ));
        }
        let e = Estimate::new(
            planes * points * 200.0 + fits * samples * 64.0 + blocks * (grid + per_block) * 512.0 + 1e7,
            planes * (cost + 1e3 * points) + fits * samples * 400.0 + blocks * grid * 100.0,
            "/block/size",
            "enlarge block.size, or lower the task's targets_per_block, samples, refine or split_depth",
        );
        // per block: its deviation grid; its swept surface (a row of grid_points vertices per
        // target and refined plane) in OBJ and glTF, ~65 and ~70 bytes a vertex on
        // jobs/hot-blade-facade.ron; its targets in the robot files. The fits in the report.
        // A block split into up to 2^split_depth parts has a swept surface and targets
        // per part: the bound counts them all.
        let parts = blocks * f64::from(1u32 << pipeline.split_depth.min(16));
        let rows = per_block * pipeline.grid_points as f64;
        let e = e.with_output(
            blocks * grid * 30.0
                + parts * (rows * 140.0 + per_block * 600.0)
                + fits * samples * 40.0
                + 2e5,
        );
        Estimate { checks, ..e }
    }

    fn run(params: &HotBladeParams, job: &Context, progress: &dyn Progress) -> Result<HotBladeRun> {
        let surface = job.surface(Self::NAME)?;
        let report = |p: hotblade::Progress<'_>| match p {
            hotblade::Progress::Start { step, total } => progress.start(step, total),
            hotblade::Progress::Tick => progress.tick(),
            hotblade::Progress::Finish => progress.finish(),
        };
        let cut =
            hotblade::rationalize(surface, &params.pipeline, &report).map_err(|e| match e {
                hotblade::HotBladeError::Geom { context, source } => HotcutError::Geom {
                    path: job.path.clone(),
                    context: context.into(),
                    source,
                },
                other => job.fail(other.to_string()),
            })?;
        let posed = cut.blocks.iter().any(|b| !b.sections.is_empty());
        let m = &params.motion;
        let cell = robot_cell::program(
            job,
            (m.speed, m.approach),
            posed,
            || worst_gouge(&cut),
            || {
                Ok(outputs::targets(
                    &cut,
                    params.pipeline.blade.length,
                    job.units,
                    &job.stiffness,
                ))
            },
        )?;
        Ok(HotBladeRun {
            cut,
            surface: SurfaceInfo::of(job, surface),
            cell,
        })
    }

    fn nothing_to_cut(run: &HotBladeRun) -> Option<String> {
        let sections: usize = run.cut.blocks.iter().map(|b| b.sections.len()).sum();
        (sections == 0).then(|| {
            format!(
                "no block of the {} × {} grid holds a fitted section ({} column halvings): the fits miss the tolerance, or the blade cannot reach them; loosen tolerance, or check blade.length against the block",
                run.cut.grid.rows,
                run.cut.grid.cols,
                run.cut.splits.len()
            )
        })
    }

    fn report(params: &HotBladeParams, run: &HotBladeRun, job: &Context) -> HotBladeReport {
        let p = &params.pipeline;
        let cut = &run.cut;
        HotBladeReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            surface: run.surface.clone(),
            model_bounds: crate::report::ModelBounds::of(Ok(outputs::scene(cut, p.tolerance_max))),
            settings: HotBladeSettings {
                targets_per_block: p.targets,
                constraint: params.constraint,
                continuity: params.continuity,
                split_depth: p.split_depth,
                samples: p.samples,
                refine: p.refine,
                planes: if cut.follows_curve {
                    "Curve"
                } else {
                    "Parallel"
                }
                .into(),
                blade_length: p.blade.length,
                max_curvature: p.blade.max_curvature,
                max_inflections: p.blade.max_inflections,
                tolerance_rms: p.tolerance_rms,
                tolerance_max: p.tolerance_max,
                max_plane_angle: p.max_plane_angle,
                speed: params.motion.speed,
                approach: params.motion.approach,
                kerf: job.kerf.report(params.motion.speed),
            },
            grid: cut.grid.info(),
            summary: cut.summary.clone(),
            splits: cut.splits.clone(),
            blocks: cut.blocks.iter().map(|b| b.report.clone()).collect(),
            cell: run.cell.as_ref().map(|c| c.report.clone()),
        }
    }

    fn figures(
        _: &HotBladeParams,
        run: &HotBladeRun,
        r: &HotBladeReport,
        job: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let v3 = |a: [f64; 3]| nalgebra::Vector3::from(a);
        let axes = [v3(r.grid.axis_d), v3(r.grid.axis_u), v3(r.grid.axis_v)];
        let height = job
            .surface
            .as_ref()
            .and_then(|s| ruled::Height::new(s).ok());
        let mut part = 0.0;
        for b in &r.blocks {
            if let Some(h) = &height {
                part +=
                    crate::process::solid_in_block(h, b.origin, axes, b.size, 100).unwrap_or(0.0);
            }
        }
        let stock: f64 = r
            .blocks
            .iter()
            .map(|b| b.size.iter().product::<f64>())
            .sum();
        let flagged: Vec<String> = r
            .blocks
            .iter()
            .filter(|b| b.flags.any())
            .map(|b| b.block.to_string())
            .collect();
        let why_not = (!flagged.is_empty() || !r.summary.all_ok).then(|| {
            format!(
                "blocks {} break a constraint ({}); largest deviation {:.4}",
                flagged.join(", "),
                crate::process::nonzero(&r.summary.flagged),
                r.summary.max_deviation
            )
        });
        let rms = r.blocks.iter().map(|b| b.max_rms).fold(0.0, f64::max);
        Some(crate::robot_cell::blade_figures(
            run.cell.as_ref(),
            why_not,
            (r.blocks.len(), stock, part),
            Some(crate::process::Deviation {
                rms,
                max: r.summary.max_deviation,
            }),
            job.per_mm(),
        ))
    }

    fn page(r: &HotBladeReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &HotBladeReport, job: &Context) -> String {
        let units = job.units.symbol();
        let s = &r.summary;
        let f = &s.flagged;
        let verdict = if s.all_ok {
            String::new()
        } else {
            format!(
                "\n  warning: blocks breaking a constraint — approximation {}, blade strain {}, shape {}, blade length {}, flat blade {}, block height {}, overlap {}, gouge {}, blade stability {}",
                f.approximation, f.blade_strain, f.shape, f.blade_length, f.flat_blade, f.block_height, f.overlap, f.gouge, f.stability
            )
        };
        let cell = r
            .cell
            .as_ref()
            .map(|c| format!("\n{}", c.summary()))
            .unwrap_or_default();
        format!(
            "{} (HotBlade, {:?}, {:?}): {} block(s) in {} row(s) × {} column(s), {} split(s)\n  {} section(s): L2 min {:.4}, max {:.4}, avg {:.4}; largest fit distance {:.4} {units}, deviation {:.4} {units}\n  blade: max |κ| {:.4e} /{units}, ≤ {} inflection(s); plane angle ≤ {:.1}°; face gap {:.1e} {units}, angle {:.1e} rad{verdict}{cell}",
            r.job, r.settings.constraint, r.settings.continuity, s.blocks, r.grid.rows, r.grid.columns, r.splits.len(),
            s.sections, s.l2.min, s.l2.max, s.l2.avg, s.max_fit_distance, s.max_deviation,
            s.max_abs_curvature, s.max_inflections, s.max_plane_angle.to_degrees(), s.max_face_gap, s.max_face_angle,
        )
    }
}

/// How the deepest gouging blade of `cut` runs into its block (after "a blade that"), if
/// any blade gouges or has a holder inside a block.
fn worst_gouge(cut: &hotblade::Rationalization) -> Option<String> {
    let sections = cut
        .blocks
        .iter()
        .filter(|b| b.report.flags.gouge)
        .flat_map(|b| {
            b.sections
                .iter()
                .enumerate()
                .filter_map(move |(i, s)| Some(((b.report.block, i), s.clearance?)))
        });
    let ((block, section), c) = elastica::clearance::Clearance::worst(sections)?;
    Some(format!(
        "runs {:.4e} deep into what block {block} keeps (holder clearance {:.4e}) at its section {section} (report.json's index)",
        c.gouge_depth, c.holder_clearance
    ))
}
