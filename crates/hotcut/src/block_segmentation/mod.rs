//! The `BlockSegmentation` task (thesis ch. 3): the job's closed mesh covered by as few
//! freely placed blocks of `block.size` as possible, by [`blocks::segment`].
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // jobs/blocks-torus.ron:
//! //   surface: Mesh(path: "models/torus.obj", closed: true),
//! //   block: Block(size: (0.55, 0.55, 0.55)),
//! //   task: BlockSegmentation(restarts: 2, coverage: Solid),
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/blocks-torus.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{:?}", outcome.files);
//! # Ok(()) }
//! ```

/// Its files: `blocks.json`, `blocks.obj`, `model.gltf`, `progress.svg`.
mod outputs;
/// What `report.html` shows of it.
mod page;

/// `blocks.json` (schema `schemas/blocks.schema.json`).
#[derive(Debug, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlocksFile<'a> {
    /// Length unit of centres and sizes.
    pub units: Units,
    /// Every block: centre, rotation `[w, x, y, z]` (a unit quaternion taking block axes
    /// to model axes) and edge lengths, in the mesh's coordinates.
    pub blocks: &'a [blocks::Placement],
}

use geom::mesh::TriMesh;
use geom::surface::Surface;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::Estimate;
use crate::progress::Progress;
use crate::spec::{OutputKind, SurfaceSpec, Units};
use crate::task::{Output, Task};

/// Volumetric block segmentation (thesis ch. 3): cover a closed mesh
/// (`surface: Mesh(path: .., closed: true)`) with as few freely translated and rotated
/// blocks of `block.size` as possible, by the stochastic optimization of §3.3. The
/// job's `seed` seeds it. Write `BlockSegmentation(restarts: 4, coverage: Solid)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockSegmentation {
    /// Operations used: any of `Translate`, `Rotate`, `Align` (the ablation of
    /// Table 3.2). Default: all three.
    #[serde(default = "default_block_operations")]
    #[schemars(length(min = 1, max = 3))]
    pub operations: Vec<blocks::Operation>,
    /// `Solid`: the model's volume must lie in the union of blocks; `Surface`: only
    /// its surface. Default: `Solid`.
    #[serde(default)]
    pub coverage: blocks::Coverage,
    /// Exponent p of eq. 3.3 (≥ 1). Default: 2.
    #[serde(default = "default_block_p")]
    #[schemars(range(min = 1))]
    pub p: f64,
    /// ε of eq. 3.3 (> 0), as a fraction of the block's volume. Default: 1e-5.
    #[serde(default = "default_block_epsilon")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub epsilon: f64,
    /// Independent runs in parallel, seeds derived from the job's `seed`; the run
    /// with the fewest blocks is kept. Default: 1.
    #[serde(default = "default_restarts")]
    #[schemars(range(min = 1, max = 256))]
    pub restarts: u32,
    /// Iteration cap per run (an iteration is one cycle over the blocks, of moves or
    /// of alignment). Default: 200.
    #[serde(default = "default_block_iterations")]
    #[schemars(range(min = 1))]
    pub max_iterations: u32,
    /// Wall-time cap per run, seconds (> 0). Results then depend on the machine's
    /// speed; prefer `max_iterations`. Default: none.
    #[serde(default)]
    pub time_limit: Option<f64>,
    /// Interior sample spacing as a fraction of the block's shortest edge, in
    /// (0, 0.25]; blocks are shrunk by this spacing (half of it for `Surface`) when
    /// testing coverage, so that covering the samples covers the model. Default: 0.05.
    #[serde(default = "default_sample_spacing")]
    #[schemars(extend("exclusiveMinimum" = 0), range(max = 0.25))]
    pub sample_spacing: f64,
}

fn default_block_operations() -> Vec<blocks::Operation> {
    vec![
        blocks::Operation::Translate,
        blocks::Operation::Rotate,
        blocks::Operation::Align,
    ]
}
fn default_block_p() -> f64 {
    2.0
}
fn default_block_epsilon() -> f64 {
    1e-5
}
fn default_restarts() -> u32 {
    1
}
fn default_block_iterations() -> u32 {
    200
}
fn default_sample_spacing() -> f64 {
    0.05
}

