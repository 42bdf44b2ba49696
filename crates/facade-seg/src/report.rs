//! What a segmentation run reports per piece: its block, per section its part with the
//! design's measures and the blade's fit, and a verdict per constraint in which the blade
//! fits count too; and the counts over all pieces.
//!
//! Entry point: [`summarize`](crate::report::summarize).

use crate::constraints::{Constraints, FitCheck, Verdicts};
use crate::rationalize::PosedPiece;
use crate::{Facade, Segmentation};

/// The pieces of a segmentation as reported, and the counts over them.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Pieces {
    /// How many pieces and blocks, and how many break each constraint.
    pub counts: SegmentationCounts,
    /// The pieces, by band then by row.
    pub pieces: Vec<PieceReport>,
}

/// Counts over the segmentation.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SegmentationCounts {
    /// Pieces.
    pub pieces: usize,
    /// Blocks needed: one per piece.
    pub blocks: usize,
    /// Bands across the cut.
    pub bands: usize,
    /// Rows of blocks along the cut.
    pub rows: usize,
    /// Sections.
    pub sections: usize,
    /// Section parts over all pieces.
    pub parts: usize,
    /// Pieces breaking each constraint.
    pub failing: ConstraintCounts,
    /// Pieces whose blade, outside a part, runs into what the block keeps (issue 37).
    pub gouges: usize,
    /// Pieces where a held end of the blade comes within 1 % of the blade's length of the
    /// block (or inside it) on some part: the holder collides with the block.
    pub collisions: usize,
    /// Every piece meets every constraint, with no gouge and no holder collision.
    pub all_ok: bool,
    /// Blade poses over all pieces (rationalized runs).
    pub poses: usize,
    /// Section parts left without a pose: slivers shorter than 5 % of the blade.
    pub unposed: usize,
}

/// Pieces breaking each constraint of §5.1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct ConstraintCounts {
    /// Dimension (blade length, block).
    pub dimension: usize,
    /// Approximation (only measured by `LongestElastica`).
    pub approximation: usize,
    /// Shape (inflections).
    pub shape: usize,
    /// Blade strain (curvature).
    pub blade_strain: usize,
    /// Blades that do not hold their shape (unstable or marginal equilibria).
    pub stability: usize,
}

/// The block a piece is cut from.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PieceBlock {
    /// Block number (= piece id).
    pub number: usize,
    /// Min corner, the work object's origin.
    pub origin: [f64; 3],
    /// Orientation `[w, x, y, z]` of the block axes (along the cut, across it, up).
    pub rotation: [f64; 4],
    /// Size along the cut, across it and up.
    pub size: [f64; 3],
    /// The piece's extent in the block (≤ `size` when it fits).
    pub used: [f64; 3],
}

/// One section part of a piece.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PieceSection {
    /// Plane index of the section.
    pub plane: usize,
    /// Plane offset along the cutting direction.
    pub offset: f64,
    /// 3D start point of the part.
    pub start: [f64; 3],
    /// 3D end point of the part.
    pub end: [f64; 3],
    /// Arc-length range along the section from its start.
    pub s: [f64; 2],
    /// Arc length.
    pub length: f64,
    /// Inflections of the design in the part.
    pub inflections: usize,
    /// Largest |curvature| of the design in the part.
    pub max_abs_curvature: f64,
    /// The elastica fit through the part's end points the algorithm measured
    /// (`LongestElastica`).
    pub check_fit: Option<FitCheck>,
    /// The rationalized part: the blade's fit (rationalized runs; `None` for a sliver).
    pub blade_fit: Option<BladeFit>,
}

/// The fit a piece's part is cut with.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct BladeFit {
    /// `elastica`, `arc` or `line`.
    pub kind: String,
    /// RMS distance to the design part.
    pub rms: f64,
    /// Largest distance to the design part.
    pub max: f64,
    /// Largest |curvature| of the blade, over its whole length (what strains it).
    pub max_abs_curvature: f64,
    /// Inflections of the cut: the fitted segment inside the block (the shape constraint
    /// of §5.1.3).
    pub inflections: usize,
    /// Inflections of the whole blade, its extension outside the block included.
    pub blade_inflections: usize,
    /// Where the part sits along the blade: the blade's length before it.
    pub lead_in: f64,
    /// How deep the blade outside the part runs into what the block keeps (0: clean).
    pub gouge_depth: f64,
    /// How much of the blade outside the part lies in what the block keeps.
    pub gouge_length: f64,
    /// The smaller distance of the blade's held ends from the block (negative: inside).
    pub holder_clearance: f64,
    /// Both held ends at least 1 % of the blade's length from the block.
    pub holders_clear: bool,
    /// The held blade's stability margin ([`elastica::stability()`]: the second variation's
    /// smallest eigenvalue over a straight blade's, unit-free).
    pub margin: f64,
    /// Stable, marginal or unstable.
    pub stability: elastica::Class,
    /// The blade's total turning from its first end to its second, radians.
    pub turning: f64,
    /// What the holders carry.
    pub loads: elastica::HolderLoads,
}

