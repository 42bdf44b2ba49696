//! A block that its strips cannot cut is cut to the convex hull of what it keeps (thesis
//! §4.2, fig. 4.4): planar cuts on the hull's faces, chosen greedily by how much of the
//! block outside the hull each removes (measured on a lattice), at most
//! [`MAX_PLANES`](crate::cuts::MAX_PLANES). Any face plane of the hull leaves the hull,
//! and so the kept material, whole: these cuts never enter it.

use blocks::Cuboid;
use geom::hull::convex_hull;
use nalgebra::Vector3;

use crate::cuts::{mount, Cut, CutKind, WireLine, LATTICE, MAX_PLANES};
use crate::machine::MachineFrame;
use crate::solid::Probe;

/// A plane `n · x = c`, `n` the unit outward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Outward unit normal.
    pub n: Vector3<f64>,
    /// Offset.
    pub c: f64,
}

/// The hull's face planes, coplanar faces merged (outward normals), each moved out to the
/// farthest of `points` along its normal, so every plane supports every point.
pub fn hull_planes(points: &[Vector3<f64>], scale: f64) -> Option<Vec<Plane>> {
    let hull = convex_hull(points).ok()?;
    let centre = hull.vertices().iter().sum::<Vector3<f64>>() / hull.vertices().len() as f64;
    let mut planes: Vec<Plane> = Vec::new();
    for f in 0..hull.faces().len() {
        let [a, b, c] = hull.triangle(f);
        let n = (b - a).cross(&(c - a));
        let l = n.norm();
        if !(l > 0.0) {
            continue;
        }
        let mut n = n / l;
        if n.dot(&(centre - a)) > 0.0 {
            n = -n;
        }
        // the plane through the farthest point along `n`, not through the face's corner: a
        // sliver face's rounded normal is noise, and a plane through its corner could then
        // tilt into the hull; this one supports every point whatever `n` is
        let c = points
            .iter()
            .map(|p| n.dot(p))
            .fold(f64::NEG_INFINITY, f64::max);
        if !planes
            .iter()
            .any(|p| (p.n - n).norm() < 1e-9 && (p.c - c).abs() < 1e-9 * scale)
        {
            planes.push(Plane { n, c });
        }
    }
    Some(planes)
}

/// What cutting a block to its hull gives.
#[derive(Debug, Clone, PartialEq)]
pub struct HullCut {
    /// The planar cuts.
    pub cuts: Vec<Cut>,
    /// The planes chosen.
    pub planes: Vec<Plane>,
    /// Volume the cut shape holds beyond the solid (lattice estimate).
    pub added_volume: f64,
    /// Largest depth of that material over the solid's surface.
    pub added_depth: f64,
    /// Volume of the solid in the block (lattice estimate).
    pub kept_volume: f64,
}

/// Cuts block `b` to the hull of `points` (the corners of what it keeps); `kerf` moves each
/// wire half of it outward; `lead` is the lead-in and lead-out.
pub fn hull_cut(
    b: &Cuboid,
    points: &[Vector3<f64>],
    probe: &Probe<'_>,
    kerf: f64,
    lead: f64,
) -> HullCut {
    let lattice = lattice(b);
    let inside: Vec<bool> = lattice.iter().map(|p| probe.inside(p)).collect();
    hull_cut_on(b, points, (&lattice, &inside), &[], probe, (kerf, lead))
}

