//! The model's sections by planes normal to the axis: closed loops in plane coordinates,
//! counter-clockwise, each started at a point that moves continuously from section to
//! section, and split at its sharp corners into sides.

use geom::slice::{slice_mesh, PlaneFrame};
use geom::TriMesh;
use nalgebra::{Vector2, Vector3};

use crate::error::{Error, Result};

/// A turn sharper than this (60°) at a section's vertex is a corner of the model (an edge
/// of a slab, the rim of a half sphere): rails are kept on it.
pub const CORNER_ANGLE: f64 = std::f64::consts::FRAC_PI_3;

/// One closed loop of a section.
#[derive(Debug, Clone, PartialEq)]
pub struct Loop {
    /// The points, counter-clockwise in plane coordinates, not repeating the first.
    pub points: Vec<Vector2<f64>>,
    /// Indices of the corners, increasing; the loop starts at the first corner when it has
    /// any (then `corners[0] == 0`).
    pub corners: Vec<usize>,
}

impl Loop {
    /// The centroid of the enclosed area.
    pub fn centroid(&self) -> Vector2<f64> {
        let (mut a, mut c) = (0.0, Vector2::zeros());
        let n = self.points.len();
        for i in 0..n {
            let (p, q) = (self.points[i], self.points[(i + 1) % n]);
            let cross = p.x * q.y - q.x * p.y;
            a += cross;
            c += (p + q) * cross;
        }
        if a.abs() > 0.0 {
            c / (3.0 * a)
        } else {
            self.points.iter().sum::<Vector2<f64>>() / n.max(1) as f64
        }
    }

    /// The sides between consecutive corners (the whole loop when it has none), each a
    /// polyline from its corner to the next, the last ending at the first point.
    pub fn sides(&self) -> Vec<Vec<Vector2<f64>>> {
        let n = self.points.len();
        let cuts: Vec<usize> = if self.corners.is_empty() {
            vec![0]
        } else {
            self.corners.clone()
        };
        (0..cuts.len())
            .map(|k| {
                let (a, b) = (cuts[k], if k + 1 < cuts.len() { cuts[k + 1] } else { n });
                (a..=b).map(|i| self.points[i % n]).collect()
            })
            .collect()
    }
}

/// The sections: plane offsets along the axis and the loops at each.
#[derive(Debug, Clone, PartialEq)]
pub struct Sections {
    /// The frame: `normal` is the axis.
    pub frame: PlaneFrame,
    /// Offsets of the section planes along the axis, increasing.
    pub offsets: Vec<f64>,
    /// Loops per section.
    pub loops: Vec<Vec<Loop>>,
    /// The model's extent along the axis.
    pub extent: (f64, f64),
}

/// Sections of the closed `mesh` by `n` planes normal to `axis`, spread over its extent
/// with cosine spacing (denser towards the ends), the end planes `end_gap` (a share of the
/// extent) inside it; where the number of loops changes from one section to the next,
/// sections are added by bisection until the change lies within `refine` (at most
/// [`MAX_REFINED`]).
///
/// # Errors
/// [`Error::Model`] when a section is not made of closed loops (the mesh is open) or the
/// axis is zero.
pub fn section(
    mesh: &TriMesh,
    axis: Vector3<f64>,
    n: usize,
    end_gap: f64,
    refine: f64,
) -> Result<Sections> {
    let frame = PlaneFrame::from_direction(axis).map_err(|e| Error::Model(e.to_string()))?;
    let d = frame.normal;
    let (lo, hi) = mesh
        .vertices()
        .iter()
        .map(|p| d.dot(p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
            (a.min(t), b.max(t))
        });
    section_window(mesh, &frame, (lo, hi), n, (end_gap, refine), None)
}

