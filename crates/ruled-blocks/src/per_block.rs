//! The other strategy of §4.1, for comparison: segment the model into blocks first (ch. 3),
//! then rationalize each block's part on its own — its sections along whichever of the
//! block's axes fits best, clipped to the block — and plan each block's cuts from its own
//! strips. Neighbouring blocks then disagree at their common faces (fig. 4.2): a gap, and
//! rulings that change direction; [`crate::compare`] measures both.

use blocks::Cuboid;
use geom::slice::PlaneFrame;
use geom::TriMesh;
use nalgebra::{Vector2, Vector3};

use crate::cuts::{BlockPlan, PlanSettings};
use crate::error::{Error, Result};
use crate::plan::{model_samples, plan_block, Deviation, Params, SegmentationSummary};
use crate::regions::{fit_tube, tubes, FitSettings, Region};
use crate::sections::section_window;
use crate::solid::{build, End, Probe, Solid};

/// One block rationalized on its own.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockRationalization {
    /// The block axis its sections are normal to.
    pub axis: usize,
    /// Its regions.
    pub regions: Vec<Region>,
    /// Its rationalized solid (inside the block).
    pub solid: Solid,
    /// Its deviation from the model part in it.
    pub deviation: Deviation,
}

/// The per-block strategy's result.
#[derive(Debug, Clone, PartialEq)]
pub struct PerBlock {
    /// The block segmentation of the model, in brief.
    pub segmentation: SegmentationSummary,
    /// Per block, its rationalization (`None`: the model does not reach into it).
    pub rational: Vec<Option<BlockRationalization>>,
    /// Per block, its plan (an empty plan for a block without a rationalization).
    pub blocks: Vec<BlockPlan>,
    /// Deviation of the model from the union of the blocks' surfaces (each model sample to
    /// the nearest surface of a block holding it).
    pub deviation: Deviation,
    /// Its figures beside the other strategy's ([`crate::compare`]).
    pub figures: crate::compare::Figures,
}

/// Runs the per-block strategy, in the model's unit frame ([`crate::unit`]).
///
/// # Errors
/// [`Error::Params`] and [`Error::Model`] as [`crate::plan::run`], [`Error::Blocks`] when
/// the segmentation fails, [`Error::Fit`] when a block's fit does.
pub fn run(model: &TriMesh, params: &Params) -> Result<PerBlock> {
    let (f, unit_model, unit_params) = crate::unit::prepare(model, params)?;
    let r = run_unit(&unit_model, &unit_params)?;
    let rational = r
        .rational
        .into_iter()
        .map(|x| {
            x.map(|x| {
                let axis = x.solid.axis;
                Ok(BlockRationalization {
                    axis: x.axis,
                    regions: x
                        .regions
                        .into_iter()
                        .map(|g| crate::unit::region(&f, &axis, g))
                        .collect::<Result<_>>()?,
                    solid: crate::unit::solid(&f, x.solid)?,
                    deviation: crate::unit::deviation(&f, x.deviation),
                })
            })
            .transpose()
        })
        .collect::<Result<_>>()?;
    Ok(PerBlock {
        segmentation: r.segmentation,
        figures: crate::unit::figures(&f, r.figures),
        rational,
        blocks: r
            .blocks
            .into_iter()
            .map(|b| crate::unit::plan(&f, b))
            .collect(),
        deviation: crate::unit::deviation(&f, r.deviation),
    })
}