/// [`hull_cut`] with the block's lattice and its points' insideness given (computed once
/// per block), and the block keeping only its share `keep` (half-spaces `n · x ≤ c`) of the
/// solid: `points` are then the corners of that share.
pub fn hull_cut_on(
    b: &Cuboid,
    points: &[Vector3<f64>],
    (lattice, inside_solid): (&[Vector3<f64>], &[bool]),
    keep: &[Plane],
    probe: &Probe<'_>,
    (kerf, lead): (f64, f64),
) -> HullCut {
    let scale = b.half.norm();
    let inside: Vec<bool> = lattice
        .iter()
        .zip(inside_solid)
        .map(|(p, &i)| i && keep.iter().all(|pl| pl.n.dot(p) <= pl.c))
        .collect();
    let cell = 8.0 * b.half.x * b.half.y * b.half.z / lattice.len() as f64;
    let kept_volume = inside.iter().filter(|&&x| x).count() as f64 * cell;
    let planes = hull_planes(points, scale).unwrap_or_default();
    let eps = 1e-9 * scale;
    let outside = |p: &Vector3<f64>, pl: &Plane| pl.n.dot(p) - pl.c > eps;
    let mut remaining: Vec<usize> = (0..lattice.len())
        .filter(|&i| planes.iter().any(|pl| outside(&lattice[i], pl)))
        .collect();
    let mut chosen: Vec<Plane> = Vec::new();
    while !remaining.is_empty() && chosen.len() < MAX_PLANES {
        let count = |pl: &Plane| {
            remaining
                .iter()
                .filter(|&&i| outside(&lattice[i], pl))
                .count()
        };
        let Some(best) = planes
            .iter()
            .filter(|pl| !chosen.contains(pl))
            .max_by_key(|pl| count(pl))
            .copied()
        else {
            break;
        };
        if count(&best) == 0 {
            break;
        }
        remaining.retain(|&i| !outside(&lattice[i], &best));
        chosen.push(best);
    }
    let (mut added, mut depth) = (0usize, 0.0f64);
    for (p, &ins) in lattice.iter().zip(&inside) {
        if !ins && !chosen.iter().any(|pl| outside(p, pl)) {
            added += 1;
            depth = depth.max(probe.distance(p));
        }
    }
    let cuts = chosen
        .iter()
        .filter_map(|pl| plane_cut(b, pl, kerf, lead))
        .collect();
    HullCut {
        cuts,
        planes: chosen,
        added_volume: added as f64 * cell,
        added_depth: depth,
        kept_volume,
    }
}

/// Cell centres of a `LATTICE³` lattice over the block.
pub fn lattice(b: &Cuboid) -> Vec<Vector3<f64>> {
    let n = LATTICE;
    let at = |i: usize, k: usize| b.half[k] * (2.0 * (i as f64 + 0.5) / n as f64 - 1.0);
    let mut out = Vec::with_capacity(n * n * n);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                out.push(b.to_model(&Vector3::new(at(i, 0), at(j, 1), at(k, 2))));
            }
        }
    }
    out
}

/// The planar cut on `pl`: the wire in the plane along the block axis closest to it,
/// swept across the block.
fn plane_cut(b: &Cuboid, pl: &Plane, kerf: f64, lead: f64) -> Option<Cut> {
    let ax = |k: usize| b.axes().column(k).into_owned();
    let k = (0..3).min_by(|&i, &j| {
        pl.n.dot(&ax(i))
            .abs()
            .total_cmp(&pl.n.dot(&ax(j)).abs())
            .then(i.cmp(&j))
    })?;
    let w = (ax(k) - pl.n * pl.n.dot(&ax(k))).normalize();
    let m = pl.n.cross(&w);
    let m_ = mount(b, &[w], &m)?;
    let q0 = b.center - pl.n * (pl.n.dot(&b.center) - pl.c) + pl.n * (kerf / 2.0);
    let (lo, hi) = b
        .corners()
        .iter()
        .map(|c| m.dot(&(c - q0)))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), s| {
            (a.min(s), z.max(s))
        });
    let steps = 4;
    let lines: Vec<WireLine> = (0..=steps)
        .map(|i| WireLine {
            point: q0 + m * (lo + (hi - lo) * i as f64 / steps as f64),
            dir: w,
        })
        .collect();
    // the leads go on along m, in the plane (a lead along the mount's axis would leave the
    // plane, into what the block keeps), until the wire clears the block along the cut by
    // `lead` (the rapids then stay off the block)
    let mut lines = lines;
    if let (Some(&first), Some(&last)) = (lines.first(), lines.last()) {
        let f = MachineFrame::new(b, &m_);
        let rate = m.dot(&f.along).max(1e-3);
        let w = f.half[1];
        let along_at = |l: &WireLine, s: f64| f.local(&f.at_across(l, s * w))[0];
        let back = (along_at(&first, -1.0).max(along_at(&first, 1.0)) + lead).max(lead) / rate;
        let length = 2.0 * f.half[0];
        let on = (length - along_at(&last, -1.0).min(along_at(&last, 1.0)) + lead).max(lead) / rate;
        lines.insert(
            0,
            WireLine {
                point: first.point - m * back,
                dir: first.dir,
            },
        );
        lines.push(WireLine {
            point: last.point + m * on,
            dir: last.dir,
        });
    }
    Some(Cut {
        kind: CutKind::Plane,
        lines,
        mount: m_,
    })
}
