//! The optimization of eq. 2.11 for one cutting direction, in the legs' line form.
//!
//! Minimise `Σ (S(u_k, w_k) − f_k)²` over the samples, `S` the lower envelope of the legs,
//! subject to every leg lying on or above every design point (plus a margin). The only
//! non-convex part is which leg is lowest where, so the solver alternates (as k-means
//! does): with each sample assigned to a leg, the problem is a convex QP — solved by
//! `clarabel`'s interior-point method, the thesis' own solver family (Wächter & Biegler 2005) — and then
//! each sample is reassigned to the leg that is lowest over it. Every iterate is feasible
//! and the objective never increases (a sample's lowest leg is at most its assigned one,
//! and all lie above it). A small proximal term keeps legs that no sample is assigned to
//! where they were, so the QP stays strictly convex.
//!
//! The constraint is imposed on a set of points that starts as the samples and grows by
//! exchange: after each solve the legs are checked on a grid `check_density` times
//! denser in both directions; points where a leg comes closer than half the margin are
//! added and the QP is solved again, until none is left.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};

use crate::error::{PreCutError, Result};
use crate::legs::Legs;

/// A design point in frame coordinates (`f` normalised as the caller chose).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Along the cut.
    pub u: f64,
    /// Across the block.
    pub w: f64,
    /// Height of the design surface.
    pub f: f64,
}

/// Options of [`solve`] (lengths in the caller's normalised units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    /// Clearance every leg keeps above the constraint points.
    pub margin: f64,
    /// Most assignment rounds.
    pub max_rounds: usize,
    /// Most exchange rounds per assignment round.
    pub max_exchanges: usize,
    /// Most QPs in all: past it, the alternation stops with the last round's verified
    /// legs (each round ends verified, so what it returns is as safe, if less tight). The
    /// first round always finishes (at most `max_exchanges` + 1 QPs).
    pub max_qps: usize,
    /// Weight of the proximal term.
    pub proximal: f64,
    /// `(low, high, reach)`: every leg's line stays within the height range `low..high`
    /// for `|s| ≤ reach` (reach ≥ 1: the frame's width, or the wire's towers beyond it),
    /// imposed on the B-spline controls (the curve lies in their convex hull). Where a
    /// rotated block's chord is short (near its corners) nothing else holds the line's
    /// slope, and the wire, extended to the towers, would leave any machine's travel.
    pub band: (f64, f64, f64),
    /// Index of the direction (for errors).
    pub direction: usize,
}

/// What [`solve`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Solved {
    /// The unknowns (see [`Legs`]).
    pub x: Vec<f64>,
    /// Assignment rounds run.
    pub rounds: usize,
    /// QPs solved.
    pub qps: usize,
    /// Constraint points at the end (samples and exchanged points).
    pub constraint_points: usize,
    /// `Σ (S − f)²` over the samples at the end.
    pub objective: f64,
    /// Objective after each round.
    pub history: Vec<f64>,
    /// Smallest `leg − f` over the check grid (≥ margin/2 > 0 on success).
    pub clearance: f64,
}

