//! The inflection-points algorithm (thesis §5.2, "Robotic Hot-Blade Cutting" §3; category
//! b: the segmentation guides the fits). Rows of fixed-size blocks along the cut, each row
//! a sequence of blocks that may overlap across it; where two blocks overlap, the seam on
//! each section runs through the section's largest |curvature| inside the overlap (so it
//! follows the surface's ridges and valleys, and never sits on an inflection), and each
//! block owns its sections between its two seams. While some block owns a section part
//! with more than `max_inflections` inflections, the first such block is either
//! (b) translated along its row as far as possible without overloading the neighbour that
//! takes over its part (tried first), or (a) given a translated copy, placed as far along
//! as the block itself stays within the limit. Blocks left owning nothing are removed.
//! With `symmetric`, all rows share one arrangement (the moves are judged on all sections).

use crate::across::Across;
use crate::constraints::Constraints;
use crate::piece::{pieces_from_bands, rows_of, Segmentation};
use crate::section::Facade;
use crate::SegError;

/// Parameters of [`inflection_points`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct InflectionParams {
    /// All rows share one block arrangement.
    pub symmetric: bool,
    /// Candidate positions tried per translation (per block width).
    pub positions: usize,
    /// Points each part is sampled at for its checks.
    pub samples: usize,
    /// Most moves before giving up.
    pub max_moves: usize,
}

impl Default for InflectionParams {
    fn default() -> Self {
        Self {
            symmetric: false,
            positions: 64,
            samples: 64,
            max_moves: 1000,
        }
    }
}

/// One row's blocks (left `u` of each, increasing) over the sections `secs`; ownership and
/// counts follow from the positions.
struct Row<'a> {
    secs: Vec<&'a Across>,
    width: f64,
    range: (f64, f64),
    k: usize,
}

impl Row<'_> {
    /// Per section, the seams bounding each block: `seams[j][i]..seams[j][i + 1]` is block
    /// i's part.
    fn seams(&self, a: &[f64]) -> Vec<Vec<f64>> {
        self.seams_upto(a, a.len())
    }

    /// [`Row::seams`] of the first `upto` blocks only (a seam depends only on the blocks
    /// before it, so a move's checks on the blocks up to it need no more).
    fn seams_upto(&self, a: &[f64], upto: usize) -> Vec<Vec<f64>> {
        let upto = upto.min(a.len());
        let mut out: Vec<Vec<f64>> = Vec::with_capacity(self.secs.len());
        for sec in &self.secs {
            let prev = out.last();
            let mut v = Vec::with_capacity(upto + 1);
            v.push(self.range.0.min(sec.u[0]));
            for i in 0..upto.min(a.len().saturating_sub(1)) {
                let start = v[i];
                let near = prev.and_then(|p| p.get(i + 1).copied());
                v.push(sec.seam(a[i + 1], a[i] + self.width, start, self.k, near));
            }
            if upto == a.len() {
                v.push(self.range.1.max(sec.u[sec.u.len() - 1]));
            }
            out.push(v);
        }
        out
    }

    /// Largest inflection count of block `i` over the sections.
    fn load(&self, seams: &[Vec<f64>], i: usize) -> usize {
        self.secs
            .iter()
            .zip(seams)
            .map(|(sec, s)| sec.count(s[i], s[i + 1]))
            .max()
            .unwrap_or(0)
    }

    /// The first block (of those `seams` bound) holding more than `k` inflections.
    fn first_violation(&self, seams: &[Vec<f64>], k: usize) -> Option<usize> {
        let blocks = seams.first().map_or(0, |s| s.len().saturating_sub(1));
        (0..blocks).find(|&i| self.load(seams, i) > k)
    }

    fn covered(&self, a: &[f64]) -> bool {
        let slack = 1e-9 * self.width;
        a[0] <= self.range.0 + slack
            && a[a.len() - 1] + self.width >= self.range.1 - slack
            && a.windows(2)
                .all(|w| w[1] >= w[0] && w[1] <= w[0] + self.width + slack)
    }
}

