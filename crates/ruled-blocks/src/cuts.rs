//! Cuttability per block (thesis §4.2): a block is cut strip by strip, the wire following
//! each strip's rulings extended across the whole block; it can be cut when no wire
//! position enters the material the block keeps (the rationalized solid inside the block)
//! deeper than the tolerance. Where it cannot, the block is cut to the convex hull of what
//! it keeps, by planar cuts on the hull's faces, and the material this adds is measured.

use blocks::Cuboid;
use geom::bbox::Aabb;
use nalgebra::Vector3;

use crate::machine::{leads, MachineFrame};
use crate::solid::{Probe, Solid};

/// Largest angle between a wire and the machine's across axis (60°): a wire flatter than
/// this to the tower planes would need towers far beyond the block.
pub const MIN_WIRE_COS: f64 = 0.5;
/// Most planar cuts of a block cut to its hull.
pub const MAX_PLANES: usize = 16;
/// Lattice points per block edge for the hull's added material.
pub const LATTICE: usize = 16;

/// A wire position: a line through `point` along the unit `dir` (model coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireLine {
    /// A point of the wire.
    pub point: Vector3<f64>,
    /// Its unit direction.
    pub dir: Vector3<f64>,
}

/// How a block lies on the cutter for one cut: unit model vectors of the block's axes
/// (signed) along the cut, towards tower B (across), and up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mount {
    /// Block axis index and sign along the cut.
    pub along: (usize, f64),
    /// Across, towards tower B.
    pub across: (usize, f64),
    /// Up.
    pub up: (usize, f64),
}

impl Mount {
    /// The model vector of a signed block axis.
    pub fn vector(b: &Cuboid, (k, s): (usize, f64)) -> Vector3<f64> {
        b.axes().column(k) * s
    }
}

/// What a cut follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CutKind {
    /// A strip of a region.
    Strip {
        /// The region.
        region: usize,
        /// The strip.
        strip: usize,
    },
    /// A face of the block's hull.
    Plane,
}

/// One 4-axis cut: the wire's positions in order, from the lead-in to the lead-out, and
/// the block's mount.
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// What it follows.
    pub kind: CutKind,
    /// Wire positions, kerf applied.
    pub lines: Vec<WireLine>,
    /// The mount.
    pub mount: Mount,
}

/// A block's plan.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockPlan {
    /// The block.
    pub block: Cuboid,
    /// Whether the strips cut it (else: its hull).
    pub cuttable: bool,
    /// Why it is not, when it is not.
    pub reason: Option<String>,
    /// How deep a strip's wire would enter the kept material, where it first goes beyond
    /// the tolerance (0 when none does).
    pub deepest: f64,
    /// The cuts.
    pub cuts: Vec<Cut>,
    /// Material the hull adds (0 for a cuttable block), estimated on a lattice.
    pub added_volume: f64,
    /// Largest depth of the added material over the rationalized surface.
    pub added_depth: f64,
    /// Volume of the rationalized solid in the block, on the same lattice.
    pub kept_volume: f64,
    /// What the block keeps of its overlaps with neighbours: the half-spaces `n · x ≤ c` its
    /// share lies in (none: all of the solid in it).
    pub keeps: Vec<crate::hull::Plane>,
}

/// What the planner needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanSettings {
    /// Depth beyond which a wire position counts as entering the kept material.
    pub tolerance: f64,
    /// Kerf of the wire: each wire position lies half of it outside the cut surface.
    pub kerf: f64,
    /// Lead-in and lead-out beyond the block.
    pub lead: f64,
}

/// Whether a model point lies in the block (boundary included).
fn in_box(b: &Cuboid, p: &Vector3<f64>) -> bool {
    b.contains(p, -1e-12 * b.half.norm())
}

/// The part `[s0, s1]` of the line `p + s·d` inside the block, if any.
pub fn clip(b: &Cuboid, p: &Vector3<f64>, d: &Vector3<f64>) -> Option<(f64, f64)> {
    let (lp, ld) = (b.to_local(p), b.axes().tr_mul(d));
    let (mut s0, mut s1) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        if ld[k].abs() < 1e-15 {
            if lp[k].abs() > b.half[k] {
                return None;
            }
            continue;
        }
        let (a, c) = ((-b.half[k] - lp[k]) / ld[k], (b.half[k] - lp[k]) / ld[k]);
        s0 = s0.max(a.min(c));
        s1 = s1.min(a.max(c));
    }
    (s1 > s0).then_some((s0, s1))
}

