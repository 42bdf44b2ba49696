//! The trace algorithm (thesis §5.3, category b): seams that follow the facade's ridges and
//! valleys. On every section the largest |curvature| between each two consecutive
//! inflections is found; these maxima are linked from section to section (same sign, the
//! nearest within `link_distance`) into traces. Traces that end inside the facade are
//! extended, longest first, keeping the ratio of their distances to the two neighbouring
//! curves (already extended traces or the facade's edges) until they meet another trace,
//! which they absorb, or the edge. Traces that come closer than `merge_distance` are
//! merged. Bands wider than the block, with a part longer than the blade, or with more than
//! `max_inflections` inflections get extra traces down their middle. The pieces are the
//! bands between traces, cut into rows of blocks.
//!
//! Left out: the thesis smooths surfaces with many short traces and projects the smooth
//! surface's traces back; here traces shorter than `min_sections` sections are dropped
//! before extension instead.

use crate::across::Across;
use crate::constraints::Constraints;
use crate::piece::{pieces_from_bands, rows_of, Seam, Segmentation};
use crate::section::Facade;
use crate::SegError;

/// Parameters of [`trace`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct TraceParams {
    /// Farthest (in `u`) a maximum may be from the trace's point on the previous section to
    /// continue it; `None`: a quarter of the block's width.
    pub link_distance: Option<f64>,
    /// Traces closer than this (in `u`) anywhere are merged; `None`: 2 % of the block's
    /// width.
    pub merge_distance: Option<f64>,
    /// Traces over fewer sections are dropped (the stand-in for smoothing).
    pub min_sections: usize,
    /// Points each part is sampled at for its checks.
    pub samples: usize,
}

impl Default for TraceParams {
    fn default() -> Self {
        Self {
            link_distance: None,
            merge_distance: None,
            min_sections: 2,
            samples: 64,
        }
    }
}

/// A trace: `u` per section where it has a point, and the curvature sign it follows.
#[derive(Debug, Clone)]
struct Trace {
    u: Vec<Option<f64>>,
    sign: f64,
}

impl Trace {
    fn span(&self) -> (usize, usize) {
        let first = self.u.iter().position(Option::is_some).unwrap_or(0);
        let last = self.u.iter().rposition(Option::is_some).unwrap_or(0);
        (first, last)
    }
    fn len(&self) -> usize {
        self.u.iter().filter(|v| v.is_some()).count()
    }
}

/// Links the curvature maxima between consecutive inflections into traces.
fn link(across: &[Across], link_distance: f64) -> Vec<Trace> {
    let n = across.len();
    let mut traces: Vec<Trace> = Vec::new();
    for (j, sec) in across.iter().enumerate() {
        let maxima: Vec<(f64, f64)> = sec
            .inflections
            .windows(2)
            .filter_map(|w| sec.max_between(w[0], w[1]))
            .collect();
        // candidate links (distance, trace, maximum), nearest first, one-to-one
        let mut cands: Vec<(f64, usize, usize)> = Vec::new();
        for (m, &(u, k)) in maxima.iter().enumerate() {
            for (t, tr) in traces.iter().enumerate() {
                if let Some(Some(prev)) = j.checked_sub(1).map(|p| tr.u[p]) {
                    let d = (u - prev).abs();
                    if d <= link_distance && tr.sign * k > 0.0 {
                        cands.push((d, t, m));
                    }
                }
            }
        }
        cands.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let mut used_t = vec![false; traces.len()];
        let mut used_m = vec![false; maxima.len()];
        for (_, t, m) in cands {
            if !used_t[t] && !used_m[m] {
                traces[t].u[j] = Some(maxima[m].0);
                used_t[t] = true;
                used_m[m] = true;
            }
        }
        for (m, &(u, k)) in maxima.iter().enumerate() {
            if !used_m[m] {
                let mut v = vec![None; n];
                v[j] = Some(u);
                traces.push(Trace {
                    u: v,
                    sign: k.signum(),
                });
            }
        }
    }
    traces
}

