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
//! Solver: an augmented Lagrangian for the length (when fixed) around projected gradient
//! descent with Barzilai–Borwein steps and an Armijo backtracking along the projection
//! arc — the constraints are discs and segments, whose projections are exact. The energy
//! and its gradient are exact for the spline (Gauss–Legendre, 5 nodes per knot span).
//! Written here because the problem is small (tens of points), its constraints are
//! projections, and it is the method under study.

use serde::Serialize;

use crate::bezier::GAUSS;
use crate::error::{DesignError, Result};

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
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// Projected-gradient iterations, all outer rounds together.
    pub iterations: usize,
    /// Whether the optimality test was met (else the iteration bound stopped it).
    pub converged: bool,
    /// The eq. (11) residual of the result ([`crate::proxy::affine_curvature_residual`]):
    /// how far it is from an elastica (0 for one).
    pub eq11_residual: f64,
    /// The result at 200 points equally spaced in its parameter.
    pub samples: Vec<[f64; 2]>,
}

/// A clamped uniform cubic B-spline basis with `n` control points on [0, 1].
struct Basis {
    n: usize,
    knots: Vec<f64>,
}

/// One quadrature node: weight, first control index, basis values, first and second
/// derivatives of the four basis functions there.
struct Node {
    w: f64,
    first: usize,
    d1: [f64; 4],
    d2: [f64; 4],
}

impl Basis {
    fn new(n: usize) -> Self {
        let spans = n - 3;
        let mut knots = vec![0.0; 4];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend([1.0; 4]);
        Self { n, knots }
    }

