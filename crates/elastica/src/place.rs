//! Where along the blade a piece sits (issue 37, issue 52): the blade extended to its
//! length at a place along it chosen so that the extension keeps out of what the block
//! keeps, the held ends clear the block, and the blade holds its shape — a stable
//! equilibrium on every plane, carried from plane to plane without snapping.
//!
//! Entry points: [`place`](crate::place::place) (one plane), [`place_all`](crate::place::place_all) and [`place_all_by`](crate::place::place_all_by) (the planes of
//! one block, one place for all of them, and where no one place holds, a place per plane
//! chosen plane after plane).

use crate::blade::{extend_to_blade, Blade, BladeError, BladeParams};
use crate::clearance::{clearance, Clearance, Section, HOLDER_MARGIN};
use crate::memo::{key, Key, Memo};
use crate::segment::Segment;

/// Where along the blade the piece may sit, after the blade's own share of the extension
/// before the piece: a quarter of the way, three quarters, and at either end (all the
/// extension on one side).
pub const LEAD_IN_SHARES: [f64; 4] = [0.25, 0.75, 0.0, 1.0];

/// Places tried after [`LEAD_IN_SHARES`] while the blade is still outside its limits or
/// not a stable equilibrium at every one — unless the piece itself is outside the limits,
/// which no place mends: every sixteenth of the extension. Where the
/// piece sits along the blade decides where the extension's inflections fall, and with
/// them the held blade's stability.
pub const FINE_SHARES: usize = 16;

/// Every place [`place`] and [`place_all_by`] may try, in order: the blade's own, the
/// coarse ones, then the fine ones not tried yet.
fn shares(own: f64) -> impl Iterator<Item = (f64, bool)> {
    let coarse = LEAD_IN_SHARES.into_iter().map(|s| (s, false));
    let fine = (0..=FINE_SHARES)
        .map(|k| k as f64 / FINE_SHARES as f64)
        .filter(move |s| *s != own && !LEAD_IN_SHARES.contains(s))
        .map(|s| (s, true));
    coarse.chain(fine)
}

/// How many of the moves from one blade to the next (consecutive cutting planes, the
/// robots moving both ends straight) snap the blade to another shape
/// ([`crate::stability::follow::transition`]; a move that cannot be assessed counts).
pub fn snapping_moves(blades: &[Blade]) -> usize {
    snapping_moves_up_to(blades, usize::MAX)
}

/// [`snapping_moves`], counted no further than `limit + 1` (enough to tell that there
/// are more than `limit`).
fn snapping_moves_up_to(blades: &[Blade], limit: usize) -> usize {
    let mut n = 0;
    for w in blades.windows(2) {
        if n > limit {
            break;
        }
        n += usize::from(snaps(&w[0].segment, &w[1].segment));
    }
    n
}

/// How many judged moves are remembered.
const REMEMBERED: usize = 1 << 16;

/// The moves judged so far ([`crate::memo`]).
static JUDGED: Memo<(Key, Key), bool> = Memo::new(REMEMBERED);

/// Whether the move from blade `a` to blade `b` snaps ([`snapping_moves`]).
fn snaps(a: &Segment, b: &Segment) -> bool {
    // a move that cannot be assessed counts as a snap
    let judged = JUDGED.get_or((key(a), key(b)), || {
        Ok::<_, std::convert::Infallible>(
            crate::stability::follow::transition(a, b).map_or(true, |t| t.snap.is_some()),
        )
    });
    judged.unwrap_or(true)
}

/// Whether no place along the blade can bring it within its limits: the piece itself
/// bends beyond the curvature limit, or has more inflections than the blade may (the
/// blade holds the piece whole, so it bends and turns at least as the piece does). The
/// fine places are not tried then: they are for the extension's bends and inflections,
/// and the held blade's stability, which the place decides.
fn beyond_reach(section: &Segment, params: &BladeParams) -> bool {
    let bent = params
        .max_curvature
        .is_some_and(|k| section.max_abs_curvature().is_ok_and(|c| c > k));
    let waved = params
        .max_inflections
        .is_some_and(|n| section.inflections().is_ok_and(|v| v.len() > n));
    bent || waved
}

/// Within the blade's limits and a stable equilibrium.
fn within_limits(b: &Blade) -> bool {
    b.curvature_ok && b.inflections_ok && b.stability_ok
}