/// Runs the trace algorithm. `progress` is called once per section.
///
/// # Errors
/// [`SegError::Invalid`] for bad constraints; [`SegError::Section`] for a section that does
/// not run across the facade.
///
/// ```
/// # use facade_seg::{Constraints, Facade, Segmentation};
/// # use geom::expr::Expr;
/// # use geom::heightfield::HeightField;
/// # use geom::surface::{SectionParams, Surface};
/// # // the wavy facade of the crate's front page: an inflection every ~470 mm across the cut
/// # let z = Expr::parse("60*sin(y/150)")?;
/// # let surface = Surface::HeightField(HeightField::try_new(z, (0.0, 600.0), (0.0, 1800.0))?);
/// # let (frame, sections) = surface.sections(&SectionParams { count: 4, ..SectionParams::default() }, &|| {})?;
/// # let facade = Facade::new(frame, &sections)?;
/// # let c = Constraints {
/// #     block: [600.0, 600.0, 400.0], blade_length: 800.0, max_curvature: 0.011,
/// #     max_inflections: 2, tolerance_rms: 0.5, tolerance_max: 2.0,
/// # };
/// # // every section is cut into parts that meet end to end, from its start to its end
/// # let tiles = |seg: &Segmentation| facade.sections.iter().enumerate().all(|(j, sec)| {
/// #     let mut s: Vec<[f64; 2]> = seg.pieces.iter().flat_map(|p| &p.parts).filter(|q| q.plane == j).map(|q| q.s).collect();
/// #     s.sort_by(|a, b| a[0].total_cmp(&b[0]));
/// #     !s.is_empty() && s[0][0].abs() < 1e-6 && (s[s.len() - 1][1] - sec.length).abs() < 1e-6
/// #         && s.windows(2).all(|w| (w[1][0] - w[0][1]).abs() < 1e-6)
/// # });
/// use facade_seg::trace::{trace, TraceParams};
/// let seg = trace(&facade, &c, &TraceParams::default(), &|| {})?;
/// assert_eq!(seg.algorithm, "Trace");
/// assert!(tiles(&seg));
/// assert!(seg.pieces.iter().all(|p| !p.parts.is_empty()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn trace(
    facade: &Facade,
    c: &Constraints,
    p: &TraceParams,
    progress: &(dyn Fn() + Sync),
) -> Result<Segmentation, SegError> {
    c.validate()?;
    let across = Across::all(facade, progress)?;
    let link_distance = p.link_distance.unwrap_or(0.25 * c.block[1]);
    let merge_distance = p.merge_distance.unwrap_or(0.02 * c.block[1]);
    let mut traces: Vec<Trace> = link(&across, link_distance)
        .into_iter()
        .filter(|t| t.len() >= p.min_sections.max(1))
        .collect();
    // longest first (ties: leftmost start, for determinism)
    traces.sort_by(|a, b| {
        b.len().cmp(&a.len()).then_with(|| {
            let (ua, ub) = (a.u[a.span().0], b.u[b.span().0]);
            ua.unwrap_or(0.0).total_cmp(&ub.unwrap_or(0.0))
        })
    });
    // full curves: the facade's two edges, then every extended trace
    let edges: [Vec<f64>; 2] = [
        across.iter().map(|a| a.u_range().0).collect(),
        across.iter().map(|a| a.u_range().1).collect(),
    ];
    let full = extend(traces, &edges, link_distance, merge_distance);
    let mut curves: Vec<Vec<f64>> = Vec::with_capacity(full.len() + 2);
    curves.push(edges[0].clone());
    curves.extend(full);
    curves.push(edges[1].clone());
    add_middle_traces(facade, c, &across, &mut curves)?;
    // bands between consecutive curves
    let bands: Vec<Vec<Option<(f64, f64)>>> = curves
        .windows(2)
        .map(|w| {
            (0..across.len())
                .map(|j| {
                    let prep = &facade.sections[j];
                    let (s0, s1) = (across[j].s_at(prep, w[0][j]), across[j].s_at(prep, w[1][j]));
                    (s1 > s0).then_some((s0, s1))
                })
                .collect()
        })
        .collect();
    let seams = curves[1..curves.len() - 1]
        .iter()
        .map(|curve| Seam {
            points: (0..across.len())
                .map(|j| {
                    let s = across[j].s_at(&facade.sections[j], curve[j]);
                    let w = facade.world(j, s);
                    [w.x, w.y, w.z]
                })
                .collect(),
        })
        .collect();
    let pieces = pieces_from_bands(facade, c, &bands, false, p.samples);
    Ok(Segmentation {
        algorithm: "Trace".into(),
        rows: pieces.iter().map(|q| q.row + 1).max().unwrap_or(0),
        bands: bands.len(),
        pieces,
        seams,
    })
}