/// One piece.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PieceReport {
    /// 1-based id.
    pub id: usize,
    /// Row of blocks along the cut.
    pub row: usize,
    /// Band across the cut (0 at the facade's start edge).
    pub band: usize,
    /// Its block.
    pub block: PieceBlock,
    /// Per section it crosses, its part.
    pub sections: Vec<PieceSection>,
    /// Per constraint of §5.1: met (true) or not. Approximation is measured by the
    /// algorithm's own check fits (`LongestElastica`) and, in a rationalized run, by the
    /// blade fits, whose bending (over the whole blade) and inflections (inside the block)
    /// also count for blade strain and shape.
    pub verdicts: Verdicts,
    /// Largest fit distance over the rationalized parts (rationalized runs).
    pub max_blade_fit: Option<f64>,
    /// Deepest the blades outside the parts run into what the block keeps (rationalized
    /// runs; 0 where clean).
    pub max_gouge_depth: Option<f64>,
    /// Smallest distance of a held blade end from the block (rationalized runs).
    pub min_holder_clearance: Option<f64>,
    /// Every held end of the piece's blades clear of its block (rationalized runs).
    pub holders_clear: Option<bool>,
    /// The least stability margin of the piece's blades (rationalized runs).
    pub min_margin: Option<f64>,
}

/// The pieces of `seg` as reported, with the blade fits of `posed` (empty when the run
/// did not rationalize; `rationalized` says whether it did), and the counts.
pub fn summarize(
    facade: &Facade,
    seg: &Segmentation,
    posed: &[PosedPiece],
    rationalized: bool,
    c: &Constraints,
    stiffness: &elastica::Stiffness,
) -> Pieces {
    let rotation = elastica::sweep::frame_quaternion(&facade.frame.normal, &facade.frame.v);
    let pieces: Vec<PieceReport> = seg
        .pieces
        .iter()
        .map(|p| {
            let q = posed.iter().find(|q| q.id == p.id);
            piece_report(p, q, rotation, c, stiffness)
        })
        .collect();
    let count = |f: &dyn Fn(&Verdicts) -> bool| pieces.iter().filter(|p| f(&p.verdicts)).count();
    let parts: usize = pieces.iter().map(|p| p.sections.len()).sum();
    let poses: usize = posed.iter().map(|p| p.parts.len()).sum();
    let counts = SegmentationCounts {
        pieces: pieces.len(),
        blocks: pieces.len(),
        bands: seg.bands,
        rows: seg.rows,
        sections: facade.sections.len(),
        parts,
        failing: ConstraintCounts {
            dimension: count(&|v| !v.dimension),
            approximation: count(&|v| v.approximation == Some(false)),
            shape: count(&|v| !v.shape),
            blade_strain: count(&|v| !v.blade_strain),
            stability: count(&|v| !v.stability),
        },
        gouges: pieces
            .iter()
            .filter(|p| p.max_gouge_depth.is_some_and(|d| d > 0.0))
            .count(),
        collisions: pieces
            .iter()
            .filter(|p| p.holders_clear == Some(false))
            .count(),
        all_ok: pieces.iter().all(|p| p.verdicts.all() && p.is_clear()),
        poses,
        unposed: if rationalized { parts - poses } else { 0 },
    };
    Pieces { counts, pieces }
}

