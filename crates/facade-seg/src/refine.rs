//! Refinement after any segmentation algorithm: pieces that break a constraint smaller
//! pieces could meet are split until they meet it or cannot be split further.
//!
//! Entry point: [`refine`](crate::refine::refine) with [`RefineParams`](crate::refine::RefineParams).
//!
//! Every piece is measured with an elastica fitted to each of its parts (§5.1.2, whatever
//! the algorithm measured). While a piece fails its shape (too many inflections), its
//! approximation (no elastica within the tolerance) or its dimensions (a part longer than
//! the blade, wider than the block), it is split **along its sections** at one place
//! across the cut, `u*`: where the worst part's elastica is farthest from the design, at
//! the middle one of the worst part's inflections, or in the middle of its longest part.
//! Each of its parts is cut where it crosses `u*` (a part that does not reach `u*` goes
//! whole to its side). The algorithm's own cuts stay; refinement only adds cuts.
//!
//! A split is refused when it would leave a part shorter than `min_length` (the job's
//! `min_piece`), and a piece whose design breaks its blade's strain limit is never split (a
//! smaller piece bends the same). What still fails gets an [`Unresolved`](crate::refine::Unresolved): the section,
//! its part's length, what it measures and the limit, and why no smaller piece holds (a
//! report composes "section at x = 1.2 m: no elastica within 2 mm over any part longer
//! than 60 mm" from it in the job's units).
//!
//! Bounded: each split adds one piece, and a piece's parts shrink by at least
//! `min_length` per split, so there are at most (total length of the parts)/`min_length`
//! pieces; `max_pieces` caps them too.

use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams};

use crate::constraints::Constraints;
use crate::piece::{piece_of, Seam};
use crate::report::ConstraintCounts;
use crate::section::{Facade, PreparedSection};
use crate::{Piece, SegError, Segmentation};

/// Options of [`refine`].
#[derive(Debug, Clone, PartialEq)]
pub struct RefineParams {
    /// No split may leave a part shorter than this (arc length, the facade's units).
    pub min_length: f64,
    /// Points per part for checks and fits.
    pub samples: usize,
    /// Most pieces after refinement.
    pub max_pieces: usize,
}

/// A piece refinement could not make meet every constraint, and why. The numbers are in
/// the facade's units; `reason` holds none, so a report reads the same in any unit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Unresolved {
    /// The piece's id (1-based, after refinement).
    pub piece: usize,
    /// The constraint it breaks: `shape`, `approximation`, `dimension`, `blade_strain` or
    /// `stability`.
    pub constraint: String,
    /// Plane index of the section it names (its worst part's).
    pub plane: usize,
    /// Plane offset of that section along the cutting direction.
    pub offset: f64,
    /// The arc length of the piece's part on that section.
    pub length: f64,
    /// What that part measures against the constraint: its elastica's largest distance
    /// (`approximation`), its inflections (`shape`), the largest |curvature| of the design
    /// or of its elastica (`blade_strain`), its length (`dimension`, `stability`).
    pub measured: f64,
    /// The constraint's limit: `tolerance.max`, `max_inflections`, `max_curvature`, the
    /// blade's length (`dimension`, `stability`).
    pub limit: f64,
    /// Why no smaller piece meets it.
    pub reason: String,
}

/// Pieces and the pieces failing each constraint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PieceCounts {
    /// Pieces.
    pub pieces: usize,
    /// Pieces breaking any constraint.
    pub failing_pieces: usize,
    /// Pieces breaking each constraint (every part fitted).
    pub failing: ConstraintCounts,
}

/// What [`refine`] did.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct RefineReport {
    /// The algorithm's pieces, measured as refinement measures them.
    pub before: PieceCounts,
    /// After refinement.
    pub after: PieceCounts,
    /// Splits made.
    pub splits: usize,
    /// The smallest part a split could leave.
    pub min_length: f64,
    /// The pieces still failing, and why.
    pub unresolved: Vec<Unresolved>,
}

