//! The solver of the numerical road: sequential quadratic programming.
//!
//! Each control point's offset from the input, in units of ε, is the unknown: a point in
//! the unit disc, a number in [−1, 1] (a tangent end's neighbour, on the tangent line), or
//! nothing (an end). Each step solves, with `clarabel`, the quadratic model of the
//! Lagrangian (the Hessian by central differences of the exact gradient, made positive
//! definite if it is not) under the exact discs (second-order cones), the exact segments
//! and the linearized length; an ℓ₁ merit function with a second-order correction takes
//! the step. The discs stay exact, so every iterate is feasible for them.
//!
//! The bending energy is nearly flat along the curve (sliding control points along it
//! barely changes the shape), so the plain problem has a valley of near-minimizers, and a
//! first-order method stops somewhere in it that depends on its path — in mm and in m
//! differently. A tie-break `τ·E₀·Σ|offset/ε|²/k` (E₀ the input's energy, k free points,
//! τ = 10⁻⁴) makes the minimizer unique, the one nearest the input, at a price of at most
//! 10⁻⁴ E₀ in energy. The active-set Newton end game (module `polish`) then converges to
//! it tightly; smaller τ leaves the valley so flat that Newton's steps shrink only
//! linearly there.
//!
//! Written here rather than with a general NLP crate: the problem is small, its
//! constraints are cones that `clarabel` takes exactly, and it is the method under study.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

use nalgebra::{DMatrix, DVector};

use super::basis::{energy_length, Node};
use crate::error::{DesignError, Result};

/// How one control point may move.
#[derive(Debug, Clone, Copy)]
pub(super) enum Freedom {
    /// An end point.
    Fixed,
    /// Along this unit direction, at most ε either way.
    Line([f64; 2]),
    /// Anywhere within ε.
    Disc,
}

/// One numerical-spline problem in normalized units (the input's length is 1).
pub(super) struct Problem<'a> {
    /// Quadrature nodes of the basis.
    pub nodes: &'a [Node],
    /// The input's control points.
    pub x: &'a [[f64; 2]],
    /// How each control point may move.
    pub freedom: Vec<Freedom>,
    /// ε in normalized units.
    pub eps: f64,
    /// Keep the length (1).
    pub fix_length: bool,
}

/// What the solver found.
pub(super) struct Solution {
    /// The result's control points.
    pub control: Vec<[f64; 2]>,
    /// SQP steps taken.
    pub iterations: usize,
    /// Whether the active-set polish reached the KKT point, feasible, with the length
    /// kept to [`LENGTH_TOL`].
    pub converged: bool,
}

/// Relative weight of the tie-break.
const TIE: f64 = 1e-4;
/// Most SQP steps.
const MAX_STEPS: usize = 200;
/// The SQP hands over to the active-set polish when its step is below this (units of ε).
const HANDOFF: f64 = 1e-6;
/// Largest relative length error of a converged result.
pub(super) const LENGTH_TOL: f64 = 1e-12;

/// The objective and the length's error with their gradients in the unknowns.
pub(super) struct Eval {
    /// Energy (times the length) plus tie-break.
    pub f: f64,
    /// Length − 1 (0 when the length is free).
    pub c: f64,
    /// ∇f.
    pub gf: Vec<f64>,
    /// ∇c.
    pub gc: Vec<f64>,
}