/// The report of a `BlockSegmentation` run (`report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct BlockSegReport {
    /// Job name.
    pub job: String,
    /// Task name, `BlockSegmentation`.
    pub task: String,
    /// Length unit of every length.
    pub units: Units,
    /// The hotcut version that wrote it.
    pub hotcut_version: String,
    /// The model: vertices, faces, volume.
    pub model: ModelInfo,
    /// The box of what `model.gltf` shows (the model and the blocks).
    pub model_bounds: Option<crate::report::ModelBounds>,
    /// The parameters the optimizer ran with.
    pub params: blocks::Params,
    /// The result: counts, reduction, lower bound, history (fig. 3.6), acceptance
    /// counts, every restart, and the blocks.
    pub segmentation: blocks::Segmentation,
}

/// What the model is.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ModelInfo {
    /// Mesh vertices.
    pub vertices: usize,
    /// Mesh triangles.
    pub faces: usize,
    /// Enclosed volume.
    pub volume: f64,
}

/// A finished run: the segmentation and the mesh, for the output files.
#[derive(Debug, Clone)]
pub struct BlockSegRun {
    /// The optimizer's result.
    pub segmentation: blocks::Segmentation,
    /// The model.
    pub mesh: TriMesh,
}

const PTR: &str = "/task/BlockSegmentation";

