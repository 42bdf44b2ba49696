//! Several cuts through one block ("Designing for Robotic Hot-Blade Cutting" §3.1,
//! figs. 4/5, §5.3): the foam left is what lies below every cut, so the block's top is the
//! lower envelope of the cut surfaces, with a sharp crease where two of them meet. Cuts
//! are taken by priority — the primary closest to the block's base (the lowest mean
//! height over the block) — and a later cut that nowhere dips below what the earlier ones
//! left does not touch the material: it is dropped.
//!
//! The envelope is taken on a grid over the block's footprint, once for the design
//! surfaces and once for the elastica surfaces that are really cut; where they differ and
//! where their creases lie apart is the effect fig. 5 warns about: elastica that match the
//! design at the blade's ends but not in the middle move the crease.

use geom::slice::PlaneFrame;
use nalgebra::Vector3;

/// A cutting plane's offset, design curve and elastica (polylines in plane coordinates).
pub type PlaneCurves = (f64, Vec<[f64; 2]>, Vec<[f64; 2]>);

/// One cut's surfaces over a block: per cutting plane, its offset and the design curve
/// and the elastica as polylines in plane coordinates (across increasing).
#[derive(Debug, Clone)]
pub struct CutSurface {
    /// The cut's planes' frame.
    pub frame: PlaneFrame,
    /// Per plane, offsets increasing: `(offset, design, elastica)`.
    pub planes: Vec<PlaneCurves>,
}

/// Height of a polyline at across coordinate `u` (clamped to its ends).
fn polyline_height(p: &[[f64; 2]], u: f64) -> Option<f64> {
    let (first, last) = (p.first()?, p.last()?);
    let (lo, hi) = if first[0] <= last[0] {
        (first, last)
    } else {
        (last, first)
    };
    if u <= lo[0] {
        return Some(lo[1]);
    }
    if u >= hi[0] {
        return Some(hi[1]);
    }
    p.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        let (x0, x1) = (a[0].min(b[0]), a[0].max(b[0]));
        (u >= x0 && u <= x1).then(|| {
            if x1 > x0 {
                a[1] + (b[1] - a[1]) * (u - a[0]) / (b[0] - a[0])
            } else {
                a[1].min(b[1])
            }
        })
    })
}

impl CutSurface {
    /// The surface's height over the world point `(x, y)`: the design's, or with
    /// `elastica` the elastica's (linear between planes, clamped to the first and last).
    ///
    /// ```
    /// use design::envelope::{envelope, CutSurface};
    /// use geom::slice::PlaneFrame;
    /// use nalgebra::Vector3;
    ///
    /// // cuts along x over a 1 × 1 block; each plane's curve a line across it
    /// let frame = PlaneFrame::from_direction(Vector3::x())?;
    /// let line = |h: f64| vec![[-10.0, h], [10.0, h]];
    /// let plane = |x: f64, h: f64| (x, line(h), line(h));
    /// // a level cut at height 1, and one rising along the cut from 0.5 to 2.5
    /// let level = CutSurface { frame, planes: vec![plane(0.0, 1.0), plane(1.0, 1.0)] };
    /// let rising = CutSurface { frame, planes: vec![plane(0.0, 0.5), plane(1.0, 2.5)] };
    /// // linear between the planes, clamped beyond them
    /// assert!((rising.height(0.5, 0.3, false).ok_or("no height")? - 1.5).abs() < 1e-12);
    /// assert_eq!(rising.height(2.0, 0.3, true), Some(2.5));
    /// assert_eq!(level.height(0.7, 0.0, false), Some(1.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn height(&self, x: f64, y: f64, elastica: bool) -> Option<f64> {
        let p = Vector3::new(x, y, 0.0);
        let (s, u) = (self.frame.normal.dot(&p), self.frame.u.dot(&p));
        let curve = |j: usize| {
            let pl = &self.planes[j];
            polyline_height(if elastica { &pl.2 } else { &pl.1 }, u)
        };
        let n = self.planes.len();
        if n == 0 {
            return None;
        }
        if s <= self.planes[0].0 || n == 1 {
            return curve(0);
        }
        if s >= self.planes[n - 1].0 {
            return curve(n - 1);
        }
        let j = self.planes.iter().rposition(|pl| pl.0 <= s)?.min(n - 2);
        let (a, b) = (self.planes[j].0, self.planes[j + 1].0);
        let w = if b > a { (s - a) / (b - a) } else { 0.0 };
        Some(curve(j)? * (1.0 - w) + curve(j + 1)? * w)
    }
}

