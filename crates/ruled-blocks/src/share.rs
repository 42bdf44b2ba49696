//! Sharing the blocks' overlaps (thesis §4.2, fig. 4.4): two blocks of the segmentation
//! often overlap, and both then keep the material there. Where one of them is cut to its
//! convex hull, the overlap can be split between them by a plane so that each keeps only
//! its side: the hull of a smaller share adds less. For every overlapping pair with a block
//! cut to its hull, planes normal to the block's axis towards its neighbour are tried at
//! five places across the overlap (a split through the intersection of two rulings that
//! form a concave shape, fig. 4.4, is among the planes of that family when the rulings run
//! across the axis), and the one that adds least kept, when it adds less than no split.

use blocks::Cuboid;
use nalgebra::Vector3;

use crate::cuts::{kept_points_in, BlockPlan, PlanSettings};
use crate::hull::{hull_cut_on, lattice, Plane};
use crate::solid::{Probe, Solid};

/// What sharing did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sharing {
    /// Overlaps split.
    pub splits: usize,
    /// Material the hulls added before.
    pub added_before: f64,
    /// And after.
    pub added_after: f64,
}

/// A block's lattice and which of its points lie in the solid.
type Lattice = (Vec<Vector3<f64>>, Vec<bool>);

/// Places tried across an overlap.
pub const PLACES: usize = 5;

/// Splits the overlaps of `plans` (in place) where that lowers the hulls' added material.
pub fn share(
    plans: &mut [BlockPlan],
    solid: &Solid,
    probe: &Probe<'_>,
    s: &PlanSettings,
) -> Sharing {
    let before: f64 = plans.iter().map(|p| p.added_volume).sum();
    let mut lattices: Vec<Option<Lattice>> = vec![None; plans.len()];
    // per block, the corners of the box (in its frame) around what it keeps
    let mut kept_box: Vec<Option<[Vector3<f64>; 8]>> = vec![None; plans.len()];
    let mut splits = 0;
    for a in 0..plans.len() {
        for b in (a + 1)..plans.len() {
            if plans[a].cuttable && plans[b].cuttable {
                continue;
            }
            let (ba, bb) = (plans[a].block, plans[b].block);
            if !ba.intersects(&bb) {
                continue;
            }
            let n = towards(&ba, &bb);
            let span = |c: &Cuboid| {
                c.corners()
                    .iter()
                    .map(|p| n.dot(p))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), t| {
                        (l.min(t), h.max(t))
                    })
            };
            let ((a0, a1), (b0, b1)) = (span(&ba), span(&bb));
            let (lo, hi) = (a0.max(b0), a1.min(b1));
            if !(hi - lo > s.tolerance) {
                continue;
            }
            for i in [a, b] {
                if lattices[i].is_none() && !plans[i].cuttable {
                    let l = lattice(&plans[i].block);
                    let ins = l.iter().map(|p| probe.inside(p)).collect();
                    lattices[i] = Some((l, ins));
                }
            }
            for i in [a, b] {
                if kept_box[i].is_none() {
                    kept_box[i] = Some(box_of_kept(&plans[i], solid, probe));
                }
            }
            let (Some(ka), Some(kb)) = (kept_box[a], kept_box[b]) else {
                continue;
            };
            // a cheap sufficient test first: the box around what a block would give up
            // lies in the other block's share
            let eps = 1e-9 * ba.half.norm();
            let in_share = |q: &Vector3<f64>, o: &BlockPlan| {
                o.block.contains(q, -eps) && o.keeps.iter().all(|h| h.n.dot(q) <= h.c + eps)
            };
            let gives_up = |corners: &[Vector3<f64>; 8], side: f64, t: f64| -> Vec<Vector3<f64>> {
                // the corners on the side given up, and the box's edges' crossings of the plane
                let mut out: Vec<Vector3<f64>> = corners
                    .iter()
                    .filter(|q| side * (n.dot(q) - t) >= 0.0)
                    .copied()
                    .collect();
                for i in 0..8usize {
                    for j in (i + 1)..8 {
                        if (i ^ j).count_ones() != 1 {
                            continue;
                        }
                        let (dp, dq) = (n.dot(&corners[i]) - t, n.dot(&corners[j]) - t);
                        if (dp < 0.0) != (dq < 0.0) {
                            out.push(corners[i] + (corners[j] - corners[i]) * (dp / (dp - dq)));
                        }
                    }
                }
                out
            };
            let current = plans[a].added_volume + plans[b].added_volume;
            let mut best: Option<(f64, Vec<(usize, BlockPlan)>)> = None;
            for k in 0..PLACES {
                let t = lo + (hi - lo) * k as f64 / (PLACES - 1) as f64;
                let ok_a = plans[a].cuttable
                    || gives_up(&ka, 1.0, t).iter().all(|q| in_share(q, &plans[b]));
                let ok_b = plans[b].cuttable
                    || gives_up(&kb, -1.0, t)
                        .iter()
                        .all(|q| in_share(q, &plans[a]));
                if !(ok_a && ok_b) {
                    continue;
                }
                let halves = [(a, Plane { n, c: t }), (b, Plane { n: -n, c: -t })];
                let mut total = 0.0;
                let mut tried = Vec::new();
                for (i, half) in halves {
                    if plans[i].cuttable {
                        // its strips cut it whole: it keeps all it holds, adding nothing
                        continue;
                    }
                    let mut keep = plans[i].keeps.clone();
                    keep.push(half);
                    let p = restricted(&plans[i], &keep, solid, probe, s, lattices[i].as_ref());
                    total += p.added_volume;
                    tried.push((i, p));
                }
                for i in [a, b] {
                    if plans[i].cuttable {
                        total += plans[i].added_volume;
                    }
                }
                if best.as_ref().is_none_or(|x| total < x.0) {
                    best = Some((total, tried));
                }
            }
            if let Some((total, tried)) = best {
                let covered = tried.iter().all(|(i, p)| {
                    let other = if *i == a { &plans[b] } else { &plans[a] };
                    given_up_is_kept(p, other, &plans[*i].keeps, solid, probe)
                        && cuts_keep_out(p, probe, s.tolerance)
                });
                if covered && total < current * (1.0 - 1e-9) {
                    for (i, p) in tried {
                        plans[i] = p;
                        kept_box[i] = None;
                    }
                    splits += 1;
                }
            }
        }
    }
    Sharing {
        splits,
        added_before: before,
        added_after: plans.iter().map(|p| p.added_volume).sum(),
    }
}