/// Runs the alternation from an assignment of the samples to legs by equal `w` strips.
///
/// # Errors
/// [`PreCutError::Solver`] when the QP solver fails; [`PreCutError::NotVerified`] when
/// the exchange rounds run out with a leg below a check point.
pub fn solve(
    legs: &Legs,
    samples: &[Point],
    check: &[Point],
    domain: &Domain<'_>,
    opt: &SolveOptions,
    progress: &dyn Fn(usize, f64),
) -> Result<Solved> {
    let sample_basis: Vec<Vec<f64>> = samples.iter().map(|p| legs.basis(p.u)).collect();
    let check_basis: Vec<Vec<f64>> = check.iter().map(|p| legs.basis(p.u)).collect();
    let mut assign: Vec<usize> = samples
        .iter()
        .map(|p| {
            let t = (legs.s(p.w) + 1.0) / 2.0;
            ((t * legs.legs as f64).floor().max(0.0) as usize).min(legs.legs - 1)
        })
        .collect();
    let mut constraints: Vec<Point> = Vec::new(); // beyond the samples
    let mut x = vec![0.0; legs.unknowns()];
    let mut history = Vec::new();
    let mut qps = 0;
    let mut clearance = f64::NEG_INFINITY;
    let mut rounds = 0;
    // the last round's verified legs: what a run that reaches its QP budget returns
    let mut verified: Option<(Vec<f64>, f64)> = None;
    'rounds: for round in 0..opt.max_rounds {
        rounds = round + 1;
        // Solve with exchange until the check grid is clear.
        let mut exchanges = 0;
        loop {
            if qps >= opt.max_qps {
                if let Some((vx, vc)) = verified.take() {
                    (x, clearance) = (vx, vc);
                    rounds -= 1;
                    break 'rounds;
                }
            }
            x = qp(
                legs,
                samples,
                &sample_basis,
                &assign,
                &constraints,
                &x,
                opt,
                round,
            )?;
            qps += 1;
            let (worst, low) = exchange_points(legs, &x, check, &check_basis, domain, opt.margin);
            clearance = worst;
            if low.is_empty() {
                break;
            }
            exchanges += 1;
            if exchanges > opt.max_exchanges {
                let (excess, leg) = deepest(legs, &x, check, &check_basis);
                return Err(PreCutError::NotVerified {
                    direction: opt.direction,
                    leg,
                    excess,
                    tolerance: 0.0,
                });
            }
            constraints.extend(low);
        }
        let objective = objective(legs, &x, samples, &sample_basis);
        history.push(objective);
        progress(round, objective);
        verified = Some((x.clone(), clearance));
        let next: Vec<usize> = samples
            .iter()
            .zip(&sample_basis)
            .map(|(p, b)| legs.envelope(&x, b, p.w).1)
            .collect();
        if next == assign {
            break;
        }
        assign = next;
    }
    Ok(Solved {
        objective: history.last().copied().unwrap_or(f64::NAN),
        x,
        rounds,
        qps,
        constraint_points: samples.len() + constraints.len(),
        history,
        clearance,
    })
}

/// `Σ (S − f)²` over the samples.
fn objective(legs: &Legs, x: &[f64], samples: &[Point], basis: &[Vec<f64>]) -> f64 {
    samples
        .iter()
        .zip(basis)
        .map(|(p, b)| (legs.envelope(x, b, p.w).0 - p.f).powi(2))
        .sum()
}

/// Where the design is at or above a leg, for the exchange: the design function over
/// the block's footprint in frame coordinates.
pub struct Domain<'a> {
    /// `f(u, w)` (normalised), `None` off the surface.
    pub design: &'a (dyn Fn(f64, f64) -> Option<f64> + Sync),
    /// The `w` chord of the block at `u`.
    pub chord: &'a (dyn Fn(f64) -> Option<(f64, f64)> + Sync),
    /// `u` range of the block.
    pub u: (f64, f64),
    /// Spacing of the check grid along `u` and `w` (the search's first step).
    pub step: (f64, f64),
    /// How far the design may rise between neighbouring check points above the higher
    /// of them, at most ([`bulge`]): the local searches start from every check point
    /// within that (and a few margins) of a leg.
    pub bulge: f64,
}

/// The largest rise of the design between check points above their chord, estimated from
/// second differences along each row of equal `u` and across rows at the same index:
/// `|f₀ − 2f₁ + f₂| / 8` per triple, the sagitta of a parabola through them.
pub fn bulge(check: &[Point]) -> f64 {
    let mut rows: Vec<&[Point]> = Vec::new();
    let mut start = 0;
    for i in 1..=check.len() {
        if i == check.len() || check[i].u != check[start].u {
            rows.push(&check[start..i]);
            start = i;
        }
    }
    let second = |a: f64, b: f64, c: f64| (a - 2.0 * b + c).abs() / 8.0;
    let mut most: f64 = 0.0;
    for r in &rows {
        for t in r.windows(3) {
            most = most.max(second(t[0].f, t[1].f, t[2].f));
        }
    }
    for t in rows.windows(3) {
        if t[0].len() == t[1].len() && t[1].len() == t[2].len() {
            for ((a, b), c) in t[0].iter().zip(t[1]).zip(t[2]) {
                most = most.max(second(a.f, b.f, c.f));
            }
        }
    }
    most
}

/// Candidates (check points closest to a leg) searched per exchange round, besides the
/// closest of each region (see [`REGIONS`]).
const SEARCH_STARTS: usize = 256;

/// The block's frame is split into `REGIONS × REGIONS` cells; in each, every leg's closest
/// approach to the design gets a search of its own, so a cluster of near points in one
/// place (a long trough, the faces) cannot take every start while a bulge elsewhere goes
/// unsearched.
const REGIONS: usize = 16;

/// Most compass moves at one step size before it is halved anyway.
const MOVES_PER_STEP: usize = 8;