/// One piece during refinement: its row, its band (the algorithm's) and its parts.
#[derive(Debug, Clone)]
struct Cell {
    row: usize,
    band: usize,
    /// `(facade section index, s0, s1)`, in plane order.
    parts: Vec<(usize, f64, f64)>,
    /// Its place across the cut among the pieces its algorithm piece was split into: the
    /// sides taken at each split (0 left, 1 right), so the order is the tree's.
    side: Vec<u8>,
}

/// Why a piece is split, and where.
enum Split {
    /// Across the cut at `u`, through the worst part (a facade section index).
    At(f64, usize),
    /// It cannot be: the constraint, the facade section index and the reason.
    Never(&'static str, usize, String),
}

/// Refines `seg` (see the module docs). The result's pieces are fitted (approximation
/// measured for every algorithm); its bands are the algorithm's, each piece keeping its
/// band, and every split adds a seam.
///
/// # Errors
/// [`SegError::Invalid`] for a `min_length` that is not a positive number.
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
/// use facade_seg::refine::{refine, RefineParams};
/// let seg = longest_elastica(&facade, &c, &LongestParams { precision: 5.0, ..LongestParams::default() }, &|| {})?;
/// let p = RefineParams { min_length: 50.0, samples: 64, max_pieces: 1000 };
/// let (refined, report) = refine(&facade, &c, &seg, &p, &|| {})?;
/// assert!(tiles(&refined));
/// // refinement only splits: never fewer pieces, and every split adds one
/// assert_eq!(report.before.pieces, seg.pieces.len());
/// assert_eq!(report.after.pieces, refined.pieces.len());
/// assert!(report.after.pieces >= report.before.pieces);
/// assert!(report.after.failing_pieces <= report.before.failing_pieces);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn refine(
    facade: &Facade,
    c: &Constraints,
    seg: &Segmentation,
    p: &RefineParams,
    progress: &dyn Fn(),
) -> Result<(Segmentation, RefineReport), SegError> {
    refine_judged(facade, c, seg, p, &|q: &Piece| q.verdicts, progress)
}

