//! Hot-wire pre-cuts before milling (thesis ch. 2).
//!
//! A block with a design surface inside is to be milled down to the surface. Before
//! milling, a hot wire removes the bulk: a few straight through-cuts per cutting
//! direction, each sweeping a ruled surface, that together leave a piecewise ruled cap
//! above the design surface — never below it. [`pre_cut`] finds the cuts that leave the
//! least material (eq. 2.11) and reports the volumes of Table 2.1.
//!
//! ```
//! use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
//! use ruled::{pre_cut, Block, Params};
//!
//! let bump = HeightField::try_new(Expr::parse("0.5 + 0.3*exp(-8*(x*x + y*y))")?, (-1.0, 1.0), (-1.0, 1.0))?;
//! let block = Block { min: [-1.0, -1.0, 0.0], max: [1.0, 1.0, 1.0] };
//! let params = Params { sections: 12, samples: 12, ..Params::default() };
//! let cut = pre_cut(&Surface::HeightField(bump), &block, &params, &|_| {})?;
//! assert!(cut.volumes.ruled < cut.volumes.convex_hull);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Modules:
//! - [`error`]: the error type.
//! - [`frame`]: the block and a cutting direction's `(u, w, z)` frame.
//! - [`height`]: the design surface as a height function (exact or by mesh).
//! - [`legs`]: the moving polygon by its legs' lines, B-splines along the cut.
//! - [`search`]: the search over cutting directions (`Auto(n)`).
//! - [`solve`]: the alternating convex-QP optimization with constraint exchange.
//! - [`unit`](mod@unit): the block's unit frame the optimization runs in.
//! - [`volume`]: the volumes of Table 2.1.
//! - [`wire`]: wire paths to the tower planes, machine profiles, G-code and CSV.

pub mod error;
pub mod frame;
pub mod height;
pub mod legs;
pub mod search;
pub mod solve;
pub mod unit;
pub mod volume;
pub mod wire;

pub use error::{PreCutError, Result};
pub use frame::{Block, CutFrame};
pub use height::Height;
pub use volume::Volumes;
pub use wire::{Machine, WireParams};

use geom::surface::Surface;
use legs::Legs;
use solve::{Point, SolveOptions};

/// Parameters of [`pre_cut`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Params {
    /// Cuts (legs of the moving polygon) per direction (≥ 1).
    pub legs: usize,
    /// Cutting directions in the `xy` plane (any, not only the axes).
    pub directions: Vec<[f64; 2]>,
    /// B-spline degree of the legs along the cut (thesis `p`).
    pub degree: usize,
    /// Control values per leg coefficient along the cut (thesis `k`, ≥ degree + 1).
    pub controls: usize,
    /// Section planes along the cut (thesis `N`).
    pub sections: usize,
    /// Samples per section across the block (thesis `M`).
    pub samples: usize,
    /// Most assignment rounds.
    pub max_rounds: usize,
    /// Density factor of the check grid against the samples, per direction.
    pub check_density: usize,
    /// Clearance kept above the constraint points, relative to the block's longest edge.
    pub margin: f64,
    /// Grid cells per side for the volumes.
    pub volume_grid: usize,
    /// Distance between the wire's tower planes, when the cuts go to a hot-wire machine:
    /// every leg's line, extended this wide (centred on the block), stays between the
    /// block's floor (the machine's table) and a block height above its top. Without it,
    /// the same holds across the block's own width along each direction.
    pub span: Option<f64>,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            legs: 4,
            directions: vec![[1.0, 0.0]],
            degree: 3,
            controls: 8,
            sections: 30,
            samples: 30,
            max_rounds: 40,
            check_density: 8,
            margin: 1e-5,
            volume_grid: 200,
            span: None,
        }
    }
}

/// The cut polygon in one section plane.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SectionPolygon {
    /// Plane offset `u` along the cutting direction.
    pub offset: f64,
    /// Vertices in model coordinates, from one side of the block to the other.
    pub polygon: Vec<[f64; 3]>,
    /// The leg (cut) of each edge.
    pub legs: Vec<usize>,
}

/// One leg's line in a section: `z = a + m·s`, `s = (w − w_mid)/w_half`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct LegLine {
    /// Height at the block's middle `w`.
    pub a: f64,
    /// Rise over half the block's width.
    pub m: f64,
}