    /// The span holding `t` and the values and two derivatives of its four basis
    /// functions (Cox–de Boor).
    fn eval(&self, t: f64) -> (usize, [[f64; 4]; 3]) {
        let p = 3;
        let span = (p..self.n)
            .rev()
            .find(|&i| self.knots[i] <= t)
            .unwrap_or(p)
            .min(self.n - 1);
        let k = &self.knots;
        // basis functions of degrees 0..3 at t, as a triangle (The NURBS Book A2.3, with
        // derivatives from the degree-2 and degree-1 functions)
        let mut ndu = [[0.0f64; 4]; 4];
        ndu[0][0] = 1.0;
        let (mut left, mut right) = ([0.0; 4], [0.0; 4]);
        for j in 1..=p {
            left[j] = t - k[span + 1 - j];
            right[j] = k[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                ndu[j][r] = right[r + 1] + left[j - r];
                let temp = ndu[r][j - 1] / ndu[j][r];
                ndu[r][j] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            ndu[j][j] = saved;
        }
        let mut ders = [[0.0f64; 4]; 3];
        for (j, d) in ders[0].iter_mut().enumerate() {
            *d = ndu[j][p];
        }
        let mut a = [[0.0f64; 4]; 2];
        for r in 0..=p {
            let (mut s1, mut s2) = (0usize, 1usize);
            a[0][0] = 1.0;
            for kk in 1..=2usize {
                let mut d = 0.0;
                let rk = r as isize - kk as isize;
                let pk = p - kk;
                if r >= kk {
                    a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                    d = a[s2][0] * ndu[rk as usize][pk];
                }
                let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
                let j2 = if r as isize - 1 <= pk as isize {
                    kk - 1
                } else {
                    p - r
                };
                for j in j1..=j2 {
                    let idx = (rk + j as isize) as usize;
                    a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                    d += a[s2][j] * ndu[idx][pk];
                }
                if r <= pk {
                    a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                    d += a[s2][kk] * ndu[r][pk];
                }
                ders[kk][r] = d;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        let mut f = p as f64;
        for row in ders.iter_mut().skip(1) {
            row.iter_mut().for_each(|v| *v *= f);
            f *= (p - 1) as f64;
        }
        (span - p, ders)
    }

    fn point(&self, c: &[[f64; 2]], t: f64) -> [f64; 2] {
        let (first, d) = self.eval(t);
        let mut p = [0.0; 2];
        for (j, b) in d[0].iter().enumerate() {
            p[0] += b * c[first + j][0];
            p[1] += b * c[first + j][1];
        }
        p
    }

    fn nodes(&self) -> Vec<Node> {
        let mut out = Vec::new();
        for s in 3..self.n {
            let (a, b) = (self.knots[s], self.knots[s + 1]);
            if b <= a {
                continue;
            }
            for (x, w) in GAUSS {
                let t = 0.5 * (a + b) + 0.5 * (b - a) * x;
                let (first, d) = self.eval(t);
                out.push(Node {
                    w: 0.5 * (b - a) * w,
                    first,
                    d1: d[1],
                    d2: d[2],
                });
            }
        }
        out
    }
}

fn derivs(node: &Node, c: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    for j in 0..4 {
        let q = c[node.first + j];
        a[0] += node.d1[j] * q[0];
        a[1] += node.d1[j] * q[1];
        b[0] += node.d2[j] * q[0];
        b[1] += node.d2[j] * q[1];
    }
    (a, b)
}

/// ½∫κ² ds and ∫ds with their gradients with respect to every control point.
fn energy_length(nodes: &[Node], c: &[[f64; 2]]) -> (f64, f64, Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let (mut e, mut l) = (0.0, 0.0);
    let mut ge = vec![[0.0; 2]; c.len()];
    let mut gl = vec![[0.0; 2]; c.len()];
    for node in nodes {
        let (a, b) = derivs(node, c);
        let speed2 = a[0] * a[0] + a[1] * a[1];
        let speed = speed2.sqrt().max(1e-300);
        let cross = a[0] * b[1] - a[1] * b[0];
        let s5 = speed2 * speed2 * speed;
        e += node.w * 0.5 * cross * cross / s5;
        l += node.w * speed;
        // ∂/∂a and ∂/∂b of ½ cross²/|a|⁵, and ∂|a|/∂a
        let fa = [
            cross / s5 * b[1] - 2.5 * cross * cross / (s5 * speed2) * a[0],
            -cross / s5 * b[0] - 2.5 * cross * cross / (s5 * speed2) * a[1],
        ];
        let fb = [-cross / s5 * a[1], cross / s5 * a[0]];
        let la = [a[0] / speed, a[1] / speed];
        for j in 0..4 {
            let i = node.first + j;
            for k in 0..2 {
                ge[i][k] += node.w * (fa[k] * node.d1[j] + fb[k] * node.d2[j]);
                gl[i][k] += node.w * la[k] * node.d1[j];
            }
        }
    }
    (e, l, ge, gl)
}

/// The least-squares spline on `basis` through `points` at parameters `t`, ends
/// interpolated.
fn fit(basis: &Basis, points: &[[f64; 2]], t: &[f64]) -> Result<Vec<[f64; 2]>> {
    let n = basis.n;
    let (first, last) = (points[0], points[points.len() - 1]);
    let inner = n - 2;
    let mut a = nalgebra::DMatrix::<f64>::zeros(inner, inner);
    let mut rhs = nalgebra::DMatrix::<f64>::zeros(inner, 2);
    for (p, &ti) in points.iter().zip(t) {
        let (f, d) = basis.eval(ti);
        let b = d[0];
        let mut r = *p;
        for (j, bj) in b.iter().enumerate() {
            let end = match f + j {
                0 => Some(first),
                i if i == n - 1 => Some(last),
                _ => None,
            };
            if let Some(e) = end {
                r = [r[0] - bj * e[0], r[1] - bj * e[1]];
            }
        }
        let inside = |i: usize| i > 0 && i < n - 1;
        for (j, bj) in b.iter().enumerate() {
            if !inside(f + j) {
                continue;
            }
            for (k, bk) in b.iter().enumerate() {
                if inside(f + k) {
                    a[(f + j - 1, f + k - 1)] += bj * bk;
                }
            }
            rhs[(f + j - 1, 0)] += bj * r[0];
            rhs[(f + j - 1, 1)] += bj * r[1];
        }
    }
    let sol = a.cholesky().map(|c| c.solve(&rhs)).ok_or_else(|| {
        DesignError::Invalid("too few points for the refined spline: lower control_points".into())
    })?;
    let mut out = vec![first];
    out.extend((0..inner).map(|i| [sol[(i, 0)], sol[(i, 1)]]));
    out.push(last);
    Ok(out)
}

/// Control point `i`'s feasible set: a disc of radius ε about `x[i]`, or (a tangent
/// end's neighbour) the part of the tangent line inside it; the end points are fixed.
fn project(i: usize, y: [f64; 2], x: &[[f64; 2]], eps: f64, tangent: Option<[f64; 2]>) -> [f64; 2] {
    let n = x.len();
    if i == 0 || i == n - 1 {
        return x[i];
    }
    let c = x[i];
    if let Some(d) = tangent.filter(|_| i == 1 || i == n - 2) {
        let s = ((y[0] - c[0]) * d[0] + (y[1] - c[1]) * d[1]).clamp(-eps, eps);
        return [c[0] + s * d[0], c[1] + s * d[1]];
    }
    let (dx, dy) = (y[0] - c[0], y[1] - c[1]);
    let r = dx.hypot(dy);
    if r <= eps {
        y
    } else {
        [c[0] + dx * eps / r, c[1] + dy * eps / r]
    }
}

/// Largest projected-gradient iterations per outer round, and outer rounds.
const MAX_INNER: usize = 3000;
const MAX_OUTER: usize = 12;

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
/// than 6 control points or more than the points allow.
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
    if p.control_points < 6 || p.control_points > points.len() {
        return Err(DesignError::Invalid(format!(
            "control_points must be 6 to the number of points ({}), got {}",
            points.len(),
            p.control_points
        )));
    }
    // chord-length parameters
    let mut t = vec![0.0];
    for w in points.windows(2) {
        t.push(t[t.len() - 1] + (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]));
    }
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
    let tangent_of = |i: usize| if i == 1 { tangents.0 } else { tangents.1 };
    let proj = |y: &[[f64; 2]]| -> Vec<[f64; 2]> {
        y.iter()
            .enumerate()
            .map(|(i, q)| project(i, *q, &x, p.epsilon, tangent_of(i)))
            .collect()
    };
    let (e0, l0, _, _) = energy_length(&nodes, &x);
    // augmented Lagrangian of the length: E + ν(L − L₀) + μ/2 (L − L₀)², in units where
    // the length is 1 (E·L₀ and L/L₀ dimensionless)
    let (mut nu, mut mu) = (0.0, 10.0);
    let objective = |c: &[[f64; 2]], nu: f64, mu: f64| -> (f64, Vec<[f64; 2]>) {
        let (e, l, ge, gl) = energy_length(&nodes, c);
        let g = if p.fix_length { l / l0 - 1.0 } else { 0.0 };
        let f = e * l0 + nu * g + 0.5 * mu * g * g;
        let grad = ge
            .iter()
            .zip(&gl)
            .map(|(a, b)| {
                let s = if p.fix_length {
                    (nu + mu * g) / l0
                } else {
                    0.0
                };
                [a[0] * l0 + s * b[0], a[1] * l0 + s * b[1]]
            })
            .collect();
        (f, grad)
    };
    let mut y = x.clone();
    let (mut iterations, mut converged) = (0, false);
    let outer = if p.fix_length { MAX_OUTER } else { 1 };
    for _ in 0..outer {
        let (mut f, mut g) = objective(&y, nu, mu);
        let mut step = 1e-3 * l0 * l0;
        let mut inner_done = false;
        for _ in 0..MAX_INNER {
            iterations += 1;
            // projected gradient: its size tells optimality
            let trial_full: Vec<[f64; 2]> = y
                .iter()
                .zip(&g)
                .map(|(q, d)| [q[0] - d[0] * 1e-6 * l0 * l0, q[1] - d[1] * 1e-6 * l0 * l0])
                .collect();
            let pg: f64 = proj(&trial_full)
                .iter()
                .zip(&y)
                .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
                .fold(0.0, f64::max)
                / (1e-6 * l0);
            if pg < 1e-9 {
                inner_done = true;
                break;
            }
            // Armijo backtracking along the projection arc
            let mut accepted = None;
            for _ in 0..50 {
                let trial = proj(
                    &y.iter()
                        .zip(&g)
                        .map(|(q, d)| [q[0] - step * d[0], q[1] - step * d[1]])
                        .collect::<Vec<_>>(),
                );
                let (ft, gt) = objective(&trial, nu, mu);
                let descent: f64 = y
                    .iter()
                    .zip(&trial)
                    .zip(&g)
                    .map(|((a, b), d)| d[0] * (a[0] - b[0]) + d[1] * (a[1] - b[1]))
                    .sum();
                if ft.is_finite() && ft <= f - 1e-4 * descent {
                    accepted = Some((trial, ft, gt));
                    break;
                }
                step *= 0.5;
            }
            let Some((trial, ft, gt)) = accepted else {
                inner_done = true;
                break;
            };
            // Barzilai–Borwein step for the next iteration
            let (mut ss, mut sy) = (0.0, 0.0);
            for i in 0..n {
                for k in 0..2 {
                    let s = trial[i][k] - y[i][k];
                    let dy = gt[i][k] - g[i][k];
                    ss += s * s;
                    sy += s * dy;
                }
            }
            step = if sy > 0.0 {
                (ss / sy).clamp(1e-12 * l0 * l0, 1e3 * l0 * l0)
            } else {
                step * 2.0
            };
            let change = (f - ft).abs() / f.abs().max(1e-300);
            (y, f, g) = (trial, ft, gt);
            if change < 1e-14 {
                inner_done = true;
                break;
            }
        }
        let (_, l, _, _) = energy_length(&nodes, &y);
        let gap = l / l0 - 1.0;
        if !p.fix_length || gap.abs() < 1e-9 {
            converged = inner_done;
            break;
        }
        nu += mu * gap;
        mu *= 4.0;
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_a_partition_of_unity_with_matching_derivatives() {
        let b = Basis::new(9);
        for i in 0..=100 {
            let t = i as f64 / 100.0;
            let (_, d) = b.eval(t);
            assert!((d[0].iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(d[1].iter().sum::<f64>().abs() < 1e-9);
            assert!(d[2].iter().sum::<f64>().abs() < 1e-8);
        }
        // derivatives against finite differences of a curve; h³ truncation, h = 1e-5
        let c: Vec<[f64; 2]> = (0..9).map(|i| [i as f64, ((i * i) % 5) as f64]).collect();
        for t in [0.13, 0.41, 0.77] {
            let h = 1e-5;
            let (f, d) = b.eval(t);
            let num = |k: usize| (b.point(&c, t + h)[k] - b.point(&c, t - h)[k]) / (2.0 * h);
            let ana = |k: usize| (0..4).map(|j| d[1][j] * c[f + j][k]).sum::<f64>();
            for k in 0..2 {
                assert!(
                    (num(k) - ana(k)).abs() < 1e-5,
                    "{t}: {} vs {}",
                    num(k),
                    ana(k)
                );
            }
        }
    }

    #[test]
    fn energy_gradient_matches_finite_differences() {
        let b = Basis::new(8);
        let nodes = b.nodes();
        let c: Vec<[f64; 2]> = (0..8).map(|i| [i as f64, (0.7 * i as f64).sin()]).collect();
        let (_, _, ge, gl) = energy_length(&nodes, &c);
        let h = 1e-6;
        for i in 0..8 {
            for k in 0..2 {
                let (mut up, mut dn) = (c.clone(), c.clone());
                up[i][k] += h;
                dn[i][k] -= h;
                let (eu, lu, _, _) = energy_length(&nodes, &up);
                let (ed, ld, _, _) = energy_length(&nodes, &dn);
                assert!(((eu - ed) / (2.0 * h) - ge[i][k]).abs() < 1e-5 * (1.0 + ge[i][k].abs()));
                assert!(((lu - ld) / (2.0 * h) - gl[i][k]).abs() < 1e-6);
            }
        }
    }
}
