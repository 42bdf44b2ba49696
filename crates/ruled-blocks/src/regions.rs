//! Regions: runs of consecutive sections whose loops keep their number and their corners,
//! each a tube the piecewise ruled fit (eq. 4.1) approximates with rails along the axis and
//! straight rulings in the section planes — a Polar-Annular-Mesh-like split by a height
//! field along the axis (see the crate's front page for what it does not do).

use geom::surface_spline::BSplineSurface;
use nalgebra::{Vector2, Vector3};

use crate::error::{Error, Result};
use crate::fit::{fit_surface, GridSamples, RuledFitParams};
use crate::sections::{at_share, length, max_curvature, Loop, Sections};

/// A tube of the model: one loop in each of a run of consecutive sections.
#[derive(Debug, Clone, PartialEq)]
pub struct Tube {
    /// Index of its first section.
    pub first: usize,
    /// Its loop in each section of the run.
    pub loops: Vec<Loop>,
}

/// Splits the sections into tubes: a loop continues the tube of the previous section's
/// loop nearest to it when both sections have as many loops and the nearest is mutual;
/// otherwise it starts a tube.
pub fn tubes(s: &Sections) -> Vec<Tube> {
    let mut done: Vec<Tube> = Vec::new();
    let mut open: Vec<Tube> = Vec::new();
    for (k, here) in s.loops.iter().enumerate() {
        let prev: Vec<Vector2<f64>> = open
            .iter()
            .map(|t| t.loops[t.loops.len() - 1].centroid())
            .collect();
        let cur: Vec<Vector2<f64>> = here.iter().map(Loop::centroid).collect();
        let nearest = |p: &Vector2<f64>, set: &[Vector2<f64>]| {
            (0..set.len()).min_by(|&a, &b| {
                (set[a] - p)
                    .norm()
                    .total_cmp(&(set[b] - p).norm())
                    .then(a.cmp(&b))
            })
        };
        let mut next: Vec<Option<Tube>> = vec![None; here.len()];
        let same_count = prev.len() == cur.len();
        let mut taken = vec![false; open.len()];
        if same_count {
            for (i, c) in cur.iter().enumerate() {
                let Some(j) = nearest(c, &prev) else { continue };
                let mutual = nearest(&prev[j], &cur) == Some(i);
                if mutual && !taken[j] {
                    taken[j] = true;
                    let mut t = open[j].clone();
                    t.loops.push(here[i].clone());
                    next[i] = Some(t);
                }
            }
        }
        for (j, t) in open.into_iter().enumerate() {
            if !taken[j] {
                done.push(t);
            }
        }
        open = next
            .into_iter()
            .enumerate()
            .map(|(i, t)| {
                t.unwrap_or_else(|| Tube {
                    first: k,
                    loops: vec![here[i].clone()],
                })
            })
            .collect();
    }
    done.extend(open);
    done.sort_by_key(|t| (t.first, t.loops.len()));
    done
}

/// How finely to fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// Target largest distance of a region's samples from its ruled surface.
    pub tolerance: f64,
    /// Most strips around one loop.
    pub max_strips: usize,
    /// Samples per strip across (≥ 2).
    pub samples_per_strip: usize,
}

/// A fitted region: a tube's piecewise ruled surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// Index of its first section.
    pub first: usize,
    /// Index of its last section.
    pub last: usize,
    /// Its sections' offsets along the axis.
    pub offsets: Vec<f64>,
    /// The surface: `u` the offset along the axis, `v ∈ [0, strips]` around the loop (rails
    /// at whole `v`; rail `strips` is rail 0).
    pub surface: BSplineSurface,
    /// Strips around.
    pub strips: usize,
    /// Strips per side (between corners).
    pub side_strips: Vec<usize>,
    /// The fit's residuals (eq. 4.1's terms: each sample's distance to the surface point of
    /// its own parameters, an upper bound on its distance to the surface): RMS.
    pub fit_rms: f64,
    /// Largest residual.
    pub fit_max: f64,
    /// Control points per rail.
    pub controls: usize,
}

impl Region {
    /// Rail `j`'s point at offset `u` (`j` taken modulo the strips).
    pub fn rail(&self, u: f64, j: usize) -> Vector3<f64> {
        let (a, b) = (self.offsets[0], self.offsets[self.offsets.len() - 1]);
        self.surface.eval(u.clamp(a, b), (j % self.strips) as f64)
    }
}

/// Strips per side for a tube: a side of length `L` whose section bends at most by `κ`
/// needs `L·√(κ / (8·tol))` strips for a chord to stay within `tol` of it (the sagitta
/// `κ h² / 8`), at least one; scaled down together when they exceed `max`.
pub fn side_strips(t: &Tube, tol: f64, max: usize) -> Vec<usize> {
    let nsides = t.loops[0].sides().len();
    let mut need = vec![1usize; nsides];
    for l in &t.loops {
        for (k, side) in l.sides().iter().enumerate() {
            let n = length(side) * (max_curvature(side) / (8.0 * tol)).sqrt();
            if n.is_finite() {
                need[k] = need[k].max(n.ceil().min(max as f64) as usize);
            }
        }
    }
    // a closed loop needs three strips at least
    while need.iter().sum::<usize>() < 3 {
        need[0] += 1;
    }
    let total: usize = need.iter().sum();
    if total > max && max >= nsides.max(3) {
        let f = max as f64 / total as f64;
        need = need
            .iter()
            .map(|&n| ((n as f64 * f).floor() as usize).max(1))
            .collect();
        while need.iter().sum::<usize>() < 3 {
            need[0] += 1;
        }
    }
    need
}

