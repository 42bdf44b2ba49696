//! The `RuledBlocks` task (thesis ch. 4): a model that is not ruled, larger than one
//! block, rationalized as a whole by piecewise ruled strips, segmented into blocks (ch. 3)
//! and each block cut by a 4-axis hot wire, by [`ruled_blocks::run`](::ruled_blocks::run).
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/ruled-half-sphere.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{:?}", outcome.files);
//! # Ok(()) }
//! ```

/// Its files: the rationalized model (OBJ, glTF), the drawing, G-code per cut.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// `report.json`.
mod report;

use geom::surface::Surface;
use geom::TriMesh;
use ruled::wire::{Machine, Program, WireParams};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::Estimate;
use crate::progress::Progress;
use crate::spec::{defaults, OutputKind};
use crate::task::{Output, Task};
pub use report::RuledBlocksReport;

/// Segmentation versus rationalization (thesis ch. 4): the model — a closed mesh, or a
/// height field closed into a slab — rationalized as a whole by piecewise ruled strips
/// within `tolerance.max`, its regions cut along `cutting.direction`; the rationalized
/// model segmented into blocks of `block.size` (ch. 3, the job's `seed`); each block cut
/// strip by strip by the `wire`, or to its convex hull where a strip's wire would enter
/// what the block keeps. Write `RuledBlocks(sections: 40)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RuledBlocks {
    /// Sections along `cutting.direction` (4–2000): the rails are fitted through them;
    /// more are added where the model's sections split or merge. Default: 40.
    #[serde(default = "default_sections")]
    #[schemars(range(min = 4, max = 2000))]
    pub sections: usize,
    /// Most ruled strips around one section (1–1000). Default: 64.
    #[serde(default = "default_max_strips")]
    #[schemars(range(min = 1, max = 1000))]
    pub max_strips: usize,
    /// Open surfaces (height fields, B-spline surfaces): depth of the slab's floor below
    /// the surface's lowest point (> 0). Default: 50 mm.
    #[serde(default)]
    pub floor: Option<f64>,
    /// Open surfaces: cells of the grid the slab is meshed on, per side (2–2000; a
    /// B-spline surface's over its parameter domain). Default: 96.
    #[serde(default = "default_grid")]
    #[schemars(range(min = 2, max = 2000))]
    pub grid: usize,
    /// Block segmentation runs (seeds derived from the job's `seed`). Default: 1.
    #[serde(default = "default_restarts")]
    #[schemars(range(min = 1, max = 64))]
    pub restarts: u32,
    /// Block segmentation iteration cap per run. Default: 50.
    #[serde(default = "default_iterations")]
    #[schemars(range(min = 1, max = 10000))]
    pub max_iterations: u32,
    /// Which comes first: `WholeModel` (rationalize the whole model, then segment it into
    /// blocks: the thesis' choice) or `PerBlock` (segment the model, then rationalize each
    /// block on its own). Both are run and compared in the report; this one is cut.
    /// Default: `WholeModel`.
    #[serde(default)]
    pub strategy: Strategy,
    /// Block segmentation sample spacing, a fraction of the shortest block edge in
    /// (0, 0.25]. Default: 0.1.
    #[serde(default = "default_spacing")]
    #[schemars(extend("exclusiveMinimum" = 0), range(max = 0.25))]
    pub sample_spacing: f64,
}

/// Which comes first (§4.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
pub enum Strategy {
    /// Rationalize the whole model, then segment it into blocks.
    #[default]
    WholeModel,
    /// Segment the model into blocks, then rationalize each block on its own.
    PerBlock,
}

fn default_sections() -> usize {
    40
}
fn default_max_strips() -> usize {
    64
}
fn default_grid() -> usize {
    96
}
fn default_restarts() -> u32 {
    1
}
fn default_iterations() -> u32 {
    50
}
fn default_spacing() -> f64 {
    0.1
}

/// A run's parameters.
#[derive(Debug, Clone)]
pub struct RuledBlocksParams {
    /// The algorithm's.
    pub plan: ::ruled_blocks::Params,
    /// The wire's path settings.
    pub wire: Option<WireParams>,
    /// The controller.
    pub machine: Option<Machine>,
    /// The slab's floor depth (height fields).
    pub floor: f64,
    /// The slab's grid cells per side (height fields).
    pub grid: usize,
    /// The strategy cut.
    pub strategy: Strategy,
}