/// A piece's verdicts with its rationalization, if the run made one: the blades are what is
/// cut, so their fits, their bending over the whole blade and the inflections of the cut
/// count against the piece's verdicts too.
pub fn judged(p: &crate::Piece, posed: Option<&PosedPiece>, c: &Constraints) -> Verdicts {
    let mut verdicts = p.verdicts;
    let Some(q) = posed else {
        return verdicts;
    };
    let within = q
        .parts
        .iter()
        .all(|x| x.fit.rms <= c.tolerance_rms && x.fit.max <= c.tolerance_max);
    verdicts.approximation = Some(verdicts.approximation != Some(false) && within);
    verdicts.shape &= q.parts.iter().all(|x| {
        x.fit.segment.inflections().map_or(usize::MAX, |v| v.len()) <= c.max_inflections as usize
    });
    verdicts.blade_strain &= q
        .parts
        .iter()
        .all(|x| x.blade.max_abs_curvature <= c.max_curvature);
    let blades: Vec<elastica::Blade> = q.parts.iter().map(|x| x.blade.clone()).collect();
    verdicts.stability &= q
        .parts
        .iter()
        .all(|x| x.blade.stability_ok && x.blade.inflections_ok)
        && elastica::clearance::snapping_moves(&blades) == 0;
    verdicts
}

/// One piece as reported; `posed` is its rationalization, if the run made one.
fn piece_report(
    p: &crate::Piece,
    posed: Option<&PosedPiece>,
    rotation: [f64; 4],
    c: &Constraints,
    stiffness: &elastica::Stiffness,
) -> PieceReport {
    let sections: Vec<PieceSection> = p
        .parts
        .iter()
        .enumerate()
        .map(|(k, part)| {
            let blade_fit = posed
                .and_then(|q| q.parts.iter().find(|x| x.part == k))
                .map(|x| BladeFit {
                    kind: x.fit.segment.kind().to_string(),
                    rms: x.fit.rms,
                    max: x.fit.max,
                    max_abs_curvature: x.blade.max_abs_curvature,
                    inflections: x.fit.segment.inflections().map_or(usize::MAX, |v| v.len()),
                    blade_inflections: x.blade.inflections,
                    lead_in: x.blade.lead_in,
                    gouge_depth: x.clearance.gouge_depth,
                    gouge_length: x.clearance.gouge_length,
                    holder_clearance: x.clearance.holder_clearance,
                    holders_clear: x.clearance.holders_clear,
                    margin: x.blade.stability.margin,
                    stability: x.blade.stability.class,
                    turning: x.blade.stability.turning,
                    loads: x.blade.stability.loads.held(stiffness),
                });
            PieceSection {
                plane: part.plane,
                offset: part.offset,
                start: part.start,
                end: part.end,
                s: part.s,
                length: part.check.length,
                inflections: part.check.inflections,
                max_abs_curvature: part.check.max_abs_curvature,
                check_fit: part.check.fit,
                blade_fit,
            }
        })
        .collect();
    let verdicts = judged(p, posed, c);
    let fold = |f: &dyn Fn(&BladeFit) -> f64, start: f64, pick: fn(f64, f64) -> f64| {
        posed.map(|_| {
            sections
                .iter()
                .filter_map(|s| s.blade_fit.as_ref().map(f))
                .fold(start, pick)
        })
    };
    let max_blade_fit = fold(&|f| f.max, 0.0, f64::max);
    let max_gouge_depth = fold(&|f| f.gouge_depth, 0.0, f64::max);
    let min_holder_clearance =
        fold(&|f| f.holder_clearance, f64::INFINITY, f64::min).filter(|c| c.is_finite());
    let min_margin = fold(&|f| f.margin, f64::INFINITY, f64::min).filter(|m| m.is_finite());
    let holders_clear = posed.map(|_| {
        sections
            .iter()
            .all(|s| s.blade_fit.as_ref().is_none_or(|f| f.holders_clear))
    });
    PieceReport {
        id: p.id,
        row: p.row,
        band: p.band,
        block: PieceBlock {
            number: p.id,
            origin: p.block.origin,
            rotation,
            size: p.block.size,
            used: p.block.used,
        },
        sections,
        verdicts,
        max_blade_fit,
        max_gouge_depth,
        min_holder_clearance,
        holders_clear,
        min_margin,
    }
}

impl PieceReport {
    /// No blade of the piece gouges what its block keeps, and every held end clears the
    /// block (true for a run that did not rationalize: nothing was posed).
    pub fn is_clear(&self) -> bool {
        self.max_gouge_depth.is_none_or(|d| d == 0.0) && self.holders_clear != Some(false)
    }
}