/// The top of a block cut by several cuts.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Envelope {
    /// Indices of the cuts kept, in priority order (the primary first).
    pub order: Vec<usize>,
    /// Indices of the cuts dropped: they nowhere dip below what the earlier ones left.
    pub dropped: Vec<usize>,
    /// Grid points per side.
    pub grid: usize,
    /// Grid heights of the design's envelope, row by row (x fastest).
    pub design: Vec<f64>,
    /// Grid heights of the elastica's envelope.
    pub elastica: Vec<f64>,
    /// The grid's points `(x, y)`, row by row.
    pub points: Vec<[f64; 2]>,
    /// Largest |elastica − design| of the envelope.
    pub max_deviation: f64,
    /// Crease points of the design's envelope (where the lowest cut changes).
    pub design_crease: Vec<[f64; 3]>,
    /// Crease points of the elastica's envelope.
    pub elastica_crease: Vec<[f64; 3]>,
    /// Largest distance of a design crease point from the elastica's crease (and back),
    /// `None` without a crease on either.
    pub crease_deviation: Option<f64>,
}

/// The envelope of `cuts` over the footprint `[lo, hi]` (x, y), on a `grid × grid` grid
/// (≥ 2). `tolerance` is how far below what is left a cut must dip to count as touching
/// it.
///
/// ```
/// use design::envelope::{envelope, CutSurface};
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
///
/// // cuts along x over a 1 × 1 block; each plane's curve a line across it
/// let frame = PlaneFrame::from_direction(Vector3::x())?;
/// let line = |h: f64| vec![[-10.0, h], [10.0, h]];
/// let plane = |x: f64, h: f64| (x, line(h), line(h));
/// // a level cut at height 1, and one rising along the cut from 0.5 to 2.5
/// let level = CutSurface { frame, planes: vec![plane(0.0, 1.0), plane(1.0, 1.0)] };
/// let rising = CutSurface { frame, planes: vec![plane(0.0, 0.5), plane(1.0, 2.5)] };
/// let e = envelope(&[rising.clone(), level.clone()], [0.0, 0.0], [1.0, 1.0], 5, 1e-9);
/// // the level cut is lower on average: the primary; the rising one still dips below it
/// assert_eq!((e.order.as_slice(), e.dropped.as_slice()), (&[1, 0][..], &[][..]));
/// // the crease where they cross, at x = 0.25 and height 1
/// assert!(!e.design_crease.is_empty());
/// assert!(e.design_crease.iter().all(|c| (c[0] - 0.25).abs() < 1e-12 && (c[2] - 1.0).abs() < 1e-12));
/// assert_eq!(e.max_deviation, 0.0); // the "elastica" here are the design
/// // a cut above the level one everywhere touches nothing: dropped
/// let high = CutSurface { frame, planes: vec![plane(0.0, 2.0), plane(1.0, 3.0)] };
/// let e = envelope(&[level, high], [0.0, 0.0], [1.0, 1.0], 5, 1e-9);
/// assert_eq!((e.order, e.dropped), (vec![0], vec![1]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn envelope(
    cuts: &[CutSurface],
    lo: [f64; 2],
    hi: [f64; 2],
    grid: usize,
    tolerance: f64,
) -> Envelope {
    let grid = grid.max(2);
    let points: Vec<[f64; 2]> = (0..grid)
        .flat_map(|j| {
            (0..grid).map(move |i| {
                let (a, b) = (i as f64 / (grid - 1) as f64, j as f64 / (grid - 1) as f64);
                [lo[0] + a * (hi[0] - lo[0]), lo[1] + b * (hi[1] - lo[1])]
            })
        })
        .collect();
    let heights = |c: &CutSurface, el: bool| -> Vec<f64> {
        points
            .iter()
            .map(|p| c.height(p[0], p[1], el).unwrap_or(f64::INFINITY))
            .collect()
    };
    let design: Vec<Vec<f64>> = cuts.iter().map(|c| heights(c, false)).collect();
    let elastica: Vec<Vec<f64>> = cuts.iter().map(|c| heights(c, true)).collect();
    // priority: the lowest mean design height first (ties: input order)
    let mean = |h: &[f64]| h.iter().sum::<f64>() / h.len() as f64;
    let mut by_height: Vec<usize> = (0..cuts.len()).collect();
    by_height.sort_by(|&a, &b| {
        mean(&design[a])
            .total_cmp(&mean(&design[b]))
            .then(a.cmp(&b))
    });
    let (mut order, mut dropped) = (Vec::new(), Vec::new());
    let mut env = vec![f64::INFINITY; points.len()];
    for c in by_height {
        let touches =
            order.is_empty() || design[c].iter().zip(&env).any(|(h, e)| *h < e - tolerance);
        if touches {
            order.push(c);
            env.iter_mut()
                .zip(&design[c])
                .for_each(|(e, h)| *e = e.min(*h));
        } else {
            dropped.push(c);
        }
    }
    let lower =
        |hs: &[Vec<f64>]| -> (Vec<f64>, Vec<usize>) {
            (0..points.len())
                .map(|k| {
                    order.iter().map(|&c| (hs[c][k], c)).fold(
                        (f64::INFINITY, usize::MAX),
                        |m, v| if v.0 < m.0 { v } else { m },
                    )
                })
                .unzip()
        };
    let (de, downer) = lower(&design);
    let (ee, eowner) = lower(&elastica);
    let crease = |hs: &[Vec<f64>], owner: &[usize]| -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        let idx = |i: usize, j: usize| j * grid + i;
        for j in 0..grid {
            for i in 0..grid {
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di >= grid || j + dj >= grid {
                        continue;
                    }
                    let (a, b) = (idx(i, j), idx(i + di, j + dj));
                    let (p, q) = (owner[a], owner[b]);
                    if p == q || p == usize::MAX || q == usize::MAX {
                        continue;
                    }
                    let (da, db) = (hs[p][a] - hs[q][a], hs[p][b] - hs[q][b]);
                    let t = if (da - db).abs() > 0.0 {
                        (da / (da - db)).clamp(0.0, 1.0)
                    } else {
                        0.5
                    };
                    let (pa, pb) = (points[a], points[b]);
                    let x = pa[0] + t * (pb[0] - pa[0]);
                    let y = pa[1] + t * (pb[1] - pa[1]);
                    let z = hs[p][a] + t * (hs[p][b] - hs[p][a]);
                    out.push([x, y, z]);
                }
            }
        }
        out
    };
    let design_crease = crease(&design, &downer);
    let elastica_crease = crease(&elastica, &eowner);
    let far = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        a.iter()
            .map(|p| {
                b.iter()
                    .map(|q| {
                        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2))
                            .sqrt()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    let crease_deviation = (!design_crease.is_empty() && !elastica_crease.is_empty())
        .then(|| far(&design_crease, &elastica_crease).max(far(&elastica_crease, &design_crease)));
    let max_deviation = de
        .iter()
        .zip(&ee)
        .map(|(a, b)| (a - b).abs())
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    Envelope {
        order,
        dropped,
        grid,
        design: de,
        elastica: ee,
        points,
        max_deviation,
        design_crease,
        elastica_crease,
        crease_deviation,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cut along `d` whose surface is the plane z = h + slope·u (design) and that
    /// plus `bump` in the middle of every curve (elastica).
    fn tilted(d: Vector3<f64>, h: f64, slope: f64, bump: f64) -> CutSurface {
        let frame = PlaneFrame::from_direction(d).unwrap();
        let planes = (0..=10)
            .map(|j| {
                let s = -1.0 + 2.0 * j as f64 / 10.0;
                let line = |b: f64| -> Vec<[f64; 2]> {
                    (0..=40)
                        .map(|i| {
                            let u = -1.0 + 2.0 * i as f64 / 40.0;
                            [u, h + slope * u + b * (1.0 - u * u)]
                        })
                        .collect()
                };
                (s, line(0.0), line(bump))
            })
            .collect();
        CutSurface { frame, planes }
    }

    #[test]
    fn two_crossed_ridges_make_a_crease_on_the_diagonal() {
        // z = 0.5 + 0.2·y (X cut: u = y) and z = 0.5 − 0.2·x... (Y cut: u = −x, so +0.2·x)
        let a = tilted(Vector3::x(), 0.5, 0.2, 0.0);
        let b = tilted(Vector3::y(), 0.5, -0.2, 0.0);
        let e = envelope(&[a, b], [-1.0, -1.0], [1.0, 1.0], 21, 1e-9);
        assert_eq!(e.order.len(), 2);
        assert!(e.dropped.is_empty());
        // the crease is where 0.2·y = 0.2·x: the diagonal
        assert!(!e.design_crease.is_empty());
        for p in &e.design_crease {
            assert!((p[0] - p[1]).abs() < 1e-9, "{p:?}");
        }
        assert_eq!(e.crease_deviation, Some(0.0));
        assert_eq!(e.max_deviation, 0.0);
    }

    #[test]
    fn a_cut_above_the_first_is_dropped() {
        let low = tilted(Vector3::x(), 0.3, 0.1, 0.0);
        let high = tilted(Vector3::y(), 0.8, 0.1, 0.0);
        let e = envelope(&[high, low], [-1.0, -1.0], [1.0, 1.0], 11, 1e-9);
        assert_eq!(e.order, vec![1]);
        assert_eq!(e.dropped, vec![0]);
        assert!(e.design_crease.is_empty());
        assert_eq!(e.crease_deviation, None);
    }

    #[test]
    fn elastica_off_the_design_move_the_crease() {
        let a = tilted(Vector3::x(), 0.5, 0.2, 0.02);
        let b = tilted(Vector3::y(), 0.5, -0.2, 0.0);
        let e = envelope(&[a, b], [-1.0, -1.0], [1.0, 1.0], 41, 1e-9);
        let moved = e.crease_deviation.unwrap();
        assert!(moved > 1e-3 && moved < 0.2, "{moved}");
        assert!(e.max_deviation > 0.0 && e.max_deviation <= 0.02 + 1e-12);
    }
}
