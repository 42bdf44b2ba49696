use crate::constraints::{Constraints, PartCheck, Verdicts};
use crate::section::Facade;

/// The part of one section a piece holds.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PiecePart {
    /// Plane index of the section (as numbered in the input).
    pub plane: usize,
    /// Plane offset along the cutting direction.
    pub offset: f64,
    /// Arc-length range `[s0, s1]` along the section from its start.
    pub s: [f64; 2],
    /// 3D start point of the part.
    pub start: [f64; 3],
    /// 3D end point of the part.
    pub end: [f64; 3],
    /// The part measured against the constraints.
    pub check: PartCheck,
}

/// A block placed to hold a piece: axis-aligned in the facade's frame (cutting direction,
/// `u`, `v`), `origin` its min corner in world coordinates. Along the cut it is its row's
/// slab; across the cut it is centred on the piece (rationalizing may slide it, still
/// holding the piece, to clear the blade's holders); up, its top is at the piece's highest
/// point.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Block {
    /// Min corner (world).
    pub origin: [f64; 3],
    /// Size along the cut, `u` and `v`.
    pub size: [f64; 3],
    /// The piece's extent in the block's frame (≤ `size` when it fits).
    pub used: [f64; 3],
}

/// One piece of the segmentation.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Piece {
    /// 1-based id.
    pub id: usize,
    /// Row of blocks along the cut.
    pub row: usize,
    /// Band across the cut (0 at the facade's start edge).
    pub band: usize,
    /// The block it is cut from.
    pub block: Block,
    /// Its part of every section it crosses, in plane order.
    pub parts: Vec<PiecePart>,
    /// Per constraint: met by every part and by the block.
    pub verdicts: Verdicts,
}

/// A seam between two bands: one point per section, in plane order.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Seam {
    /// World points.
    pub points: Vec<[f64; 3]>,
}

/// What a segmentation algorithm returns.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Segmentation {
    /// The algorithm that made it.
    pub algorithm: String,
    /// Rows of blocks along the cut.
    pub rows: usize,
    /// Bands across the cut.
    pub bands: usize,
    /// The pieces, by band then row.
    pub pieces: Vec<Piece>,
    /// Seams between bands (`bands − 1` of them, or more where bands end early).
    pub seams: Vec<Seam>,
}