/// [`section`] over the offsets `(lo, hi)` along `frame.normal` only, each loop clipped to
/// the convex polygon `clip` (plane coordinates, counter-clockwise) when given: the model's
/// part in a block.
///
/// # Errors
/// As [`section`].
pub fn section_window(
    mesh: &TriMesh,
    frame: &PlaneFrame,
    (lo, hi): (f64, f64),
    n: usize,
    (end_gap, refine): (f64, f64),
    clip: Option<&[Vector2<f64>]>,
) -> Result<Sections> {
    let frame = *frame;
    let len = hi - lo;
    if !(len > 0.0) || n < 2 {
        return Err(Error::Model(
            "the model has no extent along the axis".into(),
        ));
    }
    let scale = mesh.aabb().size().norm();
    let (a, b) = (lo + end_gap * len, hi - end_gap * len);
    // cosine spacing: denser towards the ends, where a rounded end's loops shrink fast
    let offsets: Vec<f64> = (0..n)
        .map(|i| {
            let c = (std::f64::consts::PI * i as f64 / (n - 1) as f64).cos();
            (a + b) / 2.0 - (b - a) / 2.0 * c
        })
        .collect();
    let at = |t: f64| -> Result<Vec<Loop>> { loops_at(mesh, &frame, t, 1e-9 * scale, clip) };
    let mut sections: Vec<(f64, Vec<Loop>)> = Vec::with_capacity(n);
    for &t in &offsets {
        sections.push((t, at(t)?));
    }
    // where the loops change (split, merge, gain a corner), bisect until the change is
    // pinned to `refine` along the axis, so that the regions meet there
    let mut k = 0;
    let mut added = 0;
    while k + 1 < sections.len() && added < MAX_REFINED {
        let (t0, t1) = (sections[k].0, sections[k + 1].0);
        if signature(&sections[k].1) != signature(&sections[k + 1].1) && t1 - t0 > refine {
            let t = (t0 + t1) / 2.0;
            let l = at(t)?;
            sections.insert(k + 1, (t, l));
            added += 1;
            // look at (k, k + 1) again: the change is in one of the halves
            if signature(&sections[k].1) == signature(&sections[k + 1].1) {
                k += 1;
            }
            continue;
        }
        k += 1;
    }
    let (offsets, loops) = sections.into_iter().unzip();
    Ok(Sections {
        frame,
        offsets,
        loops,
        extent: (lo, hi),
    })
}

/// Most sections added where the loops change.
pub const MAX_REFINED: usize = 400;

/// What must match for two sections to belong to the same regions: their loop count.
fn signature(l: &[Loop]) -> usize {
    l.len()
}

fn loops_at(
    mesh: &TriMesh,
    frame: &PlaneFrame,
    t: f64,
    eps: f64,
    clip: Option<&[Vector2<f64>]>,
) -> Result<Vec<Loop>> {
    let mut here = Vec::new();
    for chain in slice_mesh(mesh, &frame.normal, t) {
        if !chain.closed {
            return Err(Error::Model(format!(
                "the section at {t} along the axis is open: the mesh must be closed"
            )));
        }
        let mut pts: Vec<Vector2<f64>> = chain
            .points(mesh)
            .iter()
            .map(|p| frame.to_plane(p))
            .collect();
        if let Some(c) = clip {
            pts = clip_polygon(&pts, c);
        }
        if let Some(l) = make_loop(pts, eps) {
            here.push(l);
        }
    }
    Ok(here)
}

/// A loop from raw section points: repeated points dropped, turned counter-clockwise,
/// corners found and the start chosen (the corner lowest-left of the centroid, else where
/// the ray from the centroid straight down leaves the loop); `None` when fewer than three points remain or it
/// encloses no area.
pub fn make_loop(raw: Vec<Vector2<f64>>, eps: f64) -> Option<Loop> {
    let mut pts: Vec<Vector2<f64>> = Vec::with_capacity(raw.len());
    for p in raw {
        if pts
            .last()
            .is_none_or(|q: &Vector2<f64>| (p - q).norm() > eps)
        {
            pts.push(p);
        }
    }
    while pts.len() > 1 && (pts[0] - pts[pts.len() - 1]).norm() <= eps {
        pts.pop();
    }
    if pts.len() < 3 {
        return None;
    }
    let area: f64 = (0..pts.len())
        .map(|i| {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            p.x * q.y - q.x * p.y
        })
        .sum();
    if area.abs() <= eps * eps {
        return None;
    }
    if area < 0.0 {
        pts.reverse();
    }
    let n = pts.len();
    let turn = |i: usize| {
        let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        let (e, f) = (b - a, c - b);
        (e.x * f.y - e.y * f.x).atan2(e.dot(&f)).abs()
    };
    let corners: Vec<usize> = (0..n).filter(|&i| turn(i) > CORNER_ANGLE).collect();
    let centre = Loop {
        points: pts.clone(),
        corners: Vec::new(),
    }
    .centroid();
    // the start: the corner lowest-left of the centroid, else where the ray from the
    // centroid straight down (−v) leaves the loop
    if corners.is_empty() {
        return Some(Loop {
            points: ray_down(&pts, centre),
            corners: Vec::new(),
        });
    }
    // the start: the corner lowest-left of the centroid
    let key = |i: &usize| {
        let d = pts[*i] - centre;
        -(d.x + d.y) / d.norm().max(eps)
    };
    let s = corners
        .iter()
        .copied()
        .max_by(|a, b| key(a).total_cmp(&key(b)).then(b.cmp(a)))
        .unwrap_or(0);
    let points: Vec<Vector2<f64>> = (0..n).map(|i| pts[(i + s) % n]).collect();
    let mut corners: Vec<usize> = corners.iter().map(|&i| (i + n - s) % n).collect();
    corners.sort_unstable();
    Some(Loop { points, corners })
}