/// Whether the wire line enters the kept material (the solid inside the block) deeper than
/// `tol`: the depth of the first point found deeper (below the solid's surface and from the
/// block's faces), else 0. The line's part in the block is walked by sphere tracing on the
/// distance to the solid's surface `d`: a point outside stays more than `tol` away from
/// any depth beyond `tol` for `d + tol` further on; within `tol` of the surface the walk
/// goes on by `max(tol − d, tol / 2)`; a point farther than `tol` is tested for inside.
pub fn penetration(b: &Cuboid, probe: &Probe<'_>, l: &WireLine, tol: f64) -> f64 {
    penetration_in(b, &[], probe, l, tol)
}

/// [`penetration`] into the block's share `keep` (half-spaces `n · x ≤ c`) of the solid.
pub fn penetration_in(
    b: &Cuboid,
    keep: &[crate::hull::Plane],
    probe: &Probe<'_>,
    l: &WireLine,
    tol: f64,
) -> f64 {
    let Some((s0, s1)) = clip(b, &l.point, &l.dir) else {
        return 0.0;
    };
    let mut s = s0;
    // every step is at least tol / 2: the walk ends
    let most = (2.0 * (s1 - s0) / tol).ceil() as usize + 2;
    for _ in 0..most {
        if s > s1 {
            break;
        }
        let p = l.point + l.dir * s;
        let d = probe.distance(&p);
        let step = if d <= tol {
            (tol - d).max(tol / 2.0)
        } else if probe.inside(&p) {
            let local = b.to_local(&p);
            let face = (0..3)
                .map(|k| b.half[k] - local[k].abs())
                .fold(f64::INFINITY, f64::min);
            let share = keep
                .iter()
                .map(|h| h.c - h.n.dot(&p))
                .fold(f64::INFINITY, f64::min);
            let depth = d.min(face).min(share);
            if depth > tol {
                return depth;
            }
            tol / 2.0
        } else {
            d + tol
        };
        s += step;
    }
    0.0
}

/// The mount for a cut whose wire directions are `dirs` and which progresses along `prog`:
/// across the block axis most parallel to the wires, along the one (of the other two) most
/// parallel to `prog`; `None` when a wire is flatter than [`MIN_WIRE_COS`] to it.
pub fn mount(b: &Cuboid, dirs: &[Vector3<f64>], prog: &Vector3<f64>) -> Option<Mount> {
    let ax = |k: usize| b.axes().column(k).into_owned();
    let score = |k: usize| dirs.iter().map(|d| d.dot(&ax(k)).abs()).sum::<f64>();
    let across = (0..3).max_by(|&i, &j| score(i).total_cmp(&score(j)).then(j.cmp(&i)))?;
    let sign = |v: f64| if v < 0.0 { -1.0 } else { 1.0 };
    let s_across = sign(dirs.iter().map(|d| d.dot(&ax(across))).sum());
    if dirs.iter().any(|d| d.dot(&ax(across)).abs() < MIN_WIRE_COS) {
        return None;
    }
    let others: Vec<usize> = (0..3).filter(|&k| k != across).collect();
    let along = if prog.dot(&ax(others[0])).abs() >= prog.dot(&ax(others[1])).abs() {
        others[0]
    } else {
        others[1]
    };
    let s_along = sign(prog.dot(&ax(along)));
    let up = 3 - across - along;
    // right-handed (along, across, up) seen from the machine: up = along × across
    let upv = (ax(along) * s_along).cross(&(ax(across) * s_across));
    Some(Mount {
        along: (along, s_along),
        across: (across, s_across),
        up: (up, sign(upv.dot(&ax(up)))),
    })
}

/// `lines` with the lead-in before and the lead-out after them (see
/// [`crate::machine::leads`]), and the positions every move into and out of them passes
/// (`n` between), for the check.
pub fn with_leads(
    b: &Cuboid,
    m: &Mount,
    lines: &[WireLine],
    lead: f64,
    n: usize,
) -> (Vec<WireLine>, Vec<WireLine>) {
    let (Some(first), Some(last)) = (lines.first(), lines.last()) else {
        return (Vec::new(), Vec::new());
    };
    let f = MachineFrame::new(b, m);
    let (lin, lout) = leads(&f, first, last, lead);
    let mut all = vec![lin];
    all.extend(lines.iter().copied());
    all.push(lout);
    let mut passed = Vec::new();
    for (a, z) in [(&lin, first), (last, &lout)] {
        for i in 1..n {
            let s = i as f64 / n as f64;
            passed.push(WireLine {
                point: a.point + (z.point - a.point) * s,
                dir: a.dir,
            });
        }
    }
    (all, passed)
}

/// Least move of a wire between two positions, a share of the model's diagonal (the unit
/// frame's length; 1.5 mm on a 1.5 m model): closer positions are one. A program skips
/// moves shorter than its last digits allow (`ruled::wire::program::min_move_mm`, 0.05 mm);
/// merged here, relative to the model, the positions a program keeps do not depend on the
/// job's unit or scale.
pub const MIN_MOVE: f64 = 1e-3;