/// A finished run: both strategies, and the one cut.
#[derive(Debug, Clone)]
pub struct RuledBlocksRun {
    /// The model as a closed solid.
    pub model: TriMesh,
    /// The whole-model strategy's result.
    pub whole: ::ruled_blocks::RuledBlocks,
    /// The per-block strategy's result.
    pub per_block: ::ruled_blocks::per_block::PerBlock,
    /// Both strategies' figures: whole model, then per block.
    pub figures: [::ruled_blocks::compare::Figures; 2],
    /// The strategy cut.
    pub strategy: Strategy,
    /// Its rationalized model (per block: every block's solid).
    pub mesh: TriMesh,
    /// Its strips.
    pub strips: Vec<::ruled_blocks::solid::Strip>,
    /// Its blocks' plans.
    pub blocks: Vec<::ruled_blocks::cuts::BlockPlan>,
    /// Its deviation from the model.
    pub deviation: ::ruled_blocks::Deviation,
    /// Per block, per cut: its program (empty without a wire).
    pub programs: Vec<Vec<Program>>,
    /// `tolerance.max`.
    pub tolerance: f64,
}

const PTR: &str = "/task/RuledBlocks";

impl RuledBlocks {
    fn plan_params(
        &self,
        job: &Context,
        block_size: [f64; 3],
        kerf: f64,
        lead: f64,
    ) -> ::ruled_blocks::Params {
        ::ruled_blocks::Params {
            axis: job.direction.into(),
            sections: self.sections,
            tolerance: job.tolerance.max,
            max_strips: self.max_strips,
            blocks: blocks::Params {
                block_size,
                restarts: self.restarts,
                seed: job.seed,
                max_iterations: self.max_iterations,
                sample_spacing: self.sample_spacing,
                ..blocks::Params::default()
            },
            kerf,
            lead,
        }
    }
}

/// The job's model as a closed solid: a mesh as it is, a height field or a B-spline surface
/// closed into a slab `floor` below its lowest point.
fn model(job: &Context, p: &RuledBlocksParams) -> Result<TriMesh> {
    let (grid, floor) = (p.grid, p.floor);
    match job.surface(RuledBlocks::NAME)? {
        Surface::Mesh(m) => Ok(m.clone()),
        Surface::HeightField(hf) => {
            let top = hf
                .to_mesh(grid, grid)
                .map_err(job.geom_err("the height field"))?;
            let low = top
                .vertices()
                .iter()
                .map(|p| p.z)
                .fold(f64::INFINITY, f64::min);
            ::ruled_blocks::model::slab(hf, grid, grid, low - floor)
                .map_err(|e| job.fail(e.to_string()))
        }
        Surface::Spline(sp) => spline_slab(sp, grid, floor).map_err(|e| job.fail(e.to_string())),
    }
}

/// A B-spline surface closed into its slab: sampled on `grid × grid` cells of its domain,
/// walls down to a floor `floor` below its lowest sample.
fn spline_slab(
    sp: &geom::surface_spline::BSplineSurface,
    grid: usize,
    floor: f64,
) -> std::result::Result<TriMesh, ::ruled_blocks::Error> {
    let ((u0, u1), (v0, v1)) = sp.domain();
    let t = |a: f64, b: f64, k: usize| a + (b - a) * k as f64 / grid as f64;
    let top: Vec<_> = (0..=grid)
        .flat_map(|i| (0..=grid).map(move |j| (i, j)))
        .map(|(i, j)| sp.eval(t(u0, u1, i), t(v0, v1, j)))
        .collect();
    let low = top.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    ::ruled_blocks::model::slab_under(top, grid, grid, low - floor)
}