/// A loop's points started where the ray from its centroid straight down leaves it (as a
/// loop without corners starts).
pub fn smooth_start(points: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let c = Loop {
        points: points.to_vec(),
        corners: Vec::new(),
    }
    .centroid();
    ray_down(points, c)
}

/// The loop rotated to start where the ray from `c` along −v first leaves it (a point
/// inserted there); at its lowest point when the ray does not leave it.
fn ray_down(pts: &[Vector2<f64>], c: Vector2<f64>) -> Vec<Vector2<f64>> {
    let n = pts.len();
    // crossings of the vertical line x = c.x below c: the one nearest c
    let mut best: Option<(f64, usize, Vector2<f64>)> = None;
    for i in 0..n {
        let (p, q) = (pts[i], pts[(i + 1) % n]);
        if (p.x - c.x) * (q.x - c.x) > 0.0 || p.x == q.x {
            continue;
        }
        let s = (c.x - p.x) / (q.x - p.x);
        let y = p.y + s * (q.y - p.y);
        if y <= c.y && best.is_none_or(|b| c.y - y < b.0) {
            best = Some((c.y - y, i, Vector2::new(c.x, y)));
        }
    }
    let Some((_, i, at)) = best else {
        // no crossing below the centroid (a non-star loop): start at its lowest point
        let low = (0..n)
            .min_by(|&a, &b| pts[a].y.total_cmp(&pts[b].y).then(a.cmp(&b)))
            .unwrap_or(0);
        return (0..n).map(|k| pts[(k + low) % n]).collect();
    };
    let mut out = vec![at];
    out.extend((1..=n).map(|k| pts[(i + k) % n]));
    if (out[out.len() - 1] - at).norm() == 0.0 {
        out.pop();
    }
    if out.len() > 1 && (out[1] - at).norm() == 0.0 {
        out.remove(1);
    }
    out
}

/// The point at arclength share `f ∈ [0, 1]` along a polyline.
pub fn at_share(poly: &[Vector2<f64>], f: f64) -> Vector2<f64> {
    let total: f64 = poly.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let mut left = f.clamp(0.0, 1.0) * total;
    for w in poly.windows(2) {
        let l = (w[1] - w[0]).norm();
        if left <= l && l > 0.0 {
            return w[0] + (w[1] - w[0]) * (left / l);
        }
        left -= l;
    }
    poly[poly.len() - 1]
}

/// Length of a polyline.
pub fn length(poly: &[Vector2<f64>]) -> f64 {
    poly.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// The largest curvature along a polyline, estimated at each inner vertex as its turning
/// angle over the mean length of its two edges.
pub fn max_curvature(poly: &[Vector2<f64>]) -> f64 {
    poly.windows(3)
        .map(|w| {
            let (e, f) = (w[1] - w[0], w[2] - w[1]);
            let turn = (e.x * f.y - e.y * f.x).atan2(e.dot(&f)).abs();
            let l = (e.norm() + f.norm()) / 2.0;
            if l > 0.0 {
                turn / l
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// The part of polygon `subject` inside the convex counter-clockwise polygon `clip`
/// (Sutherland–Hodgman; a non-convex subject's pieces stay joined along the clip's edges).
pub fn clip_polygon(subject: &[Vector2<f64>], clip: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let mut out: Vec<Vector2<f64>> = subject.to_vec();
    for k in 0..clip.len() {
        let (a, b) = (clip[k], clip[(k + 1) % clip.len()]);
        let side = |p: &Vector2<f64>| (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        let input = std::mem::take(&mut out);
        for i in 0..input.len() {
            let (p, q) = (input[i], input[(i + 1) % input.len()]);
            let (sp, sq) = (side(&p), side(&q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                out.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}
