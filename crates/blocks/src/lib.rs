//! # blocks — volumetric block segmentation (thesis ch. 3)
//!
//! Covers a closed mesh with as few freely translated and rotated stock blocks as
//! possible. Initialization: a near-minimum-volume oriented bounding box of the model and
//! a grid of blocks aligned with it, blocks that cover nothing dropped. Optimization: the
//! stochastic loop of §3.3.5 over translation (§3.3.2), rotation (§3.3.3) and alignment
//! (§3.3.4), driven by the objective E of eq. 3.3 with exact box–box overlap volumes.
//!
//! Coverage is tracked on samples of the model (see [`samples`]): every sample knows how
//! many blocks cover it, a block goes when every sample it covers has another block, and
//! no operation ever leaves a sample uncovered.
//!
//! ```
//! use blocks::{segment, Params};
//! use geom::mesh::TriMesh;
//! use nalgebra::Vector3;
//!
//! // A 3 × 1 × 1 bar covered with blocks of 1.2 × 1.2 × 1.2.
//! let v: Vec<Vector3<f64>> = (0..8)
//!     .map(|i| Vector3::new(3.0 * (i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
//!     .collect();
//! let f = vec![[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
//!              [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]];
//! let bar = TriMesh::try_new(v.clone(), f)?;
//! let params = Params { block_size: [1.2, 1.2, 1.2], ..Params::default() };
//! let seg = segment(&bar, &params, &|_| {})?;
//! // volume 3 needs at least ⌈3 / 1.728⌉ = 2 blocks; the optimization never adds any
//! assert_eq!(seg.lower_bound, 2);
//! assert!(seg.final_blocks <= seg.initial_blocks);
//! assert_eq!(seg.blocks.len(), seg.final_blocks);
//! // every corner of the bar lies in a block
//! assert!(v.iter().all(|p| seg.blocks.iter().any(|b| b.cuboid().contains(p, -1e-9))));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// An oriented block and exact box–box overlap volumes.
pub mod cuboid;
/// Why a segmentation failed.
pub mod error;
/// The translation, rotation and alignment proposals of §3.3.
pub mod moves;
/// Near-minimum-volume oriented bounding boxes of point sets.
pub mod obb;
/// The loop of §3.3.5 for one seed.
pub mod optimize;
/// Model samples and their spatial index.
pub mod samples;
/// Blocks, cover counts and the objective E.
pub mod state;
/// The unit frame a segmentation is computed in.
pub mod unit;

use std::time::Instant;

use geom::mesh::TriMesh;
use nalgebra::{UnitQuaternion, Vector3};
use rayon::prelude::*;

pub use cuboid::{overlap_volume, Cuboid};
pub use error::{BlockError, Result};
pub use obb::{box_in_frame, min_box, BoxFit};
pub use samples::{Coverage, SampleCounts};

/// One of the operations of §3.3 (the ablation of Table 3.2 picks a subset).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum Operation {
    /// Pure translation (§3.3.2).
    Translate,
    /// Rotation onto the minimal box of the block's exclusive part (§3.3.3).
    Rotate,
    /// Alignment of a block and its neighbours onto a grid (§3.3.4).
    Align,
}

/// Parameters of a block segmentation.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct Params {
    /// Block edge lengths (model units).
    pub block_size: [f64; 3],
    /// Operations used (default all three).
    pub operations: Vec<Operation>,
    /// What must be covered.
    pub coverage: Coverage,
    /// Exponent p of eq. 3.3 (≥ 1).
    pub p: f64,
    /// ε of eq. 3.3 (> 0), as a fraction of the block's volume (the paper's ε is a
    /// volume; relative, the energy does not depend on the unit of length).
    pub epsilon: f64,
    /// Independent runs (in parallel), the best kept.
    pub restarts: u32,
    /// Seed; run k uses a seed derived from it and k.
    pub seed: u64,
    /// Iteration cap per run (an iteration is one cycle over the blocks).
    pub max_iterations: u32,
    /// Wall-time cap per run in seconds. Results then depend on the machine's speed; use
    /// `max_iterations` for reproducible results.
    pub time_limit: Option<f64>,
    /// Interior sample spacing as a fraction of the shortest block edge (0 < f ≤ 0.25);
    /// also the coverage margin (half of it for `Surface` coverage).
    pub sample_spacing: f64,
    /// Most samples allowed.
    pub max_samples: usize,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            block_size: [1.0, 1.0, 1.0],
            operations: vec![Operation::Translate, Operation::Rotate, Operation::Align],
            coverage: Coverage::Solid,
            p: 2.0,
            epsilon: 1e-5,
            restarts: 1,
            seed: 0,
            max_iterations: 200,
            time_limit: None,
            sample_spacing: 0.05,
            max_samples: 8_000_000,
        }
    }
}

