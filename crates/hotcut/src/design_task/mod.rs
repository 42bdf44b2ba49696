//! The `Design` task: a surface designed so that a hot blade can cut it ("Designing for
//! Robotic Hot-Blade Cutting" §3–§5). A design file gives blocks and, per cut, design
//! curves at stations along it — Béziers joined G¹ or one C² spline, a piece per block;
//! the [`design`] crate replaces every piece by its elastica in closed form on every
//! station and cutting plane, extends it to the blade and poses it; this module reads the
//! file, checks it, and reports and writes the result.

/// The design's checks beyond its schema, shared by validation and run.
mod check;
/// Its drawings, `block_<id>.svg`.
mod drawing;
/// The design file.
pub mod file;
/// Its files: SVG per block, glTF, robot targets, RAPID.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// Its report.
pub mod report;

use std::path::PathBuf;

use design::cut::{CutParams, CutResult};
use elastica::blade::BladeParams;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{blade_of, Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::Estimate;
use crate::progress::Progress;
use crate::robot_cell::{self, CellPlan};
use crate::spec::defaults::{APPROACH_MM, BLADE_SPEED_MM_PER_S};
use crate::spec::OutputKind;
use crate::task::{Output, Task};
use check::check_design;
use design::assembly::{self as multi, Block, ResolvedCut};
use export::robot::Motion;
use file::{read, DesignFile};
use report::{
    cut_report, summary, BlockCut, BlockInfo, DesignReport, DesignSettings, EnvelopeReport,
};

/// A surface designed for the hot blade ("Designing for Robotic Hot-Blade Cutting"): the
/// design file's curves, each block's piece replaced by its elastica, with the deviation,
/// the blade's checks, robot poses and RAPID. Write
/// `Design(design: "designs/arch.json")`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Design {
    /// Design file, relative to the job file: JSON, schema `schemas/design.schema.json`
    /// (README, "Designing for the hot blade"). Coordinates in job units.
    #[schemars(length(min = 1))]
    pub design: String,
    /// Sampling density: `Design` (11 planes per cut, 60 points per curve and block, a
    /// quick look) or `Production` (51 planes, 200 points: what the robot files need).
    /// Default: `Production`.
    #[serde(default)]
    pub resolution: Resolution,
    /// Cutting speed of the blade through the block (> 0), job units per second.
    /// Default: 7 mm/s.
    #[serde(default)]
    pub speed: Option<f64>,
    /// Approach and retreat distance of the blade before and after the block, along the
    /// cut (≥ 0). Default: 50 mm.
    #[serde(default)]
    pub approach: Option<f64>,
}

/// Sampling density of a `Design` run ("Designing for Robotic Hot-Blade Cutting" §5.1).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Resolution {
    /// 11 planes per cut, 60 points per curve and block.
    Design,
    /// 51 planes per cut, 200 points per curve and block; robot files need it.
    #[default]
    Production,
}

impl Resolution {
    /// Cutting planes per cut and points per curve and block.
    pub fn density(self) -> (usize, usize) {
        match self {
            Self::Design => (11, 60),
            Self::Production => (51, 200),
        }
    }
}

/// Parameters of a `Design` run.
#[derive(Debug, Clone)]
pub struct DesignParams {
    /// The design file (resolved path, and as written).
    pub file: (PathBuf, String),
    /// The resolution.
    pub resolution: Resolution,
    /// Planes per cut.
    pub planes: usize,
    /// Points per curve and block.
    pub points: usize,
    /// The blade.
    pub blade: BladeParams,
    /// Cutting speed and approach distance of the robot programs.
    pub motion: Motion,
    /// How far the blade's path lies off the design (half the kerf), towards `+v`.
    pub offset: f64,
}