/// [`refine`] where `judge` gives a measured piece's verdicts: the blade fits of a
/// rationalized run ([`crate::report::judged`] of the piece posed), so refinement splits
/// the pieces the run's report would fail. A failure only the judge sees is split in the
/// middle of the part it measures worst, or of the longest.
///
/// # Errors
/// As [`refine`].
pub fn refine_judged(
    facade: &Facade,
    c: &Constraints,
    seg: &Segmentation,
    p: &RefineParams,
    judge: &(dyn Fn(&Piece) -> crate::constraints::Verdicts + Sync),
    progress: &dyn Fn(),
) -> Result<(Segmentation, RefineReport), SegError> {
    if !(p.min_length > 0.0 && p.min_length.is_finite()) {
        return Err(SegError::Invalid {
            what: "min_piece".into(),
            message: format!("must be a positive length, got {}", p.min_length),
        });
    }
    let index_of = |plane: usize| facade.sections.iter().position(|s| s.index == plane);
    let mut cells: Vec<Cell> = seg
        .pieces
        .iter()
        .map(|piece| {
            let parts: Vec<(usize, f64, f64)> = piece
                .parts
                .iter()
                .filter_map(|q| index_of(q.plane).map(|j| (j, q.s[0], q.s[1])))
                .collect();
            Cell {
                row: piece.row,
                band: piece.band,
                parts,
                side: Vec::new(),
            }
        })
        .collect();
    let measure = |cell: &Cell| {
        piece_of(
            facade,
            c,
            (0, cell.row, cell.band),
            &cell.parts,
            true,
            p.samples,
        )
        .map(|mut q| {
            q.verdicts = judge(&q);
            q
        })
    };
    // every piece is judged on its own (its blades posed, when the run rationalizes):
    // in parallel, in piece order
    let mut measured: Vec<Option<Piece>> = {
        use rayon::prelude::*;
        cells.par_iter().map(measure).collect()
    };
    let before = counts(&measured);
    let mut seams: Vec<Seam> = Vec::new();
    let mut settled = vec![false; cells.len()];
    let mut splits = 0;
    // each pass splits one piece or settles one; every piece settles or splits into
    // pieces at least min_length shorter, and max_pieces caps them
    let mut reasons: Vec<(usize, &'static str, usize, String)> = Vec::new();
    while let Some(i) = (0..cells.len())
        .find(|&i| !settled[i] && measured[i].as_ref().is_some_and(|q| !q.verdicts.all()))
    {
        progress();
        let Some(piece) = measured[i].clone() else {
            settled[i] = true;
            continue;
        };
        let split = if cells.len() >= p.max_pieces {
            Split::Never(
                failing(&piece, c),
                cells[i].parts[0].0,
                format!("the refinement reached its cap of {} pieces", p.max_pieces),
            )
        } else {
            where_to_split(facade, c, &cells[i], &piece, p)
        };
        match split {
            Split::At(u, worst) => match cut_cell(facade, &cells[i], u, worst, p.min_length) {
                // a piece whose blade does not hold is split only where one half then
                // holds: the blade's stability hangs on where the inflections of the
                // extension fall, not on the piece's length alone, and halves that fail
                // as the whole did only multiply the pieces
                Some((a, b, seam)) => {
                    let (ma, mb) = rayon::join(|| measure(&a), || measure(&b));
                    let holds =
                        |m: &Option<Piece>| m.as_ref().is_some_and(|q| q.verdicts.stability);
                    if failing(&piece, c) == "stability" && !holds(&ma) && !holds(&mb) {
                        let (what, j) = worst_part(facade, c, &piece);
                        reasons.push((
                            i,
                            what,
                            j,
                            "the blade extended from its parts does not hold its shape (an unstable or marginal equilibrium) at any place along it, nor from either half of the piece".into(),
                        ));
                        settled[i] = true;
                        continue;
                    }
                    cells.splice(i..=i, [a, b]);
                    measured.splice(i..=i, [ma, mb]);
                    settled.splice(i..=i, [false, false]);
                    seams.push(seam);
                    splits += 1;
                }
                None => {
                    let (what, j) = worst_part(facade, c, &piece);
                    reasons.push((i, what, j, too_small(what)));
                    settled[i] = true;
                }
            },
            Split::Never(what, j, reason) => {
                reasons.push((i, what, j, reason));
                settled[i] = true;
            }
        }
    }
    // bands renumbered so that they still run across the facade in every row: a piece split
    // in two becomes two bands, the left one first; a band of the algorithm that some row
    // split into k pieces becomes k bands (in the other rows the later ones are empty)
    let mut rank = vec![0usize; cells.len()];
    for i in 0..cells.len() {
        rank[i] = (0..cells.len())
            .filter(|&k| {
                cells[k].row == cells[i].row
                    && cells[k].band == cells[i].band
                    && cells[k].side < cells[i].side
            })
            .count();
    }
    let mut keys: Vec<(usize, usize)> =
        (0..cells.len()).map(|i| (cells[i].band, rank[i])).collect();
    keys.sort_unstable();
    keys.dedup();
    let band_of = |i: usize| keys.partition_point(|&k| k < (cells[i].band, rank[i]));
    // pieces by band, then row; ids from 1
    let mut order: Vec<usize> = (0..cells.len()).collect();
    order.sort_by_key(|&i| (band_of(i), cells[i].row));
    let mut pieces = Vec::with_capacity(cells.len());
    let mut unresolved = Vec::new();
    for &i in &order {
        let Some(mut piece) = measured[i].clone() else {
            continue;
        };
        piece.id = pieces.len() + 1;
        piece.band = band_of(i);
        for (_, what, j, reason) in reasons.iter().filter(|r| r.0 == i) {
            unresolved.push(unresolved_of(facade, c, &piece, what, *j, reason));
        }
        pieces.push(piece);
    }
    let after = counts(&pieces.iter().cloned().map(Some).collect::<Vec<_>>());
    let mut all_seams = seg.seams.clone();
    all_seams.extend(seams);
    Ok((
        Segmentation {
            algorithm: seg.algorithm.clone(),
            rows: seg.rows,
            bands: keys.len(),
            pieces,
            seams: all_seams,
        },
        RefineReport {
            before,
            after,
            splits,
            min_length: p.min_length,
            unresolved,
        },
    ))
}

fn counts(pieces: &[Option<Piece>]) -> PieceCounts {
    let all: Vec<&Piece> = pieces.iter().flatten().collect();
    let n = |f: &dyn Fn(&Piece) -> bool| all.iter().filter(|q| f(q)).count();
    PieceCounts {
        pieces: all.len(),
        failing_pieces: n(&|q| !q.verdicts.all()),
        failing: ConstraintCounts {
            dimension: n(&|q| !q.verdicts.dimension),
            approximation: n(&|q| q.verdicts.approximation == Some(false)),
            shape: n(&|q| !q.verdicts.shape),
            blade_strain: n(&|q| !q.verdicts.blade_strain),
            stability: n(&|q| !q.verdicts.stability),
        },
    }
}

/// The first constraint a piece breaks, in the order refinement treats them. A blade
/// strain the design itself breaks is `blade_strain` (never split); one only its fitted
/// elastica breaks (the fit bending where the design does not) is `fit_strain`, reported as
/// `blade_strain`, and split in the middle of the part.
fn failing(piece: &Piece, c: &Constraints) -> &'static str {
    let v = &piece.verdicts;
    let design_strain = piece
        .parts
        .iter()
        .any(|q| q.check.max_abs_curvature > c.max_curvature);
    if !v.blade_strain && design_strain {
        "blade_strain"
    } else if !v.shape {
        "shape"
    } else if v.approximation == Some(false) {
        "approximation"
    } else if !v.blade_strain
        && piece.parts.iter().any(|q| {
            q.check
                .fit
                .is_some_and(|f| f.max_abs_curvature > c.max_curvature)
        })
    {
        "fit_strain"
    } else if !v.stability {
        // a blade that does not hold its shape at any place along it (a judge's verdict):
        // a shorter part leaves more places, and its own fit
        "stability"
    } else if !v.blade_strain {
        // only the blade extended beyond its part to its length bends too much (a judge's
        // verdict): a shorter part extends it further
        "blade_extension"
    } else {
        "dimension"
    }
}