impl Task for RuledBlocks {
    const NAME: &'static str = "RuledBlocks";
    const REPORT_SCHEMA: &'static str = "ruled-blocks-report.schema.json";
    const REPORTS_NOTHING_TO_CUT: bool = true;
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Obj, outputs::obj),
        Output::new(OutputKind::Gltf, outputs::gltf),
        Output::new(OutputKind::GCode, outputs::gcode),
    ];
    type Params = RuledBlocksParams;
    type Run = RuledBlocksRun;
    type Report = RuledBlocksReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        job.require_surface_and_block(
            Self::NAME,
            " (a closed mesh, a height field or a B-spline surface)",
            "model is",
            errors,
        );
        if job.block.is_some_and(|b| b.origin.is_some()) {
            errors.push(job.error(
                "/block/origin",
                "RuledBlocks places its blocks itself: leave origin out",
            ));
        }
        if let Some(w) = job.wire {
            crate::wire_machine::check(job, w, errors);
        }
        if job.outputs.iter().any(|o| o.kind() == OutputKind::GCode) && job.wire.is_none() {
            errors.push(job.error(
                "/wire",
                "GCode needs the machine: `wire: Wire(machine: LinuxCncXyuv, tower_distance: .., kerf: ..)`",
            ));
        }
        if self.floor.is_some_and(|f| !(f.is_finite() && f > 0.0)) {
            errors.push(job.error(&format!("{PTR}/floor"), "floor must be positive"));
        }
        if !(self.sample_spacing > 0.0 && self.sample_spacing <= 0.25) {
            errors.push(job.error(
                &format!("{PTR}/sample_spacing"),
                "sample_spacing must be in (0, 0.25]",
            ));
        }
    }

    fn params(&self, job: &Context) -> Result<RuledBlocksParams> {
        let b = job.block(Self::NAME)?;
        let wire = crate::wire_machine::wire_params(job).map(|w| WireParams { steps: 2, ..w });
        let (kerf, lead) = wire
            .as_ref()
            .map_or((0.0, 0.0), |w| (w.kerf_at(w.speed), w.lead));
        Ok(RuledBlocksParams {
            plan: self.plan_params(job, [b.size.0, b.size.1, b.size.2], kerf, lead),
            wire,
            machine: crate::wire_machine::machine(job),
            floor: self
                .floor
                .unwrap_or(defaults::RULED_FLOOR_MM * job.per_mm()),
            grid: self.grid,
            strategy: self.strategy,
        })
    }

    fn estimate(p: &RuledBlocksParams, job: &Context) -> Estimate {
        let faces = match &job.surface {
            Some(Surface::Mesh(m)) => m.faces().len() as f64,
            Some(_) => 4.0 * (p.grid * p.grid) as f64,
            None => 0.0,
        };
        let e = estimate(p, faces, job.surface.as_ref().map(|s| s.aabb()));
        let mut e = Estimate::new(
            e.0,
            e.1,
            "/task/RuledBlocks/sections",
            "lower the task's sections or max_strips, enlarge block.size, or coarsen the model",
        );
        for problem in p.plan.problems() {
            let pointer = match problem.0 {
                "tolerance" => "/tolerance/max".to_string(),
                "block_size" => "/block/size".to_string(),
                "axis" => "/cutting/direction".to_string(),
                "kerf" | "lead" => format!("/wire/{}", problem.0),
                f => format!("{PTR}/{f}"),
            };
            e.checks.push((pointer, problem.1));
        }
        if let Some(Surface::Mesh(m)) = &job.surface {
            let t = m.topology();
            if t.boundary_edges > 0 {
                e.checks.push((
                    "/surface/Mesh/path".into(),
                    format!(
                        "RuledBlocks cuts a solid, but the mesh is open: {} boundary edges in {} loops; close it in the modeller",
                        t.boundary_edges, t.boundary_loops
                    ),
                ));
            } else if let Err(err) = m.validate(true) {
                e.checks
                    .push(("/surface/Mesh/path".into(), err.to_string()));
            }
        }
        // an open B-spline surface must close into a slab: the run's check, made here
        if let Some(Surface::Spline(sp)) = &job.surface {
            if let Err(err) = spline_slab(sp, p.grid, p.floor) {
                e.checks
                    .push(("/surface/Spline/path".into(), err.to_string()));
            }
        }
        if let (Some(w), Some(m), Some(b)) = (&p.wire, &p.machine, &job.block) {
            let widest = b.size.0.max(b.size.1).max(b.size.2);
            if let Err(err) = m.check() {
                e.checks.push(("/wire/machine".into(), err.to_string()));
            }
            if let Err(err) = ruled::wire::check(widest, w) {
                e.checks.push((
                    crate::wire_machine::pointer(err_name(&err)),
                    err.to_string(),
                ));
            }
        }
        e
    }

    fn run(
        params: &RuledBlocksParams,
        job: &Context,
        progress: &dyn Progress,
    ) -> Result<RuledBlocksRun> {
        let model = model(job, params)?;
        progress.start("ruled blocks: whole model", 0);
        let whole = ::ruled_blocks::run(&model, &params.plan, &|p: ::ruled_blocks::Progress| {
            progress.message(&format!("{} {}/{}", p.phase, p.done, p.total));
        })
        .map_err(|e| job.fail(e.to_string()))?;
        progress.message("per block");
        let per_block = ::ruled_blocks::per_block::run(&model, &params.plan)
            .map_err(|e| job.fail(e.to_string()))?;
        progress.finish();
        let figures = [whole.figures.clone(), per_block.figures.clone()];
        let (mesh, strips, blocks, deviation) = match params.strategy {
            Strategy::WholeModel => (
                whole.solid.mesh.clone(),
                whole.solid.strips.clone(),
                whole.blocks.clone(),
                whole.deviation,
            ),
            Strategy::PerBlock => {
                let solids: Vec<&::ruled_blocks::solid::Solid> = per_block
                    .rational
                    .iter()
                    .flatten()
                    .map(|r| &r.solid)
                    .collect();
                (
                    union(&solids).map_err(|e| job.fail(e))?,
                    solids
                        .iter()
                        .flat_map(|s| s.strips.iter().cloned())
                        .collect(),
                    per_block.blocks.clone(),
                    per_block.deviation,
                )
            }
        };
        let mut run = RuledBlocksRun {
            model,
            whole,
            per_block,
            figures,
            strategy: params.strategy,
            mesh,
            strips,
            blocks,
            deviation,
            programs: Vec::new(),
            tolerance: params.plan.tolerance,
        };
        // a run that cuts nothing has no programs (its report lists none)
        if refusal(&run).is_none() {
            run.programs = outputs::programs(&run.blocks, params, job)?;
        }
        Ok(run)
    }

    fn nothing_to_cut(run: &RuledBlocksRun) -> Option<String> {
        refusal(run)
    }

    fn report(
        params: &RuledBlocksParams,
        run: &RuledBlocksRun,
        job: &Context,
    ) -> RuledBlocksReport {
        report::make(params, run, job)
    }

    fn figures(
        _: &RuledBlocksParams,
        run: &RuledBlocksRun,
        r: &RuledBlocksReport,
        job: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let stock: f64 = r
            .blocks
            .iter()
            .map(|b| b.placement.size.iter().product::<f64>())
            .sum();
        let cuts = r.blocks.iter().flat_map(|b| &b.cuts);
        let cut_mm: f64 = cuts.clone().map(|c| c.cut_length_mm).sum();
        let minutes: f64 = cuts.clone().map(|c| c.cut_minutes).sum();
        let programs = cuts.filter(|c| c.program.is_some()).count();
        let hulls: Vec<String> = r
            .blocks
            .iter()
            .filter(|b| !b.cuttable)
            .map(|b| b.index.to_string())
            .collect();
        let why_not = if let Some(n) = &r.nothing_to_cut {
            Some(n.clone())
        } else if !r.deviation.within_tolerance {
            Some(format!(
                "the ruled rationalization deviates up to {:.4} from the design (tolerance {})",
                r.deviation.max, r.tolerance
            ))
        } else if !hulls.is_empty() && r.totals.added_depth > r.tolerance {
            Some(format!(
                "{} of {} blocks (number {}) cannot be cut by their strips, only to their convex hulls, which add {:.4e} of material up to {:.4} deep (tolerance {})",
                hulls.len(),
                r.blocks.len(),
                hulls.join(", "),
                r.totals.added_volume,
                r.totals.added_depth,
                r.tolerance
            ))
        } else if programs == 0 {
            Some("no wire program (the job gives no `wire`)".into())
        } else {
            None
        };
        Some(crate::process::ProcessFigures {
            why_not,
            blocks: r.blocks.len(),
            stock_volume: stock,
            part_volume: r.model.volume,
            milling_volume: 0.0,
            milled_area: 0.0,
            cutter: crate::process::Cutter::Wire,
            cut_length: cut_mm * job.per_mm(),
            cut_speed: if minutes > 0.0 {
                cut_mm * job.per_mm() / (60.0 * minutes)
            } else {
                0.0
            },
            dwell_s: run
                .programs
                .iter()
                .flatten()
                .map(|p| p.summary.preheat_s)
                .sum(),
            // a block is mounted again for every cut whose mount differs from the last
            setups: r
                .blocks
                .iter()
                .map(|b| {
                    let turns = b
                        .cuts
                        .windows(2)
                        .filter(|w| w[0].mount != w[1].mount)
                        .count();
                    usize::from(!b.cuts.is_empty()) + turns
                })
                .sum(),
            programs,
            // a block cut to its hull keeps material up to `added_depth` above the design
            deviation: Some(crate::process::Deviation {
                rms: r.deviation.rms,
                max: r.deviation.max.max(r.totals.added_depth),
            }),
        })
    }

    fn page(r: &RuledBlocksReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &RuledBlocksReport, job: &Context) -> String {
        format!(
            "{} (RuledBlocks, {:?}): {} region(s), deviation RMS {:.4} max {:.4} {} ({:.3e} / {:.3e} of the diagonal, tolerance {}); {} block(s), {} cut by their strips, {} to their hulls (added {:.4e} {}³); {} cut(s)",
            job.name,
            r.strategy,
            r.regions.len(),
            r.deviation.rms,
            r.deviation.max,
            job.units.symbol(),
            r.deviation.rms_fraction,
            r.deviation.max_fraction,
            r.tolerance,
            r.blocks.len(),
            r.totals.cuttable,
            r.blocks.len() - r.totals.cuttable,
            r.totals.added_volume,
            job.units.symbol(),
            r.totals.cuts
        )
    }
}