/// What a `Design` run produced.
#[derive(Debug, Clone)]
pub struct DesignRun {
    /// The design file.
    pub design: DesignFile,
    /// Its blocks.
    pub blocks: Vec<Block>,
    /// Per cut: resolved, and its elastica.
    pub cuts: Vec<(ResolvedCut, CutResult)>,
    /// Per block: the cuts through it and, with several, their envelope.
    pub multi: Vec<multi::BlockCuts>,
    /// The (cut, piece) pairs the robots cut, in order.
    pub order: Vec<(usize, usize)>,
    /// The robot cell's plan (when the job writes RAPID or gives a cell).
    pub cell: Option<CellPlan>,
}

const PTR: &str = "/task/Design";

impl Design {
    fn design_error(&self, job: &JobFields<'_>, pointer: &str, m: String) -> JobError {
        job.error(
            &format!("{PTR}/design"),
            format!("{} {pointer}: {m}", self.design),
        )
    }
}

impl Task for Design {
    const NAME: &'static str = "Design";
    const REPORT_SCHEMA: &'static str = "design-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Gltf, outputs::gltf),
        Output::new(OutputKind::RobotTargets, outputs::robot),
        Output::new(OutputKind::Rapid, outputs::robot),
    ];
    type Params = DesignParams;
    type Run = DesignRun;
    type Report = DesignReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        if job.surface.is_some() {
            errors.push(job.error(
                "/surface",
                "task Design takes its geometry from the design file: leave surface out",
            ));
        }
        if job.block.is_some() {
            errors.push(job.error(
                "/block",
                "task Design takes its blocks from the design file: leave block out",
            ));
        }
        robot_cell::check(job, (PTR, self.speed, self.approach), errors);
        if self.resolution == Resolution::Design {
            for (i, o) in job.outputs.iter().enumerate() {
                if matches!(o.kind(), OutputKind::RobotTargets | OutputKind::Rapid) {
                    errors.push(job.error(
                        &format!("/outputs/{i}"),
                        format!("robot files are written at Production resolution: set the task's resolution to Production, or leave {} out", o.name()),
                    ));
                }
            }
        }
        match read(&job.base.join(&self.design)) {
            Err(m) => errors.push(job.error(&format!("{PTR}/design"), m)),
            Ok(d) => {
                let blade = blade_of(job.blade, job.units).length;
                for (p, m) in check_design(
                    &d,
                    blade,
                    self.resolution.density().0,
                    1.0 / job.units.per_mm(),
                )
                .0
                {
                    errors.push(self.design_error(job, &p, m));
                }
            }
        }
    }

    fn params(&self, job: &Context) -> Result<DesignParams> {
        let base = job.path.parent().unwrap_or(std::path::Path::new("."));
        let (planes, points) = self.resolution.density();
        let per_mm = job.per_mm();
        let speed = self.speed.unwrap_or(BLADE_SPEED_MM_PER_S * per_mm);
        Ok(DesignParams {
            offset: 0.5 * job.kerf.at(speed),
            file: (base.join(&self.design), self.design.clone()),
            resolution: self.resolution,
            planes,
            points,
            blade: BladeParams {
                length: job.blade.length,
                lead_in_share: 0.5,
                max_curvature: Some(job.blade.max_curvature),
                max_inflections: Some(job.blade.max_inflections as usize),
                stability: elastica::StabilityParams::default(),
            },
            motion: Motion {
                speed,
                approach: self.approach.unwrap_or(APPROACH_MM * per_mm),
            },
        })
    }

    fn estimate(p: &DesignParams, _: &Context) -> Estimate {
        // per cut: its pieces solved on every station and every plane; per block cut
        // several times: their envelope on a grid of (2·planes − 1)² nodes (at most 101²),
        // each node against every cut's planes and points
        let (cuts, solves, envelope) = read(&p.file.0).map_or((1.0, 1.0, 0.0), |d| {
            let solves: f64 = d
                .cuts
                .iter()
                .map(|c| (c.blocks.len() * (p.planes + c.stations.len())) as f64)
                .sum();
            let mut through: std::collections::HashMap<&str, f64> =
                std::collections::HashMap::new();
            for c in &d.cuts {
                for b in &c.blocks {
                    *through.entry(b.as_str()).or_default() += 1.0;
                }
            }
            let grid = ((2 * p.planes).saturating_sub(1).min(101) as f64).powi(2);
            let nodes: f64 = through
                .values()
                .filter(|&&k| k > 1.0)
                .map(|k| k * grid * (p.planes + p.points) as f64)
                .sum();
            (d.cuts.len() as f64, solves, nodes)
        });
        // a closed-form boundary-value solve with its discrete start: ~10⁶ steps (some
        // milliseconds; nearly taut pieces take up to a hundred times longer)
        Estimate::new(
            solves * (4e4 + 64.0 * p.points as f64) + cuts * 1e4 + envelope * 16.0 + 1e7,
            solves * 1e6 + envelope * 20.0,
            "/task/Design/resolution",
            "use resolution Design if it is Production, or split the design into fewer cuts, stations and blocks",
        )
        // drawings, glTF, report and page: every solved curve's points, some tens of bytes
        // each in each (a 3-cut, 100-block, 100-station design wrote 145 per point)
        .with_output(solves * p.points as f64 * 180.0 + 1e5)
    }

    fn run(params: &DesignParams, job: &Context, progress: &dyn Progress) -> Result<DesignRun> {
        let design = read(&params.file.0)
            .map_err(|m| JobError::semantic(&job.path, &format!("{PTR}/design"), m))?;
        let (problems, resolved) = check_design(
            &design,
            params.blade.length,
            params.planes,
            1.0 / job.per_mm(),
        );
        if let Some((p, m)) = problems.into_iter().next() {
            return Err(job.fail(format!("{} {p}: {m}", params.file.1)));
        }
        let blocks = design.blocks();
        let total: usize = resolved
            .iter()
            .map(|c| c.stations.len() + params.planes)
            .sum();
        progress.start("solving the elastica of every curve", total as u64);
        let tick = || progress.tick();
        let cuts = resolved
            .into_iter()
            .zip(&design.cuts)
            .map(|(r, spec)| {
                let cp = CutParams {
                    frame: r.frame,
                    faces: r.faces.clone(),
                    stations: r.stations.clone(),
                    blade: params.blade.clone(),
                    planes: params.planes,
                    offset: params.offset,
                    heights: r.heights.clone(),
                };
                design::cut::solve(&cp, &tick)
                    .map(|res| (r, res))
                    .map_err(|e| job.fail(format!("cut `{}`: {e}", spec.id)))
            })
            .collect::<Result<Vec<_>>>()?;
        progress.finish();
        let grid = (2 * params.planes - 1).min(101);
        let multi = multi::block_cuts(&blocks, &cuts, grid, params.points);
        let order = multi::robot_order(&multi, &cuts);
        // strict refuses robot programs for such a blade; a report alone is written
        let m = &params.motion;
        let cell = robot_cell::program(
            job,
            (m.speed, m.approach),
            true,
            || gouge_message(&cuts, &blocks),
            || {
                Ok(outputs::targets(
                    &blocks,
                    &cuts,
                    &order,
                    params.blade.length,
                    job.units,
                    &job.stiffness,
                ))
            },
        )?;
        Ok(DesignRun {
            design,
            blocks,
            cuts,
            multi,
            order,
            cell,
        })
    }

    fn nothing_to_cut(run: &DesignRun) -> Option<String> {
        let poses: usize = run
            .order
            .iter()
            .map(|&(c, _)| run.cuts[c].1.planes.len())
            .sum();
        (poses == 0).then(|| "the design has no cut with a blade pose".to_string())
    }

    fn report(params: &DesignParams, run: &DesignRun, job: &Context) -> DesignReport {
        let cuts: Vec<_> = run
            .cuts
            .iter()
            .zip(&run.design.cuts)
            .map(|((r, res), spec)| {
                let blocks: Vec<&Block> = r.blocks.iter().map(|&k| &run.blocks[k]).collect();
                cut_report(&spec.id, &blocks, &r.faces, res)
            })
            .collect();
        DesignReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            model_bounds: crate::report::ModelBounds::of(Ok(outputs::scene(
                run,
                params.points,
                job.tolerance.max,
            ))),
            design: params.file.1.clone(),
            settings: DesignSettings {
                resolution: params.resolution,
                planes_per_block: params.planes,
                points_per_curve: params.points,
                blade_length: params.blade.length,
                max_curvature: job.blade.max_curvature,
                max_inflections: job.blade.max_inflections,
                speed: params.motion.speed,
                approach: params.motion.approach,
                kerf: job.kerf.report(params.motion.speed),
            },
            blocks: run
                .blocks
                .iter()
                .zip(&run.multi)
                .map(|(b, m)| block_info(b, m, run))
                .collect(),
            summary: {
                let mut s = summary(&cuts);
                s.poses = run
                    .order
                    .iter()
                    .map(|&(c, _)| run.cuts[c].1.planes.len())
                    .sum();
                s
            },
            cuts,
            cell: run.cell.as_ref().map(|c| c.report.clone()),
        }
    }

    fn page(r: &DesignReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &DesignReport, job: &Context) -> String {
        let units = job.units.symbol();
        let s = &r.summary;
        let mut multi = String::new();
        for b in r.blocks.iter().filter(|b| b.envelope.is_some()) {
            let order: Vec<&str> = b
                .cuts
                .iter()
                .filter(|c| c.note.is_none())
                .map(|c| c.cut.as_str())
                .collect();
            let e = b
                .envelope
                .as_ref()
                .map(|e| (e.max_deviation, e.crease_deviation));
            multi.push_str(&format!(
                "\n  block {}: cuts {} (primary first); top: elastica vs design ≤ {:.3} {units}, crease moved ≤ {}",
                b.id,
                order.join(" → "),
                e.map_or(0.0, |e| e.0),
                e.and_then(|e| e.1).map_or("— (no crease)".to_string(), |d| format!("{d:.3} {units}")),
            ));
            for c in b.cuts.iter().filter(|c| c.note.is_some()) {
                multi.push_str(&format!(
                    "\n  note: block {}: cut `{}` dropped: {}",
                    b.id,
                    c.cut,
                    c.note.as_deref().unwrap_or("")
                ));
            }
        }
        let verdict = {
            let mut v = Vec::new();
            if s.strain_flags + s.inflection_flags + s.stability_flags > 0 {
                v.push(format!(
                    "  warning: blades breaking a limit — strain {}, inflections {}, stability {}",
                    s.strain_flags, s.inflection_flags, s.stability_flags
                ));
            }
            if let Some(first) = first_gouge(r) {
                v.push(format!(
                    "  warning: the blade outside its piece runs into what a block keeps on {} plane(s), holders touching a block on {}: {first}",
                    s.gouge_flags, s.collision_flags
                ));
            }
            v.iter().map(|l| format!("\n{l}")).collect::<String>()
        };
        let cell = r
            .cell
            .as_ref()
            .map(|c| format!("\n{}", c.summary()))
            .unwrap_or_default();
        format!(
            "{} (Design, {:?}, {}): {} cut(s), {} block(s), {} curve(s), {} blade pose(s)\n  design vs elastica: ≤ {:.3} % of the length; eq. (11) residual ≤ {:.3}; blade max |κ| {:.4e} /{units}{multi}{verdict}{cell}",
            r.job, r.settings.resolution, r.design, s.cuts, r.blocks.len(), s.curves, s.poses,
            s.max_deviation_percent, s.max_eq11_residual, s.blade_max_curvature,
        )
    }
}