/// One leg's coefficient functions along the cut as B-spline control values:
/// `a(u) = Σ B_c(u)·a[c]`, `m(u) = Σ B_c(u)·m[c]` on the direction's knots.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct LegSpline {
    /// Control values of `a` (model units).
    pub a: Vec<f64>,
    /// Control values of `m` (model units).
    pub m: Vec<f64>,
}

/// The cuts of one direction.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct DirectionCut {
    /// Unit cutting direction `[dx, dy, 0]`.
    pub direction: [f64; 3],
    /// Unit direction across the block `[−dy, dx, 0]`.
    pub across: [f64; 3],
    /// `u` range of the block.
    pub u: (f64, f64),
    /// `w` range of the block.
    pub w: (f64, f64),
    /// B-spline degree of the legs along the cut.
    pub degree: usize,
    /// Knots along the cut (`u`), clamped.
    pub knots: Vec<f64>,
    /// Middle of the `w` range (`s = (w − w_mid)/w_half`).
    pub w_mid: f64,
    /// Half the `w` range.
    pub w_half: f64,
    /// Every leg's line as B-splines along the cut: the exact cut surface.
    pub legs: Vec<LegSpline>,
    /// The polygon at `sections + 1` equally spaced planes from block end to block end.
    pub sections: Vec<SectionPolygon>,
    /// Every leg's line at the same planes: `lines[section][leg]`.
    pub lines: Vec<Vec<LegLine>>,
    /// Assignment rounds.
    pub rounds: usize,
    /// QPs solved.
    pub qps: usize,
    /// Constraint points at the end.
    pub constraint_points: usize,
    /// `Σ (cut − f)²` over the samples, per round (block-scale units).
    pub objective_history: Vec<f64>,
    /// Least height of a leg above the design on the check grid (model units, > 0).
    pub clearance: f64,
}

impl DirectionCut {
    /// The cut surface (the lower envelope of the legs, capped at height `top`) as a grid
    /// mesh: one row per section, `across + 1` points across each section's chord. `None`
    /// for an empty section or a degenerate grid.
    pub fn surface_mesh(&self, top: f64, across: usize) -> Option<geom::mesh::TriMesh> {
        let along = nalgebra::Vector2::new(self.direction[0], self.direction[1]);
        let dir_across = nalgebra::Vector2::new(self.across[0], self.across[1]);
        let mut v = Vec::new();
        for (s, lines) in self.sections.iter().zip(&self.lines) {
            let w_of = |p: &[f64; 3]| dir_across.dot(&nalgebra::Vector2::new(p[0], p[1]));
            let (first, last) = (s.polygon.first()?, s.polygon.last()?);
            let (w0, w1) = (w_of(first), w_of(last));
            for k in 0..=across {
                let w = w0 + (w1 - w0) * k as f64 / across as f64;
                let t = (w - self.w_mid) / self.w_half;
                let z = lines.iter().map(|l| l.a + l.m * t).fold(top, f64::min);
                let p = along * s.offset + dir_across * w;
                v.push(nalgebra::Vector3::new(p.x, p.y, z));
            }
        }
        let rows = self.sections.len();
        let n = (across + 1) as u32;
        let mut f = Vec::new();
        for i in 0..rows.saturating_sub(1) as u32 {
            for k in 0..across as u32 {
                let a = i * n + k;
                f.push([a, a + n, a + n + 1]);
                f.push([a, a + n + 1, a + 1]);
            }
        }
        geom::mesh::TriMesh::try_new(v, f).ok()
    }
}

/// The result of [`pre_cut`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PreCut {
    /// Per direction.
    pub directions: Vec<DirectionCut>,
    /// Table 2.1.
    pub volumes: Volumes,
    /// Design samples used per direction (inside the block and over the surface).
    pub samples: usize,
}

/// Progress of [`pre_cut`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Direction index.
    pub direction: usize,
    /// Assignment round.
    pub round: usize,
    /// Objective after it.
    pub objective: f64,
}