/// Whether what `p` gives up of the solid (its share before, `before`, minus its share now)
/// lies in block `other`'s share: the corners of that part inside `other`'s box and
/// half-spaces (the part lies in their hull, so in the convex share).
fn given_up_is_kept(
    p: &BlockPlan,
    other: &BlockPlan,
    before: &[Plane],
    solid: &Solid,
    probe: &Probe<'_>,
) -> bool {
    let Some(new) = p.keeps.last() else {
        return true;
    };
    let mut beyond = before.to_vec();
    beyond.push(Plane {
        n: -new.n,
        c: -new.c,
    });
    let eps = 1e-9 * p.block.half.norm();
    kept_points_in(&p.block, &beyond, solid, probe)
        .iter()
        .all(|q| {
            other.block.contains(q, -eps) && other.keeps.iter().all(|h| h.n.dot(q) <= h.c + eps)
        })
}

/// Whether no wire position of `p`'s cuts, nor the moves between them, enters its share of
/// the solid deeper than `tol` (the same check as a strip's).
fn cuts_keep_out(p: &BlockPlan, probe: &Probe<'_>, tol: f64) -> bool {
    p.cuts.iter().all(|c| {
        c.lines.windows(2).all(|w| {
            (0..=4).all(|k| {
                let t = k as f64 / 4.0;
                let l = crate::cuts::WireLine {
                    point: w[0].point + (w[1].point - w[0].point) * t,
                    dir: (w[0].dir + (w[1].dir - w[0].dir) * t).normalize(),
                };
                crate::cuts::penetration_in(&p.block, &p.keeps, probe, &l, tol) == 0.0
            })
        })
    })
}

/// The corners of the box, in `p`'s block frame, around the corners of what it keeps.
fn box_of_kept(p: &BlockPlan, solid: &Solid, probe: &Probe<'_>) -> [Vector3<f64>; 8] {
    let b = &p.block;
    let pts = kept_points_in(b, &p.keeps, solid, probe);
    let (mut lo, mut hi) = (b.half, -b.half);
    for q in &pts {
        let l = b.to_local(q);
        lo = lo.inf(&l);
        hi = hi.sup(&l);
    }
    if pts.is_empty() {
        return [b.center; 8];
    }
    std::array::from_fn(|i| {
        let l = Vector3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        b.to_model(&l)
    })
}

/// The axis of `a` (signed) most along the way to `b`.
fn towards(a: &Cuboid, b: &Cuboid) -> Vector3<f64> {
    let d = b.center - a.center;
    let k = (0..3)
        .max_by(|&i, &j| {
            let (x, y) = (
                a.axes().column(i).dot(&d).abs(),
                a.axes().column(j).dot(&d).abs(),
            );
            x.total_cmp(&y).then(j.cmp(&i))
        })
        .unwrap_or(0);
    let e = a.axes().column(k).into_owned();
    if e.dot(&d) < 0.0 {
        -e
    } else {
        e
    }
}

/// The plan of a block cut to the hull of its share `keep`.
fn restricted(
    p: &BlockPlan,
    keep: &[Plane],
    solid: &Solid,
    probe: &Probe<'_>,
    s: &PlanSettings,
    lattice: Option<&Lattice>,
) -> BlockPlan {
    let b = &p.block;
    let pts = kept_points_in(b, keep, solid, probe);
    let owned;
    let (l, ins) = match lattice {
        Some((l, i)) => (l, i),
        None => {
            let l = crate::hull::lattice(b);
            let i = l.iter().map(|q| probe.inside(q)).collect::<Vec<_>>();
            owned = (l, i);
            (&owned.0, &owned.1)
        }
    };
    let h = hull_cut_on(b, &pts, (l, ins), keep, probe, (s.kerf, s.lead));
    BlockPlan {
        cuts: h.cuts,
        added_volume: h.added_volume,
        added_depth: h.added_depth,
        kept_volume: h.kept_volume,
        keeps: keep.to_vec(),
        ..p.clone()
    }
}