/// The report of block `b` with its cuts `m`.
fn block_info(b: &Block, m: &multi::BlockCuts, run: &DesignRun) -> BlockInfo {
    let number = |c: usize| {
        run.order
            .iter()
            .position(|&(k, p)| k == c && run.cuts[k].0.blocks[p] == m.block)
            .map(|n| n + 1)
    };
    let id = |c: usize| run.design.cuts[c].id.clone();
    let mut cuts: Vec<(usize, BlockCut)> = m
        .cuts
        .iter()
        .map(|&(c, _)| {
            let rank = m.rank(c);
            let note = rank.is_none().then(|| {
                "it lies above the material the earlier cuts leave: it would cut nothing"
                    .to_string()
            });
            (
                rank.unwrap_or(usize::MAX),
                BlockCut {
                    cut: id(c),
                    number: number(c),
                    note,
                },
            )
        })
        .collect();
    cuts.sort_by_key(|c| c.0);
    BlockInfo {
        id: b.id.clone(),
        min: b.min.into(),
        max: b.max.into(),
        cuts: cuts.into_iter().map(|c| c.1).collect(),
        envelope: m.envelope.as_ref().map(|e| EnvelopeReport {
            grid: e.grid,
            max_deviation: e.max_deviation,
            crease_deviation: e.crease_deviation,
            crease_points: [e.design_crease.len(), e.elastica_crease.len()],
        }),
    }
}