/// `section` extended to the blade and placed along it so that the blade outside the
/// piece keeps out of what `block` keeps and its held ends out of the block: the blade's
/// own `lead_in_share` when that is clean (and within the blade's limits), else the first
/// such of [`LEAD_IN_SHARES`], else the least bad — within the blade's limits first, then
/// the smallest gouge depth plus shortfall of a held end below [`HOLDER_MARGIN`] — whose
/// [`Clearance`] then says so. `tolerance` as in [`clearance`].
///
/// ```
/// use elastica::blade::BladeParams;
/// use elastica::clearance::{place, Section};
/// use elastica::segment::Segment;
/// // a quarter circle leaving the left face of a block [0, 1] × [0, 2] straight up and
/// // turning right to the top's far corner: half the extension before it would follow
/// // the circle down under the piece, into what the block keeps; all after it runs out
/// let quarter = std::f64::consts::FRAC_PI_2;
/// let piece = Segment::Arc { x0: 0.0, y0: 1.0, phi: quarter, curvature: -1.0, length: quarter };
/// let r = [[0.0, 0.0], [1.0, 2.0]];
/// let block = Section { rect: r, block: r, keeps_below: true };
/// let (blade, c) = place(&piece, &BladeParams::new(quarter + 1.0), &block, 1e-9).unwrap();
/// // all the extension after the piece: no gouge, but the held end sits on the face
/// assert_eq!(c.gouge_depth, 0.0);
/// assert!(!c.holders_clear);
/// assert_eq!(blade.lead_in, 0.0);
/// ```
///
/// # Errors
/// The blade cannot be extended or evaluated.
pub fn place(
    section: &Segment,
    params: &BladeParams,
    block: &Section,
    tolerance: f64,
) -> Result<(Blade, Clearance), BladeError> {
    let margin = HOLDER_MARGIN * params.length;
    // within the blade's limits first, then the least bad (gouge + holder shortfall)
    // (outside the limits, least margin, badness): a blade outside its limits that holds
    // is better than one that does not
    let key = |b: &Blade, c: &Clearance| {
        let m = if b.stability_ok {
            f64::NEG_INFINITY
        } else {
            -b.stability.margin
        };
        (!within_limits(b), m, c.badness(margin))
    };
    let first = extend_to_blade(section, params)?;
    let mut best = (clearance(&first, block, tolerance)?, first);
    let hopeless = std::cell::OnceCell::new();
    for (share, fine) in shares(params.lead_in_share) {
        if within_limits(&best.1) && (best.0.is_clean() || fine) {
            break;
        }
        if fine && *hopeless.get_or_init(|| beyond_reach(section, params)) {
            break;
        }
        let blade = extend_to_blade(
            section,
            &BladeParams {
                lead_in_share: share,
                ..params.clone()
            },
        )?;
        let c = clearance(&blade, block, tolerance)?;
        let (k, kb) = (key(&blade, &c), key(&best.1, &best.0));
        // (within the limits, then the least bad): tuples compare in that order
        if k.0
            .cmp(&kb.0)
            .then(k.1.total_cmp(&kb.1))
            .then(k.2.total_cmp(&kb.2))
            .is_lt()
        {
            best = (c, blade);
        }
    }
    Ok((best.1, best.0))
}

/// [`place`] for the sections of one block on consecutive cutting planes, with one place
/// along the blade for all of them — so that the robots do not slide the blade through
/// its holders between two neighbouring planes: the blade's own share when it is clean on
/// every plane, else the first of [`LEAD_IN_SHARES`] that is, else the one that leaves
/// the fewest planes outside the blade's limits, then the fewest not clean, then the
/// smallest worst badness. `sections[i]` is checked against `blocks[i]`.
///
/// # Errors
/// A blade cannot be extended or evaluated; `sections` and `blocks` differ in length.
///
/// ```
/// use elastica::clearance::{place_all, Section};
/// use elastica::{BladeParams, Segment};
/// // one block's flat top on two neighbouring planes (1 and 0.9 high), cut by a blade 4 long
/// let tops = [
///     Segment::Line { x0: 0.0, y0: 1.0, phi: 0.0, length: 2.0 },
///     Segment::Line { x0: 0.0, y0: 0.9, phi: 0.0, length: 2.0 },
/// ];
/// let blocks: Vec<Section> = [1.0, 0.9]
///     .iter()
///     .map(|&h| Section { rect: [[0.0, 0.0], [2.0, h]], block: [[0.0, 0.0], [2.0, h]], keeps_below: true })
///     .collect();
/// let placed = place_all(&tops, &BladeParams::new(4.0), &blocks, 1e-9)?;
/// assert_eq!(placed.len(), 2);
/// assert!(placed.iter().all(|(_, c)| c.is_clean()));
/// // one place along the blade on every plane: the extension is centred on both
/// assert!(placed.iter().all(|(b, _)| (b.lead_in - 1.0).abs() < 1e-12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn place_all(
    sections: &[Segment],
    params: &BladeParams,
    blocks: &[Section],
    tolerance: f64,
) -> Result<Vec<(Blade, Clearance)>, BladeError> {
    place_all_by(sections, params, tolerance, &|_| blocks.to_vec()).map(|(placed, _)| placed)
}