/// Finds the pre-cuts of `surface` in `block`.
///
/// # Errors
/// [`PreCutError::InvalidParameter`] for bad parameters; [`PreCutError::Placement`] when
/// the surface leaves the block or nothing of it is over the block;
/// [`PreCutError::Solver`] / [`PreCutError::NotVerified`] from the optimization.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use ruled::{pre_cut, Block, Params, PreCutError};
///
/// // a tilted plane: one straight cut along x removes all but a sliver above it
/// let plane = Surface::HeightField(HeightField::try_new(Expr::parse("0.4 + 0.1*x")?, (0.0, 2.0), (0.0, 1.0))?);
/// let block = Block { min: [0.0, 0.0, 0.0], max: [2.0, 1.0, 1.0] };
/// let params = Params { legs: 1, sections: 4, samples: 4, ..Params::default() };
/// let cut = pre_cut(&plane, &block, &params, &|_| {})?;
/// let d = &cut.directions[0];
/// assert!(d.clearance > 0.0); // the cut never dips below the design
/// let v = cut.volumes;
/// // volumes are shares of the block's: the model below z = 0.4 + 0.1·x is half of it,
/// // milling from the block removes the other half, after the cut only a sliver is left
/// assert!((v.model - 0.5).abs() < 1e-9 && (v.bounding_box - 0.5).abs() < 1e-9);
/// assert!(v.ruled >= 0.0 && v.ruled < 1e-3);
/// // parameters out of range are refused before anything runs
/// let bad = Params { legs: 0, ..params };
/// assert!(matches!(pre_cut(&plane, &block, &bad, &|_| {}), Err(PreCutError::InvalidParameter { name: "legs", .. })));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn pre_cut(
    surface: &Surface,
    block: &Block,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<PreCut> {
    validate(block, params)?;
    // computed in the block's unit frame, the same numbers in any unit
    let unit = unit::frame(block);
    let height = unit::height(&unit, surface)?;
    let params = Params {
        span: params.span.map(|s| unit.length(s)),
        ..params.clone()
    };
    let cut = pre_cut_in(
        &unit,
        &height,
        &unit::block(&unit, block),
        &params,
        progress,
    )?;
    Ok(unit::result(&unit, cut))
}

/// [`pre_cut`] in the unit frame `unit` (for messages in model units).
fn pre_cut_in(
    unit: &unit::UnitFrame,
    height: &Height,
    block: &Block,
    params: &Params,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<PreCut> {
    let mut directions = Vec::new();
    let mut samples_used = 0;
    for (di, &dir) in params.directions.iter().enumerate() {
        let frame = CutFrame::new(dir, block)?;
        let (legs, x, result, samples) =
            cut_direction(unit, &frame, height, block, params, di, progress)?;
        samples_used = samples;
        directions.push((frame, legs, x, result));
    }
    let cut = |x: f64, y: f64| -> f64 {
        directions
            .iter()
            .map(|(frame, legs, coef, _)| {
                let p = nalgebra::Vector2::new(x, y);
                let (u, w) = (frame.along.dot(&p), frame.across.dot(&p));
                legs.envelope(coef, &legs.basis(u.clamp(frame.u.0, frame.u.1)), w)
                    .0
            })
            .fold(f64::INFINITY, f64::min)
    };
    let volumes = volume::volumes(height, block, params.volume_grid, &cut)?;
    Ok(PreCut {
        directions: directions.into_iter().map(|d| d.3).collect(),
        volumes,
        samples: samples_used,
    })
}

/// The block's height.
fn height_of(block: &Block) -> f64 {
    block.max[2] - block.min[2]
}

/// The cut of direction `di` (frame `frame`): the legs, their coefficients in model units,
/// the result, and the number of samples the optimizer used.
fn cut_direction(
    unit: &unit::UnitFrame,
    frame: &CutFrame,
    height: &Height,
    block: &Block,
    params: &Params,
    di: usize,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<(Legs, Vec<f64>, DirectionCut, usize)> {
    let scale = block.scale();
    let z_top = block.max[2];
    // Normalised heights: (z − z_top)/scale, so the numbers the QP sees are O(1).
    let norm = |z: f64| (z - z_top) / scale;
    let (n, m, dense) = (params.sections, params.samples, params.check_density);
    let samples = grid_points(unit, frame, height, n, m, false, block)?;
    let check = grid_points(unit, frame, height, n * dense, m * dense, true, block)?;
    if samples.is_empty() {
        return Err(PreCutError::Placement(
            "no part of the surface lies over the block".into(),
        ));
    }
    let to_norm = |p: &Point| Point { f: norm(p.f), ..*p };
    let samples: Vec<Point> = samples.iter().map(to_norm).collect();
    let check: Vec<Point> = check.iter().map(to_norm).collect();
    let legs = Legs::new(
        params.legs,
        params.degree,
        params.controls,
        frame.u,
        frame.w,
    );
    let design = |u: f64, w: f64| -> Option<f64> {
        let p = frame.xy_on_block(u, w)?;
        height.at(p.x, p.y).map(norm)
    };
    let chord = |u: f64| frame.chord(u);
    let domain = solve::Domain {
        design: &design,
        chord: &chord,
        u: frame.u,
        step: (
            (frame.u.1 - frame.u.0) / (n * dense) as f64,
            (frame.w.1 - frame.w.0) / (m * dense) as f64,
        ),
        bulge: solve::bulge(&check),
    };
    let solved = solve::solve(
        &legs,
        &samples,
        &check,
        &domain,
        &SolveOptions {
            margin: params.margin,
            max_rounds: params.max_rounds,
            max_exchanges: 50,
            // bounds the run: a QP and its exchange take up to ~0.4 s on a 4 × 3 m block
            // at the default density
            max_qps: 3 * params.max_rounds.max(1),
            proximal: 1e-8,
            // from the floor (the table) to a block height above the top, over the span
            band: (
                -height_of(block) / scale,
                height_of(block) / scale,
                params
                    .span
                    .map_or(1.0, |t| (0.5 * t / legs.w_half).max(1.0)),
            ),
            direction: di,
        },
        &|round, objective| {
            progress(Progress {
                direction: di,
                round,
                objective,
            })
        },
    )?;
    // Back to model units: a = z_top + scale·a', m = scale·m'.
    let x: Vec<f64> = solved
        .x
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let is_a = (i / params.controls).is_multiple_of(2);
            if is_a {
                z_top + scale * v
            } else {
                scale * v
            }
        })
        .collect();
    let (sections, lines) = polygons(frame, &legs, &x, params);
    let result = DirectionCut {
        degree: legs.degree,
        knots: legs.knots().to_vec(),
        w_mid: legs.w_mid,
        w_half: legs.w_half,
        legs: (0..params.legs)
            .map(|j| {
                let k = params.controls;
                LegSpline {
                    a: x[2 * j * k..(2 * j + 1) * k].to_vec(),
                    m: x[(2 * j + 1) * k..(2 * j + 2) * k].to_vec(),
                }
            })
            .collect(),
        direction: [frame.along.x, frame.along.y, 0.0],
        across: [frame.across.x, frame.across.y, 0.0],
        u: frame.u,
        w: frame.w,
        sections,
        lines,
        rounds: solved.rounds,
        qps: solved.qps,
        constraint_points: solved.constraint_points,
        objective_history: solved.history.iter().map(|o| o * scale * scale).collect(),
        clearance: solved.clearance * scale,
    };
    Ok((legs, x, result, samples.len()))
}