/// A block in the result: centre, rotation `[w, x, y, z]` (a unit quaternion taking block
/// axes to model axes) and edge lengths, in the mesh's coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub struct Placement {
    /// Centre.
    pub center: [f64; 3],
    /// Unit quaternion `[w, x, y, z]` with `w ≥ 0`.
    pub rotation: [f64; 4],
    /// Edge lengths along the block's axes.
    pub size: [f64; 3],
}

impl Placement {
    /// The placement of a block.
    ///
    /// ```
    /// use blocks::{Cuboid, Placement};
    /// use nalgebra::{UnitQuaternion, Vector3};
    /// let q = UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3);
    /// let b = Cuboid::new(Vector3::new(1.0, 2.0, 3.0), q, Vector3::new(0.5, 1.0, 1.5));
    /// let p = Placement::of(&b);
    /// assert_eq!((p.center, p.size), ([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]));
    /// assert!(p.rotation[0] >= 0.0);
    /// // and back: the same block
    /// let back = p.cuboid();
    /// assert!(back.corners().iter().zip(b.corners()).all(|(a, c)| (a - c).norm() < 1e-12));
    /// ```
    pub fn of(b: &Cuboid) -> Self {
        let q = b.rotation.into_inner();
        let s = if q.w < 0.0 { -1.0 } else { 1.0 };
        Self {
            center: b.center.into(),
            rotation: [s * q.w, s * q.i, s * q.j, s * q.k],
            size: (b.half * 2.0).into(),
        }
    }

    /// The block it describes.
    pub fn cuboid(&self) -> Cuboid {
        let [w, x, y, z] = self.rotation;
        Cuboid::new(
            Vector3::from(self.center),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
            Vector3::from(self.size) / 2.0,
        )
    }

    /// The block as a closed box mesh ([`geom::mesh::TriMesh::cuboid`] of
    /// [`Cuboid::corners`]).
    ///
    /// # Errors
    /// A box with a non-finite corner.
    pub fn mesh(&self) -> std::result::Result<geom::mesh::TriMesh, geom::GeomError> {
        geom::mesh::TriMesh::cuboid(self.cuboid().corners())
    }
}

/// Which step of the loop an iteration was.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub enum Phase {
    /// The initial grid.
    Init,
    /// A cycle of translations and rotations.
    Move,
    /// An alignment pass.
    Align,
}

/// Block count and objective after one iteration (fig. 3.6).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct IterationRecord {
    /// Iteration number (0: the initial state).
    pub iteration: usize,
    /// What the iteration did.
    pub phase: Phase,
    /// Blocks after it.
    pub blocks: usize,
    /// E of eq. 3.3 after it.
    pub energy: f64,
}

/// Accepted operations of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Acceptance {
    /// Translations performed.
    pub translations: usize,
    /// Rotations performed.
    pub rotations: usize,
    /// Alignments performed.
    pub alignments: usize,
    /// Blocks removed (by removal checks and alignments).
    pub removals: usize,
}

/// Why a run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub enum StopReason {
    /// Two alignment passes in a row removed nothing (or, without alignment, a cycle
    /// of moves improved nothing).
    Converged,
    /// `max_iterations` reached.
    IterationCap,
    /// `time_limit` reached.
    TimeCap,
}

/// One restart's outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct RestartSummary {
    /// Its seed.
    pub seed: u64,
    /// Blocks at the end.
    pub blocks: usize,
    /// E at the end.
    pub energy: f64,
    /// Iterations run.
    pub iterations: usize,
    /// Why it stopped.
    pub stop: StopReason,
}

/// A finished block segmentation.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Segmentation {
    /// The blocks, in the mesh's coordinates.
    pub blocks: Vec<Placement>,
    /// Blocks of the initial grid.
    pub initial_blocks: usize,
    /// Blocks at the end.
    pub final_blocks: usize,
    /// `100 · (initial − final) / initial`.
    pub reduction_percent: f64,
    /// ⌈model volume / block volume⌉: no cover of the solid can use fewer blocks.
    pub lower_bound: usize,
    /// Model volume.
    pub model_volume: f64,
    /// Volume of one block.
    pub block_volume: f64,
    /// The model's oriented bounding box that the initial grid is aligned with.
    pub bounding_box: Placement,
    /// Samples by kind, spacing and margin.
    pub sampling: SamplingInfo,
    /// The seed of the job.
    pub seed: u64,
    /// Index of the restart kept.
    pub best_restart: usize,
    /// Every restart's outcome.
    pub restarts: Vec<RestartSummary>,
    /// The kept run's iterations (fig. 3.6).
    pub history: Vec<IterationRecord>,
    /// The kept run's accepted operations.
    pub accepted: Acceptance,
    /// E at the end.
    pub energy: f64,
}