/// [`place_all`] where the block may depend on the blades: `blocks(blades)` gives, for
/// the blades of one place along the blade, the block's section on each plane (a block
/// that is moved to clear the held ends). Returns the placed blades with their
/// clearances, and the share of the extension before the piece that was chosen.
///
/// # Errors
/// The blade cannot be extended or evaluated at `params`' own share (other places that
/// fail are passed over); `blocks` returns other than one section per plane.
pub fn place_all_by(
    sections: &[Segment],
    params: &BladeParams,
    tolerance: f64,
    blocks: &dyn Fn(&[Blade]) -> Vec<Section>,
) -> Result<(Vec<(Blade, Clearance)>, f64), BladeError> {
    let margin = HOLDER_MARGIN * params.length;
    let blades_at = |share: f64| -> Result<Vec<Blade>, BladeError> {
        let p = BladeParams {
            lead_in_share: share,
            ..params.clone()
        };
        sections.iter().map(|s| extend_to_blade(s, &p)).collect()
    };
    let cleared = |blades: Vec<Blade>| -> Result<Vec<(Blade, Clearance)>, BladeError> {
        let secs = blocks(&blades);
        if secs.len() != blades.len() {
            return Err(BladeError::Invalid(format!(
                "{} sections for {} blocks",
                blades.len(),
                secs.len()
            )));
        }
        blades
            .into_iter()
            .zip(&secs)
            .map(|(blade, b)| {
                let c = clearance(&blade, b, tolerance)?;
                Ok((blade, c))
            })
            .collect()
    };
    // the blades' part of the score: (planes outside the limits or not stable, and — when
    // every blade holds — the moves from one plane's blade to the next that snap; the
    // least margin among those)
    let held = |all: &[Blade], limit: usize| {
        let broken = all.iter().filter(|b| !within_limits(b)).count();
        let snaps = if broken == 0 {
            snapping_moves_up_to(all, limit)
        } else {
            0
        };
        let shaky = all
            .iter()
            .filter(|b| !b.stability_ok)
            .map(|b| -b.stability.margin)
            .fold(f64::NEG_INFINITY, f64::max);
        (broken + snaps, shaky)
    };
    // then (planes not clean, the worst badness)
    let score = |all: &[(Blade, Clearance)], (broken, shaky): (usize, f64)| {
        let unclean = all.iter().filter(|(_, c)| !c.is_clean()).count();
        let worst = all
            .iter()
            .map(|(_, c)| c.badness(margin))
            .fold(0.0, f64::max);
        (broken, shaky, unclean, worst)
    };
    let better = |a: &(usize, f64, usize, f64), b: &(usize, f64, usize, f64)| {
        a.0.cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.cmp(&b.2))
            .then(a.3.total_cmp(&b.3))
            .is_lt()
    };
    let own = blades_at(params.lead_in_share)?;
    let own_held = held(&own, usize::MAX);
    let mut best = (cleared(own)?, params.lead_in_share);
    let mut best_score = score(&best.0, own_held);
    let hopeless = std::cell::OnceCell::new();
    for (share, fine) in shares(params.lead_in_share) {
        // the fine places are tried only for blades outside the limits or unstable, and
        // only where a place could bring them within
        if best_score.0 == 0 && (best_score.2 == 0 || fine) {
            break;
        }
        if fine && *hopeless.get_or_init(|| sections.iter().any(|s| beyond_reach(s, params))) {
            break;
        }
        // a place the blade cannot be extended to (or evaluated at) is not a candidate
        let Ok(blades) = blades_at(share) else {
            continue;
        };
        // the block is slid and the blades cleared only for places whose blades hold at
        // least as well as the best's
        // (counting snaps no further than it takes to lose to the best)
        let (broken, shaky) = held(&blades, best_score.0);
        if (broken, shaky) > (best_score.0, best_score.1) {
            continue;
        }
        let Ok(all) = cleared(blades) else {
            continue;
        };
        let s = score(&all, (broken, shaky));
        if better(&s, &best_score) {
            (best, best_score) = ((all, share), s);
        }
    }
    Ok(best)
}