/// The cut polygon and every leg's line at `sections + 1` planes from block end to block
/// end (planes where the block has no chord are left out).
fn polygons(
    frame: &CutFrame,
    legs: &Legs,
    x: &[f64],
    params: &Params,
) -> (Vec<SectionPolygon>, Vec<Vec<LegLine>>) {
    let mut sections = Vec::new();
    let mut lines = Vec::new();
    for s in 0..=params.sections {
        let u = frame.u.0 + (frame.u.1 - frame.u.0) * s as f64 / params.sections as f64;
        let Some((w0, w1)) = frame.chord(u) else {
            continue;
        };
        let (verts, which) = legs.polygon(x, u, w0, w1);
        let polygon = verts
            .iter()
            .map(|&(w, z)| {
                let p = frame.xy(u, w);
                [p.x, p.y, z]
            })
            .collect();
        let basis = legs.basis(u);
        lines.push(
            (0..params.legs)
                .map(|j| {
                    let (a, m) = legs.line(x, &basis, j);
                    LegLine { a, m }
                })
                .collect(),
        );
        sections.push(SectionPolygon {
            offset: u,
            polygon,
            legs: which,
        });
    }
    (sections, lines)
}

/// Design points on an `n × m` grid of the frame: slab centres (or, with `ends`, evenly
/// from end to end) along the cut and across each chord, where the surface is over the
/// block; with `ends`, then points along the block's faces. Checks the surface stays
/// inside the block.
fn grid_points(
    unit: &unit::UnitFrame,
    frame: &CutFrame,
    height: &Height,
    n: usize,
    m: usize,
    ends: bool,
    block: &Block,
) -> Result<Vec<Point>> {
    let at = |i: usize, count: usize, lo: f64, hi: f64| {
        if ends {
            lo + (hi - lo) * i as f64 / (count - 1).max(1) as f64
        } else {
            lo + (hi - lo) * (i as f64 + 0.5) / count as f64
        }
    };
    let count = |c: usize| if ends { c + 1 } else { c };
    let tol = 1e-9 * block.scale();
    let mut grid = Vec::new();
    for i in 0..count(n) {
        let u = at(i, count(n), frame.u.0, frame.u.1);
        let Some((w0, w1)) = frame.chord(u) else {
            continue;
        };
        for k in 0..count(m) {
            let w = at(k, count(m), w0, w1);
            // a chord's ends lie on the block's edge: moved onto it, not lost to rounding
            if let Some(p) = frame.xy_on_block(u, w) {
                grid.push((u, w, p));
            }
        }
    }
    if ends {
        // the check covers the block's faces too, end faces and sides, at the grid's
        // finer spacing: between the grid's lines a rotated frame's chord ends sweep the
        // faces, where the design must stay below every leg as well
        let step = ((frame.u.1 - frame.u.0) / n.max(1) as f64)
            .min((frame.w.1 - frame.w.0) / m.max(1) as f64);
        grid.extend(frame.perimeter(step));
    }
    let mut out = Vec::new();
    for (u, w, p) in grid {
        let Some(f) = height.at(p.x, p.y) else {
            continue;
        };
        if !f.is_finite() || f > block.max[2] + tol || f < block.min[2] - tol {
            let at = unit.to_model(nalgebra::Vector3::new(p.x, p.y, f));
            let (lo, hi) = (unit.origin.z, unit.to_model(block.max.into()).z);
            return Err(PreCutError::Placement(format!(
                "the surface is at z = {} over ({:.6}, {:.6}), outside the block's z range [{lo}, {hi}]",
                at.z, at.x, at.y
            )));
        }
        out.push(Point { u, w, f });
    }
    Ok(out)
}