impl Problem<'_> {
    /// Unknowns: (control point, its freedom) per unknown, in order.
    fn unknowns(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (i, f) in self.freedom.iter().enumerate() {
            match f {
                Freedom::Fixed => {}
                Freedom::Line(_) => out.push((i, 0)),
                Freedom::Disc => out.extend([(i, 0), (i, 1)]),
            }
        }
        out
    }

    fn controls(&self, z: &[f64]) -> Vec<[f64; 2]> {
        let mut y = self.x.to_vec();
        let mut k = 0;
        for (i, f) in self.freedom.iter().enumerate() {
            match f {
                Freedom::Fixed => {}
                Freedom::Line(d) => {
                    y[i] = [
                        y[i][0] + self.eps * z[k] * d[0],
                        y[i][1] + self.eps * z[k] * d[1],
                    ];
                    k += 1;
                }
                Freedom::Disc => {
                    y[i] = [y[i][0] + self.eps * z[k], y[i][1] + self.eps * z[k + 1]];
                    k += 2;
                }
            }
        }
        y
    }

    /// Chain rule from control points to unknowns.
    fn pull_back(&self, g: &[[f64; 2]]) -> Vec<f64> {
        let mut out = Vec::new();
        for (i, f) in self.freedom.iter().enumerate() {
            match f {
                Freedom::Fixed => {}
                Freedom::Line(d) => out.push(self.eps * (g[i][0] * d[0] + g[i][1] * d[1])),
                Freedom::Disc => out.extend([self.eps * g[i][0], self.eps * g[i][1]]),
            }
        }
        out
    }

    /// f, c and their gradients at `z`, with tie-break weight `tie`.
    pub(super) fn eval(&self, z: &[f64], tie: f64) -> Eval {
        let (e, l, ge, gl) = energy_length(self.nodes, &self.controls(z));
        let mut gf = self.pull_back(&ge);
        for (g, v) in gf.iter_mut().zip(z) {
            *g += 2.0 * tie * v;
        }
        Eval {
            f: e + tie * z.iter().map(|v| v * v).sum::<f64>(),
            c: if self.fix_length { l - 1.0 } else { 0.0 },
            gf,
            gc: self.pull_back(&gl),
        }
    }

    /// The exact feasible point nearest `z`.
    pub(super) fn project(&self, z: &mut [f64]) {
        let mut k = 0;
        for f in &self.freedom {
            match f {
                Freedom::Fixed => {}
                Freedom::Line(_) => {
                    z[k] = z[k].clamp(-1.0, 1.0);
                    k += 1;
                }
                Freedom::Disc => {
                    let r = z[k].hypot(z[k + 1]);
                    if r > 1.0 {
                        z[k] /= r;
                        z[k + 1] /= r;
                    }
                    k += 2;
                }
            }
        }
    }
}

/// The Hessian of `f + ν c` by central differences of the exact gradient, kept to the
/// band where two unknowns share a knot span (control points at most 3 apart), symmetric.
fn hessian(
    pb: &Problem,
    unknowns: &[(usize, usize)],
    z: &[f64],
    nu: f64,
    tie: f64,
) -> DMatrix<f64> {
    let m = z.len();
    // a step of 10⁻⁵ of the length in the control points: truncation ~10⁻¹⁰, rounding
    // ~10⁻¹¹ relative
    let h = 1e-5 / pb.eps;
    let grad = |z: &[f64]| {
        let e = pb.eval(z, tie);
        e.gf.iter()
            .zip(&e.gc)
            .map(|(a, b)| a + nu * b)
            .collect::<Vec<_>>()
    };
    let mut hm = DMatrix::<f64>::zeros(m, m);
    let mut zz = z.to_vec();
    for j in 0..m {
        zz[j] = z[j] + h;
        let up = grad(&zz);
        zz[j] = z[j] - h;
        let dn = grad(&zz);
        zz[j] = z[j];
        for k in 0..m {
            if unknowns[j].0.abs_diff(unknowns[k].0) <= 3 {
                hm[(k, j)] = (up[k] - dn[k]) / (2.0 * h);
            }
        }
    }
    0.5 * (&hm + hm.transpose())
}

/// `hm + σI` for the least σ of 0, 10⁻⁸·d, 10⁻⁷·d, … (d the largest diagonal entry) that
/// makes it positive definite.
fn convexify(hm: &mut DMatrix<f64>) {
    let m = hm.nrows();
    let d = hm.diagonal().amax().max(1e-300);
    let mut sigma = 0.0;
    for round in 0..24 {
        let a = &*hm + DMatrix::<f64>::identity(m, m) * sigma;
        if a.cholesky().is_some() {
            break;
        }
        sigma = d * 10f64.powi(round - 8);
    }
    for i in 0..m {
        hm[(i, i)] += sigma;
    }
}