/// A length for a message: 3 decimals, or 3 significant digits below 0.01.
fn short(x: f64) -> String {
    if x != 0.0 && x.abs() < 0.01 {
        format!("{x:.3e}")
    } else {
        format!("{x:.3}")
    }
}

/// The worst plane whose blade gouges or whose holder touches a block, named: cut, plane
/// (report.json's index), block, depth and clearance.
fn first_gouge(r: &DesignReport) -> Option<String> {
    let rows = r
        .cuts
        .iter()
        .flat_map(|c| c.planes.clearance.iter().map(move |k| (c, k)));
    rows.filter(|(_, k)| k.gouge_depth > 0.0 || !k.holders_clear)
        .max_by(|a, b| {
            a.1.gouge_depth
                .total_cmp(&b.1.gouge_depth)
                .then(b.1.holder_clearance.total_cmp(&a.1.holder_clearance))
        })
        .map(|(c, k)| {
            format!(
                "worst cut `{}`, plane {} (of 0–{}), block `{}`: {} deep over {}, holder clearance {}",
                geom::text::terminal(&geom::text::clip(&c.id, 40)),
                k.plane,
                c.planes.planes.saturating_sub(1),
                geom::text::terminal(&geom::text::clip(&k.block, 40)),
                short(k.gouge_depth),
                short(k.gouge_length),
                short(k.holder_clearance)
            )
        })
}

/// For `strict`: the worst plane whose blade outside its piece enters what a block keeps,
/// or whose held end touches a block.
fn gouge_message(cuts: &[(ResolvedCut, CutResult)], blocks: &[Block]) -> Option<String> {
    let pieces = cuts.iter().flat_map(|(r, res)| {
        res.planes.iter().enumerate().flat_map(move |(j, c)| {
            c.pieces
                .iter()
                .enumerate()
                .filter_map(move |(k, p)| Some(((r, res, j, k), p.clearance?)))
        })
    });
    let ((r, res, j, k), g) = elastica::clearance::Clearance::worst(pieces)?;
    let shown = |s: &str| geom::text::terminal(&geom::text::clip(s, 40));
    let block = r
        .blocks
        .get(k)
        .and_then(|&b| blocks.get(b))
        .map_or(String::new(), |b| shown(&b.id));
    Some(format!(
        "runs {} deep into what block `{block}` keeps (holder clearance {}) on plane {j} (of 0–{}) of cut `{}`",
        short(g.gouge_depth),
        short(g.holder_clearance),
        res.planes.len().saturating_sub(1),
        shown(&r.id)
    ))
}
