//! The whole chain of §4.2: section the model, split it into regions, fit each by
//! piecewise ruled strips, close them into the rationalized solid, measure its deviation
//! from the model, segment it into blocks (ch. 3) and plan each block's cuts.

use blocks::{Cuboid, Segmentation};
use geom::TriMesh;
use nalgebra::Vector3;

use crate::cuts::{kept_points, strip_cuts, BlockPlan, PlanSettings};
use crate::error::{Error, Result};
use crate::hull::hull_cut;
use crate::regions::{fit_tube, tubes, FitSettings, Region};
use crate::sections::section;
use crate::solid::{build, End, Probe, Solid};

/// What to do.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// The axis the sections are normal to; the rails run along it.
    pub axis: [f64; 3],
    /// Sections along the axis (≥ 4).
    pub sections: usize,
    /// Largest distance of the rationalized surface from the model (> 0).
    pub tolerance: f64,
    /// Most strips around one loop.
    pub max_strips: usize,
    /// The block segmentation (its `block_size`, seed, restarts, caps).
    pub blocks: blocks::Params,
    /// Kerf of the wire (≥ 0).
    pub kerf: f64,
    /// Lead-in and lead-out of every cut beyond its block (≥ 0).
    pub lead: f64,
}

/// Deviation of the rationalized surface from the model, at the model's samples.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    /// Samples measured.
    pub samples: usize,
    /// Root mean square distance.
    pub rms: f64,
    /// Largest distance.
    pub max: f64,
}

/// Per region.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionResult {
    /// The fitted region.
    pub region: Region,
    /// Its deviation from the model (model samples whose closest point is on it).
    pub deviation: Deviation,
}

/// A block segmentation in brief.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentationSummary {
    /// Blocks of the initial grid.
    pub initial_blocks: usize,
    /// Blocks at the end.
    pub final_blocks: usize,
    /// ⌈volume / block volume⌉.
    pub lower_bound: usize,
    /// The seed.
    pub seed: u64,
}

impl SegmentationSummary {
    /// The summary of `s`.
    pub fn of(s: &Segmentation) -> Self {
        Self {
            initial_blocks: s.initial_blocks,
            final_blocks: s.final_blocks,
            lower_bound: s.lower_bound,
            seed: s.seed,
        }
    }
}

/// Progress: a phase and how far into it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// The phase.
    pub phase: &'static str,
    /// Done.
    pub done: usize,
    /// Of.
    pub total: usize,
}

/// The result.
#[derive(Debug, Clone, PartialEq)]
pub struct RuledBlocks {
    /// The regions.
    pub regions: Vec<RegionResult>,
    /// The rationalized solid.
    pub solid: Solid,
    /// Whole-model deviation.
    pub deviation: Deviation,
    /// The model's bounding-box diagonal.
    pub diagonal: f64,
    /// Sections, the refined ones included.
    pub sections: usize,
    /// Its figures beside the other strategy's ([`crate::compare`]).
    pub figures: crate::compare::Figures,
    /// What sharing the blocks' overlaps saved ([`crate::share`]).
    pub sharing: crate::share::Sharing,
    /// The block segmentation of the rationalized solid, in brief.
    pub segmentation: SegmentationSummary,
    /// Each block's plan, in the segmentation's order.
    pub blocks: Vec<BlockPlan>,
}

