//! The `PreCut` task (thesis ch. 2): hot-wire cuts that remove the bulk of a block above
//! the design surface before milling, never cutting into it, by [`ruled::pre_cut`].
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // jobs/precut-bump.ron:
//! //   surface: HeightField(z: "...", x: (-0.5, 0.5), y: (-0.5, 0.5)),
//! //   block: Block(size: (1.0, 1.0, 0.6)),
//! //   task: PreCut(legs: 4, directions: [X]),
//! let job = hotcut::load::load_job(std::path::Path::new("jobs/precut-bump.ron"))
//!     .map_err(|errors| format!("{errors:?}"))?;
//! let outcome = hotcut::run::run_job(&job, std::path::Path::new("out"), &hotcut::NoProgress)?;
//! println!("{:?}", outcome.files);
//! # Ok(()) }
//! ```

pub mod outputs;

use geom::surface::Surface;
use schemars::JsonSchema;
use serde::Serialize;

use crate::error::{HotcutError, Result};
use crate::job::{TaskSpec, Units};
use crate::load::ResolvedJob;
use crate::Progress;

/// The report of a `PreCut` run (`report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PreCutReport {
    /// Length unit of every length.
    pub units: Units,
    /// The block: minimum and maximum corner.
    pub block: ruled::Block,
    /// The optimizer's parameters as run.
    pub params: ruled::Params,
    /// Table 2.1: volumes normalised by the block.
    pub volumes: ruled::Volumes,
    /// Per direction: rounds, QPs, constraint points, objective history, clearance.
    pub directions: Vec<DirectionSummary>,
}

/// What the optimizer did for one direction.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct DirectionSummary {
    /// Unit cutting direction.
    pub direction: [f64; 3],
    /// Assignment rounds.
    pub rounds: usize,
    /// QPs solved.
    pub qps: usize,
    /// Constraint points at the end.
    pub constraint_points: usize,
    /// Objective per round.
    pub objective_history: Vec<f64>,
    /// Least height of a cut above the design on the check grid (> 0).
    pub clearance: f64,
}

/// A finished run.
#[derive(Debug, Clone)]
pub struct PreCutRun {
    /// The report.
    pub report: PreCutReport,
    /// The full result (polygons, legs).
    pub cut: ruled::PreCut,
    /// The design surface.
    pub surface: Surface,
    /// The wire machine, when the job has one (`GCode`, `Csv`).
    pub wire: Option<ruled::wire::WireParams>,
    /// The job's name.
    pub name: String,
}

/// The wire machine's settings of a job, in job units (`None` without `wire`).
pub fn wire_params(job: &ResolvedJob) -> Option<ruled::wire::WireParams> {
    let w = job.job.wire.as_ref()?;
    let unit = job.job.units.per_mm();
    Some(ruled::wire::WireParams {
        tower_distance: w.tower_distance,
        kerf: w.kerf,
        speed: w.speed.unwrap_or(300.0 * unit),
        lead: w.lead.unwrap_or(20.0 * unit),
        clearance: w.clearance.unwrap_or(50.0 * unit),
        steps: 0,
        mm_per_unit: 1.0 / unit,
    })
}

/// The optimizer's parameters and block for a resolved `PreCut` job (`None` for other
/// tasks or without a block).
pub fn params_from_job(job: &ResolvedJob) -> Option<(ruled::Params, ruled::Block)> {
    let TaskSpec::PreCut {
        legs,
        directions,
        degree,
        controls,
        sections,
        samples,
        max_rounds,
    } = &job.job.task
    else {
        return None;
    };
    let spec = job.job.block.as_ref()?;
    let origin = match spec.origin {
        Some(o) => [o.0, o.1, o.2],
        None => {
            let b = job.surface.as_ref()?.aabb();
            [b.min.x, b.min.y, b.min.z]
        }
    };
    let size = [spec.size.0, spec.size.1, spec.size.2];
    let block = ruled::Block {
        min: origin,
        max: [
            origin[0] + size[0],
            origin[1] + size[1],
            origin[2] + size[2],
        ],
    };
    Some((
        ruled::Params {
            legs: *legs as usize,
            directions: directions.iter().map(|d| d.vector()).collect(),
            degree: *degree as usize,
            controls: *controls as usize,
            sections: *sections as usize,
            samples: *samples as usize,
            max_rounds: *max_rounds as usize,
            ..ruled::Params::default()
        },
        block,
    ))
}

/// Runs the task.
///
/// # Errors
/// [`HotcutError::Task`] for a job without a surface or block, or when the optimizer
/// rejects the input or cannot verify its result.
pub fn pre_cut(job: &ResolvedJob, progress: &dyn Progress) -> Result<PreCutRun> {
    let fail = |message: String| HotcutError::Task {
        path: job.path.clone(),
        message,
    };
    let (params, block) = params_from_job(job)
        .ok_or_else(|| fail("task PreCut needs a surface and a block".into()))?;
    let Some(surface) = &job.surface else {
        return Err(fail("task PreCut needs a surface".into()));
    };
    progress.start(
        "pre-cut",
        (params.directions.len() * params.max_rounds) as u64,
    );
    let cut = ruled::pre_cut(surface, &block, &params, &|p: ruled::Progress| {
        progress.tick();
        progress.message(&format!(
            "direction {} · round {} · Σd² {:.4e}",
            p.direction + 1,
            p.round + 1,
            p.objective
        ));
    })
    .map_err(|e| fail(e.to_string()))?;
    progress.finish();
    let report = PreCutReport {
        units: job.job.units,
        block,
        params: params.clone(),
        volumes: cut.volumes,
        directions: cut
            .directions
            .iter()
            .map(|d| DirectionSummary {
                direction: d.direction,
                rounds: d.rounds,
                qps: d.qps,
                constraint_points: d.constraint_points,
                objective_history: d.objective_history.clone(),
                clearance: d.clearance,
            })
            .collect(),
    };
    let wire = wire_params(job).map(|w| ruled::wire::WireParams {
        steps: params.sections + 1,
        ..w
    });
    if let Some(w) = &wire {
        // Refuse bad machine settings now rather than while writing files.
        for (i, d) in cut.directions.iter().enumerate() {
            ruled::wire::paths(d, i, block.min[2], w).map_err(|e| fail(e.to_string()))?;
        }
    }
    Ok(PreCutRun {
        report,
        cut,
        surface: surface.clone(),
        wire,
        name: job.job.name.clone(),
    })
}
