//! The purely numerical road to an elastica ("Hot Blade Cuttings" §5.2, eq. 13): the input
//! curve is written as a clamped cubic B-spline `x` on a refined uniform knot vector (a
//! least-squares fit of its points, ends interpolated), and a spline `y` on the same basis
//! minimizes the bending energy ½∫κ² ds while every control point stays within ε of its
//! counterpart. The end points are kept; optionally the end tangents (the second and
//! second-to-last control points move along them) and the length.
//!
//! The paper bounds each coordinate of `xᵢ − yᵢ`; we bound its length (a disc), so that
//! the result does not depend on how the curve is turned. Either way the difference of the
//! two curves is a spline whose control points lie in the disc, so the curves are within
//! ε of each other everywhere (convex hull).
//!
//! Solver: sequential quadratic programming with `clarabel` (the discs as second-order
//! cones, the length linearized), in units where the input is 1 long, with a tie-break
//! that makes the minimizer unique (module `sqp`). The energy and its gradient are exact for the
//! spline (module `basis`).

use crate::error::{DesignError, Result};

/// The refined spline: basis, energy, length and the least-squares fit.
mod basis;
/// The active-set Newton end game.
mod polish;
/// The SQP solver.
mod sqp;

use basis::{energy_length, fit, Basis};
use sqp::Freedom;

/// Most control points of the refined spline: the solver's work grows with their cube
/// (a dense Newton system per step), and the paper's curves need a few dozen.
pub const MAX_CONTROL_POINTS: usize = 96;

/// Settings of the numerical spline approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumericalParams {
    /// Largest distance of a control point from the input's, in the input's units.
    pub epsilon: f64,
    /// Control points of the refined spline (≥ 6).
    pub control_points: usize,
    /// Keep the end tangents of the input spline.
    pub fix_tangents: bool,
    /// Keep the length of the input spline.
    pub fix_length: bool,
}

/// What the numerical approach found.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct NumericalResult {
    /// The input as a spline on the refined basis: its control points.
    pub input_control: Vec<[f64; 2]>,
    /// The result's control points.
    pub control: Vec<[f64; 2]>,
    /// Largest distance of an input point from the input spline (the refinement's error).
    pub input_fit_distance: f64,
    /// Largest distance of an input point from the result.
    pub max_distance: f64,
    /// Largest distance of a control point from the input's (≤ ε).
    pub max_control_offset: f64,
    /// Control points whose constraint is active (offset within 10⁻⁶ of ε).
    pub active_constraints: usize,
    /// ½∫κ² ds of the input spline and of the result (per unit length: times the length,
    /// dimensionless).
    pub energy_before: f64,
    /// See `energy_before`.
    pub energy_after: f64,
    /// Lengths of the input spline and of the result.
    pub input_length: f64,
    /// See `input_length`.
    pub length: f64,
    /// SQP steps taken.
    pub iterations: usize,
    /// Whether the SQP step fell below 10⁻⁹ ε with the length kept to 10⁻¹² (else the step
    /// bound or a line search that found no descent stopped it).
    pub converged: bool,
    /// The eq. (11) residual of the result ([`crate::proxy::affine_curvature_residual`]):
    /// how far it is from an elastica (0 for one).
    pub eq11_residual: f64,
    /// The result at 200 points equally spaced in its parameter.
    pub samples: Vec<[f64; 2]>,
}