/// How the model was sampled.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SamplingInfo {
    /// Samples by kind.
    pub counts: SampleCounts,
    /// Interior grid spacing.
    pub spacing: f64,
    /// Margin blocks are shrunk by when testing coverage.
    pub margin: f64,
}

/// Progress after one iteration of one restart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// The restart.
    pub restart: usize,
    /// Its iteration.
    pub iteration: usize,
    /// Blocks now.
    pub blocks: usize,
    /// E now.
    pub energy: f64,
}

pub use geom::ParamProblem;

impl Params {
    /// Every parameter [`segment`] refuses, in field order (none: it runs).
    pub fn problems(&self) -> Vec<ParamProblem> {
        let mut out = Vec::new();
        let mut bad = |field: &'static str, index: Option<usize>, message: String| {
            out.push(ParamProblem {
                field,
                index,
                message,
            });
        };
        if self
            .block_size
            .iter()
            .any(|&s| !(s > 0.0) || !s.is_finite())
        {
            bad(
                "block_size",
                None,
                format!(
                    "edges must be positive and finite, got {:?}",
                    self.block_size
                ),
            );
        }
        if self.operations.is_empty() {
            bad(
                "operations",
                None,
                "needs at least one of Translate, Rotate, Align".into(),
            );
        }
        for (i, o) in self.operations.iter().enumerate() {
            if self.operations[..i].contains(o) {
                bad("operations", Some(i), "is listed twice".into());
            }
        }
        if !(self.p >= 1.0) || !self.p.is_finite() {
            bad(
                "p",
                None,
                format!("must be a finite number ≥ 1, got {:?}", self.p),
            );
        }
        if !(self.epsilon > 0.0) || !self.epsilon.is_finite() {
            bad(
                "epsilon",
                None,
                format!("must be positive and finite, got {:?}", self.epsilon),
            );
        }
        if !(1..=256).contains(&self.restarts) {
            bad(
                "restarts",
                None,
                format!("must be 1–256, got {}", self.restarts),
            );
        }
        if self.max_iterations == 0 {
            bad("max_iterations", None, "must be at least 1".into());
        }
        if let Some(t) = self.time_limit {
            if !(t > 0.0) || !t.is_finite() {
                bad(
                    "time_limit",
                    None,
                    format!("must be positive seconds, got {t}"),
                );
            }
        }
        if !(self.sample_spacing > 0.0 && self.sample_spacing <= 0.25) {
            bad(
                "sample_spacing",
                None,
                format!(
                    "must be in (0, 0.25] of the shortest block edge, got {:?}",
                    self.sample_spacing
                ),
            );
        }
        out
    }
}

