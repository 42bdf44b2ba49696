//! The search over cutting directions (thesis §2.4: "relaxing this condition and allowing
//! any cutting direction will improve the result"): `n` directions evenly over the half
//! turn in the block's `xy` plane, each cut on its own by [`pre_cut`], and the one that
//! leaves the least material kept.
//!
//! A direction and its reverse give the same cuts mirrored, so half a turn covers every
//! direction. The candidates are independent and run in parallel; the choice depends only
//! on their volumes (ties go to the lower angle), so it is the same for any thread count.

use rayon::prelude::*;

use crate::error::{PreCutError, Result};
use crate::frame::Block;
use crate::{pre_cut, Params, PreCut, Progress};
use geom::surface::Surface;

/// Most candidate directions of a search.
pub const MAX_CANDIDATES: usize = 36;

/// One direction tried by [`search_directions`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Candidate {
    /// Angle from +x towards +y, degrees, in [0, 180).
    pub degrees: f64,
    /// Unit direction in the `xy` plane.
    pub direction: [f64; 2],
    /// Material left for milling, as a fraction of the block (`Volumes::ruled`); `None`
    /// when the optimizer failed for this direction.
    pub left_for_milling: Option<f64>,
    /// `Volumes::more_than_hull_percent` of this direction's cuts.
    pub more_than_hull_percent: Option<f64>,
    /// Why the optimizer failed, when it did.
    pub error: Option<String>,
}

/// What [`search_directions`] found.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct DirectionSearch {
    /// Index of the kept candidate.
    pub best: usize,
    /// Every candidate, by angle.
    pub candidates: Vec<Candidate>,
}

/// The `n` candidate directions: `i · 180° / n` for `i = 0 … n − 1`.
pub fn candidates(n: usize) -> Vec<(f64, [f64; 2])> {
    (0..n)
        .map(|i| {
            let deg = 180.0 * i as f64 / n as f64;
            let r = deg.to_radians();
            (deg, [r.cos(), r.sin()])
        })
        .collect()
}

/// Cuts `surface` in `block` along each of `n` directions (see [`candidates`]) with
/// `params` (its `directions` are ignored) and returns the cuts of the direction that
/// leaves the least material, with every candidate's result. `progress` reports each
/// candidate's rounds with `direction` = the candidate's index.
///
/// # Errors
/// [`PreCutError::InvalidParameter`] for `n` outside 1–[`MAX_CANDIDATES`] or bad
/// parameters; the first candidate's error when every candidate fails.
///
/// # Example
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use ruled::{search::search_directions, Block, Params};
/// // a ridge along the diagonal: the best cut runs across it (sections along its crest)
/// let ridge = HeightField::try_new(Expr::parse("0.5 + 0.3*exp(-20*(x - y)^2)")?, (-1.0, 1.0), (-1.0, 1.0))?;
/// let block = Block { min: [-1.0, -1.0, 0.0], max: [1.0, 1.0, 1.0] };
/// let params = Params { sections: 10, samples: 10, legs: 3, max_rounds: 8, ..Params::default() };
/// let (cut, search) = search_directions(&Surface::HeightField(ridge), &block, &params, 4, &|_| {})?;
/// assert_eq!(search.candidates[search.best].degrees, 135.0);
/// assert_eq!(cut.directions.len(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn search_directions(
    surface: &Surface,
    block: &Block,
    params: &Params,
    n: usize,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<(PreCut, DirectionSearch)> {
    if !(1..=MAX_CANDIDATES).contains(&n) {
        return Err(PreCutError::InvalidParameter {
            name: "directions",
            reason: format!("Auto needs 1–{MAX_CANDIDATES} directions, got {n}"),
        });
    }
    let runs: Vec<(f64, [f64; 2], Result<PreCut>)> = candidates(n)
        .into_par_iter()
        .enumerate()
        .map(|(i, (deg, d))| {
            let p = Params {
                directions: vec![d],
                ..params.clone()
            };
            let tick = |pr: Progress| progress(Progress { direction: i, ..pr });
            (deg, d, pre_cut(surface, block, &p, &tick))
        })
        .collect();
    let mut best: Option<(usize, f64)> = None;
    let mut list = Vec::with_capacity(n);
    for (i, (deg, d, r)) in runs.iter().enumerate() {
        let (left, more, error) = match r {
            Ok(c) => (
                Some(c.volumes.ruled),
                Some(c.volumes.more_than_hull_percent),
                None,
            ),
            Err(e) => (None, None, Some(e.to_string())),
        };
        if let Some(v) = left {
            if best.is_none_or(|(_, b)| v < b) {
                best = Some((i, v));
            }
        }
        list.push(Candidate {
            degrees: *deg,
            direction: *d,
            left_for_milling: left,
            more_than_hull_percent: more,
            error,
        });
    }
    let Some((b, _)) = best else {
        // every candidate failed: the first one's error
        let first = runs.into_iter().find_map(|r| r.2.err());
        return Err(first.unwrap_or(PreCutError::Placement("no candidate direction".into())));
    };
    let cut = runs
        .into_iter()
        .nth(b)
        .and_then(|r| r.2.ok())
        .ok_or_else(|| PreCutError::Placement("the best candidate vanished".into()))?;
    Ok((
        cut,
        DirectionSearch {
            best: b,
            candidates: list,
        },
    ))
}