/// The numerical spline approach on `points` (≥ 4, the curve's samples in order).
///
/// ```
/// use design::numerical::{numerical_spline, NumericalParams};
/// // a quarter of a circle of radius 1: its energy can only drop within ε
/// let pts: Vec<[f64; 2]> = (0..50)
///     .map(|i| { let a = 1.5708 * i as f64 / 49.0; [a.cos(), a.sin()] })
///     .collect();
/// let p = NumericalParams { epsilon: 0.01, control_points: 12, fix_tangents: false, fix_length: false };
/// let r = numerical_spline(&pts, &p).unwrap();
/// assert!(r.energy_after < r.energy_before);
/// assert!(r.max_control_offset <= 0.01 + 1e-12);
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] for too few or coincident points, a non-positive ε, fewer
/// than 6 control points or more than the points or [`MAX_CONTROL_POINTS`] allow, or a
/// curve whose energy cannot be evaluated (e.g. ε so large that the spline collapses).
pub fn numerical_spline(points: &[[f64; 2]], p: &NumericalParams) -> Result<NumericalResult> {
    if points.len() < 4 || points.iter().flatten().any(|v| !v.is_finite()) {
        return Err(DesignError::Invalid("need at least 4 finite points".into()));
    }
    if !(p.epsilon > 0.0) || !p.epsilon.is_finite() {
        return Err(DesignError::Invalid(format!(
            "epsilon must be positive, got {}",
            p.epsilon
        )));
    }
    if p.control_points < 6 || p.control_points > points.len().min(MAX_CONTROL_POINTS) {
        return Err(DesignError::Invalid(format!(
            "control_points must be 6 to the number of points ({}) and at most {MAX_CONTROL_POINTS}, got {}",
            points.len(),
            p.control_points
        )));
    }
    // chord-length parameters
    let mut t = geom::polyline::chord_lengths(points);
    let total = t[t.len() - 1];
    if !(total > 0.0) {
        return Err(DesignError::Invalid("the points coincide".into()));
    }
    t.iter_mut().for_each(|v| *v /= total);
    let basis = Basis::new(p.control_points);
    let x = fit(&basis, points, &t)?;
    let nodes = basis.nodes();
    let n = x.len();
    let unit = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let r = dx.hypot(dy);
        (r > 0.0).then(|| [dx / r, dy / r])
    };
    let tangents = if p.fix_tangents {
        (unit(x[0], x[1]), unit(x[n - 1], x[n - 2]))
    } else {
        (None, None)
    };
    let (e0, l0, _, _) = energy_length(&nodes, &x);
    if !(l0 > 0.0) || !e0.is_finite() {
        return Err(DesignError::Invalid(
            "the refined spline of the points is degenerate".into(),
        ));
    }
    // normalized units: the input spline starts at the origin and is 1 long, so that the
    // solver sees the same numbers in mm and in m
    let origin = x[0];
    let to_unit = |q: &[f64; 2]| [(q[0] - origin[0]) / l0, (q[1] - origin[1]) / l0];
    let xn: Vec<[f64; 2]> = x.iter().map(to_unit).collect();
    let freedom = (0..n)
        .map(|i| {
            let tangent = match i {
                1 => tangents.0,
                i if i == n - 2 => tangents.1,
                _ => None,
            };
            if i == 0 || i == n - 1 {
                Freedom::Fixed
            } else if let Some(d) = tangent {
                Freedom::Line(d)
            } else {
                Freedom::Disc
            }
        })
        .collect();
    let solution = sqp::solve(&sqp::Problem {
        nodes: &nodes,
        x: &xn,
        freedom,
        eps: p.epsilon / l0,
        fix_length: p.fix_length,
    })?;
    let mut y: Vec<[f64; 2]> = solution
        .control
        .iter()
        .map(|q| [origin[0] + q[0] * l0, origin[1] + q[1] * l0])
        .collect();
    // the ends are the input's, bit for bit
    y[0] = x[0];
    y[n - 1] = x[n - 1];
    let (iterations, converged) = (solution.iterations, solution.converged);
    let (e1, l1, _, _) = energy_length(&nodes, &y);
    let offset = |i: usize| (y[i][0] - x[i][0]).hypot(y[i][1] - x[i][1]);
    let max_control_offset = (0..n).map(offset).fold(0.0, f64::max);
    let active_constraints = (1..n - 1)
        .filter(|&i| offset(i) >= p.epsilon * (1.0 - 1e-6))
        .count();
    let dist = |c: &[[f64; 2]]| {
        points
            .iter()
            .zip(&t)
            .map(|(q, &ti)| {
                let r = basis.point(c, ti);
                (r[0] - q[0]).hypot(r[1] - q[1])
            })
            .fold(0.0, f64::max)
    };
    let rows: Vec<([f64; 2], f64)> = (0..=200)
        .map(|i| {
            let ti = i as f64 / 200.0;
            let (f, d) = basis.eval(ti);
            let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
            for j in 0..4 {
                for k in 0..2 {
                    a[k] += d[1][j] * y[f + j][k];
                    b[k] += d[2][j] * y[f + j][k];
                }
            }
            let speed = a[0].hypot(a[1]).max(1e-300);
            (
                basis.point(&y, ti),
                (a[0] * b[1] - a[1] * b[0]) / speed.powi(3),
            )
        })
        .collect();
    Ok(NumericalResult {
        eq11_residual: crate::proxy::affine_curvature_residual(&rows, l1),
        input_fit_distance: dist(&x),
        max_distance: dist(&y),
        max_control_offset,
        active_constraints,
        energy_before: e0 * l0,
        energy_after: e1 * l0,
        input_length: l0,
        length: l1,
        iterations,
        converged,
        samples: (0..200)
            .map(|i| basis.point(&y, i as f64 / 199.0))
            .collect(),
        input_control: x,
        control: y,
    })
}
