//! The longest-elastica algorithm (thesis §5.4, category a: the elastica fits guide the
//! segmentation). From the facade's start edge, each section's longest part that an
//! elastica fits within tolerance is found by a halving search; the parts' ends, evened
//! out so that no part is more than `max_step` longer than its neighbour's, form a seam;
//! the search restarts from that seam until the facade is covered.
//!
//! A part is accepted only when it meets every constraint that segmenting can help with:
//! the elastica through its end points fits within both tolerances, neither the design nor
//! the elastica has more than `max_inflections` inflections (the shape constraint, which
//! the thesis names as the next step), neither bends beyond `max_curvature` (blade strain),
//! and the part fits the block across the facade.

use rayon::prelude::*;

use crate::constraints::{Constraints, PartCheck};
use crate::piece::{pieces_from_bands, rows_of, Seam, Segmentation};
use crate::section::Facade;
use crate::SegError;

/// Parameters of [`longest_elastica`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct LongestParams {
    /// Precision of the halving search (the last step), in facade units: the search takes
    /// ⌈log₂(blade length / precision)⌉ steps (1 mm on a 1 m blade: 10).
    pub precision: f64,
    /// Most a part may be longer than its neighbour's (seam smoothing); `None`: the mean
    /// spacing between sections, so seams run at most 45° to the cut.
    pub max_step: Option<f64>,
    /// Points each part is sampled at for its fit.
    pub samples: usize,
    /// Most bands before giving up.
    pub max_bands: usize,
}

impl Default for LongestParams {
    fn default() -> Self {
        Self {
            precision: 1.0,
            max_step: None,
            samples: 64,
            max_bands: 200,
        }
    }
}

/// Share of the blade length below which the rest of a section after a part is a sliver
/// that the part should share instead of leaving (a blade pose on a few millimetres means
/// nothing).
pub const SLIVER_SHARE: f64 = 0.05;

/// Whether the part `[s0, s1]` of section `j` is acceptable.
fn accepted(facade: &Facade, c: &Constraints, j: usize, s0: f64, s1: f64, n: usize) -> bool {
    let check = PartCheck::of(&facade.sections[j], s0, s1, n, true);
    let v = check.verdicts(c, true);
    v.dimension && v.approximation == Some(true) && v.shape && v.blade_strain
}

/// The longest acceptable part of section `j` from `s0`, by the halving search of §5.4.
/// Returns its length and whether any length was accepted (if none, the shortest tried).
fn longest_from(
    facade: &Facade,
    c: &Constraints,
    p: &LongestParams,
    j: usize,
    s0: f64,
) -> (f64, bool) {
    let remaining = facade.sections[j].length - s0;
    let l = c.blade_length;
    let steps = (l / p.precision).log2().ceil().max(1.0) as u32;
    let test = |len: f64| accepted(facade, c, j, s0, s0 + len, p.samples);
    if remaining <= l && test(remaining) {
        return (remaining, true);
    }
    let mut len = l.min(remaining);
    let mut best: Option<f64> = None;
    let mut ok = test(len);
    if ok {
        best = Some(len);
    }
    let mut shortest = len;
    for i in 1..=steps {
        let step = l / f64::from(1u32 << i.min(30));
        len = if ok { len + step } else { len - step };
        len = len.clamp(0.0, remaining.min(l));
        if len <= 0.0 {
            ok = false;
            continue;
        }
        shortest = shortest.min(len);
        ok = test(len);
        if ok && best.is_none_or(|b| len > b) {
            best = Some(len);
        }
    }
    match best {
        // a sliver would be left (e.g. a facade exactly as wide as whole blocks, where the
        // search's precision stops each part a hair short): split the rest evenly with the
        // next part instead, when the shorter part still passes
        Some(b) if remaining - b > 0.0 && remaining - b < SLIVER_SHARE * l => {
            let half = 0.5 * remaining;
            if half < b && test(half) {
                (half, true)
            } else {
                (b, true)
            }
        }
        Some(b) => (b, true),
        None => (shortest.max(p.precision).min(remaining), false),
    }
}

/// The longest acceptable part of section `j` from `s0` no longer than `len`: `len`
/// itself when it passes, else a halving search below it to the search's precision (the
/// shortest tried when none passes).
fn longest_within(
    facade: &Facade,
    c: &Constraints,
    p: &LongestParams,
    j: usize,
    s0: f64,
    len: f64,
) -> f64 {
    let test = |l: f64| accepted(facade, c, j, s0, s0 + l, p.samples);
    if test(len) {
        return len;
    }
    let steps = (len / p.precision).log2().ceil().clamp(1.0, 60.0) as u32;
    let (mut lo, mut hi) = (0.0, len);
    let mut best = None;
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        if test(mid) {
            best = Some(mid);
            lo = mid;
        } else {
            hi = mid;
        }
    }
    best.unwrap_or_else(|| hi.max(p.precision.min(len)))
}