/// The meshes as one (their vertices and faces side by side).
fn union(solids: &[&::ruled_blocks::solid::Solid]) -> std::result::Result<TriMesh, String> {
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for s in solids {
        let base = v.len() as u32;
        v.extend_from_slice(s.mesh.vertices());
        f.extend(s.mesh.faces().iter().map(|t| t.map(|i| i + base)));
    }
    TriMesh::try_new(v, f).map_err(|e| e.to_string())
}

/// Memory (bytes) and work (steps, ~10⁸ a second) of a run on a model of `faces`
/// triangles in the box `bounds`: both strategies slice every face at every section (the
/// per-block one for each block and each of its three axes), and probe each block's strips
/// and lattice. Blocks are counted as the box's volume over a block's, and sections with
/// as many again added where loops split or merge. Measured against run times in
/// BENCHMARKS.md ("Segmentation versus rationalization").
fn estimate(p: &RuledBlocksParams, faces: f64, bounds: Option<geom::bbox::Aabb>) -> (f64, f64) {
    let size = p.plan.blocks.block_size;
    let blocks = bounds.map_or(1.0, |b| {
        let s = b.size();
        (0..3)
            .map(|k| (s[k] / size[k]).ceil().max(1.0))
            .product::<f64>()
    });
    let sections = 2.0 * p.plan.sections as f64;
    let strips = p.plan.max_strips as f64;
    let slicing = (1.0 + 3.0 * blocks) * sections * faces * 20.0;
    let probing = blocks * (strips * sections * 400.0 + 4096.0 * 400.0);
    // the run grows with the square of the sections (every ruling's wire checked against
    // rows of every section): measured on the half sphere (4 blocks by this count, 48
    // strips) as about 1e-3 s · sections² from 24 to 400 sections, ~540 steps per block,
    // strip and section²; counted 700 (a tilted cutting direction is slower)
    let checks = blocks * strips * (p.plan.sections as f64).powi(2) * 700.0;
    let solid = strips * sections * 2.0;
    let memory = faces * 400.0 + blocks * solid * 200.0 + 5e7;
    (memory, slicing + probing + checks)
}

fn err_name(e: &ruled::PreCutError) -> &'static str {
    match e {
        ruled::PreCutError::InvalidParameter { name, .. } => name,
        _ => "machine",
    }
}

/// Why a run cuts nothing (the rationalized model is off the model by more than the
/// tolerance, or no block has a cut), with numbers; `None` when it cuts.
fn refusal(run: &RuledBlocksRun) -> Option<String> {
    let d = &run.deviation;
    if d.max > run.tolerance {
        return Some(format!(
            "no piecewise ruled surface of these settings comes within the tolerance ({:?}): deviation max {:.6} (RMS {:.6}) > tolerance.max {}; add sections or max_strips, or raise tolerance.max",
            run.strategy, d.max, d.rms, run.tolerance
        ));
    }
    if run.blocks.iter().all(|b| b.cuts.is_empty()) {
        return Some("no block has a cut".into());
    }
    None
}
