//! The stochastic optimization loop of §3.3.5 for one seed.
//!
//! Cycles of single-block moves (for every block in random order: the best of the
//! translation and the eight rotations if it lowers E, then removal checks of the blocks
//! the move touched) until a cycle brings no improvement; then one alignment pass; repeat
//! until two alignment passes in a row remove nothing, or a cap is reached.

use std::time::Instant;

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::cuboid::Cuboid;
use crate::moves;
use crate::state::State;
use crate::{Acceptance, IterationRecord, Params, Phase, Progress, StopReason};

/// What one seeded run produced.
#[derive(Debug, Clone)]
pub struct Run {
    /// The final blocks.
    pub blocks: Vec<Cuboid>,
    /// Objective at the end.
    pub energy: f64,
    /// One record per iteration (the initial state first).
    pub history: Vec<IterationRecord>,
    /// Accepted operations.
    pub accepted: Acceptance,
    /// Why it stopped.
    pub stop: StopReason,
}

/// Which operations a run may use.
#[derive(Debug, Clone, Copy)]
pub struct Ops {
    /// Pure translation (§3.3.2).
    pub translate: bool,
    /// Rotation (§3.3.3).
    pub rotate: bool,
    /// Alignment (§3.3.4).
    pub align: bool,
}

/// Runs the loop from `init` with the given seed.
pub fn run(
    state: &mut State<'_>,
    params: &Params,
    ops: Ops,
    seed: u64,
    restart: usize,
    started: Instant,
    progress: &(dyn Fn(Progress) + Sync),
) -> Run {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut accepted = Acceptance::default();
    let mut history = vec![IterationRecord {
        iteration: 0,
        phase: Phase::Init,
        blocks: state.len(),
        energy: state.energy(),
    }];
    let mut iteration = 0usize;
    let mut quiet_alignments = 0;
    // Blocks after the previous alignment pass: a round (alignment and the move cycles
    // after it) that removed nothing counts as a quiet alignment.
    let mut after_last_alignment = usize::MAX;
    let capped = |iteration: usize| -> Option<StopReason> {
        if iteration >= params.max_iterations as usize {
            Some(StopReason::IterationCap)
        } else if params
            .time_limit
            .is_some_and(|t| started.elapsed().as_secs_f64() >= t)
        {
            Some(StopReason::TimeCap)
        } else {
            None
        }
    };
    let mut record = |state: &State<'_>, iteration: usize, phase: Phase| {
        let r = IterationRecord {
            iteration,
            phase,
            blocks: state.len(),
            energy: state.energy(),
        };
        progress(Progress {
            restart,
            iteration,
            blocks: r.blocks,
            energy: r.energy,
        });
        history.push(r);
    };
    let stop = 'outer: loop {
        if ops.translate || ops.rotate {
            loop {
                if let Some(s) = capped(iteration) {
                    break 'outer s;
                }
                iteration += 1;
                let improved = move_cycle(state, ops, &mut rng, &mut accepted);
                record(state, iteration, Phase::Move);
                if !improved {
                    break;
                }
            }
        }
        if !ops.align {
            break StopReason::Converged;
        }
        if let Some(s) = capped(iteration) {
            break s;
        }
        iteration += 1;
        align_pass(state, &mut rng, &mut accepted);
        record(state, iteration, Phase::Align);
        let removed = after_last_alignment.saturating_sub(state.len());
        after_last_alignment = state.len();
        if removed == 0 {
            quiet_alignments += 1;
            if quiet_alignments >= 2 {
                break StopReason::Converged;
            }
        } else {
            quiet_alignments = 0;
        }
    };
    Run {
        blocks: state
            .alive_ids()
            .into_iter()
            .map(|i| state.blocks[i])
            .collect(),
        energy: state.energy(),
        history,
        accepted,
        stop,
    }
}

/// One cycle of single-block moves; whether anything improved E (a move or a removal).
fn move_cycle(state: &mut State<'_>, ops: Ops, rng: &mut ChaCha8Rng, acc: &mut Acceptance) -> bool {
    let mut order = state.alive_ids();
    order.shuffle(rng);
    let margin = state.samples().margin;
    let tolerance = 1e-9 * state.pair_scale();
    let mut improved = false;
    for i in order {
        if !state.alive[i] {
            continue;
        }
        let exclusive = state.exclusive(i);
        if exclusive.is_empty() {
            state.remove(i);
            acc.removals += 1;
            improved = true;
            continue;
        }
        let pts = state.points(&exclusive);
        let current = state.blocks[i];
        let base = state.pair_sum(i, &current);
        let mut best: Option<(f64, Cuboid, bool)> = None;
        let mut consider = |c: Cuboid, is_translation: bool, state: &State<'_>| {
            let gain = state.pair_sum(i, &c) - base;
            if gain > tolerance
                && best.as_ref().is_none_or(|(g, ..)| gain > *g + tolerance)
                && moves::keeps(std::slice::from_ref(&c), &pts, margin)
            {
                best = Some((gain, c, is_translation));
            }
        };
        if ops.translate {
            if let Some(t) = moves::translation(&current, &pts, margin) {
                consider(t, true, state);
            }
        }
        if ops.rotate {
            for r in moves::rotations(&current, &pts, margin) {
                consider(r, false, state);
            }
        }
        let Some((_, to, is_translation)) = best else {
            continue;
        };
        state.place(i, to);
        if is_translation {
            acc.translations += 1;
        } else {
            acc.rotations += 1;
        }
        improved = true;
        let touched: Vec<usize> = state
            .alive_ids()
            .into_iter()
            .filter(|&j| {
                let b = &state.blocks[j];
                j == i || b.intersects(&current) || b.intersects(&to)
            })
            .collect();
        acc.removals += removal_checks(state, &touched);
    }
    improved
}

