//! A design's blocks and the cuts through them (§3.1, §5.3 of "Designing for Robotic
//! Hot-Blade Cutting"): each cut resolved against its blocks
//! ([`resolve_cut`](crate::assembly::resolve_cut)), per block its cuts in priority order
//! with the ones that touch nothing dropped
//! ([`block_cuts`](crate::assembly::block_cuts), with [`crate::envelope`]), and the order
//! the robots cut every (cut, block) pair in
//! ([`robot_order`](crate::assembly::robot_order)). Coordinates are in the caller's units.

use geom::slice::PlaneFrame;
use nalgebra::Vector3;

use crate::bezier::Bezier;
use crate::cut::{CutResult, DesignCurve, Station};
use crate::envelope::{envelope, CutSurface, Envelope};
use crate::spline::BSpline;

/// A block, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Its name.
    pub id: String,
    /// Smallest corner.
    pub min: Vector3<f64>,
    /// Largest corner.
    pub max: Vector3<f64>,
}

/// A design curve across a cut, as given: one Bézier per block, or one B-spline's
/// control points.
#[derive(Debug, Clone, PartialEq)]
pub enum CurveInput {
    /// One cubic Bézier per block, `[b0, b1, b2, b3]`, ends on the block's faces.
    Bezier(Vec<[[f64; 2]; 4]>),
    /// The control points of one cubic B-spline whose knots are the blocks' faces.
    Spline(Vec<[f64; 2]>),
}

/// A design curve at a station along a cut.
#[derive(Debug, Clone, PartialEq)]
pub struct StationInput {
    /// Where along the blocks, as a fraction from the entry face (0) to the exit face (1).
    pub at: f64,
    /// The curve, in plane coordinates `[across, height]`.
    pub curve: CurveInput,
}

/// A cut as given: its name, its planes' frame, its blocks by name and its stations.
#[derive(Debug, Clone, PartialEq)]
pub struct CutInput {
    /// Its name.
    pub id: String,
    /// The cutting planes' frame: normal along the cut, `u` across, `v` up.
    pub frame: PlaneFrame,
    /// Its blocks across the cut, in increasing `u`.
    pub blocks: Vec<String>,
    /// Its stations, from the entry face (`at: 0`) to the exit face (`at: 1`).
    pub stations: Vec<StationInput>,
}

/// A cut resolved against its blocks: what [`crate::cut::solve`] needs but the blade and
/// the planes.
#[derive(Debug, Clone)]
pub struct ResolvedCut {
    /// Its name.
    pub id: String,
    /// Indices of its blocks in the design's block list, across the cut.
    pub blocks: Vec<usize>,
    /// The planes' frame.
    pub frame: PlaneFrame,
    /// Faces across the cut.
    pub faces: Vec<f64>,
    /// Entry and exit offsets along the cut.
    pub span: (f64, f64),
    /// Per block, its base and top along the planes' `v` (up).
    pub heights: Vec<[f64; 2]>,
    /// Stations.
    pub stations: Vec<Station>,
}

/// Extent of a block along `axis` (a world axis or its negative).
fn extent(b: &Block, axis: &Vector3<f64>) -> (f64, f64) {
    let (a, c) = (axis.dot(&b.min), axis.dot(&b.max));
    (a.min(c), a.max(c))
}