/// One QP with linear term `q`: the step, the length's multiplier and each unknown's
/// disc or segment multiplier.
fn qp_step(
    pb: &Problem,
    z: &[f64],
    hm: &DMatrix<f64>,
    q: &[f64],
    e: &Eval,
) -> Result<(Vec<f64>, f64, Vec<f64>)> {
    let m = z.len();
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for j in 0..m {
        for k in 0..=j {
            if hm[(k, j)] != 0.0 {
                rowval.push(k);
                nzval.push(hm[(k, j)]);
            }
        }
        colptr.push(rowval.len());
    }
    let pm = CscMatrix::new(m, m, colptr, rowval, nzval);
    // constraint rows: A d + s = b, s in the cones
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
    let mut b = Vec::new();
    let mut cones = Vec::new();
    if pb.fix_length {
        for (j, g) in e.gc.iter().enumerate() {
            cols[j].push((0, *g));
        }
        b.push(-e.c);
        cones.push(SupportedConeT::ZeroConeT(1));
    }
    let mut k = 0;
    for f in &pb.freedom {
        match f {
            Freedom::Fixed => {}
            Freedom::Line(_) => {
                cols[k].push((b.len(), 1.0));
                b.push(1.0 - z[k]);
                cols[k].push((b.len(), -1.0));
                b.push(1.0 + z[k]);
                cones.push(SupportedConeT::NonnegativeConeT(2));
                k += 1;
            }
            Freedom::Disc => {
                b.push(1.0);
                for v in 0..2 {
                    cols[k + v].push((b.len(), -1.0));
                    b.push(z[k + v]);
                }
                cones.push(SupportedConeT::SecondOrderConeT(3));
                k += 2;
            }
        }
    }
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for col in &cols {
        for &(r, v) in col {
            rowval.push(r);
            nzval.push(v);
        }
        colptr.push(rowval.len());
    }
    let am = CscMatrix::new(b.len(), m, colptr, rowval, nzval);
    let fail = |s: String| DesignError::Invalid(format!("numerical spline: QP {s}"));
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .tol_gap_abs(1e-11)
        .tol_gap_rel(1e-11)
        .tol_feas(1e-11)
        .build()
        .map_err(|e| fail(format!("{e:?}")))?;
    let mut solver = DefaultSolver::new(&pm, q, &am, &b, &cones, settings)
        .map_err(|e| fail(format!("{e:?}")))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {}
        s => return Err(fail(format!("{s:?}"))),
    }
    let dual = &solver.solution.z;
    let nu = if pb.fix_length { dual[0] } else { 0.0 };
    // each cone's multiplier of ½(|offset|² − 1) ≤ 0 (equal to that of |offset| ≤ 1 on the
    // boundary): the segment's two rows together, the disc's t row
    let mut mu = Vec::with_capacity(m);
    let mut row = usize::from(pb.fix_length);
    for f in &pb.freedom {
        match f {
            Freedom::Fixed => {}
            Freedom::Line(_) => {
                mu.push((dual[row] + dual[row + 1]).max(0.0));
                row += 2;
            }
            Freedom::Disc => {
                let v = dual[row].max(0.0);
                mu.extend([v, v]);
                row += 3;
            }
        }
    }
    Ok((solver.solution.x.clone(), nu, mu))
}