/// Removes every block of `ids` (in order) that has become removable; how many went.
fn removal_checks(state: &mut State<'_>, ids: &[usize]) -> usize {
    let mut removed = 0;
    for &j in ids {
        if state.alive[j] && state.removable(j) {
            state.remove(j);
            removed += 1;
        }
    }
    removed
}

/// One alignment pass over the blocks in random order; how many blocks it removed.
fn align_pass(state: &mut State<'_>, rng: &mut ChaCha8Rng, acc: &mut Acceptance) -> usize {
    let mut order = state.alive_ids();
    order.shuffle(rng);
    let margin = state.samples().margin;
    let mut done = vec![false; state.blocks.len()];
    let mut group_count = vec![0u16; state.samples().points.len()];
    let mut removed = 0;
    for i in order {
        if !state.alive[i] || done[i] {
            continue;
        }
        let b = state.blocks[i];
        let group: Vec<usize> = state
            .alive_ids()
            .into_iter()
            .filter(|&j| j == i || state.blocks[j].intersects(&b))
            .collect();
        // M_I: samples the group covers and no block outside it does.
        let mut touched = Vec::new();
        for &j in &group {
            state.for_each_covered(&state.blocks[j], |id| {
                if group_count[id] == 0 {
                    touched.push(id);
                }
                group_count[id] += 1;
            });
        }
        touched.sort_unstable();
        let exclusive: Vec<usize> = touched
            .iter()
            .copied()
            .filter(|&id| group_count[id] == state.count(id))
            .collect();
        for &id in &touched {
            group_count[id] = 0;
        }
        if exclusive.is_empty() {
            removed += removal_checks(state, &group);
            continue;
        }
        let pts = state.points(&exclusive);
        let frames: Vec<_> = group.iter().map(|&j| state.blocks[j].rotation).collect();
        let Some(poses) = moves::alignment(&b.half, &pts, margin, group.len(), &frames)
            .filter(|poses| moves::keeps(poses, &pts, margin))
        else {
            continue;
        };
        state.replace(&group, &poses);
        acc.alignments += 1;
        removed += group.len() - poses.len();
        for &j in &group {
            done[j] = true;
        }
        removed += removal_checks(state, &group);
    }
    acc.removals += removed;
    removed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obb::min_box;
    use crate::samples::{sample, Coverage};
    use nalgebra::Vector3;

    /// An L-shaped closed mesh (two boxes fused), 3 × 2 × 1 with a 1 × 1 notch.
    fn l_shape() -> geom::mesh::TriMesh {
        // Extruded L polygon: (0,0) (3,0) (3,1) (1,1) (1,2) (0,2), z ∈ [0, 1].
        let poly = [
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ];
        let mut v = Vec::new();
        for z in [0.0, 1.0] {
            for (x, y) in poly {
                v.push(Vector3::new(x, y, z));
            }
        }
        let mut f: Vec<[u32; 3]> = Vec::new();
        // Bottom (outward −z) and top caps, as fans over a convex split of the L.
        for t in [[0u32, 3, 1], [1, 3, 2], [0, 5, 3], [3, 5, 4]] {
            f.push([t[0], t[1], t[2]]);
            f.push([t[0] + 6, t[2] + 6, t[1] + 6]);
        }
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            f.push([i, j, j + 6]);
            f.push([i, j + 6, i + 6]);
        }
        geom::mesh::TriMesh::try_new(v, f).unwrap()
    }

    /// Every sample stays covered after every single operation (the state checks all
    /// samples after each change) with all three operations, on two seeds.
    #[test]
    fn every_sample_stays_covered_after_every_operation() {
        let mesh = l_shape();
        assert!((mesh.volume() - 4.0).abs() < 1e-12, "{}", mesh.volume());
        let frame = min_box(mesh.vertices()).unwrap();
        let samples = sample(&mesh, &frame, 0.07, Coverage::Solid, 1_000_000, 0.35).unwrap();
        let half = Vector3::repeat(0.7);
        let init = crate::initial_grid(&frame, &half, &samples);
        let params = crate::Params {
            block_size: [1.4; 3],
            max_iterations: 40,
            ..crate::Params::default()
        };
        let ops = Ops {
            translate: true,
            rotate: true,
            align: true,
        };
        for seed in [1, 2] {
            let mut state = State::new(&samples, init.clone(), 2.0, 1e-5);
            state.paranoid = true;
            assert_eq!(state.uncovered(), 0);
            let run = run(&mut state, &params, ops, seed, 0, Instant::now(), &|_| {});
            assert_eq!(state.uncovered(), 0);
            assert!(
                run.blocks.len() < init.len(),
                "{} of {}",
                run.blocks.len(),
                init.len()
            );
            assert!(run.accepted.translations + run.accepted.rotations > 0);
            // Blocks are never added.
            for w in run.history.windows(2) {
                assert!(w[1].blocks <= w[0].blocks);
            }
        }
    }
}