/// Resolves cut `c` against `blocks`: its blocks found by name, side by side across the
/// cut and sharing their extent along it, its stations from the entry face to the exit
/// face with curves that end on the blocks' faces.
///
/// # Errors
/// Every problem, as `(pointer under the cut, message)`: `/blocks/<i>` or
/// `/stations/<i>[/at|/curve]`.
///
/// ```
/// use design::assembly::{resolve_cut, Block, CurveInput, CutInput, StationInput};
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
///
/// // two 1 × 1 × 0.5 blocks side by side along y, a cut along x through both
/// let block = |id: &str, y: f64| Block {
///     id: id.into(),
///     min: Vector3::new(0.0, y, 0.0),
///     max: Vector3::new(1.0, y + 1.0, 0.5),
/// };
/// let blocks = [block("a", 0.0), block("b", 1.0)];
/// let frame = PlaneFrame::from_direction(Vector3::x()).unwrap();
/// // one cubic Bézier per block, in (across, height), ends on the faces y = 0, 1, 2
/// // (G¹ at the face between them: both legs there horizontal)
/// let arch = |h: f64| CurveInput::Bezier(vec![
///     [[0.0, 0.2], [0.33, 0.2 + h], [0.67, 0.3], [1.0, 0.3]],
///     [[1.0, 0.3], [1.33, 0.3], [1.67, 0.3 - h], [2.0, 0.25]],
/// ]);
/// let cut = CutInput {
///     id: "c".into(),
///     frame,
///     blocks: vec!["a".into(), "b".into()],
///     stations: vec![
///         StationInput { at: 0.0, curve: arch(0.0) },
///         StationInput { at: 1.0, curve: arch(0.05) },
///     ],
/// };
/// let r = resolve_cut(&cut, &blocks).unwrap();
/// assert_eq!(r.blocks, [0, 1]);
/// assert_eq!(r.faces, [0.0, 1.0, 2.0]);
/// assert_eq!(r.span, (0.0, 1.0));
///
/// // the same cut naming its blocks the wrong way round
/// let swapped = CutInput { blocks: vec!["b".into(), "a".into()], ..cut };
/// let errors = resolve_cut(&swapped, &blocks).unwrap_err();
/// assert_eq!(errors[0].0, "/blocks/1");
/// ```
pub fn resolve_cut(c: &CutInput, blocks: &[Block]) -> Result<ResolvedCut, Vec<(String, String)>> {
    let mut errors = Vec::new();
    let frame = c.frame;
    let mut idx = Vec::new();
    for (i, id) in c.blocks.iter().enumerate() {
        match blocks.iter().position(|b| &b.id == id) {
            Some(k) if idx.contains(&k) => errors.push((
                format!("/blocks/{i}"),
                format!("block `{id}` is listed twice"),
            )),
            Some(k) => idx.push(k),
            None => errors.push((format!("/blocks/{i}"), format!("no block `{id}`"))),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let across: Vec<(f64, f64)> = idx.iter().map(|&k| extent(&blocks[k], &frame.u)).collect();
    let along: Vec<(f64, f64)> = idx
        .iter()
        .map(|&k| extent(&blocks[k], &frame.normal))
        .collect();
    let span = along[0];
    let scale = (span.1 - span.0).abs() + (across[across.len() - 1].1 - across[0].0).abs();
    let tol = 1e-9 * scale;
    for (i, a) in along.iter().enumerate().skip(1) {
        if (a.0 - span.0).abs() > tol || (a.1 - span.1).abs() > tol {
            errors.push((
                format!("/blocks/{i}"),
                format!(
                    "block `{}` spans {:.6}…{:.6} along the cut, the first block {:.6}…{:.6}: a cut's blocks share their extent along it",
                    c.blocks[i], a.0, a.1, span.0, span.1
                ),
            ));
        }
    }
    for (i, w) in across.windows(2).enumerate() {
        if (w[1].0 - w[0].1).abs() > tol {
            errors.push((
                format!("/blocks/{}", i + 1),
                format!(
                    "block `{}` starts at {:.6} across the cut but `{}` ends at {:.6}: list the blocks side by side, in increasing across coordinate",
                    c.blocks[i + 1], w[1].0, c.blocks[i], w[0].1
                ),
            ));
        }
    }
    let mut faces: Vec<f64> = across.iter().map(|a| a.0).collect();
    faces.push(across[across.len() - 1].1);
    if c.stations.first().map(|s| s.at) != Some(0.0) || c.stations.last().map(|s| s.at) != Some(1.0)
    {
        errors.push((
            "/stations".into(),
            "the first station is at the entry face (at: 0) and the last at the exit face (at: 1)"
                .into(),
        ));
    }
    for (i, w) in c.stations.windows(2).enumerate() {
        if !(w[1].at > w[0].at) {
            errors.push((
                format!("/stations/{}/at", i + 1),
                "stations must be listed in increasing `at`".into(),
            ));
        }
    }
    let mut stations = Vec::new();
    for (i, s) in c.stations.iter().enumerate() {
        let curve = match &s.curve {
            CurveInput::Bezier(p) => Ok(DesignCurve::Bezier(
                p.iter().map(|p| Bezier { p: *p }).collect(),
            )),
            CurveInput::Spline(p) => BSpline::new(faces.clone(), p.clone())
                .map(DesignCurve::Spline)
                .map_err(|e| e.to_string()),
        };
        match curve {
            Ok(curve) => {
                for m in curve.problems(&faces) {
                    errors.push((format!("/stations/{i}/curve"), m));
                }
                stations.push(Station {
                    offset: span.0 + s.at * (span.1 - span.0),
                    curve,
                });
            }
            Err(m) => errors.push((format!("/stations/{i}/curve"), m)),
        }
    }
    if errors.is_empty() {
        let heights = idx
            .iter()
            .map(|&k| {
                let (lo, hi) = extent(&blocks[k], &frame.v);
                [lo, hi]
            })
            .collect();
        Ok(ResolvedCut {
            id: c.id.clone(),
            blocks: idx,
            frame,
            faces,
            span,
            heights,
            stations,
        })
    } else {
        Err(errors)
    }
}

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
/// envelope ([`envelope`]) on a `grid × grid` grid from curves sampled at `points`.
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
