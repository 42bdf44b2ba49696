//! Rationalizing a piece: every section part fitted by an elastica as the `hotblade`
//! pipeline fits a block's sections (warm-started sweeps along the cut), extended to the
//! blade and posed for the two robots, one pose per section the piece crosses.
//!
//! Entry points: [`pose_piece`](crate::rationalize::pose_piece),
//! [`pose_pieces`](crate::rationalize::pose_pieces).

use elastica::blade::Blade;
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams, FitResult};
use elastica::sweep::{blade_pose, frame_quaternion, BladePose};
use hotblade::{make_blade, sweep_fits, BladeLimits, Clipped, SHORTEST_PART};
use rayon::prelude::*;
use serde::Serialize;

use crate::{Facade, Piece, SegError};

/// Parameters of [`pose_piece`].
#[derive(Debug, Clone, PartialEq)]
pub struct RationalizeParams {
    /// What each fit keeps: `EndPoints` or `EndPointsAndLength` (`Free` is taken as
    /// `EndPoints`: neighbouring pieces must meet).
    pub constraint: FitConstraint,
    /// Points each section part is sampled at.
    pub samples: usize,
    /// The blade.
    pub blade: BladeLimits,
    /// Largest-distance tolerance: a length-keeping fit beyond it is restarted from the
    /// end-point fit.
    pub tolerance_max: f64,
}

/// One section part of a piece, fitted and posed.
#[derive(Debug, Clone, Serialize)]
pub struct PosedPart {
    /// Index of the part in the piece.
    pub part: usize,
    /// The design part (plane coordinates).
    pub design: Clipped,
    /// Its elastica.
    pub fit: FitResult,
    /// The blade: the fit extended to the blade length.
    pub blade: Blade,
    /// The 3D pose.
    pub pose: BladePose,
}

/// A rationalized piece.
#[derive(Debug, Clone, Serialize)]
pub struct PosedPiece {
    /// Piece id.
    pub id: usize,
    /// Orientation `[w, x, y, z]` of the block axes (along the cut, across it, up).
    pub rotation: [f64; 4],
    /// Posed parts in cutting order (slivers shorter than [`SHORTEST_PART`] of the blade
    /// are left out).
    pub parts: Vec<PosedPart>,
}

/// The design parts of a piece as `hotblade` clips them: sampled equally in arc length,
/// slivers shorter than [`SHORTEST_PART`] of the blade left out (`None`).
fn designs(facade: &Facade, piece: &Piece, params: &RationalizeParams) -> Vec<Option<Clipped>> {
    let shortest = SHORTEST_PART * params.blade.length;
    piece
        .parts
        .iter()
        .map(|part| {
            let sec = facade.sections.iter().find(|s| s.index == part.plane)?;
            let (points, s) = sec.samples(part.s[0], part.s[1], params.samples);
            let length = part.s[1] - part.s[0];
            let angle = |a: [f64; 2], b: [f64; 2]| (b[1] - a[1]).atan2(b[0] - a[0]);
            let n = points.len();
            (length >= shortest && n >= 2).then(|| Clipped {
                end_angles: [
                    angle(points[0], points[1]),
                    angle(points[n - 2], points[n - 1]),
                ],
                points,
                s,
                length,
            })
        })
        .collect()
}

/// Fits every part of a piece (warm-started sweeps along the cut, as `hotblade` does per
/// block), extends each fit to the blade and poses it.
///
/// # Errors
/// [`SegError::Rationalize`] naming the section a part could not be fitted or extended on.
pub fn pose_piece(
    facade: &Facade,
    piece: &Piece,
    params: &RationalizeParams,
) -> Result<PosedPiece, SegError> {
    let constraint = params.constraint.with_end_points();
    let fail = |k: usize, message: String| SegError::Rationalize {
        piece: piece.id,
        plane: piece.parts[k].plane,
        message,
    };
    let designs = designs(facade, piece, params);
    let mut fits =
        sweep_fits(&designs, constraint).map_err(|e| fail(e.plane, e.source.to_string()))?;
    if constraint == FitConstraint::EndPointsAndLength {
        restart_poor_fits(&designs, &mut fits, params.tolerance_max);
    }
    let mut parts = Vec::new();
    for (k, (design, fit)) in designs.into_iter().zip(fits).enumerate() {
        let (Some(design), Some(fit)) = (design, fit) else {
            continue;
        };
        let blade = make_blade(&fit.segment, &params.blade).map_err(|e| fail(k, e.to_string()))?;
        let pose = blade_pose(&facade.frame, piece.parts[k].offset, &blade);
        parts.push(PosedPart {
            part: k,
            design,
            fit,
            blade,
            pose,
        });
    }
    Ok(PosedPiece {
        id: piece.id,
        rotation: frame_quaternion(&facade.frame.normal, &facade.frame.v),
        parts,
    })
}

/// Every piece of `seg` rationalized ([`pose_piece`]), in parallel, in piece order;
/// `tick` is called once per piece (from worker threads).
///
/// # Errors
/// The first piece's error, in piece order.
pub fn pose_pieces(
    facade: &Facade,
    seg: &crate::Segmentation,
    params: &RationalizeParams,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<PosedPiece>, SegError> {
    let posed: Vec<Result<PosedPiece, SegError>> = seg
        .pieces
        .par_iter()
        .map(|piece| {
            let p = pose_piece(facade, piece, params);
            tick();
            p
        })
        .collect();
    posed.into_iter().collect()
}

/// A length-keeping fit over tolerance may sit in a poor local minimum that neither a
/// cold start nor its neighbours escape (a part with an inflection near one end): start
/// it again from the end-point fit, which has no length to keep, and keep the better.
fn restart_poor_fits(
    designs: &[Option<Clipped>],
    fits: &mut [Option<FitResult>],
    tolerance_max: f64,
) {
    for (design, fit) in designs.iter().zip(fits.iter_mut()) {
        let (Some(design), Some(f)) = (design, fit.as_mut()) else {
            continue;
        };
        if f.max <= tolerance_max {
            continue;
        }
        let run = |constraint, warm_start| {
            let fp = FitParams {
                constraint,
                warm_start,
                ..FitParams::default()
            };
            fit_points_with_arclength(&design.points, &design.s, &fp).ok()
        };
        // from the end-point fit, and cold (the fit's own candidates): a poor minimum
        // reached by a chain of warm starts is left whichever start finds a better one
        let from_ends = run(FitConstraint::EndPoints, None)
            .and_then(|e| run(FitConstraint::EndPointsAndLength, Some(e.segment)));
        let cold = run(FitConstraint::EndPointsAndLength, None);
        for b in [from_ends, cold].into_iter().flatten() {
            if b.l2 < f.l2 {
                *f = b;
            }
        }
    }
}