fn validate(block: &Block, p: &Params) -> Result<()> {
    let size = block.size();
    if !(size.iter().all(|s| s.is_finite() && *s > 0.0) && block.min.iter().all(|v| v.is_finite()))
    {
        return Err(PreCutError::InvalidParameter {
            name: "block",
            reason: format!("size {:?} must be finite and positive", size.as_slice()),
        });
    }
    match p.problems().into_iter().next() {
        Some(e) => Err(PreCutError::InvalidParameter {
            name: e.field,
            reason: match e.index {
                Some(i) => format!("{} {i} {}", e.field, e.message),
                None => e.message,
            },
        }),
        None => Ok(()),
    }
}

pub use geom::ParamProblem;

impl Params {
    /// Every parameter [`pre_cut`] refuses, in field order (none: it runs).
    pub fn problems(&self) -> Vec<ParamProblem> {
        let mut out = Vec::new();
        let mut bad = |field: &'static str, index: Option<usize>, message: String| {
            out.push(ParamProblem {
                field,
                index,
                message,
            });
        };
        let mut range = |field: &'static str, v: usize, lo: usize, hi: usize| {
            if !(lo..=hi).contains(&v) {
                bad(field, None, format!("must be {lo}–{hi}, got {v}"));
            }
        };
        range("legs", self.legs, 1, 32);
        range("degree", self.degree, 1, 5);
        range("controls", self.controls, self.degree + 1, 64);
        range("sections", self.sections, 2, 500);
        range("samples", self.samples, 2, 500);
        range("check_density", self.check_density, 2, 32);
        range("max_rounds", self.max_rounds, 1, 10_000);
        range("volume_grid", self.volume_grid, 10, 4000);
        if !(self.margin.is_finite() && self.margin > 0.0 && self.margin < 0.01) {
            bad(
                "margin",
                None,
                format!("must be in (0, 0.01), got {:?}", self.margin),
            );
        }
        if self.directions.is_empty() {
            bad(
                "directions",
                None,
                "needs at least one cutting direction, e.g. [X]".into(),
            );
        }
        for (i, &[x, y]) in self.directions.iter().enumerate() {
            if !(x.is_finite() && y.is_finite()) || x.hypot(y) < 1e-9 {
                bad(
                    "directions",
                    Some(i),
                    "is not a direction in the xy plane (finite, not zero)".into(),
                );
            } else if self.directions[..i].iter().any(|&[a, b]| {
                (a * y - b * x).abs() < 1e-9 * x.hypot(y) * a.hypot(b) && a * x + b * y > 0.0
            }) {
                bad("directions", Some(i), "repeats an earlier direction".into());
            }
        }
        out
    }
}
