//! The moving polygon of one cutting direction, by its legs' supporting lines.
//!
//! In the section plane at `u` (normal to the cutting direction) leg `j` lies on the line
//! `z = a_j(u) + m_j(u)·s`, `s = (w − w_mid)/w_half ∈ [−1, 1]`, where `a_j` and `m_j` are
//! B-splines in `u` of the thesis' degree `p` with `k` control values each (eq. 2.1 with
//! the polygon's vertices replaced by its edges' lines). The polygon is the lower envelope
//! of the lines, so it is planar (it lies in the plane `u`), convex, spans the block from
//! side to side and its rulings turn less than 180° — constraints 2.4–2.10 hold by
//! construction — and "no extended ruling enters the design surface" (eq. 2.3 for every
//! ruling extended across the block) is `a_j(u) + m_j(u)·s ≥ f` at every design point:
//! linear in the unknowns.
//!
//! Unknowns: `x[(2j)·k + c] = a_{j,c}`, `x[(2j + 1)·k + c] = m_{j,c}`.

use geom::bspline::{clamped_uniform_knots, nonzero_basis};

/// The B-spline space of the legs' coefficient functions and the `w` normalisation.
#[derive(Debug, Clone, PartialEq)]
pub struct Legs {
    /// Number of legs (cuts).
    pub legs: usize,
    /// B-spline degree along the cut.
    pub degree: usize,
    /// Control values per coefficient function.
    pub controls: usize,
    knots: Vec<f64>,
    /// Middle of the `w` range.
    pub w_mid: f64,
    /// Half width of the `w` range.
    pub w_half: f64,
}

impl Legs {
    /// Legs over `u ∈ [u0, u1]` and `w ∈ [w0, w1]`; `controls ≥ degree + 1`.
    pub fn new(legs: usize, degree: usize, controls: usize, u: (f64, f64), w: (f64, f64)) -> Self {
        Self {
            legs,
            degree,
            controls,
            knots: clamped_uniform_knots(degree, controls, u.0, u.1),
            w_mid: (w.0 + w.1) / 2.0,
            w_half: ((w.1 - w.0) / 2.0).max(f64::MIN_POSITIVE),
        }
    }

    /// The knot vector along the cut (clamped, uniform).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of unknowns.
    pub fn unknowns(&self) -> usize {
        2 * self.controls * self.legs
    }

    /// The B-spline basis values at `u` (all `controls` of them; most are 0).
    pub fn basis(&self, u: f64) -> Vec<f64> {
        // the degree + 1 non-zero ones by the triangular scheme (the recursive definition
        // per function took 70 % of a PreCut run in the exchange's local searches); at
        // and past the domain's end the last function is 1
        let (first, nonzero) = nonzero_basis(self.degree, &self.knots, self.controls, u);
        let mut b = vec![0.0; self.controls];
        b[first..first + nonzero.len()].copy_from_slice(&nonzero);
        b
    }

    /// The normalised across coordinate of `w`.
    pub fn s(&self, w: f64) -> f64 {
        (w - self.w_mid) / self.w_half
    }

    /// The nonzero coefficients of leg `j`'s height at `(u, w)` as `(unknown, value)`.
    pub fn row(&self, basis: &[f64], w: f64, j: usize) -> Vec<(usize, f64)> {
        let s = self.s(w);
        let k = self.controls;
        let mut r = Vec::with_capacity(2 * (self.degree + 1));
        for (c, &b) in basis.iter().enumerate() {
            if b != 0.0 {
                r.push((2 * j * k + c, b));
                r.push(((2 * j + 1) * k + c, b * s));
            }
        }
        r
    }

    /// `(a_j(u), m_j(u))` from the basis at `u`.
    pub fn line(&self, x: &[f64], basis: &[f64], j: usize) -> (f64, f64) {
        let k = self.controls;
        basis
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(a, m), (c, &b)| {
                (a + b * x[2 * j * k + c], m + b * x[(2 * j + 1) * k + c])
            })
    }

    /// Leg `j`'s height at `(u, w)` from the basis at `u`.
    pub fn height(&self, x: &[f64], basis: &[f64], w: f64, j: usize) -> f64 {
        let (a, m) = self.line(x, basis, j);
        a + m * self.s(w)
    }

    /// The lower envelope (the cut surface) at `(u, w)` and the leg attaining it (the
    /// first of equal ones).
    pub fn envelope(&self, x: &[f64], basis: &[f64], w: f64) -> (f64, usize) {
        (0..self.legs)
            .map(|j| (self.height(x, basis, w, j), j))
            .fold(
                (f64::INFINITY, 0),
                |best, h| if h.0 < best.0 { h } else { best },
            )
    }

    /// The polygon in the section plane at `u` over `w ∈ [w0, w1]`: its vertices `(w, z)`
    /// from left to right (ends and the corners where the active leg changes), with the
    /// leg of each edge.
    pub fn polygon(&self, x: &[f64], u: f64, w0: f64, w1: f64) -> (Vec<(f64, f64)>, Vec<usize>) {
        let basis = self.basis(u);
        let lines: Vec<(f64, f64)> = (0..self.legs).map(|j| self.line(x, &basis, j)).collect();
        // Breakpoints: every pairwise crossing inside (w0, w1).
        let mut cuts = vec![w0, w1];
        for i in 0..lines.len() {
            for j in i + 1..lines.len() {
                let dm = lines[i].1 - lines[j].1;
                if dm.abs() > 1e-15 {
                    let s = (lines[j].0 - lines[i].0) / dm;
                    let w = self.w_mid + s * self.w_half;
                    if w > w0 && w < w1 {
                        cuts.push(w);
                    }
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        let mut legs: Vec<usize> = Vec::new();
        let mut verts = vec![(w0, self.envelope(x, &basis, w0).0)];
        for pair in cuts.windows(2) {
            if pair[1] - pair[0] <= 1e-12 * self.w_half {
                continue;
            }
            let (_, j) = self.envelope(x, &basis, (pair[0] + pair[1]) / 2.0);
            if legs.last() != Some(&j) {
                if !legs.is_empty() {
                    verts.push((pair[0], self.height(x, &basis, pair[0], j)));
                }
                legs.push(j);
            }
        }
        verts.push((w1, self.envelope(x, &basis, w1).0));
        (verts, legs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_of_two_crossing_lines() {
        // Constant coefficients: leg 0 z = 1 + s, leg 1 z = 1 − s over w ∈ [0, 2] (s = w − 1).
        let legs = Legs::new(2, 1, 2, (0.0, 1.0), (0.0, 2.0));
        let x = vec![1.0, 1.0, 1.0, 1.0, 1.0, 1.0, -1.0, -1.0];
        let (v, l) = legs.polygon(&x, 0.5, 0.0, 2.0);
        assert_eq!(l, vec![0, 1]);
        let want = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)];
        assert_eq!(v.len(), 3);
        for (a, b) in v.iter().zip(want) {
            assert!(
                (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12,
                "{v:?}"
            );
        }
        // Partition of unity: a constant spline is that constant everywhere.
        for u in [0.0, 0.3, 1.0] {
            let s: f64 = legs.basis(u).iter().sum();
            assert!((s - 1.0).abs() < 1e-12);
        }
    }
}