/// The tube's samples on the fit's grid: `u` the sections' offsets, `v = j / k` around the
/// loop (`k` samples per strip), each side's samples spread by arclength over its strips.
fn grid(t: &Tube, s: &Sections, sides: &[usize], k: usize) -> GridSamples {
    let (u, loops) = stations(t, s);
    let total: usize = sides.iter().sum();
    let v: Vec<f64> = (0..=total * k).map(|j| j as f64 / k as f64).collect();
    let mut points = Vec::with_capacity(u.len() * v.len());
    // which side and share each v falls on
    let mut at: Vec<(usize, f64)> = Vec::with_capacity(v.len());
    for (side, &n) in sides.iter().enumerate() {
        let first = if side == 0 { 0 } else { 1 };
        for m in first..=n * k {
            at.push((side, m as f64 / (n * k) as f64));
        }
    }
    let sided: Vec<Vec<Vec<Vector2<f64>>>> = loops.iter().map(|l| l.sides()).collect();
    for &(side, f) in &at {
        for (i, l) in sided.iter().enumerate() {
            let q = at_share(&l[side], f);
            let p = s.frame.to_world(u[i], &q);
            points.push([p.x, p.y, p.z]);
        }
    }
    GridSamples { u, v, points }
}

/// The tube with corners its loops agree on: the most common corner count among its loops
/// (more than half of them must have it, else none); a loop with another count (a tiny
/// polygon near a tip, a facet's kink) takes the vertices nearest to the corners of the
/// nearest loop that has it, mapped by the similarity of their centroids and areas. Loops
/// without corners start where the ray from their centroid straight down leaves them.
pub fn aligned(t: &Tube) -> Tube {
    let counts: Vec<usize> = t.loops.iter().map(|l| l.corners.len()).collect();
    let mut mode = (0usize, 0usize); // (how many, count)
    for &c in &counts {
        let k = counts.iter().filter(|&&x| x == c).count();
        if k > mode.0 || (k == mode.0 && c < mode.1) {
            mode = (k, c);
        }
    }
    let smooth = || Tube {
        first: t.first,
        loops: t
            .loops
            .iter()
            .map(|l| Loop {
                points: crate::sections::smooth_start(&l.points),
                corners: Vec::new(),
            })
            .collect(),
    };
    let n = mode.1;
    if n == 0 || 2 * mode.0 <= counts.len() {
        return smooth();
    }
    let mut loops = Vec::with_capacity(t.loops.len());
    for (i, l) in t.loops.iter().enumerate() {
        if counts[i] == n {
            loops.push(l.clone());
            continue;
        }
        let Some(j) = (0..counts.len())
            .filter(|&j| counts[j] == n)
            .min_by_key(|&j| (j.abs_diff(i), j))
        else {
            return smooth();
        };
        match corners_like(l, &t.loops[j]) {
            Some(x) => loops.push(x),
            None => return smooth(),
        }
    }
    Tube {
        first: t.first,
        loops,
    }
}

fn signed_area(p: &[Vector2<f64>]) -> f64 {
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
        / 2.0
}

/// `l` with corners at its vertices nearest to `model`'s corners (mapped onto `l` by
/// centroid and area), started at the first; `None` when two fall on one vertex.
fn corners_like(l: &Loop, model: &Loop) -> Option<Loop> {
    let (cl, cm) = (l.centroid(), model.centroid());
    let s = (signed_area(&l.points) / signed_area(&model.points))
        .abs()
        .sqrt();
    let nearest = |q: Vector2<f64>| {
        (0..l.points.len()).min_by(|&a, &b| {
            (l.points[a] - q)
                .norm()
                .total_cmp(&(l.points[b] - q).norm())
                .then(a.cmp(&b))
        })
    };
    let idx: Vec<usize> = model
        .corners
        .iter()
        .map(|&i| nearest(cl + (model.points[i] - cm) * s))
        .collect::<Option<_>>()?;
    let n = l.points.len();
    let start = idx[0];
    let mut corners: Vec<usize> = idx.iter().map(|&i| (i + n - start) % n).collect();
    let before = corners.len();
    corners.sort_unstable();
    corners.dedup();
    if corners.len() != before {
        return None;
    }
    Some(Loop {
        points: (0..n).map(|k| l.points[(k + start) % n]).collect(),
        corners,
    })
}