impl Params {
    /// Problems with the parameters, as `(field, message)`.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        let a = Vector3::from(self.axis);
        if !(a.norm() > 0.0 && a.iter().all(|v| v.is_finite())) {
            out.push(("axis", "must be a finite, non-zero direction".into()));
        }
        if !(4..=2000).contains(&self.sections) {
            out.push(("sections", format!("{} must be in 4..=2000", self.sections)));
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            out.push(("tolerance", format!("{} must be positive", self.tolerance)));
        }
        if !(1..=1000).contains(&self.max_strips) {
            out.push((
                "max_strips",
                format!("{} must be in 1..=1000", self.max_strips),
            ));
        }
        if !(self.lead.is_finite() && self.lead >= 0.0) {
            out.push(("lead", format!("{} must be ≥ 0", self.lead)));
        }
        if !(self.kerf.is_finite() && self.kerf >= 0.0) {
            out.push(("kerf", format!("{} must be ≥ 0", self.kerf)));
        }
        let small = self
            .blocks
            .block_size
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if small <= self.tolerance {
            out.push((
                "block_size",
                format!(
                    "the smallest edge, {small}, must exceed the tolerance, {}",
                    self.tolerance
                ),
            ));
        }
        for p in self.blocks.problems() {
            out.push((p.field, p.message));
        }
        out
    }
}

