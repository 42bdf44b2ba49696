//! Rationalizing a piece: every section part fitted by an elastica as the `hotblade`
//! pipeline fits a block's sections (warm-started sweeps along the cut), extended to the
//! blade and posed for the two robots, one pose per section the piece crosses.
//!
//! Entry points: [`pose_piece`](crate::rationalize::pose_piece),
//! [`pose_pieces`](crate::rationalize::pose_pieces).

use elastica::blade::{Blade, BladeParams};
use elastica::clearance::{place_all_by, Clearance, Section};
use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams, FitResult};
use elastica::sweep::{blade_pose, frame_quaternion, BladePose};
use hotblade::fit::blade_params_over;
use hotblade::{sweep_fits, BladeLimits, Clipped, SHORTEST_PART};
use rayon::prelude::*;

use crate::holders::{block_section, slide_block};
use crate::piece::Block;
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
    /// RMS tolerance: with `tolerance_max`, how close the arc through a part's ends must
    /// come to replace an elastica whose blade would not hold its shape.
    pub tolerance_rms: f64,
}

/// One section part of a piece, fitted and posed.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
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
    /// The blade outside the part against the piece's block (issue 37): how deep it runs
    /// into what the block keeps, and how far its held ends stay from the block.
    pub clearance: Clearance,
}

/// A rationalized piece.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PosedPiece {
    /// Piece id.
    pub id: usize,
    /// The block it is cut from: the segmentation's, slid across the cut where that
    /// clears the blades' held ends ([`crate::holders::slide_block`]).
    pub block: Block,
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
    let kept: Vec<(usize, Clipped, FitResult)> = designs
        .into_iter()
        .zip(fits)
        .enumerate()
        .filter_map(|(k, (d, f))| Some((k, d?, f?)))
        .collect();
    let longest = kept
        .iter()
        .map(|(_, _, f)| f.segment.length())
        .fold(0.0, f64::max);
    // the shape constraint (§5.1.3) counts the cut's inflections; the whole blade's are
    // limited only by `max_blade_inflections` (and its stability)
    let bp = BladeParams {
        max_inflections: params.blade.max_blade_inflections.map(|v| v as usize),
        ..blade_params_over(longest, &params.blade)
    };
    let first_plane = kept.first().map_or(0, |(k, _, _)| piece.parts[*k].plane);
    let fail_blade = |e: elastica::blade::BladeError| SegError::Rationalize {
        piece: piece.id,
        plane: first_plane,
        message: e.to_string(),
    };
    // one place along the blade for every part (the piece is one block, cut plane after
    // plane), the extension kept out of what the block keeps where it can be; for each
    // place tried the block is slid across the cut to clear the blades' held ends
    let segments: Vec<_> = kept.iter().map(|(_, _, f)| f.segment).collect();
    // the piece's extent across the cut (plane u), which the block must keep holding
    let extent = kept
        .iter()
        .flat_map(|(_, d, _)| d.points.iter().map(|q| q[0]))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), u| {
            (lo.min(u), hi.max(u))
        });
    let slid = |blades: &[Blade]| slide_block(facade, &piece.block, extent, blades, bp.length);
    let sections_in = |block: &Block| -> Vec<Section> {
        kept.iter()
            .map(|(_, d, _)| block_section(facade, block, d))
            .collect()
    };
    let place = |segments: &[elastica::Segment]| {
        place_all_by(segments, &bp, 1e-6 * bp.length, &|blades| {
            sections_in(&slid(blades))
        })
        .map(|(placed, _)| placed)
        .map_err(fail_blade)
    };
    let mut placed = place(&segments)?;
    // blades that do not hold their shape, and moves between planes that snap
    let trouble = |placed: &[(Blade, elastica::Clearance)]| {
        let blades: Vec<Blade> = placed.iter().map(|(b, _)| b.clone()).collect();
        let unstable = blades.iter().filter(|b| !b.stability_ok).count();
        unstable + elastica::clearance::snapping_moves(&blades)
    };
    let before = trouble(&placed);
    // where a blade does not hold its shape at any place, or the blades snap from plane to
    // plane: each such part (every part, for snaps) whose arc through its ends is within
    // the tolerance takes the arc instead (a circle is stable and carries no force; the
    // elastica it replaces followed noise or a slight wave), kept when that holds better
    let mut arcs: Vec<Option<FitResult>> = vec![None; kept.len()];
    if before > 0 {
        let snapping = placed.iter().all(|(b, _)| b.stability_ok);
        let mut tried = segments.clone();
        for (k, (_, design, _)) in kept.iter().enumerate() {
            if placed[k].0.stability_ok && !snapping {
                continue;
            }
            if let Some(arc) = elastica::fit::arc_through_ends(&design.points, &design.s) {
                if arc.max <= params.tolerance_max && arc.rms <= params.tolerance_rms {
                    tried[k] = arc.segment;
                    arcs[k] = Some(arc);
                }
            }
        }
        if arcs.iter().any(Option::is_some) {
            let again = place(&tried)?;
            if trouble(&again) < before {
                placed = again;
            } else {
                arcs.iter_mut().for_each(|a| *a = None);
            }
        }
    }
    let blades: Vec<Blade> = placed.iter().map(|(b, _)| b.clone()).collect();
    let block = slid(&blades);
    let parts = kept
        .into_iter()
        .zip(arcs)
        .zip(placed)
        .map(|(((k, design, fit), arc), (blade, clearance))| PosedPart {
            fit: arc.unwrap_or(fit),
            part: k,
            pose: blade_pose(&facade.frame, piece.parts[k].offset, &blade),
            design,
            blade,
            clearance,
        })
        .collect();
    Ok(PosedPiece {
        id: piece.id,
        block,
        rotation: frame_quaternion(&facade.frame.normal, &facade.frame.v),
        parts,
    })
}