/// The constraint a piece breaks first and the facade index of its worst part for it.
fn worst_part(facade: &Facade, c: &Constraints, piece: &Piece) -> (&'static str, usize) {
    let what = failing(piece, c);
    let score = |q: &crate::PiecePart| -> f64 {
        let k = &q.check;
        match what {
            "blade_strain" => k.max_abs_curvature,
            "shape" => k.inflections.max(k.fit.map_or(0, |f| f.inflections)) as f64,
            "approximation" => k.fit.map_or(f64::INFINITY, |f| {
                (f.max / c.tolerance_max).max(f.rms / c.tolerance_rms)
            }),
            "fit_strain" => k.fit.map_or(0.0, |f| f.max_abs_curvature),
            "blade_extension" => k.length.recip(),
            "stability" => k.length,
            _ => k.length / c.blade_length,
        }
    };
    let best = piece
        .parts
        .iter()
        .max_by(|a, b| score(a).total_cmp(&score(b)))
        .map(|q| q.plane)
        .unwrap_or(0);
    let j = facade
        .sections
        .iter()
        .position(|s| s.index == best)
        .unwrap_or(0);
    (what, j)
}

/// Where to split a failing piece (see the module docs), or why it is never split.
fn where_to_split(
    facade: &Facade,
    c: &Constraints,
    cell: &Cell,
    piece: &Piece,
    p: &RefineParams,
) -> Split {
    let (what, j) = worst_part(facade, c, piece);
    let Some(&(_, s0, s1)) = cell.parts.iter().find(|q| q.0 == j) else {
        return Split::Never(what, j, "its worst part is not in the piece".into());
    };
    let sec = &facade.sections[j];
    let s = match what {
        "blade_strain" => {
            return Split::Never(
                what,
                j,
                "the design bends beyond the blade: a smaller piece bends the same".into(),
            );
        }
        "blade_extension" => {
            return Split::Never(
                what,
                j,
                "the blade, extended beyond its shortest part to its length, bends beyond the limit: a shorter part extends it further".into(),
            );
        }
        "shape" => {
            let inside: Vec<f64> = sec
                .inflections
                .iter()
                .copied()
                .filter(|&x| x > s0 && x < s1)
                .collect();
            if inside.is_empty() {
                0.5 * (s0 + s1)
            } else {
                inside[inside.len() / 2]
            }
        }
        "approximation" => worst_point(sec, s0, s1, p.samples).unwrap_or(0.5 * (s0 + s1)),
        _ => 0.5 * (s0 + s1),
    };
    // no closer to the part's ends than the minimum (when the part allows it)
    let s = if s1 - s0 >= 2.0 * p.min_length {
        // on the grid, and inside the bounds the grid step may have crossed
        let step = (s1 - s0) / SNAP;
        let s = snap(s.clamp(s0 + p.min_length, s1 - p.min_length), s0, s1);
        if s1 - s < p.min_length {
            s - step
        } else if s - s0 < p.min_length {
            s + step
        } else {
            s
        }
    } else {
        snap(s, s0, s1)
    };
    Split::At(sec.point(s).x, j)
}