impl Task for BlockSegmentation {
    const NAME: &'static str = "BlockSegmentation";
    const REPORT_SCHEMA: &'static str = "block-segmentation-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Blocks, outputs::blocks_json),
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Obj, outputs::obj),
        Output::new(OutputKind::Gltf, outputs::gltf),
    ];
    type Params = blocks::Params;
    type Run = BlockSegRun;
    type Report = BlockSegReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        job.require_surface_and_block(Self::NAME, " (a closed mesh)", "model is", errors);
        // whether the mesh is closed is checked on the mesh itself (`estimate`), so
        // `closed: true` need not be written
        match job.surface {
            Some(SurfaceSpec::Mesh { .. }) | None => {}
            Some(_) => errors.push(job.error(
                "/surface",
                "BlockSegmentation needs a closed triangle mesh: `Mesh(path: ..)`",
            )),
        }
        if job.block.is_some_and(|b| b.origin.is_some()) {
            errors.push(job.error(
                "/block/origin",
                "BlockSegmentation places its blocks itself: leave origin out",
            ));
        }
        // the optimizer's own checks, on these fields (the block's size is checked by load)
        let problems = self.optimizer([1.0; 3], 0).problems();
        let problems = problems.into_iter().map(|e| (e.field, e.index, e.message));
        let element = |i: usize| format!("{:?}", self.operations[i]);
        job.param_problems(PTR, problems, element, errors);
    }

    fn params(&self, job: &Context) -> Result<blocks::Params> {
        let b = job.block(Self::NAME)?;
        Ok(self.optimizer([b.size.0, b.size.1, b.size.2], job.seed))
    }

    fn estimate(p: &blocks::Params, job: &Context) -> Estimate {
        let (samples, open) = match &job.surface {
            Some(Surface::Mesh(mesh)) => {
                let t = mesh.topology();
                let open = (t.boundary_edges > 0).then_some((t.boundary_edges, t.boundary_loops));
                (blocks::estimated_samples(mesh, p), open)
            }
            _ => (0.0, None),
        };
        let mut e = Estimate::new(
            samples * 96.0 + 1e7,
            samples * 2e3 * p.restarts as f64,
            "/block/size",
            "enlarge block.size or the task's sample_spacing, or lower its restarts",
        );
        if let Some((edges, loops)) = open {
            e.checks.push((
                "/surface/Mesh/path".into(),
                format!(
                    "BlockSegmentation covers a solid, but the mesh is open: {edges} boundary edges in {loops} loops; close it in the modeller"
                ),
            ));
        }
        if !(samples <= p.max_samples as f64) {
            e.checks.push((
                format!("{PTR}/sample_spacing"),
                format!(
                    "about {samples:.3e} samples would be needed, more than the cap of {}: use a larger block or a coarser sample_spacing",
                    p.max_samples
                ),
            ));
        }
        e
    }

    fn run(params: &blocks::Params, job: &Context, progress: &dyn Progress) -> Result<BlockSegRun> {
        let Some(Surface::Mesh(mesh)) = &job.surface else {
            return Err(job.fail("task BlockSegmentation needs a closed mesh surface"));
        };
        let total = params.max_iterations as u64 * params.restarts as u64;
        progress.start("block segmentation", total);
        let segmentation = blocks::segment(mesh, params, &|p: blocks::Progress| {
            progress.tick();
            progress.message(&format!(
                "run {} · iteration {} · {} blocks · E {:.4}",
                p.restart + 1,
                p.iteration,
                p.blocks,
                p.energy
            ));
        })
        .map_err(|e| job.fail(e.to_string()))?;
        progress.finish();
        Ok(BlockSegRun {
            segmentation,
            mesh: mesh.clone(),
        })
    }

    fn nothing_to_cut(run: &BlockSegRun) -> Option<String> {
        run.segmentation
            .blocks
            .is_empty()
            .then(|| "the segmentation placed no block".to_string())
    }

    fn figures(
        params: &blocks::Params,
        run: &BlockSegRun,
        report: &BlockSegReport,
        _: &Context,
    ) -> Option<crate::process::ProcessFigures> {
        let s = &report.segmentation;
        let stock: f64 = s
            .blocks
            .iter()
            .map(|b| b.size.iter().product::<f64>())
            .sum();
        // milling stock must hold the solid, not only its surface
        let why_not = (params.coverage != blocks::Coverage::Solid).then(|| {
            "the blocks cover the model's surface only (coverage: Surface): milling stock must hold the solid, set coverage: Solid".to_string()
        });
        Some(crate::process::ProcessFigures::milled(
            s.blocks.len(),
            stock,
            s.model_volume,
            run.mesh.area(),
            why_not,
        ))
    }

    fn report(params: &blocks::Params, run: &BlockSegRun, job: &Context) -> BlockSegReport {
        BlockSegReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            model: ModelInfo {
                vertices: run.mesh.vertices().len(),
                faces: run.mesh.faces().len(),
                volume: run.segmentation.model_volume,
            },
            model_bounds: crate::report::ModelBounds::of(outputs::scene(run)),
            params: params.clone(),
            segmentation: run.segmentation.clone(),
        }
    }

    fn page(r: &BlockSegReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &BlockSegReport, job: &Context) -> String {
        let s = &r.segmentation;
        format!(
            "{} (BlockSegmentation): {} → {} block(s), {:.1} % fewer (lower bound {}); best of {} run(s), {} iteration(s); accepted {} translation(s), {} rotation(s), {} alignment(s)",
            job.name,
            s.initial_blocks,
            s.final_blocks,
            s.reduction_percent,
            s.lower_bound,
            s.restarts.len(),
            s.history.last().map_or(0, |h| h.iteration),
            s.accepted.translations,
            s.accepted.rotations,
            s.accepted.alignments
        )
    }
}

impl BlockSegmentation {
    /// The optimizer's parameters for blocks of `block_size`.
    fn optimizer(&self, block_size: [f64; 3], seed: u64) -> blocks::Params {
        blocks::Params {
            block_size,
            operations: self.operations.clone(),
            coverage: self.coverage,
            p: self.p,
            epsilon: self.epsilon,
            restarts: self.restarts,
            seed,
            max_iterations: self.max_iterations,
            time_limit: self.time_limit,
            sample_spacing: self.sample_spacing,
            ..blocks::Params::default()
        }
    }
}