/// The longest part of section `j` from `cur[j]` whose far end stays within a block's width
/// (across the facade) of the smallest start in its row of blocks (`rows`): a piece is cut
/// from one block. Infinite when the rest of the section fits. Sections already done
/// (`active` false) do not count: on an oblique cut a row's first sections can end long
/// before its others start.
fn row_cap(
    facade: &Facade,
    c: &Constraints,
    rows: &[usize],
    j: usize,
    cur: &[f64],
    active: &[bool],
) -> f64 {
    let across_u = |j: usize, s: f64| facade.sections[j].point(s).x;
    let umin = (0..cur.len())
        .filter(|&i| rows[i] == rows[j] && active[i])
        .map(|i| across_u(i, cur[i]))
        .fold(f64::INFINITY, f64::min);
    let limit = umin + c.block[1] * (1.0 - 1e-12);
    let sec = &facade.sections[j];
    let (mut lo, mut hi) = (cur[j], sec.length);
    if across_u(j, hi) <= limit {
        return f64::INFINITY;
    }
    // u grows along a section that runs across the facade: bisection to 1e-9 of it
    for _ in 0..200 {
        if hi - lo <= 1e-9 * sec.length {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if across_u(j, mid) <= limit {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo - cur[j]
}

/// Part lengths evened out: each at most `max_step` longer than its neighbours' bounds,
/// swept forward then backward.
fn even_out(bound: Vec<f64>, max_step: f64) -> Vec<f64> {
    let n = bound.len();
    let mut limit = bound;
    for j in 1..n {
        limit[j] = limit[j].min(limit[j - 1] + max_step);
    }
    for j in (0..n.saturating_sub(1)).rev() {
        limit[j] = limit[j].min(limit[j + 1] + max_step);
    }
    limit
}

/// Runs the longest-elastica algorithm. `progress` is called once per section per band.
///
/// # Errors
/// [`SegError::Invalid`] for bad constraints or parameters; [`SegError::TooManyPieces`]
/// when more than `max_bands` bands would be needed.
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
/// use facade_seg::longest::{longest_elastica, LongestParams};
/// let seg = longest_elastica(&facade, &c, &LongestParams { precision: 5.0, ..LongestParams::default() }, &|| {})?;
/// assert_eq!(seg.algorithm, "LongestElastica");
/// assert!(tiles(&seg));
/// // pieces as long as an elastica fits within the tolerance
/// assert!(seg.pieces.iter().all(|p| p.verdicts.approximation != Some(false)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn longest_elastica(
    facade: &Facade,
    c: &Constraints,
    p: &LongestParams,
    progress: &(dyn Fn() + Sync),
) -> Result<Segmentation, SegError> {
    c.validate()?;
    if !(p.precision.is_finite() && p.precision > 0.0) {
        return Err(SegError::Invalid {
            what: "precision".into(),
            message: format!("must be a positive number, got {:?}", p.precision),
        });
    }
    let n = facade.sections.len();
    let max_step = p
        .max_step
        .unwrap_or_else(|| facade.spacing().max(p.precision));
    // a part shorter than this is rounding: the section is done
    let done = |j: usize, s: f64| facade.sections[j].length - s <= 1e-9 * c.blade_length;
    let rows = rows_of(facade, c);
    let mut cur = vec![0.0f64; n];
    let mut bands: Vec<Vec<Option<(f64, f64)>>> = Vec::new();
    let mut seams = Vec::new();
    let mut unmet: Vec<usize> = Vec::new();
    while (0..n).any(|j| !done(j, cur[j])) {
        if bands.len() >= p.max_bands {
            return Err(SegError::TooManyPieces {
                cap: p.max_bands,
                why: format!(
                    "no acceptable part on section(s) {unmet:?} (e.g. a design curvature above the blade's): loosen tolerance, or raise blade.max_curvature, blade.max_inflections or block.size"
                ),
            });
        }
        let found: Vec<Option<(f64, bool)>> = (0..n)
            .into_par_iter()
            .map(|j| {
                let r = (!done(j, cur[j])).then(|| longest_from(facade, c, p, j, cur[j]));
                progress();
                r
            })
            .collect();
        // a piece is cut from one block: within a row of blocks, no part may end farther
        // across the facade than a block's width from the row's first start
        let active: Vec<bool> = found.iter().map(Option::is_some).collect();
        let found: Vec<Option<(f64, bool)>> = found
            .into_iter()
            .enumerate()
            .map(|(j, f)| {
                f.map(|(len, ok)| (len.min(row_cap(facade, c, &rows, j, &cur, &active)), ok))
            })
            .collect();
        // even the parts out: a part limited by its fit bounds its neighbours' lengths;
        // parts reaching the far edge bound nothing
        let bound: Vec<f64> = (0..n)
            .map(|j| match found[j] {
                Some((len, _)) if !done(j, cur[j] + len) => len,
                _ => f64::INFINITY,
            })
            .collect();
        let limit = even_out(bound, max_step);
        unmet = (0..n)
            .filter(|&j| found[j].is_some_and(|(_, ok)| !ok))
            .map(|j| facade.sections[j].index)
            .collect();
        // a part cut short (row cap, evening out) is a new part: its elastica can bend
        // differently (an extra inflection), so it is checked again, and shortened further
        // where it fails
        let lengths: Vec<Option<f64>> = (0..n)
            .into_par_iter()
            .map(|j| {
                found[j].map(|(len, ok)| {
                    let cut = len.min(limit[j]);
                    if ok && cut < len {
                        longest_within(facade, c, p, j, cur[j], cut)
                    } else {
                        cut
                    }
                })
            })
            .collect();
        let mut band = Vec::with_capacity(n);
        let mut seam = Vec::new();
        for j in 0..n {
            match lengths[j] {
                Some(len) => {
                    band.push(Some((cur[j], cur[j] + len)));
                    cur[j] += len;
                    if !done(j, cur[j]) {
                        let w = facade.world(j, cur[j]);
                        seam.push([w.x, w.y, w.z]);
                    }
                }
                None => band.push(None),
            }
        }
        if !seam.is_empty() {
            seams.push(Seam { points: seam });
        }
        bands.push(band);
    }
    let pieces = pieces_from_bands(facade, c, &bands, true, p.samples);
    let rows = pieces.iter().map(|q| q.row + 1).max().unwrap_or(0);
    Ok(Segmentation {
        algorithm: "LongestElastica".into(),
        rows,
        bands: bands.len(),
        pieces,
        seams,
    })
}