/// The seed of restart `k` (SplitMix64 of the job's seed and `k`).
pub fn restart_seed(seed: u64, k: usize) -> u64 {
    let mut z = seed.wrapping_add((k as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// About how many samples [`segment`] takes on `mesh` with `params` (its sample cap,
/// `params.max_samples`, is checked against this before anything is sampled).
pub fn estimated_samples(mesh: &TriMesh, params: &Params) -> f64 {
    let spacing = params.sample_spacing
        * params
            .block_size
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
    samples::estimate(mesh, spacing, params.coverage)
}

/// Segments a closed mesh into blocks.
///
/// # Errors
/// [`BlockError::Invalid`] for parameters out of range, [`BlockError::Model`] for a mesh
/// that is not closed or has no volume, [`BlockError::TooManySamples`] when the block is
/// too small for the model at the chosen sample spacing.
///
/// ```
/// use blocks::{segment, BlockError, Params};
/// use geom::bbox::Aabb;
/// use geom::mesh::TriMesh;
/// use nalgebra::Vector3;
/// // a 2 × 1 × 1 box and blocks of 1.1: at least ⌈2 / 1.331⌉ = 2 of them
/// let corners = Aabb { min: Vector3::zeros(), max: Vector3::new(2.0, 1.0, 1.0) }.corners();
/// let model = TriMesh::cuboid(corners)?;
/// let params = Params { block_size: [1.1, 1.1, 1.1], max_iterations: 20, ..Params::default() };
/// let seg = segment(&model, &params, &|_| {})?;
/// assert_eq!(seg.lower_bound, 2);
/// assert!((seg.model_volume - 2.0).abs() < 1e-6); // computed in a unit frame
/// assert!(seg.final_blocks >= seg.lower_bound && seg.final_blocks <= seg.initial_blocks);
/// // the blocks cover the model: every corner lies in one
/// assert!(corners.iter().all(|p| seg.blocks.iter().any(|b| b.cuboid().contains(p, -1e-9))));
/// // an open mesh has no volume to cover
/// let open = TriMesh::try_new(model.vertices().to_vec(), model.faces()[1..].to_vec())?;
/// assert!(matches!(segment(&open, &params, &|_| {}), Err(BlockError::Model(_))));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn segment(
    mesh: &TriMesh,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Segmentation> {
    validate(params)?;
    mesh.validate(true)
        .map_err(|e| BlockError::Model(e.to_string()))?;
    // computed in the unit frame, the same numbers in any unit
    let frame = unit::frame(mesh, params);
    let seg = segment_in(
        &unit::mesh(&frame, mesh)?,
        &unit::params(&frame, params),
        progress,
    )?;
    Ok(unit::result(&frame, seg))
}

/// [`segment`] of a mesh and parameters in the unit frame.
fn segment_in(
    mesh: &TriMesh,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Segmentation> {
    let model_volume = mesh.volume().abs();
    if !(model_volume > 0.0) {
        return Err(BlockError::Model("the mesh encloses no volume".into()));
    }
    let started = Instant::now();
    let half = Vector3::from(params.block_size) / 2.0;
    let frame = obb::min_box(mesh.vertices())
        .ok_or_else(|| BlockError::Model("the mesh has no finite vertices".into()))?;
    let spacing = params.sample_spacing * half.min() * 2.0;
    let samples = samples::sample(
        mesh,
        &frame,
        spacing,
        params.coverage,
        params.max_samples,
        half.min() / 2.0,
    )?;
    let init = initial_grid(&frame, &half, &samples);
    let initial_blocks = init.len();
    let ops = optimize::Ops {
        translate: params.operations.contains(&Operation::Translate),
        rotate: params.operations.contains(&Operation::Rotate),
        align: params.operations.contains(&Operation::Align),
    };
    let runs: Vec<optimize::Run> = (0..params.restarts as usize)
        .into_par_iter()
        .map(|k| {
            let mut state = state::State::new(&samples, init.clone(), params.p, params.epsilon);
            optimize::run(
                &mut state,
                params,
                ops,
                restart_seed(params.seed, k),
                k,
                started,
                progress,
            )
        })
        .collect();
    // Fewest blocks, then lowest E, then first restart: independent of thread count.
    let best = (0..runs.len())
        .min_by(|&a, &b| {
            runs[a]
                .blocks
                .len()
                .cmp(&runs[b].blocks.len())
                .then(runs[a].energy.total_cmp(&runs[b].energy))
                .then(a.cmp(&b))
        })
        .unwrap_or(0);
    let restarts = runs
        .iter()
        .enumerate()
        .map(|(k, r)| RestartSummary {
            seed: restart_seed(params.seed, k),
            blocks: r.blocks.len(),
            energy: r.energy,
            iterations: r.history.last().map_or(0, |h| h.iteration),
            stop: r.stop,
        })
        .collect();
    let run = runs
        .into_iter()
        .nth(best)
        .ok_or_else(|| BlockError::Invalid {
            what: "restarts",
            message: "no run".into(),
        })?;
    let block_volume = 8.0 * half.x * half.y * half.z;
    let final_blocks = run.blocks.len();
    Ok(Segmentation {
        blocks: run.blocks.iter().map(Placement::of).collect(),
        initial_blocks,
        final_blocks,
        reduction_percent: if initial_blocks == 0 {
            0.0
        } else {
            100.0 * (initial_blocks - final_blocks) as f64 / initial_blocks as f64
        },
        lower_bound: crate::moves::cells(model_volume, block_volume),
        model_volume,
        block_volume,
        bounding_box: Placement {
            center: frame.center.into(),
            rotation: Placement::of(&Cuboid::new(frame.center, frame.rotation, half)).rotation,
            size: frame.size.into(),
        },
        sampling: SamplingInfo {
            counts: samples.counts,
            spacing: samples.spacing,
            margin: samples.margin,
        },
        seed: params.seed,
        best_restart: best,
        restarts,
        history: run.history,
        accepted: run.accepted,
        energy: run.energy,
    })
}

/// The grid of blocks over the model's box (§3.3, fig. 3.1): blocks whose shrunk boxes
/// tile it, centred on it, block axes assigned to the box's axes to need the fewest
/// blocks; blocks that cover no sample are dropped.
pub fn initial_grid(
    frame: &obb::BoxFit,
    half: &Vector3<f64>,
    samples: &samples::Samples,
) -> Vec<Cuboid> {
    moves::Grid::over(frame, half, samples.margin)
        .blocks()
        .into_iter()
        .filter(|b| {
            let mut any = false;
            samples.for_each_covered(b, |_| any = true);
            any
        })
        .collect()
}

fn validate(p: &Params) -> Result<()> {
    match p.problems().into_iter().next() {
        Some(e) => Err(BlockError::Invalid {
            what: e.field,
            message: match e.index {
                Some(i) => format!("{} {i} {}", e.field, e.message),
                None => e.message,
            },
        }),
        None => Ok(()),
    }
}
