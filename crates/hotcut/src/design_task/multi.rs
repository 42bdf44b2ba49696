//! Blocks cut by several cuts (§3.1, §5.3): per block its cuts in priority order with the
//! ones that touch nothing dropped ([`design::envelope`]), and the order the robots cut
//! every (cut, block) pair in.

use design::cut::CutResult;
use design::envelope::{envelope, CutSurface, Envelope};

use super::file::{Block, ResolvedCut};

/// The cuts through one block and their envelope.
#[derive(Debug, Clone)]
pub struct BlockCuts {
    /// The block (index in the design's list).
    pub block: usize,
    /// Every cut through it: `(cut index, piece index in that cut)`, in the design's
    /// order.
    pub cuts: Vec<(usize, usize)>,
    /// With two or more cuts: their envelope (indices into `cuts`).
    pub envelope: Option<Envelope>,
}

impl BlockCuts {
    /// The rank of cut `cut` on this block (0: primary), `None` if dropped.
    pub fn rank(&self, cut: usize) -> Option<usize> {
        let k = self.cuts.iter().position(|c| c.0 == cut)?;
        match &self.envelope {
            None => Some(0),
            Some(e) => e.order.iter().position(|&o| o == k),
        }
    }
}

/// Per block of the design (in its order), the cuts through it and, with several, their
/// envelope on a `grid × grid` grid from curves sampled at `points`.
pub fn block_cuts(
    blocks: &[Block],
    cuts: &[(ResolvedCut, CutResult)],
    grid: usize,
    points: usize,
) -> Vec<BlockCuts> {
    blocks
        .iter()
        .enumerate()
        .map(|(b, block)| {
            let through: Vec<(usize, usize)> = cuts
                .iter()
                .enumerate()
                .filter_map(|(c, (r, _))| r.blocks.iter().position(|&k| k == b).map(|p| (c, p)))
                .collect();
            let envelope = (through.len() > 1).then(|| {
                let surfaces: Vec<CutSurface> = through
                    .iter()
                    .map(|&(c, piece)| {
                        let (r, res) = &cuts[c];
                        CutSurface {
                            frame: r.frame,
                            planes: res
                                .planes
                                .iter()
                                .map(|pl| {
                                    let (d, e) = pl.sampled(piece, points);
                                    (pl.offset, d, e)
                                })
                                .collect(),
                        }
                    })
                    .collect();
                let size = block.max - block.min;
                envelope(
                    &surfaces,
                    [block.min.x, block.min.y],
                    [block.max.x, block.max.y],
                    grid,
                    1e-9 * size.norm(),
                )
            });
            BlockCuts {
                block: b,
                cuts: through,
                envelope,
            }
        })
        .collect()
}

/// The (cut, piece) pairs the robots cut, in order: every block's primary cut first (in
/// the design's order of cuts and across each), then the second cuts, and so on; dropped
/// pairs left out.
pub fn robot_order(multi: &[BlockCuts], cuts: &[(ResolvedCut, CutResult)]) -> Vec<(usize, usize)> {
    let mut pairs: Vec<(usize, usize, usize)> = Vec::new();
    for (c, (r, _)) in cuts.iter().enumerate() {
        for (piece, &b) in r.blocks.iter().enumerate() {
            if let Some(rank) = multi.get(b).and_then(|m| m.rank(c)) {
                pairs.push((rank, c, piece));
            }
        }
    }
    pairs.sort();
    pairs.into_iter().map(|(_, c, p)| (c, p)).collect()
}