/// The smallest `leg − f` seen, and the points to add as constraints: from the check
/// points where some leg comes within `margin` of the design, the closest ones are
/// taken as starts of a local search for the maximum of `f − leg` (compass search,
/// shrinking from the grid step to 1e-7 of it), and every point found with
/// `f − leg > −margin/2` is returned.
fn exchange_points(
    legs: &Legs,
    x: &[f64],
    check: &[Point],
    basis: &[Vec<f64>],
    domain: &Domain<'_>,
    margin: f64,
) -> (f64, Vec<Point>) {
    let mut worst = f64::INFINITY;
    let mut near: Vec<(f64, usize, usize)> = Vec::new();
    // between check points the design may rise above them by up to the bulge: a point
    // that close is near too
    let reach = 4.0 * margin + 2.0 * domain.bulge;
    for (i, (p, b)) in check.iter().zip(basis).enumerate() {
        for j in 0..legs.legs {
            let gap = legs.height(x, b, p.w, j) - p.f;
            worst = worst.min(gap);
            if gap < reach {
                near.push((gap, i, j));
            }
        }
    }
    // closest first; gaps equal to 10⁻¹² (normalised heights: rounding, which differs with
    // the unit of length) count as ties and keep the grid's order
    let key = |g: f64| (g * 1e12).round();
    near.sort_by(|a, b| {
        key(a.0)
            .total_cmp(&key(b.0))
            .then(a.1.cmp(&b.1))
            .then(a.2.cmp(&b.2))
    });
    let gap_at = |u: f64, w: f64, j: usize| -> Option<(f64, f64)> {
        let (w0, w1) = (domain.chord)(u)?;
        if u < domain.u.0 || u > domain.u.1 || w < w0 || w > w1 {
            return None;
        }
        let f = (domain.design)(u, w)?;
        Some((legs.height(x, &legs.basis(u), w, j) - f, f))
    };
    let mut out: Vec<Point> = Vec::new();
    // every (region, leg)'s closest point, then the closest others, in `near`'s order
    let (w_lo, w_hi) = check
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
            (a.0.min(p.w), a.1.max(p.w))
        });
    let cell = |lo: f64, hi: f64, v: f64| {
        let r = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
        ((r * REGIONS as f64) as usize).min(REGIONS - 1)
    };
    let mut first = std::collections::BTreeSet::new();
    let mut chosen = vec![false; near.len()];
    for (k, &(_, i, j)) in near.iter().enumerate() {
        let key = (
            cell(domain.u.0, domain.u.1, check[i].u),
            cell(w_lo, w_hi, check[i].w),
            j,
        );
        if first.insert(key) {
            chosen[k] = true;
        }
    }
    let mut extra = 0;
    for c in chosen.iter_mut() {
        if !*c && extra < SEARCH_STARTS {
            *c = true;
            extra += 1;
        }
    }
    let starts = near
        .iter()
        .zip(&chosen)
        .filter(|(_, c)| **c)
        .map(|(n, _)| n);
    for &(gap, i, j) in starts {
        let (mut u, mut w, mut g) = (check[i].u, check[i].w, gap);
        let mut f = check[i].f;
        let (mut hu, mut hw) = domain.step;
        let stop = 1e-7 * domain.step.0.max(domain.step.1);
        // moves at one step size, at most: along an oblique trough the gap keeps falling
        // a little at every step, and an unbounded walk at a tiny step crossed the block
        // in millions of steps (a default PreCut ran for hours)
        let mut moves_here = 0;
        while hu.max(hw) > stop {
            let mut moved = false;
            for (du, dw) in [
                (1.0, 0.0),
                (-1.0, 0.0),
                (0.0, 1.0),
                (0.0, -1.0),
                (1.0, 1.0),
                (-1.0, -1.0),
                (1.0, -1.0),
                (-1.0, 1.0),
            ] {
                if let Some((g2, f2)) = gap_at(u + du * hu, w + dw * hw, j) {
                    if g2 < g {
                        (u, w, g, f) = (u + du * hu, w + dw * hw, g2, f2);
                        moved = true;
                    }
                }
            }
            moves_here += 1;
            if !moved || moves_here >= MOVES_PER_STEP {
                hu /= 2.0;
                hw /= 2.0;
                moves_here = 0;
            }
        }
        worst = worst.min(g);
        // the start's local maximum, or the start itself where the search found none below
        // it: the constraint set grew by both per start before (11 000 points on a rotated
        // cut, a QP of seconds); points already added (to rounding) are not added again
        let radius = 1e-9 * (domain.step.0 + domain.step.1);
        let fresh = |out: &[Point], u: f64, w: f64| {
            out.iter()
                .all(|p| (p.u - u).abs() + (p.w - w).abs() > radius)
        };
        if g < margin / 2.0 && fresh(&out, u, w) {
            out.push(Point { u, w, f });
        } else if gap < margin / 2.0 && fresh(&out, check[i].u, check[i].w) {
            out.push(check[i]);
        }
    }
    (worst, out)
}