/// Arranges one row's blocks; returns their left edges.
fn arrange(
    row: &Row<'_>,
    k: usize,
    p: &InflectionParams,
    moves: &mut usize,
) -> Result<Vec<f64>, SegError> {
    let w = row.width;
    let cols = (((row.range.1 - row.range.0) / w).ceil() as usize).max(1);
    let mut a: Vec<f64> = (0..cols).map(|i| row.range.0 + i as f64 * w).collect();
    let steps = p.positions.max(4);
    // a shift step: a share of the block's width, or of the facade's when the block is
    // wider (so copies and shifts land on the facade)
    let unit = w.min(row.range.1 - row.range.0).max(w * 1e-12) / steps as f64;
    while let Some(b) = row.first_violation(&row.seams(&a), k) {
        *moves += 1;
        if *moves > p.max_moves {
            return Err(SegError::TooManyPieces {
                cap: p.max_moves,
                why: format!(
                    "the inflection-points algorithm did not settle: {} blocks in a row, and a section with {} inflections (at most {k} per block) still overloads one (a noisy mesh section? raise tolerance.smoothing, blade.max_inflections or block.size)",
                    a.len(),
                    row.secs.iter().map(|s| s.inflections.len()).max().unwrap_or(0)
                ),
            });
        }
        // (b) translate b, away from the neighbour that takes over: farthest shift first
        let mut moved = false;
        'shift: for dir in [1.0, -1.0] {
            for i in (1..=steps).rev() {
                let mut t = a.clone();
                t[b] += dir * unit * i as f64;
                if !row.covered(&t) {
                    continue;
                }
                // b, the blocks before it and its neighbours: the seams up to b + 1
                let seams = row.seams_upto(&t, b + 2);
                let nb = if dir > 0.0 {
                    b.checked_sub(1)
                } else {
                    Some(b + 1)
                };
                // b, every block before it and the neighbour that takes over b's part
                // within the limit afterwards: each move advances the first overloaded
                // block, so the loop ends
                let ok_nb = nb.is_none_or(|n| n >= t.len() || row.load(&seams, n) <= k);
                if ok_nb && row.first_violation(&seams, k).is_none_or(|v| v > b) {
                    a = t;
                    moved = true;
                    break 'shift;
                }
            }
        }
        if moved {
            continue;
        }
        // (a) a translated copy of b right after it, as far along as b stays within the limit
        let mut best: Option<Vec<f64>> = None;
        for i in (1..=steps).rev() {
            let mut t = a.clone();
            t.insert(b + 1, a[b] + unit * i as f64);
            if !row.covered(&t) {
                continue;
            }
            let seams = row.seams_upto(&t, b + 1);
            if row.load(&seams, b) <= k {
                best = Some(t);
                break;
            }
        }
        a = match best {
            Some(t) => t,
            None => {
                let mut t = a.clone();
                t.insert(b + 1, a[b] + unit);
                t
            }
        };
        // drop blocks that own nothing on any section
        loop {
            let seams = row.seams(&a);
            let empty = (0..a.len()).find(|&i| {
                a.len() > 1 && seams.iter().all(|s| s[i + 1] <= s[i]) && {
                    let mut t = a.clone();
                    t.remove(i);
                    row.covered(&t)
                        && row
                            .first_violation(&row.seams_upto(&t, b + 1), k)
                            .is_none_or(|v| v > b)
                }
            });
            match empty {
                Some(i) => {
                    a.remove(i);
                }
                None => break,
            }
        }
    }
    Ok(a)
}

/// Runs the inflection-points algorithm. `progress` is called once per row.
///
/// # Errors
/// [`SegError::Invalid`] for bad constraints; [`SegError::Section`] for a section that
/// does not run across the facade; [`SegError::TooManyPieces`] when the moves do not
/// settle within `max_moves`.
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
/// use facade_seg::inflection::{inflection_points, InflectionParams};
/// let seg = inflection_points(&facade, &c, &InflectionParams::default(), &|| {})?;
/// assert!(tiles(&seg));
/// // cut at the inflections: no part holds more than the blade's two
/// assert!(seg.pieces.iter().all(|p| p.verdicts.shape));
/// assert!(seg.pieces.len() > 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn inflection_points(
    facade: &Facade,
    c: &Constraints,
    p: &InflectionParams,
    progress: &(dyn Fn() + Sync),
) -> Result<Segmentation, SegError> {
    c.validate()?;
    let across = Across::all(facade, &|| {})?;
    let range = across
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |r, s| {
            (r.0.min(s.u[0]), r.1.max(s.u[s.u.len() - 1]))
        });
    let rows = rows_of(facade, c);
    let n_rows = rows.iter().copied().max().map_or(0, |r| r + 1);
    let k = c.max_inflections as usize;
    let mut moves = 0;
    let make_row = |r: Option<usize>| Row {
        secs: across
            .iter()
            .enumerate()
            .filter(|(j, _)| r.is_none_or(|r| rows[*j] == r))
            .map(|(_, s)| s)
            .collect(),
        width: c.block[1],
        range,
        k,
    };
    let shared = if p.symmetric {
        Some(arrange(&make_row(None), k, p, &mut moves)?)
    } else {
        None
    };
    let mut bands: Vec<Vec<Option<(f64, f64)>>> = Vec::new();
    let mut band_of: Vec<usize> = Vec::new();
    for r in 0..n_rows {
        let row = make_row(Some(r));
        let a = match &shared {
            Some(a) => a.clone(),
            None => arrange(&row, k, p, &mut moves)?,
        };
        let seams = row.seams(&a);
        let idx: Vec<usize> = (0..facade.sections.len())
            .filter(|&j| rows[j] == r)
            .collect();
        for i in 0..a.len() {
            let mut band = vec![None; facade.sections.len()];
            for (m, &j) in idx.iter().enumerate() {
                let sec = &across[j];
                let prep = &facade.sections[j];
                let (s0, s1) = (sec.s_at(prep, seams[m][i]), sec.s_at(prep, seams[m][i + 1]));
                if s1 > s0 {
                    band[j] = Some((s0, s1));
                }
            }
            bands.push(band);
            band_of.push(i);
        }
        progress();
    }
    let mut pieces = pieces_from_bands(facade, c, &bands, false, p.samples);
    // pieces_from_bands numbers bands globally; here a band is a block of its row
    let mut kept = Vec::new();
    for mut piece in pieces.drain(..) {
        piece.band = band_of[piece.band];
        piece.id = kept.len() + 1;
        kept.push(piece);
    }
    Ok(Segmentation {
        algorithm: if p.symmetric {
            "Inflection(symmetric)".into()
        } else {
            "Inflection".into()
        },
        rows: n_rows,
        bands: kept.iter().map(|q| q.band + 1).max().unwrap_or(0),
        pieces: kept,
        seams: Vec::new(),
    })
}