/// The traces (longest first) extended over every section, each keeping the ratio of its
/// distances to its neighbours (the facade's `edges` and the curves made so far) and
/// absorbing the pending traces it meets; a curve closer than `merge_distance` to one made
/// before or to an edge is dropped. Returns the curves across the facade, in order, each
/// no left of the one before on any section.
fn extend(
    traces: Vec<Trace>,
    edges: &[Vec<f64>; 2],
    link_distance: f64,
    merge_distance: f64,
) -> Vec<Vec<f64>> {
    let n = edges[0].len();
    let mut full: Vec<Vec<f64>> = Vec::new();
    let mut pending: Vec<Option<Trace>> = traces.into_iter().map(Some).collect();
    for i in 0..pending.len() {
        let Some(mut tr) = pending[i].take() else {
            continue;
        };
        let neighbours = |u: f64, j: usize, full: &Vec<Vec<f64>>| {
            let mut lo = edges[0][j];
            let mut hi = edges[1][j];
            for f in full {
                if f[j] < u && f[j] > lo {
                    lo = f[j];
                }
                if f[j] > u && f[j] < hi {
                    hi = f[j];
                }
            }
            (lo, hi)
        };
        // extend forward, then backward, keeping the ratio to the neighbours
        for forward in [true, false] {
            loop {
                let (first, last) = tr.span();
                let (from, to) = if forward {
                    if last + 1 >= n {
                        break;
                    }
                    (last, last + 1)
                } else {
                    if first == 0 {
                        break;
                    }
                    (first, first - 1)
                };
                let u0 = tr.u[from].unwrap_or(0.0);
                let (l0, h0) = neighbours(u0, from, &full);
                let ratio = if h0 > l0 { (u0 - l0) / (h0 - l0) } else { 0.5 };
                let (l1, h1) = neighbours(u0, to, &full);
                let u1 = l1 + ratio * (h1 - l1);
                tr.u[to] = Some(u1);
                absorb(&mut tr, &mut pending, to, forward, u1, link_distance);
            }
        }
        let curve: Vec<f64> = tr.u.iter().map(|v| v.unwrap_or(0.0)).collect();
        // merge with a curve it comes too close to (the longer one stays)
        let close = full.iter().any(|f| {
            f.iter()
                .zip(&curve)
                .any(|(a, b)| (a - b).abs() < merge_distance)
        });
        let on_edge = curve
            .iter()
            .enumerate()
            .any(|(j, &u)| u - edges[0][j] < merge_distance || edges[1][j] - u < merge_distance);
        if !close && !on_edge {
            full.push(curve);
        }
    }
    // sort across the facade and keep the order on every section
    full.sort_by(|a, b| a[0].total_cmp(&b[0]));
    for i in 1..full.len() {
        let (done, rest) = full.split_at_mut(i);
        for (v, prev) in rest[0].iter_mut().zip(&done[i - 1]) {
            *v = v.max(*prev);
        }
    }
    full
}

/// Trace `tr`, just extended to section `to` at `u1`, meets a pending trace that starts
/// (or, going backward, ends) there within `link_distance`: it absorbs it.
fn absorb(
    tr: &mut Trace,
    pending: &mut [Option<Trace>],
    to: usize,
    forward: bool,
    u1: f64,
    link_distance: f64,
) {
    let hit = pending.iter().position(|q| {
        q.as_ref().is_some_and(|q| {
            let (qf, ql) = q.span();
            let at = if forward { qf } else { ql };
            at == to && q.u[to].is_some_and(|v| (v - u1).abs() <= link_distance)
        })
    });
    if let Some(q) = hit.and_then(|h| pending[h].take()) {
        for (j, v) in q.u.iter().enumerate() {
            if v.is_some() && tr.u[j].is_none() || j == to {
                tr.u[j] = *v;
            }
        }
    }
}