/// The arc length in `[s0, s1]` of `sec` where its end-point elastica is farthest from it.
fn worst_point(sec: &PreparedSection, s0: f64, s1: f64, samples: usize) -> Option<f64> {
    let (pts, ss) = sec.samples(s0, s1, samples);
    let fit = fit_points_with_arclength(
        &pts,
        &ss,
        &FitParams {
            constraint: FitConstraint::EndPoints,
            ..FitParams::default()
        },
    )
    .ok()?;
    let e = fit.segment.evaluator().ok()?;
    let (mut best, mut at) = (-1.0, None);
    for ((q, s), &t) in pts.iter().zip(&ss).zip(&fit.t) {
        let r = e.eval(t).p;
        let d = (q[0] - r[0]).hypot(q[1] - r[1]);
        if d > best {
            (best, at) = (d, Some(s0 + s));
        }
    }
    at
}

/// Split positions are kept on a grid of [`SNAP`] steps per part: the same job in
/// millimetres and in metres (its inputs a rounding apart) then cuts its pieces at the same
/// relative places and judges them alike, where a position computed to the last bit could
/// tip a fit across its tolerance one way in one unit and the other way in the other.
const SNAP: f64 = 4096.0;

/// `s` moved to the nearest of [`SNAP`] even steps of `[s0, s1]`.
fn snap(s: f64, s0: f64, s1: f64) -> f64 {
    let len = s1 - s0;
    if !(len > 0.0) {
        return s;
    }
    s0 + ((s - s0) / len * SNAP).round() / SNAP * len
}

/// The arc length on `[s0, s1]` of `sec` where `u` (across) is reached, by bisection; `None`
/// when the part does not reach it.
fn s_at_u(sec: &PreparedSection, s0: f64, s1: f64, u: f64) -> Option<f64> {
    let (u0, u1) = (sec.point(s0).x, sec.point(s1).x);
    if !((u0 - u) * (u1 - u) < 0.0) {
        return None;
    }
    let (mut a, mut b) = (s0, s1);
    // 60 halvings: below f64 resolution of any part
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if (sec.point(m).x - u) * (u0 - u) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}

