//! The refined spline of the numerical road: a clamped uniform cubic B-spline basis, its
//! bending energy and length with exact gradients (Gauss–Legendre, 5 nodes per knot span),
//! and the least-squares fit of the input's points.

use crate::bezier::GAUSS;
use crate::error::{DesignError, Result};

/// A clamped uniform cubic B-spline basis with `n` control points on [0, 1].
pub(super) struct Basis {
    pub(super) n: usize,
    knots: Vec<f64>,
}

/// One quadrature node: weight, first control index, basis values, first and second
/// derivatives of the four basis functions there.
pub(super) struct Node {
    w: f64,
    first: usize,
    d1: [f64; 4],
    d2: [f64; 4],
}

impl Basis {
    pub(super) fn new(n: usize) -> Self {
        let spans = n - 3;
        let mut knots = vec![0.0; 4];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend([1.0; 4]);
        Self { n, knots }
    }

    /// The span holding `t` and the values and two derivatives of its four basis
    /// functions (Cox–de Boor).
    pub(super) fn eval(&self, t: f64) -> (usize, [[f64; 4]; 3]) {
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

    pub(super) fn point(&self, c: &[[f64; 2]], t: f64) -> [f64; 2] {
        let (first, d) = self.eval(t);
        let mut p = [0.0; 2];
        for (j, b) in d[0].iter().enumerate() {
            p[0] += b * c[first + j][0];
            p[1] += b * c[first + j][1];
        }
        p
    }

    pub(super) fn nodes(&self) -> Vec<Node> {
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
pub(super) fn energy_length(
    nodes: &[Node],
    c: &[[f64; 2]],
) -> (f64, f64, Vec<[f64; 2]>, Vec<[f64; 2]>) {
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
pub(super) fn fit(basis: &Basis, points: &[[f64; 2]], t: &[f64]) -> Result<Vec<[f64; 2]>> {
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