fn arr(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Row of blocks (along the cut) of each section: slabs of `block[0]` from half a spacing
/// before the first plane, numbered from 0 over the slabs that hold a section (so a block
/// far shorter than the spacing gives one row per section, not an index out of range).
pub fn rows_of(facade: &Facade, c: &Constraints) -> Vec<usize> {
    let slab = slabs(facade, c);
    // sections come in plane order, so their slabs do not decrease
    let mut rows = Vec::with_capacity(slab.len());
    let mut row = 0;
    for (j, v) in slab.iter().enumerate() {
        if j > 0 && *v != slab[j - 1] {
            row += 1;
        }
        rows.push(row);
    }
    rows
}

/// The slab of `block[0]` (counted from half a spacing before the first plane) each
/// section lies in: where its row's blocks start along the cut.
fn slabs(facade: &Facade, c: &Constraints) -> Vec<f64> {
    let first = facade.sections[0].offset - 0.5 * facade.spacing();
    facade
        .sections
        .iter()
        .map(|s| ((s.offset - first) / c.block[0]).floor().max(0.0))
        .collect()
}

/// Pieces from bands: `bands[b][j]` is band b's arc-length range on section j (`None` where
/// the band does not cross it). Each band is cut into rows of blocks; every part is
/// measured (fitted with `fit`) on `samples` points.
pub fn pieces_from_bands(
    facade: &Facade,
    c: &Constraints,
    bands: &[Vec<Option<(f64, f64)>>],
    fit: bool,
    samples: usize,
) -> Vec<Piece> {
    let rows = rows_of(facade, c);
    let n_rows = rows.iter().copied().max().map_or(0, |r| r + 1);
    let mut pieces = Vec::new();
    for (b, band) in bands.iter().enumerate() {
        for row in 0..n_rows {
            let ranges: Vec<(usize, f64, f64)> = band
                .iter()
                .enumerate()
                .filter(|(j, r)| rows[*j] == row && r.is_some_and(|(s0, s1)| s1 > s0))
                .map(|(j, r)| {
                    let (s0, s1) = r.unwrap_or_default();
                    (j, s0, s1)
                })
                .collect();
            if let Some(piece) =
                piece_of(facade, c, (pieces.len() + 1, row, b), &ranges, fit, samples)
            {
                pieces.push(piece);
            }
        }
    }
    pieces
}

/// The piece `(id, row, band)` holding the part `[s0, s1]` of every facade section `j` in
/// `ranges` (all of one row): its parts measured on `samples` points (fitted with `fit`),
/// its block, its verdicts. `None` for no part.
pub fn piece_of(
    facade: &Facade,
    c: &Constraints,
    (id, row, band): (usize, usize, usize),
    ranges: &[(usize, f64, f64)],
    fit: bool,
    samples: usize,
) -> Option<Piece> {
    let rows = rows_of(facade, c);
    let first = facade.sections[0].offset - 0.5 * facade.spacing();
    // each row's slab along the cut (rows are numbered densely, slabs may skip)
    let slab = slabs(facade, c);
    let slab_of_row = |row: usize| {
        rows.iter()
            .position(|&r| r == row)
            .map_or(row as f64, |j| slab[j])
    };
    let parts: Vec<PiecePart> = ranges
        .iter()
        .map(|&(j, s0, s1)| {
            let sec = &facade.sections[j];
            PiecePart {
                plane: sec.index,
                offset: sec.offset,
                s: [s0, s1],
                start: arr(&facade.world(j, s0)),
                end: arr(&facade.world(j, s1)),
                check: PartCheck::of(sec, s0, s1, samples, fit),
            }
        })
        .collect();
    if parts.is_empty() {
        return None;
    }
    // extents in plane coordinates (u, v) over all parts
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for &(j, s0, s1) in ranges {
        let (pts, _) = facade.sections[j].samples(s0, s1, samples);
        for q in pts {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
    }
    let d0 = first + slab_of_row(row) * c.block[0];
    let (d_lo, d_hi) = parts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
            (a.0.min(p.offset), a.1.max(p.offset))
        });
    let used = [d_hi - d_lo, hi[0] - lo[0], hi[1] - lo[1]];
    let f = &facade.frame;
    // across the cut the block is centred on the piece: the blade, longer than the block
    // is wide, then runs through the whole block with both held ends beyond its faces
    // (issue 37: a piece at the block's edge leaves one holder inside the block). Up, the
    // piece's highest point is at the block's top: the block keeps what lies below the
    // design (the mould), the blade removes what lies above.
    let u0 = 0.5 * (lo[0] + hi[0]) - 0.5 * c.block[1];
    let v0 = hi[1] - c.block[2];
    let origin = f.normal * d0 + f.u * u0 + f.v * v0;
    let fits = (0..3).all(|k| used[k] <= c.block[k] * (1.0 + 1e-12));
    let mut verdicts = Verdicts {
        dimension: fits,
        approximation: fit.then_some(true),
        shape: true,
        blade_strain: true,
        stability: true,
    };
    for p in &parts {
        let v = p.check.verdicts(c, fit);
        verdicts.dimension &= v.dimension;
        verdicts.shape &= v.shape;
        verdicts.blade_strain &= v.blade_strain;
        if let (Some(a), Some(b)) = (verdicts.approximation, v.approximation) {
            verdicts.approximation = Some(a && b);
        }
    }
    Some(Piece {
        id,
        row,
        band,
        block: Block {
            origin: arr(&origin),
            size: c.block,
            used,
        },
        parts,
        verdicts,
    })
}
