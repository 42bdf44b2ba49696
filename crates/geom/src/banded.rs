//! A symmetric positive-definite banded solver (Cholesky), used by the spline fits.
//!
//! Written here because the fits' normal equations are banded with a half-bandwidth equal
//! to the spline degree; a dense solve would cost O(n³) where this costs O(n·b²), and
//! nalgebra has no banded factorisation.

/// Symmetric band matrix stored by rows: `rows[i][k]` is entry `(i, i + k)` for `k <= band`.
#[derive(Debug, Clone)]
pub(crate) struct SymBand {
    pub band: usize,
    pub rows: Vec<Vec<f64>>,
}

impl SymBand {
    /// A zero matrix of size `n` with half-bandwidth `band`.
    pub fn zeros(n: usize, band: usize) -> Self {
        Self {
            band,
            rows: vec![vec![0.0; band + 1]; n],
        }
    }

    /// Adds `v` to entry `(i, j)` (and by symmetry `(j, i)`); entries outside the band are ignored
    /// by construction of the callers.
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let (a, b) = if i <= j { (i, j) } else { (j, i) };
        debug_assert!(b - a <= self.band);
        self.rows[a][b - a] += v;
    }

    /// Solves `A x = rhs` for several right-hand sides (columns of `rhs`, stored per row).
    /// Returns `None` when the matrix is not (numerically) positive definite.
    // rows i and k of the same right-hand side are read and written together
    #[allow(clippy::needless_range_loop)]
    pub fn solve<const D: usize>(&self, rhs: &[[f64; D]]) -> Option<Vec<[f64; D]>> {
        let n = self.rows.len();
        let b = self.band;
        // Cholesky A = Lᵀ L with L upper-banded, stored like A.
        let mut l = self.rows.clone();
        for i in 0..n {
            for k in i.saturating_sub(b)..i {
                let lki = l[k][i - k];
                if lki == 0.0 {
                    continue;
                }
                for j in i..(k + b + 1).min(n) {
                    let lkj = l[k][j - k];
                    l[i][j - i] -= lki * lkj;
                }
            }
            let d = l[i][0];
            if d <= 0.0 || !d.is_finite() {
                return None;
            }
            let d = d.sqrt();
            l[i][0] = d;
            for j in (i + 1)..(i + b + 1).min(n) {
                l[i][j - i] /= d;
            }
        }
        // Forward: Lᵀ y = rhs.
        let mut y = rhs.to_vec();
        for i in 0..n {
            for k in i.saturating_sub(b)..i {
                let lki = l[k][i - k];
                for c in 0..D {
                    y[i][c] -= lki * y[k][c];
                }
            }
            for c in 0..D {
                y[i][c] /= l[i][0];
            }
        }
        // Backward: L x = y.
        for i in (0..n).rev() {
            for j in (i + 1)..(i + b + 1).min(n) {
                let lij = l[i][j - i];
                for c in 0..D {
                    y[i][c] -= lij * y[j][c];
                }
            }
            for c in 0..D {
                y[i][c] /= l[i][0];
            }
        }
        Some(y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_tridiagonal_exactly() {
        // A = tridiag(-1, 4, -1), x = (1, 2, 3, 4, 5)
        let n = 5;
        let mut a = SymBand::zeros(n, 1);
        for i in 0..n {
            a.add(i, i, 4.0);
            if i + 1 < n {
                a.add(i, i + 1, -1.0);
            }
        }
        let x: Vec<f64> = (1..=n).map(|v| v as f64).collect();
        let rhs: Vec<[f64; 1]> = (0..n)
            .map(|i| {
                let mut s = 4.0 * x[i];
                if i > 0 {
                    s -= x[i - 1];
                }
                if i + 1 < n {
                    s -= x[i + 1];
                }
                [s]
            })
            .collect();
        let sol = a.solve(&rhs).expect("SPD");
        for i in 0..n {
            assert!((sol[i][0] - x[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn rejects_indefinite() {
        let mut a = SymBand::zeros(2, 1);
        a.add(0, 0, 1.0);
        a.add(0, 1, 2.0);
        a.add(1, 1, 1.0);
        assert!(a.solve(&[[1.0], [1.0]]).is_none());
    }
}