/// Rationalizes `model` (a closed mesh) and plans its blocks, computing in the model's
/// unit frame ([`crate::unit`]).
///
/// # Errors
/// [`Error::Params`] for bad parameters, [`Error::Model`] for an open mesh or one without
/// sections, [`Error::Fit`] and [`Error::Blocks`] when a step fails.
pub fn run(
    model: &TriMesh,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<RuledBlocks> {
    let (f, unit_model, unit_params) = crate::unit::prepare(model, params)?;
    let r = run_unit(&unit_model, &unit_params, progress)?;
    let axis = r.solid.axis;
    Ok(RuledBlocks {
        regions: r
            .regions
            .into_iter()
            .map(|g| {
                Ok(RegionResult {
                    region: crate::unit::region(&f, &axis, g.region)?,
                    deviation: crate::unit::deviation(&f, g.deviation),
                })
            })
            .collect::<Result<_>>()?,
        solid: crate::unit::solid(&f, r.solid)?,
        deviation: crate::unit::deviation(&f, r.deviation),
        diagonal: model.aabb().size().norm(),
        sections: r.sections,
        figures: crate::unit::figures(&f, r.figures),
        sharing: crate::share::Sharing {
            added_before: r.sharing.added_before * f.scale.powi(3),
            added_after: r.sharing.added_after * f.scale.powi(3),
            ..r.sharing
        },
        segmentation: r.segmentation,
        blocks: r
            .blocks
            .into_iter()
            .map(|b| crate::unit::plan(&f, b))
            .collect(),
    })
}

/// [`run`] in the unit frame.
fn run_unit(
    model: &TriMesh,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<RuledBlocks> {
    let axis = Vector3::from(params.axis).normalize();
    progress(Progress {
        phase: "sections",
        done: 0,
        total: 1,
    });
    let s = section(model, axis, params.sections, 1e-3, params.tolerance)?;
    let ts = tubes(&s);
    if ts.is_empty() {
        return Err(Error::Model("no section of the model has a loop".into()));
    }
    let settings = FitSettings {
        tolerance: params.tolerance,
        max_strips: params.max_strips,
        samples_per_strip: 4,
    };
    let mut regions = Vec::with_capacity(ts.len());
    for (i, t) in ts.iter().enumerate() {
        progress(Progress {
            phase: "fit",
            done: i,
            total: ts.len(),
        });
        regions.push(fit_tube(regions.len(), t, &s, &settings)?);
    }
    if regions.is_empty() {
        return Err(Error::Model(
            "every region is a single section: add sections".into(),
        ));
    }
    let ends: Vec<(End, End)> = regions.iter().map(|r| region_ends(r, &s, model)).collect();
    let solid = build(&regions, &ends, axis)?;
    let probe = Probe::new(&solid);
    let (deviation, per_region) = deviation(model, &solid, &probe, params.tolerance, regions.len());
    let regions = regions
        .into_iter()
        .zip(per_region)
        .map(|(region, deviation)| RegionResult { region, deviation })
        .collect();
    progress(Progress {
        phase: "blocks",
        done: 0,
        total: 1,
    });
    let segmentation = blocks::segment(&solid.mesh, &params.blocks, &|p| {
        progress(Progress {
            phase: "blocks",
            done: p.iteration,
            total: params.blocks.max_iterations as usize,
        });
    })
    .map_err(|e| Error::Blocks(e.to_string()))?;
    let plan = PlanSettings {
        tolerance: params.tolerance,
        kerf: params.kerf,
        lead: params.lead,
    };
    let cuboids: Vec<Cuboid> = segmentation.blocks.iter().map(|b| b.cuboid()).collect();
    let mut blocks = plan_blocks(&cuboids, &solid, &probe, &plan, progress);
    progress(Progress {
        phase: "overlaps",
        done: 0,
        total: 1,
    });
    let sharing = crate::share::share(&mut blocks, &solid, &probe, &plan);
    let solids: Vec<Option<&Solid>> = blocks.iter().map(|_| Some(&solid)).collect();
    let figures = crate::compare::figures(model, &blocks, &solids, deviation, params.tolerance);
    Ok(RuledBlocks {
        regions,
        diagonal: model.aabb().size().norm(),
        sections: s.offsets.len(),
        figures,
        sharing,
        deviation,
        segmentation: SegmentationSummary::of(&segmentation),
        blocks,
        solid,
    })
}

/// Each block's plan (in parallel with the `parallel` feature; the same result).
fn plan_blocks(
    cuboids: &[Cuboid],
    solid: &Solid,
    probe: &Probe<'_>,
    s: &PlanSettings,
    progress: &(dyn Fn(Progress) + Sync),
) -> Vec<BlockPlan> {
    let one = |(i, b): (usize, &Cuboid)| {
        progress(Progress {
            phase: "cuts",
            done: i,
            total: cuboids.len(),
        });
        plan_block(b, solid, probe, s)
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        cuboids.par_iter().enumerate().map(one).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        cuboids.iter().enumerate().map(one).collect()
    }
}

/// One block: its strips if they can cut it, else its hull.
pub fn plan_block(b: &Cuboid, solid: &Solid, probe: &Probe<'_>, s: &PlanSettings) -> BlockPlan {
    let (cuts, deepest, reason) = strip_cuts(b, solid, probe, s);
    if reason.is_none() {
        let kept = crate::hull::lattice(b)
            .iter()
            .filter(|p| probe.inside(p))
            .count();
        let cell = 8.0 * b.half.x * b.half.y * b.half.z / crate::cuts::LATTICE.pow(3) as f64;
        return BlockPlan {
            block: *b,
            cuttable: true,
            reason: None,
            deepest,
            cuts,
            added_volume: 0.0,
            added_depth: 0.0,
            kept_volume: kept as f64 * cell,
            keeps: Vec::new(),
        };
    }
    let pts = kept_points(b, solid, probe);
    let h = hull_cut(b, &pts, probe, s.kerf, s.lead);
    BlockPlan {
        block: *b,
        cuttable: false,
        reason,
        deepest,
        cuts: h.cuts,
        added_volume: h.added_volume,
        added_depth: h.added_depth,
        kept_volume: h.kept_volume,
        keeps: Vec::new(),
    }
}

/// How a region starts and ends: at the model's end a cone to the model's tip beyond its
/// end section, else a flat cap halfway to the neighbouring section.
fn region_ends(r: &Region, s: &crate::sections::Sections, model: &TriMesh) -> (End, End) {
    let d = s.frame.normal;
    let last = r.last;
    let row = |u: f64| -> Vec<Vector3<f64>> { (0..r.strips).map(|j| r.rail(u, j)).collect() };
    let tip = |u: f64, sign: f64| -> Option<Vector3<f64>> {
        let ring = row(u);
        let plane: Vec<_> = ring.iter().map(|p| s.frame.to_plane(p)).collect();
        let (mut lo, mut hi) = (plane[0], plane[0]);
        for q in &plane {
            lo = lo.inf(q);
            hi = hi.sup(q);
        }
        let pad = (hi - lo) * 0.1;
        let (lo, hi) = (lo - pad, hi + pad);
        let beyond: Vec<&Vector3<f64>> = model
            .vertices()
            .iter()
            .filter(|p| {
                let q = s.frame.to_plane(p);
                sign * (d.dot(p) - u) > 0.0
                    && q.x >= lo.x
                    && q.x <= hi.x
                    && q.y >= lo.y
                    && q.y <= hi.y
            })
            .collect();
        if beyond.is_empty() {
            return None;
        }
        let far = beyond
            .iter()
            .map(|p| sign * d.dot(p))
            .fold(f64::NEG_INFINITY, f64::max)
            * sign;
        let mean = beyond
            .iter()
            .map(|p| s.frame.to_plane(p))
            .sum::<nalgebra::Vector2<f64>>()
            / beyond.len() as f64;
        Some(s.frame.to_world(far, &mean))
    };
    let (u0, u1) = (r.offsets[0], r.offsets[r.offsets.len() - 1]);
    let start = if r.first == 0 {
        tip(u0, -1.0).map_or(End::Flat(u0), End::Tip)
    } else {
        End::Flat(s.offsets[r.first] - (s.offsets[r.first] - s.offsets[r.first - 1]) / 2.0)
    };
    let end = if last + 1 == s.offsets.len() {
        tip(u1, 1.0).map_or(End::Flat(u1), End::Tip)
    } else {
        End::Flat(s.offsets[last] + (s.offsets[last + 1] - s.offsets[last]) / 2.0)
    };
    (start, end)
}

/// Distances from the model's samples ([`model_samples`]) to the rationalized surface:
/// whole and per region (a sample counts for the region of its closest face).
fn deviation(
    model: &TriMesh,
    solid: &Solid,
    probe: &Probe<'_>,
    tolerance: f64,
    n: usize,
) -> (Deviation, Vec<Deviation>) {
    let samples = model_samples(model, tolerance);
    let mut whole = (0usize, 0.0f64, 0.0f64);
    let mut per = vec![(0usize, 0.0f64, 0.0f64); n];
    for p in &samples {
        let Some((f, d)) = probe.closest(p) else {
            continue;
        };
        for acc in [&mut whole, &mut per[solid.face_region[f]]] {
            acc.0 += 1;
            acc.1 += d * d;
            acc.2 = acc.2.max(d);
        }
    }
    let dev = |(k, s, m): (usize, f64, f64)| Deviation {
        samples: k,
        rms: if k > 0 { (s / k as f64).sqrt() } else { 0.0 },
        max: m,
    };
    (dev(whole), per.into_iter().map(dev).collect())
}

/// Most subdivisions of a face's edges for the deviation's samples.
pub const MAX_FACE_DIVISIONS: usize = 4;

/// The model's samples for the deviation: its vertices, then per face (in order) the points
/// of a barycentric lattice dividing its edges into `k = ⌈longest edge / spacing⌉` parts
/// (1 to [`MAX_FACE_DIVISIONS`]), its corners left out — the centroid alone when `k` is 1
/// or 2 — so that the samples lie at most about `spacing` apart (the tolerance: the
/// deviation is not measured only where the model's vertices are).
pub fn model_samples(model: &TriMesh, spacing: f64) -> Vec<Vector3<f64>> {
    let mut out: Vec<Vector3<f64>> = model.vertices().to_vec();
    for f in 0..model.faces().len() {
        let [a, b, c] = model.triangle(f);
        let longest = (b - a).norm().max((c - b).norm()).max((a - c).norm());
        let k = ((longest / spacing).ceil() as usize).clamp(1, MAX_FACE_DIVISIONS);
        if k <= 2 {
            out.push((a + b + c) / 3.0);
            continue;
        }
        for i in 0..=k {
            for j in 0..=(k - i) {
                if (i == 0 && j == 0) || i == k || j == k {
                    continue;
                }
                out.push(a + (b - a) * (i as f64 / k as f64) + (c - a) * (j as f64 / k as f64));
            }
        }
    }
    out
}