/// The deepest violation on the check grid: `(f − leg, leg)`.
fn deepest(legs: &Legs, x: &[f64], check: &[Point], basis: &[Vec<f64>]) -> (f64, usize) {
    check
        .iter()
        .zip(basis)
        .map(|(p, b)| {
            let (h, j) = legs.envelope(x, b, p.w);
            (p.f - h, j)
        })
        .fold((f64::NEG_INFINITY, 0), |a, c| if c.0 > a.0 { c } else { a })
}

/// One convex QP: least squares of the assigned legs to the samples, proximal term,
/// every leg above every sample and every exchanged check point by the margin.
#[allow(clippy::too_many_arguments)]
fn qp(
    legs: &Legs,
    samples: &[Point],
    sample_basis: &[Vec<f64>],
    assign: &[usize],
    constraints: &[Point],
    prev: &[f64],
    opt: &SolveOptions,
    round: usize,
) -> Result<Vec<f64>> {
    let n = legs.unknowns();
    // P = RᵀR + ρI (dense: n is a few hundred at most), q = −(Rᵀf + ρ·prev).
    let mut p = vec![0.0; n * n];
    let mut q: Vec<f64> = prev.iter().map(|v| -opt.proximal * v).collect();
    for ((pt, b), &j) in samples.iter().zip(sample_basis).zip(assign) {
        let row = legs.row(b, pt.w, j);
        for &(c1, v1) in &row {
            q[c1] -= pt.f * v1;
            for &(c2, v2) in &row {
                p[c1 * n + c2] += v1 * v2;
            }
        }
    }
    for i in 0..n {
        p[i * n + i] += opt.proximal;
    }
    // Upper triangle in CSC.
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for c in 0..n {
        for r in 0..=c {
            let v = p[r * n + c];
            if v != 0.0 {
                rowval.push(r);
                nzval.push(v);
            }
        }
        colptr.push(rowval.len());
    }
    let pm = CscMatrix::new(n, n, colptr, rowval, nzval);
    // −leg ≤ −(f + margin) for every leg at every constraint point.
    let points = samples
        .iter()
        .zip(sample_basis)
        .map(|(p, b)| (*p, b.clone()))
        .chain(constraints.iter().map(|p| (*p, legs.basis(p.u))));
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut b = Vec::new();
    for (pt, basis) in points {
        for j in 0..legs.legs {
            let r = b.len();
            for (c, v) in legs.row(&basis, pt.w, j) {
                cols[c].push((r, -v));
            }
            b.push(-(pt.f + opt.margin));
        }
    }
    // band: low ≤ a ± reach·m ≤ high for every control of every leg
    let k = legs.controls;
    for j in 0..legs.legs {
        for c in 0..k {
            let (a, slope) = (2 * j * k + c, (2 * j + 1) * k + c);
            for side in [-1.0, 1.0] {
                for (sign, bound) in [(1.0, opt.band.1), (-1.0, -opt.band.0)] {
                    let r = b.len();
                    cols[a].push((r, sign));
                    cols[slope].push((r, sign * side * opt.band.2));
                    b.push(bound);
                }
            }
        }
    }
    let m = b.len();
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for col in &cols {
        for &(r, v) in col {
            rowval.push(r);
            nzval.push(v);
        }
        colptr.push(rowval.len());
    }
    let am = CscMatrix::new(m, n, colptr, rowval, nzval);
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .build()
        .map_err(|e| solver_error(format!("{e:?}"), opt, round))?;
    let cones = [NonnegativeConeT(m)];
    let mut solver = DefaultSolver::new(&pm, &q, &am, &b, &cones, settings)
        .map_err(|e| solver_error(format!("{e:?}"), opt, round))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(solver.solution.x.clone()),
        s => Err(solver_error(format!("{s:?}"), opt, round)),
    }
}

fn solver_error(status: String, opt: &SolveOptions, round: usize) -> PreCutError {
    PreCutError::Solver {
        status,
        direction: opt.direction,
        round,
    }
}