/// `cell` cut across the cut at `u`: the two pieces and the seam, or `None` when the
/// worst part `worst` (a facade section index) would leave a part shorter than
/// `min_length`, or a side would be empty. Another part that `u` would leave a sliver of
/// goes whole to the side holding most of it.
fn cut_cell(
    facade: &Facade,
    cell: &Cell,
    u: f64,
    worst: usize,
    min_length: f64,
) -> Option<(Cell, Cell, Seam)> {
    let (mut left, mut right, mut seam) = (Vec::new(), Vec::new(), Vec::new());
    for &(j, s0, s1) in &cell.parts {
        let sec = &facade.sections[j];
        match s_at_u(sec, s0, s1, u).map(|s| snap(s, s0, s1)) {
            Some(s) if s - s0 >= min_length && s1 - s >= min_length => {
                left.push((j, s0, s));
                right.push((j, s, s1));
                seam.push(arr(&facade.world(j, s)));
            }
            Some(_) if j == worst => return None,
            Some(s) if s - s0 >= s1 - s => left.push((j, s0, s1)),
            Some(_) => right.push((j, s0, s1)),
            None if sec.point(s1).x <= u => left.push((j, s0, s1)),
            None => right.push((j, s0, s1)),
        }
    }
    if left.is_empty() || right.is_empty() || seam.is_empty() {
        return None;
    }
    let side = |s: u8| {
        let mut v = cell.side.clone();
        v.push(s);
        v
    };
    Some((
        Cell {
            side: side(0),
            parts: left,
            ..cell.clone()
        },
        Cell {
            side: side(1),
            parts: right,
            ..cell.clone()
        },
        Seam { points: seam },
    ))
}

fn arr(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Why a piece failing `what` could not be split further (unit-free).
fn too_small(what: &str) -> String {
    let cause = match what {
        "approximation" => "no elastica within the tolerance over its part",
        "shape" => "its part has more inflections than the blade makes",
        "fit_strain" => "its part's elastica bends beyond the blade where the design does not",
        "stability" => "the blade extended from its parts does not hold its shape (an unstable or marginal equilibrium) at any place along it",
        _ => "its part is longer than the blade or the piece wider than its block",
    };
    format!("{cause}, and no split leaves parts of at least min_piece")
}

/// The report of a piece failing `what` on facade section `j`.
fn unresolved_of(
    facade: &Facade,
    c: &Constraints,
    piece: &Piece,
    what: &str,
    j: usize,
    reason: &str,
) -> Unresolved {
    let sec = &facade.sections[j];
    let part = piece.parts.iter().find(|q| q.plane == sec.index);
    let length = part.map_or(0.0, |q| q.check.length);
    let fit = part.and_then(|q| q.check.fit);
    let (measured, limit) = match what {
        "approximation" => (fit.map_or(0.0, |f| f.max), c.tolerance_max),
        "shape" => (
            part.map_or(0, |q| {
                q.check.inflections.max(fit.map_or(0, |f| f.inflections))
            }) as f64,
            c.max_inflections as f64,
        ),
        "blade_strain" => (
            part.map_or(0.0, |q| q.check.max_abs_curvature),
            c.max_curvature,
        ),
        "fit_strain" => (fit.map_or(0.0, |f| f.max_abs_curvature), c.max_curvature),
        "blade_extension" => (
            part.map_or(0.0, |q| q.check.max_abs_curvature),
            c.max_curvature,
        ),
        _ => (length, c.blade_length),
    };
    Unresolved {
        piece: piece.id,
        constraint: if what == "fit_strain" || what == "blade_extension" {
            "blade_strain".into()
        } else {
            what.into()
        },
        plane: sec.index,
        offset: sec.offset,
        length,
        measured,
        limit,
        reason: reason.into(),
    }
}