/// The offsets and loops the fit goes through: the tube's own, or for a tube of one section
/// its loop twice, a quarter of the neighbouring gap to either side (a prism).
fn stations<'t>(t: &'t Tube, s: &Sections) -> (Vec<f64>, Vec<&'t Loop>) {
    let u: Vec<f64> = (0..t.loops.len()).map(|i| s.offsets[t.first + i]).collect();
    if t.loops.len() > 1 {
        return (u, t.loops.iter().collect());
    }
    let k = t.first;
    let gaps = [
        k.checked_sub(1).map(|j| s.offsets[k] - s.offsets[j]),
        s.offsets.get(k + 1).map(|o| o - s.offsets[k]),
    ];
    let q = gaps
        .iter()
        .flatten()
        .copied()
        .fold(f64::INFINITY, f64::min)
        .min(s.extent.1 - s.extent.0)
        / 4.0;
    (vec![u[0] - q, u[0] + q], vec![&t.loops[0], &t.loops[0]])
}

/// Fits one tube: strips from the curvature, then control points per rail doubled from
/// a quarter of the sections until the samples lie within the tolerance (or every
/// section has its own); the closing rail is the mean of the first and last fitted rails,
/// so the loop closes exactly.
///
/// # Errors
/// [`Error::Fit`] when no fit can be made (too few sections for a cubic rail).
pub fn fit_tube(index: usize, t: &Tube, s: &Sections, f: &FitSettings) -> Result<Region> {
    let t = &aligned(t);
    let sides = side_strips(t, f.tolerance / 2.0, f.max_strips);
    let strips: usize = sides.iter().sum();
    let k = f.samples_per_strip.max(2);
    let g = grid(t, s, &sides, k);
    let nu = g.u.len();
    let try_fit = |degree: usize, controls: usize| {
        fit_surface(
            &g,
            &RuledFitParams {
                strips,
                degree,
                controls,
            },
        )
    };
    let worst = |r: &[f64]| r.iter().copied().fold(0.0, f64::max);
    // control points doubled from a quarter of the sections until every sample's residual
    // is within the tolerance; where the sections leave a knot span empty (few, unevenly
    // spread sections), fewer, then a lower degree
    let degree = 3.min(nu - 1).max(1);
    let most = nu;
    let first = (nu / 4).max(degree + 1).min(most);
    let mut best: Option<(BSplineSurface, Vec<f64>, usize)> = None;
    let mut controls = first;
    let mut tried = first;
    loop {
        let attempt = try_fit(degree, controls).or_else(|e| {
            // more control points than the sections pin: the most between the last that
            // fitted and this
            (tried + 1..controls)
                .rev()
                .find_map(|c| try_fit(degree, c).ok().map(|r| (r, c)))
                .map(|(r, c)| {
                    controls = c;
                    r
                })
                .ok_or(e)
        });
        let Ok((surface, residuals)) = attempt else {
            break;
        };
        tried = controls;
        let done = worst(&residuals) <= f.tolerance;
        if best
            .as_ref()
            .is_none_or(|b| worst(&residuals) < worst(&b.1))
        {
            best = Some((surface, residuals, controls));
        }
        let next = (controls * 2).min(most);
        if done || next == controls {
            break;
        }
        controls = next;
    }
    if best.is_none() {
        'lower: for d in (1..=degree).rev() {
            for c in (d + 1..=first.min(nu)).rev() {
                if let Ok((surface, residuals)) = try_fit(d, c) {
                    best = Some((surface, residuals, c));
                    break 'lower;
                }
            }
        }
    }
    let Some((surface, _, controls)) = best else {
        return Err(Error::Fit {
            region: index,
            source: try_fit(1, 2)
                .err()
                .unwrap_or(crate::fit::FitError::Samples("no fit".into())),
        });
    };
    let surface = close_loop(&surface, strips)?;
    let residuals = residuals_of(&g, &surface);
    let (fit_rms, fit_max) = (
        (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len().max(1) as f64).sqrt(),
        worst(&residuals),
    );
    Ok(Region {
        first: t.first,
        last: t.first + t.loops.len() - 1,
        offsets: g.u,
        surface,
        strips,
        side_strips: sides,
        fit_rms,
        fit_max,
        controls,
    })
}

/// Each sample's distance to the surface point of its own parameters.
fn residuals_of(g: &GridSamples, s: &BSplineSurface) -> Vec<f64> {
    let nu = g.u.len();
    g.v.iter()
        .enumerate()
        .flat_map(|(j, &v)| {
            g.u.iter()
                .enumerate()
                .map(move |(i, &u)| (Vector3::from(g.points[j * nu + i]) - s.eval(u, v)).norm())
        })
        .collect()
}

/// The surface with its last rail (`v = strips`) and first rail replaced by their mean.
fn close_loop(s: &BSplineSurface, strips: usize) -> Result<BSplineSurface> {
    let (nc, nr) = s.grid_size();
    debug_assert_eq!(nr, strips + 1);
    let mut ctrl = s.control_points().to_vec();
    for i in 0..nc {
        let m = (ctrl[i * nr] + ctrl[i * nr + nr - 1]) / 2.0;
        ctrl[i * nr] = m;
        ctrl[i * nr + nr - 1] = m;
    }
    BSplineSurface::try_new(
        s.degrees(),
        s.knots_u().to_vec(),
        s.knots_v().to_vec(),
        (nc, nr),
        ctrl,
    )
    .map_err(|e| Error::Model(e.to_string()))
}