/// Solve `pb` from the input (offsets 0).
pub(super) fn solve(pb: &Problem) -> Result<Solution> {
    let unknowns = pb.unknowns();
    let m = unknowns.len();
    let mut z = vec![0.0; m];
    let free_points = pb
        .freedom
        .iter()
        .filter(|f| !matches!(f, Freedom::Fixed))
        .count()
        .max(1);
    let e0 = pb.eval(&z, 0.0).f;
    let tie = TIE * e0.max(1e-6) / free_points as f64;
    let mut e = pb.eval(&z, tie);
    let (mut nu, mut rho) = (0.0, 0.0f64);
    let mut mu = vec![0.0; m];
    let (mut iterations, mut converged) = (0, false);
    if m == 0 {
        converged = true;
    }
    for _ in 0..if m == 0 { 0 } else { MAX_STEPS } {
        iterations += 1;
        let mut hm = hessian(pb, &unknowns, &z, nu, tie);
        if hm.iter().any(|v| !v.is_finite()) {
            // the spline is near collapse (a zero speed) where the energy is singular
            break;
        }
        // terms that vanish where the QP's solution lies but make its model convex there:
        // the active discs' and segments' curvature μ·½(|offset + d|² − 1), and the
        // linearized length's ½ρ(gᵀd + c)²
        let mut q = e.gf.clone();
        for j in 0..m {
            hm[(j, j)] += mu[j];
            q[j] += mu[j] * z[j];
        }
        if pb.fix_length {
            let g2: f64 = e.gc.iter().map(|g| g * g).sum::<f64>().max(1e-300);
            let r = hm.diagonal().amax() / g2;
            let g = DVector::from_column_slice(&e.gc);
            hm += &g * g.transpose() * r;
            for (qj, gj) in q.iter_mut().zip(&e.gc) {
                *qj += r * e.c * gj;
            }
        }
        convexify(&mut hm);
        // a QP that clarabel cannot finish (extreme scales) ends the SQP at its last
        // feasible point; the polish may still finish from there
        let Ok((d, nu_new, mu_new)) = qp_step(pb, &z, &hm, &q, &e) else {
            break;
        };
        nu = nu_new;
        let step = d.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if step < HANDOFF && e.c.abs() < 1e-9 {
            break;
        }
        rho = rho.max(2.0 * nu.abs() + 1e-12);
        let merit = |e: &Eval| e.f + rho * e.c.abs();
        let slope: f64 = e.gf.iter().zip(&d).map(|(g, v)| g * v).sum::<f64>() - rho * e.c.abs();
        let trial_at = |alpha: f64, extra: Option<&[f64]>| {
            let mut t: Vec<f64> = z
                .iter()
                .zip(&d)
                .enumerate()
                .map(|(j, (a, v))| a + alpha * v + extra.map_or(0.0, |x| x[j]))
                .collect();
            pb.project(&mut t);
            let ev = pb.eval(&t, tie);
            (t, ev)
        };
        let phi = merit(&e);
        let mut accepted = None;
        let (t, ev) = trial_at(1.0, None);
        if merit(&ev) <= phi + 1e-4 * slope {
            accepted = Some((t, ev));
        } else if pb.fix_length {
            // second-order correction: back onto the length along its gradient
            let g2: f64 = e.gc.iter().map(|g| g * g).sum::<f64>().max(1e-300);
            let corr: Vec<f64> = e.gc.iter().map(|g| -g * ev.c / g2).collect();
            let (t, ev2) = trial_at(1.0, Some(&corr));
            if merit(&ev2) <= phi + 1e-4 * slope {
                accepted = Some((t, ev2));
            }
        }
        if accepted.is_none() {
            let mut alpha = 0.5;
            for _ in 0..40 {
                let (t, ev) = trial_at(alpha, None);
                if merit(&ev) <= phi + 1e-4 * alpha * slope {
                    accepted = Some((t, ev));
                    break;
                }
                alpha *= 0.5;
            }
        }
        let Some((t, ev)) = accepted else {
            if mu.iter().any(|v| *v != 0.0) {
                // the cones' curvature terms come from the last QP's multipliers; when
                // they spoil descent, step once without them
                mu.iter_mut().for_each(|v| *v = 0.0);
                continue;
            }
            // no descent left: rounding has the last word
            break;
        };
        z = t;
        e = ev;
        mu = mu_new;
    }
    if m > 0 {
        let feasible = |z: &[f64]| {
            let mut t = z.to_vec();
            pb.project(&mut t);
            t.iter().zip(z).all(|(a, b)| (a - b).abs() <= 1e-12)
        };
        let polished = super::polish::polish(pb, &z, nu, tie).filter(|zp| {
            let ep = pb.eval(zp, tie);
            ep.f <= e.f + 1e-9 * e.f.abs() && ep.c.abs() < LENGTH_TOL && feasible(zp)
        });
        if let Some(mut zp) = polished {
            pb.project(&mut zp);
            z = zp;
            converged = true;
        }
    }
    Ok(Solution {
        control: pb.controls(&z),
        iterations,
        converged,
    })
}