/// `lines` without the positions that move the wire less than [`MIN_MOVE`] from the last
/// one kept (measured at the wire's point and `reach` along it, both ways).
pub fn distinct(lines: &[WireLine], reach: f64) -> Vec<WireLine> {
    let mut out: Vec<WireLine> = Vec::with_capacity(lines.len());
    for l in lines {
        let moved = out.last().is_none_or(|k: &WireLine| {
            [-reach, 0.0, reach]
                .iter()
                .map(|&s| ((l.point + l.dir * s) - (k.point + k.dir * s)).norm())
                .fold(0.0, f64::max)
                >= MIN_MOVE
        });
        if moved {
            out.push(*l);
        }
    }
    out
}

/// The strip cuts of a block: every strip with a ruling in it, its rulings from the first
/// to the last whose line crosses the block, offset by half the kerf; with the deepest any of its
/// wire positions (the sweeps in and out included) enters the kept material, and why the
/// block cannot be cut this way (`None`: it can).
pub fn strip_cuts(
    b: &Cuboid,
    solid: &Solid,
    probe: &Probe<'_>,
    s: &PlanSettings,
) -> (Vec<Cut>, f64, Option<String>) {
    let mut cuts = Vec::new();
    let mut deepest: f64 = 0.0;
    let mut reason = None;
    for st in &solid.strips {
        let meets = |r: &crate::solid::Ruling| {
            let d = r.b - r.a;
            let len = d.norm();
            if len <= 0.0 {
                return in_box(b, &r.a);
            }
            clip(b, &r.a, &(d / len)).is_some_and(|(s0, s1)| {
                s1 > 0.0 && s0 < len && s1.min(len) - s0.max(0.0) > s.tolerance.min(len)
            })
        };
        if !st.rulings.iter().any(meets) {
            continue;
        }
        // the wire follows every ruling whose line crosses the block
        let crosses = |r: &crate::solid::Ruling| clip(b, &r.a, &r.dir).is_some();
        let Some(k0) = st.rulings.iter().position(crosses) else {
            continue;
        };
        let k1 = st.rulings.iter().rposition(crosses).unwrap_or(k0);
        // and one more on either side, whose line misses the block: the wire enters and
        // leaves along the strip itself
        let (k0, k1) = (k0.saturating_sub(1), (k1 + 1).min(st.rulings.len() - 1));
        let lines: Vec<WireLine> = st.rulings[k0..=k1]
            .iter()
            .map(|r| WireLine {
                point: (r.a + r.b) / 2.0 + r.normal * (s.kerf / 2.0),
                dir: r.dir,
            })
            .collect();
        let dirs: Vec<Vector3<f64>> = lines.iter().map(|l| l.dir).collect();
        let Some(m) = mount(b, &dirs, &solid.axis) else {
            reason.get_or_insert_with(|| {
                format!(
                    "strip {} of region {}: its rulings turn more than 60° from any one block axis",
                    st.index + 1,
                    st.region + 1
                )
            });
            continue;
        };
        let lines = distinct(&lines, b.half.norm());
        let (lines, passed) = with_leads(b, &m, &lines, s.lead, 8);
        let mut deep: f64 = 0.0;
        for l in lines.iter().chain(&passed) {
            deep = penetration(b, probe, l, s.tolerance);
            if deep > 0.0 {
                break;
            }
        }
        if deep > s.tolerance {
            reason.get_or_insert_with(|| {
                format!(
                    "strip {} of region {}: extended as the wire it enters the kept material deeper than the tolerance",
                    st.index + 1,
                    st.region + 1
                )
            });
        }
        deepest = deepest.max(deep);
        if reason.is_some() {
            // the block goes to its hull: its strips' cuts are not needed
            break;
        }
        cuts.push(Cut {
            kind: CutKind::Strip {
                region: st.region,
                strip: st.index,
            },
            lines,
            mount: m,
        });
    }
    (cuts, deepest, reason)
}

/// The corners of the polyhedron `solid ∩ block`: the solid's vertices in the block, its
/// edges' crossings of the block's faces, the block's edges' crossings of its faces and
/// the block's corners inside it ([`kept_points_in`] with no further half-space).
pub fn kept_points(b: &Cuboid, solid: &Solid, probe: &Probe<'_>) -> Vec<Vector3<f64>> {
    kept_points_in(b, &[], solid, probe)
}