/// Every piece of `seg` rationalized ([`pose_piece`]), in parallel, in piece order;
/// `tick` is called once per piece (from worker threads).
///
/// # Errors
/// The first piece's error, in piece order.
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
/// use elastica::FitConstraint;
/// use facade_seg::inflection::{inflection_points, InflectionParams};
/// use facade_seg::rationalize::{pose_pieces, RationalizeParams};
/// use hotblade::BladeLimits;
/// let seg = inflection_points(&facade, &c, &InflectionParams::default(), &|| {})?;
/// let params = RationalizeParams {
///     constraint: FitConstraint::EndPointsAndLength,
///     samples: 64,
///     blade: BladeLimits::new(c.blade_length, c.max_curvature, c.max_inflections),
///     tolerance_max: c.tolerance_max,
///     tolerance_rms: c.tolerance_rms,
/// };
/// let posed = pose_pieces(&facade, &seg, &params, &|| {})?;
/// assert_eq!(posed.len(), seg.pieces.len());
/// // every part of every piece gets a blade of the blade's length, both ends held on the
/// // part's cutting plane
/// for part in posed.iter().flat_map(|p| &p.parts) {
///     assert!((part.blade.segment.length() - c.blade_length).abs() < 1e-6);
///     let n = part.pose.plane_normal;
///     let [a, b] = part.pose.ends.map(|e| n[0] * e.position[0] + n[1] * e.position[1] + n[2] * e.position[2]);
///     assert!((a - b).abs() < 1e-9);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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

/// Every piece of `seg` given the block it was posed in (`posed[i].block`: slid across
/// the cut where that clears the holders), so that drawings, robot files and reports
/// agree on where each block is.
pub fn adopt_blocks(seg: &mut crate::Segmentation, posed: &[PosedPiece]) {
    for q in posed {
        if let Some(p) = seg.pieces.iter_mut().find(|p| p.id == q.id) {
            p.block = q.block.clone();
        }
    }
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