/// Most curves [`add_middle_traces`] may make: enough to halve every band of every row down
/// to half a block across, split every section between its inflections and cut it into
/// blade-length parts, with room to spare. Derived from the facade and the constraints,
/// so a run that needs more is reported, not looped on.
fn curve_cap(facade: &Facade, c: &Constraints, across: &[Across], rows: usize) -> usize {
    let span = across
        .iter()
        .map(|a| a.u_range().1 - a.u_range().0)
        .fold(0.0, f64::max);
    let per_row = (2.0 * span / c.block[1]).ceil().min(1e6) as usize + 1;
    let inflections = across
        .iter()
        .map(|a| a.inflections.len())
        .max()
        .unwrap_or(0);
    let blade = facade
        .sections
        .iter()
        .map(|s| (2.0 * s.length / c.blade_length).ceil().min(1e6) as usize)
        .max()
        .unwrap_or(0);
    4 * (rows.max(1) * per_row + inflections + blade) + 16
}

/// Bands between consecutive `curves` that are too wide for the block (within a row of
/// blocks, or on one section), too long for the blade or hold too many inflections get a
/// new curve, until none does (or a band is too thin to halve):
/// - a band too wide, too long or too full on some section: a curve down its middle;
/// - a band that fits on every section but not within a row of blocks (its sections shift
///   across the facade along the cut, as on a facade cut obliquely): in each such row, a
///   curve at the middle of the row's span across the facade, clamped into the band on each
///   section, so each half spans at most half the row's span.
///
/// # Errors
/// [`SegError::TooManyPieces`] when more curves than [`curve_cap`] would be needed.
fn add_middle_traces(
    facade: &Facade,
    c: &Constraints,
    across: &[Across],
    curves: &mut Vec<Vec<f64>>,
) -> Result<(), SegError> {
    let n = across.len();
    let k = c.max_inflections as usize;
    let rows = rows_of(facade, c);
    let n_rows = rows.iter().copied().max().map_or(0, |r| r + 1);
    let cap = curve_cap(facade, c, across, n_rows);
    let thin = 1e-9 * c.block[1];
    // a piece is cut from one block: its band, within a row of blocks, must fit the block's
    // width across the facade; spans only over the sections the band crosses
    let row_spans = |lo: &[f64], hi: &[f64]| {
        let mut span = vec![(f64::INFINITY, f64::NEG_INFINITY); n_rows];
        for j in (0..n).filter(|&j| hi[j] - lo[j] > thin) {
            let r = &mut span[rows[j]];
            *r = (r.0.min(lo[j]), r.1.max(hi[j]));
        }
        span
    };
    let mut i = 0;
    while i + 1 < curves.len() {
        let (lo, hi) = (&curves[i], &curves[i + 1]);
        let section_problem = (0..n).any(|j| {
            let sec = &across[j];
            let prep = &facade.sections[j];
            hi[j] - lo[j] > c.block[1]
                || sec.s_at(prep, hi[j]) - sec.s_at(prep, lo[j]) > c.blade_length
                || sec.count(lo[j], hi[j]) > k
        });
        let wide_enough = (0..n).any(|j| hi[j] - lo[j] > 1e-6 * c.block[1]);
        let spans = row_spans(lo, hi);
        let wide_rows = spans.iter().any(|(a, b)| b - a > c.block[1]);
        let new = if section_problem && wide_enough {
            Some((0..n).map(|j| 0.5 * (lo[j] + hi[j])).collect::<Vec<f64>>())
        } else if wide_rows {
            Some(
                (0..n)
                    .map(|j| {
                        let (a, b) = spans[rows[j]];
                        if b - a > c.block[1] {
                            (0.5 * (a + b)).clamp(lo[j], hi[j])
                        } else {
                            lo[j]
                        }
                    })
                    .collect(),
            )
        } else {
            None
        };
        match new {
            Some(mid) => {
                if curves.len() >= cap {
                    return Err(SegError::TooManyPieces {
                        cap,
                        why: "the trace algorithm could not make its bands fit the block and the blade (inflections closer together than the block allows, e.g. a noisy mesh section? raise tolerance.smoothing, blade.max_inflections or block.size)".into(),
                    });
                }
                curves.insert(i + 1, mid);
            }
            None => i += 1,
        }
    }
    Ok(())
}