/// [`kept_points`] of `solid ∩ block ∩ keep`, `keep` half-spaces `n · x ≤ c` (a block's share
/// of an overlap): the corners of that polyhedron — the solid's edges clipped to the block
/// and the half-spaces, the polytope's edges (the block's, clipped, and those of its cuts by
/// each plane) crossing the solid's faces, the polytope's corners inside the solid.
pub fn kept_points_in(
    b: &Cuboid,
    keep: &[crate::hull::Plane],
    solid: &Solid,
    probe: &Probe<'_>,
) -> Vec<Vector3<f64>> {
    let mut pts = Vec::new();
    let (lo, hi) = b.aabb();
    let faces = solid_faces_in(solid, &Aabb { min: lo, max: hi });
    // the part of segment p → q (unit d, length len) in the half-spaces, and in the block
    // unless it lies on the block (its edges: a slab test would drop them by a rounding)
    let clipped =
        |p: &Vector3<f64>, d: &Vector3<f64>, len: f64, in_box: bool| -> Option<(f64, f64)> {
            let (mut a, mut c) = if in_box {
                (0.0, len)
            } else {
                let (s0, s1) = clip(b, p, d)?;
                (s0.max(0.0), s1.min(len))
            };
            for pl in keep {
                let (at, rate) = (pl.n.dot(p) - pl.c, pl.n.dot(d));
                if rate.abs() < 1e-300 {
                    if at > 0.0 {
                        return None;
                    }
                    continue;
                }
                let s = -at / rate;
                if rate > 0.0 {
                    c = c.min(s);
                } else {
                    a = a.max(s);
                }
            }
            (c >= a).then_some((a, c))
        };
    for &f in &faces {
        let t = solid.mesh.triangle(f);
        for k in 0..3 {
            let (p, q) = (t[k], t[(k + 1) % 3]);
            let d = q - p;
            let len = d.norm();
            if len <= 0.0 {
                continue;
            }
            if let Some((a, c)) = clipped(&p, &(d / len), len, false) {
                pts.push(p + d / len * a);
                pts.push(p + d / len * c);
            }
        }
    }
    // the polytope's edges: the block's, and each plane's section of the block
    let corners = b.corners();
    let mut edges: Vec<(Vector3<f64>, Vector3<f64>)> = Vec::new();
    for i in 0..8usize {
        for j in (i + 1)..8 {
            if (i ^ j).count_ones() == 1 {
                edges.push((corners[i], corners[j]));
            }
        }
    }
    let box_edges = edges.clone();
    for pl in keep {
        let mut ring: Vec<Vector3<f64>> = box_edges
            .iter()
            .filter_map(|(p, q)| {
                let (dp, dq) = (pl.n.dot(p) - pl.c, pl.n.dot(q) - pl.c);
                ((dp <= 0.0) != (dq <= 0.0)).then(|| p + (q - p) * (dp / (dp - dq)))
            })
            .collect();
        if ring.len() < 3 {
            continue;
        }
        let c = ring.iter().sum::<Vector3<f64>>() / ring.len() as f64;
        let u = (ring[0] - c).normalize();
        let v = pl.n.cross(&u);
        ring.sort_by(|x, y| {
            let ax = (x - c).dot(&v).atan2((x - c).dot(&u));
            let ay = (y - c).dot(&v).atan2((y - c).dot(&u));
            ax.total_cmp(&ay)
        });
        for k in 0..ring.len() {
            edges.push((ring[k], ring[(k + 1) % ring.len()]));
        }
    }
    for (p, q) in &edges {
        let d = q - p;
        let len = d.norm();
        if len <= 0.0 {
            continue;
        }
        let Some((a, c)) = clipped(p, &(d / len), len, true) else {
            continue;
        };
        let (p0, p1) = (p + d / len * a, p + d / len * c);
        for end in [p0, p1] {
            if probe.inside(&end) {
                pts.push(end);
            }
        }
        for &f in &faces {
            let [ta, tb, tc] = solid.mesh.triangle(f);
            if let Some(x) = segment_triangle(&p0, &p1, &ta, &tb, &tc) {
                pts.push(x);
            }
        }
    }
    pts
}

fn solid_faces_in(solid: &Solid, b: &Aabb) -> Vec<usize> {
    (0..solid.mesh.faces().len())
        .filter(|&f| {
            let t = solid.mesh.triangle(f);
            let lo = t[0].inf(&t[1]).inf(&t[2]);
            let hi = t[0].sup(&t[1]).sup(&t[2]);
            (0..3).all(|k| lo[k] <= b.max[k] && hi[k] >= b.min[k])
        })
        .collect()
}

/// Where segment `pq` crosses triangle `abc`.
fn segment_triangle(
    p: &Vector3<f64>,
    q: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> Option<Vector3<f64>> {
    let d = q - p;
    let (e1, e2) = (b - a, c - a);
    let h = d.cross(&e2);
    let det = e1.dot(&h);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = p - a;
    let u = s.dot(&h) / det;
    let qv = s.cross(&e1);
    let v = d.dot(&qv) / det;
    let t = e2.dot(&qv) / det;
    ((0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t))
        .then(|| p + d * t)
}
