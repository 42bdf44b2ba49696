//! The `BlockSegmentation` task (thesis ch. 3): the job's closed mesh covered by as few
//! freely placed blocks of `block.size` as possible, by [`blocks::segment`].
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // jobs/blocks-torus.ron:
//! //   surface: Mesh(path: "../../shared/data/meshes/torus.obj", closed: true),
//! //   block: Block(size: (0.55, 0.55, 0.55)),
//! //   task: BlockSegmentation(restarts: 2, coverage: Solid),
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/blocks-torus.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{:?}", outcome.files);
//! # Ok(()) }
//! ```

pub mod outputs;

use std::sync::atomic::{AtomicUsize, Ordering};

use geom::mesh::TriMesh;
use geom::surface::Surface;
use schemars::JsonSchema;
use serde::Serialize;

use crate::error::{HotcutError, Result};
use crate::job::{TaskSpec, Units};
use crate::load::ResolvedJob;
use crate::Progress;

/// The report of a `BlockSegmentation` run (`report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct BlockSegReport {
    /// Length unit of every length.
    pub units: Units,
    /// The model: vertices, faces, volume.
    pub model: ModelInfo,
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

/// A finished run: the report and the mesh, for the output files.
#[derive(Debug, Clone)]
pub struct BlockSegRun {
    /// The report.
    pub report: BlockSegReport,
    /// The model.
    pub mesh: TriMesh,
}

/// The optimizer's parameters for a resolved `BlockSegmentation` job (`None` for other
/// tasks or without a block).
pub fn params_from_job(job: &ResolvedJob) -> Option<blocks::Params> {
    let TaskSpec::BlockSegmentation {
        operations,
        coverage,
        p,
        epsilon,
        restarts,
        max_iterations,
        time_limit,
        sample_spacing,
    } = &job.job.task
    else {
        return None;
    };
    let block = job.job.block.as_ref()?;
    Some(blocks::Params {
        block_size: [block.size.0, block.size.1, block.size.2],
        operations: operations.clone(),
        coverage: *coverage,
        p: *p,
        epsilon: *epsilon,
        restarts: *restarts,
        seed: job.job.seed,
        max_iterations: *max_iterations,
        time_limit: *time_limit,
        sample_spacing: *sample_spacing,
        ..blocks::Params::default()
    })
}

/// Runs the task.
///
/// # Errors
/// [`HotcutError::Task`] for a job without a mesh or block, or when the optimizer
/// rejects the model or parameters.
pub fn block_segmentation(job: &ResolvedJob, progress: &dyn Progress) -> Result<BlockSegRun> {
    let fail = |message: String| HotcutError::Task {
        path: job.path.clone(),
        message,
    };
    let params =
        params_from_job(job).ok_or_else(|| fail("task BlockSegmentation needs a block".into()))?;
    let Some(Surface::Mesh(mesh)) = &job.surface else {
        return Err(fail(
            "task BlockSegmentation needs a closed mesh surface".into(),
        ));
    };
    let total = params.max_iterations as u64 * params.restarts as u64;
    progress.start("block segmentation", total);
    let done = AtomicUsize::new(0);
    let seg = blocks::segment(mesh, &params, &|p: blocks::Progress| {
        done.fetch_add(1, Ordering::Relaxed);
        progress.tick();
        progress.message(&format!(
            "run {} · iteration {} · {} blocks · E {:.4}",
            p.restart + 1,
            p.iteration,
            p.blocks,
            p.energy
        ));
    })
    .map_err(|e| fail(e.to_string()))?;
    progress.finish();
    Ok(BlockSegRun {
        report: BlockSegReport {
            units: job.job.units,
            model: ModelInfo {
                vertices: mesh.vertices().len(),
                faces: mesh.faces().len(),
                volume: seg.model_volume,
            },
            params,
            segmentation: seg,
        },
        mesh: mesh.clone(),
    })
}
