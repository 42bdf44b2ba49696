//! The two strategies side by side (§4.1, fig. 4.2): across every pair of blocks that
//! meet, the gap between their surfaces (C⁰) and the jump of their rulings' direction,
//! measured at the model's samples that both blocks hold; and the deviation, the added
//! material and the number of cuts.

use blocks::Cuboid;
use geom::TriMesh;

use crate::cuts::BlockPlan;
use crate::plan::{model_samples, Deviation};
use crate::solid::{Probe, Solid};

/// One strategy's figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Figures {
    /// Pairs of blocks that meet (their boxes overlap or touch).
    pub seams: usize,
    /// Model samples held by both blocks of a pair, summed over the pairs.
    pub seam_samples: usize,
    /// Largest gap between the two blocks' surfaces at a seam sample.
    pub max_gap: f64,
    /// RMS gap.
    pub rms_gap: f64,
    /// Largest angle between the two blocks' rulings at a seam sample, degrees.
    pub max_jump_deg: f64,
    /// Median angle, degrees (robust: a sample whose closest point lies on an edge between
    /// two faces may take either face's ruling).
    pub median_jump_deg: f64,
    /// Deviation from the model.
    pub deviation: Deviation,
    /// Material added by hulls.
    pub added_volume: f64,
    /// Cuts.
    pub cuts: usize,
    /// Blocks.
    pub blocks: usize,
    /// Blocks cut by their strips.
    pub cuttable: usize,
}

/// The figures of a plan whose block `i` is cut from `solids[i]` (the same solid for every
/// block in the whole-model strategy; `None`: the block holds no model), at the model's
/// samples `spacing` apart ([`crate::plan::model_samples`]).
pub fn figures(
    model: &TriMesh,
    plans: &[BlockPlan],
    solids: &[Option<&Solid>],
    deviation: Deviation,
    spacing: f64,
) -> Figures {
    let samples = model_samples(model, spacing);
    let probes: Vec<Option<Probe<'_>>> = solids.iter().map(|s| s.map(Probe::new)).collect();
    let cubes: Vec<&Cuboid> = plans.iter().map(|p| &p.block).collect();
    let (mut seams, mut n, mut max_gap, mut sum_gap2, mut max_jump) =
        (0usize, 0usize, 0.0f64, 0.0f64, 0.0f64);
    let mut jumps: Vec<f64> = Vec::new();
    for a in 0..cubes.len() {
        for b in (a + 1)..cubes.len() {
            let margin = 0.01 * cubes[a].half.min().min(cubes[b].half.min());
            let (Some(pa), Some(pb)) = (&probes[a], &probes[b]) else {
                continue;
            };
            let (Some(sa), Some(sb)) = (solids[a], solids[b]) else {
                continue;
            };
            let mut met = false;
            for p in &samples {
                if !(cubes[a].contains(p, -margin) && cubes[b].contains(p, -margin)) {
                    continue;
                }
                let (Some(ca), Some(cb)) = (pa.closest_point(p), pb.closest_point(p)) else {
                    continue;
                };
                met = true;
                n += 1;
                let gap = (ca.1 - cb.1).norm();
                max_gap = max_gap.max(gap);
                sum_gap2 += gap * gap;
                let (da, db) = (sa.face_ruling[ca.0], sb.face_ruling[cb.0]);
                // the angle between two lines, exact 0 for the same direction
                let jump = da.cross(&db).norm().atan2(da.dot(&db).abs()).to_degrees();
                max_jump = max_jump.max(jump);
                jumps.push(jump);
            }
            if met {
                seams += 1;
            }
        }
    }
    Figures {
        seams,
        seam_samples: n,
        max_gap,
        rms_gap: if n > 0 {
            (sum_gap2 / n as f64).sqrt()
        } else {
            0.0
        },
        max_jump_deg: max_jump,
        median_jump_deg: median(&mut jumps),
        deviation,
        added_volume: plans.iter().map(|p| p.added_volume).sum(),
        cuts: plans.iter().map(|p| p.cuts.len()).sum(),
        blocks: plans.len(),
        cuttable: plans.iter().filter(|p| p.cuttable).count(),
    }
}

/// The median (0 for none).
fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        (v[m - 1] + v[m]) / 2.0
    }
}