/// [`run`] in the unit frame.
fn run_unit(model: &TriMesh, params: &Params) -> Result<PerBlock> {
    let segmentation = blocks::segment(model, &params.blocks, &|_| {})
        .map_err(|e| Error::Blocks(e.to_string()))?;
    let samples = model_samples(model, params.tolerance);
    let cuboids: Vec<Cuboid> = segmentation.blocks.iter().map(|b| b.cuboid()).collect();
    let mut rational = Vec::with_capacity(cuboids.len());
    for b in &cuboids {
        let inside: Vec<Vector3<f64>> = samples
            .iter()
            .filter(|p| b.contains(p, 0.0))
            .copied()
            .collect();
        let mut best: Option<BlockRationalization> = None;
        for k in 0..3 {
            let Some((regions, solid)) = rationalize_in(model, b, k, params)? else {
                continue;
            };
            let probe = Probe::new(&solid);
            let deviation = deviation_of(&inside, &probe);
            if best
                .as_ref()
                .is_none_or(|x| deviation.max < x.deviation.max)
            {
                best = Some(BlockRationalization {
                    axis: k,
                    regions,
                    solid,
                    deviation,
                });
            }
        }
        rational.push(best);
    }
    let s = PlanSettings {
        tolerance: params.tolerance,
        kerf: params.kerf,
        lead: params.lead,
    };
    let blocks: Vec<BlockPlan> = cuboids
        .iter()
        .zip(&rational)
        .map(|(b, r)| match r {
            Some(r) => {
                let mut solid = r.solid.clone();
                // strips on the block's faces cut nothing
                solid.strips.retain(|st| !on_faces(b, st, params.tolerance));
                let probe = Probe::new(&r.solid);
                plan_block(b, &solid, &probe, &s)
            }
            None => BlockPlan {
                block: *b,
                cuttable: true,
                reason: None,
                deepest: 0.0,
                cuts: Vec::new(),
                added_volume: 0.0,
                added_depth: 0.0,
                kept_volume: 0.0,
                keeps: Vec::new(),
            },
        })
        .collect();
    let probes: Vec<Option<Probe<'_>>> = rational
        .iter()
        .map(|r| r.as_ref().map(|r| Probe::new(&r.solid)))
        .collect();
    let mut acc = (0usize, 0.0f64, 0.0f64);
    for p in &samples {
        let d = cuboids
            .iter()
            .zip(&probes)
            .filter(|(b, _)| b.contains(p, -1e-9 * b.half.norm()))
            .filter_map(|(_, pr)| pr.as_ref().map(|pr| pr.distance(p)))
            .fold(f64::INFINITY, f64::min);
        if d.is_finite() {
            acc.0 += 1;
            acc.1 += d * d;
            acc.2 = acc.2.max(d);
        }
    }
    let deviation = Deviation {
        samples: acc.0,
        rms: if acc.0 > 0 {
            (acc.1 / acc.0 as f64).sqrt()
        } else {
            0.0
        },
        max: acc.2,
    };
    let solids: Vec<Option<&Solid>> = rational
        .iter()
        .map(|r| r.as_ref().map(|r| &r.solid))
        .collect();
    let figures = crate::compare::figures(model, &blocks, &solids, deviation, params.tolerance);
    Ok(PerBlock {
        segmentation: SegmentationSummary::of(&segmentation),
        figures,
        rational,
        blocks,
        deviation,
    })
}

/// Whether every ruling of a strip lies on one of the block's faces (within `tol`).
fn on_faces(b: &Cuboid, st: &crate::solid::Strip, tol: f64) -> bool {
    (0..3).any(|k| {
        [-1.0, 1.0].iter().any(|&s| {
            st.rulings.iter().all(|r| {
                [r.a, r.b]
                    .iter()
                    .all(|p| (b.to_local(p)[k] - s * b.half[k]).abs() <= tol)
            })
        })
    })
}

fn deviation_of(samples: &[Vector3<f64>], probe: &Probe<'_>) -> Deviation {
    let d: Vec<f64> = samples.iter().map(|p| probe.distance(p)).collect();
    let n = d.len();
    Deviation {
        samples: n,
        rms: if n > 0 {
            (d.iter().map(|x| x * x).sum::<f64>() / n as f64).sqrt()
        } else {
            0.0
        },
        max: d.iter().copied().fold(0.0, f64::max),
    }
}

/// Block `b`'s model part rationalized with sections normal to its axis `k`: `None` when
/// no section of the model meets the block.
fn rationalize_in(
    model: &TriMesh,
    b: &Cuboid,
    k: usize,
    params: &Params,
) -> Result<Option<(Vec<Region>, Solid)>> {
    let ax = |i: usize| b.axes().column(i).into_owned();
    let frame = PlaneFrame::from_direction(ax(k)).map_err(|e| Error::Model(e.to_string()))?;
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let c = b.center;
    let mut clip: Vec<Vector2<f64>> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(s, t)| frame.to_plane(&(c + ax(i) * (s * b.half[i]) + ax(j) * (t * b.half[j]))))
        .collect();
    let area: f64 = (0..4)
        .map(|m| {
            let (p, q) = (clip[m], clip[(m + 1) % 4]);
            p.x * q.y - q.x * p.y
        })
        .sum();
    if area < 0.0 {
        clip.reverse();
    }
    let mid = frame.normal.dot(&c);
    // a hair inside the block's faces: the solid's end caps then lie strictly in the block
    let inner = b.half[k] * (1.0 - 1e-7);
    let window = (mid - inner, mid + inner);
    let s = section_window(
        model,
        &frame,
        window,
        params.sections,
        (1e-3, params.tolerance),
        Some(&clip),
    )?;
    let settings = FitSettings {
        tolerance: params.tolerance,
        max_strips: params.max_strips,
        samples_per_strip: 4,
    };
    let mut regions = Vec::new();
    for t in &tubes(&s) {
        regions.push(fit_tube(regions.len(), t, &s, &settings)?);
    }
    if regions.is_empty() {
        return Ok(None);
    }
    let n = s.offsets.len();
    let ends: Vec<(End, End)> = regions
        .iter()
        .map(|r| {
            let last = r.last;
            let gap = |a: usize, z: usize| (s.offsets[z] - s.offsets[a]) / 2.0;
            let start = if r.first == 0 {
                End::Flat(window.0)
            } else {
                End::Flat(s.offsets[r.first] - gap(r.first - 1, r.first))
            };
            let end = if last + 1 == n {
                End::Flat(window.1)
            } else {
                End::Flat(s.offsets[last] + gap(last, last + 1))
            };
            (start, end)
        })
        .collect();
    let solid = build(&regions, &ends, frame.normal)?;
    Ok(Some((regions, solid)))
}
