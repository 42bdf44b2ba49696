//! The linear algebra of the second variation: a symmetric tridiagonal operator `T`
//! restricted to the vectors orthogonal to (at most) two constraint rows, its eigenvalues
//! counted below a shift in O(n) and the smallest one found by bisection; and the solve of
//! a tridiagonal system bordered by two rows, which is every Newton step of the discrete
//! blade.
//!
//! Counting uses two classical facts. The number of negative pivots of the `LDLᵀ`
//! factorisation of `T − νI` is the number of eigenvalues of `T` below ν (Sylvester's law
//! of inertia, the Sturm count of tridiagonal bisection). For `G` of full row rank `r`,
//! the bordered matrix `[[A, Gᵀ], [G, 0]]` has `r` more negative eigenvalues than `A`
//! restricted to the null space of `G`, and by Haynsworth's inertia additivity it has as
//! many as `A` plus the Schur complement `−G A⁻¹ Gᵀ` (an r×r matrix). Together: the
//! restricted eigenvalues below ν are `neg(A) + neg(−G A⁻¹ Gᵀ) − r`, with `A = T − νI`.
//! Written here because no linear-algebra crate offers a Sturm count of a bordered pencil,
//! and a dense eigen-decomposition (O(n³)) at every pose along every robot move would cost
//! more than the rest of a run.

/// A symmetric tridiagonal matrix and the constraint rows its quadratic form is
/// restricted by.
#[derive(Debug, Clone)]
pub(crate) struct Pencil {
    /// Diagonal (length m).
    pub diag: Vec<f64>,
    /// Off-diagonal (length m − 1).
    pub off: Vec<f64>,
    /// The constraint rows, orthonormalised; a row dependent on the others is dropped.
    rows: Vec<Vec<f64>>,
    /// The matrix's size: largest |diagonal| plus twice the largest |off-diagonal|.
    scale: f64,
}

impl Pencil {
    /// The restriction of tridiagonal `(diag, off)` to the vectors orthogonal to `rows`.
    pub fn new(diag: Vec<f64>, off: Vec<f64>, rows: [Vec<f64>; 2]) -> Self {
        let mut kept: Vec<Vec<f64>> = Vec::with_capacity(2);
        for mut r in rows {
            let norm0 = dot(&r, &r).sqrt();
            for q in &kept {
                let c = dot(&r, q);
                r.iter_mut().zip(q).for_each(|(a, b)| *a -= c * b);
            }
            let norm = dot(&r, &r).sqrt();
            // a row that is (to rounding) a combination of the others constrains nothing new
            if norm > 1e-10 * norm0.max(f64::MIN_POSITIVE) && norm.is_finite() {
                r.iter_mut().for_each(|a| *a /= norm);
                kept.push(r);
            }
        }
        let scale = diag.iter().fold(0.0f64, |a, d| a.max(d.abs()))
            + 2.0 * off.iter().fold(0.0f64, |a, o| a.max(o.abs()));
        Pencil {
            diag,
            off,
            rows: kept,
            scale: scale.max(f64::MIN_POSITIVE),
        }
    }

    /// Size of the unrestricted matrix.
    pub fn len(&self) -> usize {
        self.diag.len()
    }

    /// How many eigenvalues of the restricted matrix are below `nu`: one pass of the
    /// `LDLᵀ` recurrence of `T − νI`, which also forward-solves the rows, since the Schur
    /// complement `−G A⁻¹ Gᵀ = −Σᵢ yᵢ yᵢᵀ / dᵢ` with `y = L⁻¹ Gᵀ` needs no back substitution.
    pub fn count_below(&self, nu: f64) -> usize {
        let m = self.len();
        if m == 0 {
            return 0;
        }
        let tiny = f64::EPSILON * (self.scale + nu.abs());
        let r = self.rows.len();
        let none: &[f64] = &[];
        let g0 = self.rows.first().map_or(none, |v| v.as_slice());
        let g1 = self.rows.get(1).map_or(none, |v| v.as_slice());
        let mut negative = 0usize;
        let (mut l, mut y0, mut y1) = (0.0, 0.0, 0.0);
        let mut s = [0.0f64; 3];
        for i in 0..m {
            let mut p = self.diag[i] - nu;
            if i > 0 {
                p -= self.off[i - 1] * l;
            }
            // a zero pivot is nudged, as tridiagonal bisection does: the count stays that
            // of a nearby shift
            if p.abs() < tiny {
                p = -tiny;
            }
            if p < 0.0 {
                negative += 1;
            }
            let inv = 1.0 / p;
            if r > 0 {
                y0 = g0[i] - l * y0;
                s[0] -= y0 * y0 * inv;
                if r > 1 {
                    y1 = g1[i] - l * y1;
                    s[1] -= y0 * y1 * inv;
                    s[2] -= y1 * y1 * inv;
                }
            }
            l = if i + 1 < m { self.off[i] * inv } else { 0.0 };
        }
        let neg_s = match r {
            0 => 0,
            1 => usize::from(s[0] < 0.0),
            _ => {
                let det = s[0] * s[2] - s[1] * s[1];
                let trace = s[0] + s[2];
                if det < 0.0 {
                    1
                } else if trace < 0.0 {
                    if det > 0.0 {
                        2
                    } else {
                        1
                    }
                } else {
                    0
                }
            }
        };
        (negative + neg_s).saturating_sub(r).min(m - r)
    }

    /// Gershgorin bounds of the unrestricted matrix's eigenvalues, which bound the
    /// restricted ones too (Cauchy interlacing).
    fn bounds(&self) -> (f64, f64) {
        let m = self.len();
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in 0..m {
            let mut r = 0.0;
            if i > 0 {
                r += self.off[i - 1].abs();
            }
            if i + 1 < m {
                r += self.off[i].abs();
            }
            lo = lo.min(self.diag[i] - r);
            hi = hi.max(self.diag[i] + r);
        }
        (lo, hi)
    }

    /// The Rayleigh quotient of the `k`-th sine mode projected off the rows (`None` when
    /// nothing of it is left).
    fn rayleigh_sine(&self, k: usize) -> Option<f64> {
        let m = self.len();
        let w = std::f64::consts::PI * k as f64 / (m + 1) as f64;
        let mut v: Vec<f64> = (1..=m).map(|i| (w * i as f64).sin()).collect();
        let before = dot(&v, &v);
        for g in &self.rows {
            let c = dot(&v, g);
            v.iter_mut().zip(g).for_each(|(a, b)| *a -= c * b);
        }
        let vv = dot(&v, &v);
        if !(vv > 1e-6 * before) {
            return None;
        }
        let mut vtv = 0.0;
        for i in 0..m {
            let mut tv = self.diag[i] * v[i];
            if i > 0 {
                tv += self.off[i - 1] * v[i - 1];
            }
            if i + 1 < m {
                tv += self.off[i] * v[i + 1];
            }
            vtv += v[i] * tv;
        }
        let q = vtv / vv;
        // a hair above, so that the bracket holds the eigenvalue despite rounding
        q.is_finite()
            .then(|| q + 1e-12 * (q.abs() + self.scale * 1e-6))
    }

    /// The smallest eigenvalue of the restricted matrix, to `tol` (absolute); `None` when
    /// the rows leave no vector free or the matrix is not finite.
    pub fn smallest(&self, tol: f64) -> Option<f64> {
        if self.len() <= self.rows.len() {
            return None;
        }
        let (mut lo, mut hi) = self.bounds();
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        // the Rayleigh quotient of any vector orthogonal to the rows bounds the smallest
        // restricted eigenvalue from above (min–max): the low sine modes, projected
        hi = (1..=3)
            .filter_map(|k| self.rayleigh_sine(k))
            .fold(hi, f64::min);
        // widen by a hair so that the bounds themselves bracket
        let pad = 1e-12 * (lo.abs() + hi.abs()) + f64::MIN_POSITIVE;
        lo -= pad;
        hi += pad;
        // bisection halves the bracket: the iterations are bounded by the bits of f64
        for _ in 0..2100 {
            if hi - lo <= tol.max(4.0 * f64::EPSILON * lo.abs().max(hi.abs())) {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if self.count_below(mid) >= 1 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves the symmetric tridiagonal system `(diag, off) x = b` by `LDLᵀ` without
/// pivoting (one division per row): `None` when a pivot is small enough that pivoting
/// would be needed (then [`tridiagonal_solve`]).
fn symmetric_solve(diag: &[f64], off: &[f64], b: &[&[f64]]) -> Option<Vec<Vec<f64>>> {
    let m = diag.len();
    let scale = diag.iter().chain(off).fold(0.0f64, |a, v| a.max(v.abs()));
    if !(scale > 0.0) || !scale.is_finite() {
        return None;
    }
    let mut d = Vec::with_capacity(m);
    let mut l = Vec::with_capacity(m);
    for i in 0..m {
        let p = if i > 0 {
            diag[i] - off[i - 1] * l[i - 1]
        } else {
            diag[0]
        };
        if !(p.abs() > 1e-6 * scale) {
            return None;
        }
        d.push(p);
        l.push(if i + 1 < m { off[i] / p } else { 0.0 });
    }
    Some(
        b.iter()
            .map(|rhs| {
                let mut x = rhs.to_vec();
                for i in 1..m {
                    x[i] -= l[i - 1] * x[i - 1];
                }
                for i in 0..m {
                    x[i] /= d[i];
                }
                for i in (0..m.saturating_sub(1)).rev() {
                    x[i] -= l[i] * x[i + 1];
                }
                x
            })
            .collect(),
    )
}

/// Solves the tridiagonal system `(sub, diag, sup) x = b` by Gaussian elimination with
/// partial pivoting (the matrix may be indefinite); `None` when it is singular.
fn tridiagonal_solve(
    sub: &[f64],
    diag: &[f64],
    sup: &[f64],
    b: &[&[f64]],
) -> Option<Vec<Vec<f64>>> {
    let m = diag.len();
    // rows of the upper-triangular factor: u0 (diagonal), u1, u2 (two super-diagonals)
    let mut u0 = diag.to_vec();
    let mut u1: Vec<f64> = (0..m)
        .map(|i| if i + 1 < m { sup[i] } else { 0.0 })
        .collect();
    let mut u2 = vec![0.0; m];
    let mut rhs: Vec<Vec<f64>> = b.iter().map(|v| v.to_vec()).collect();
    let scale = diag
        .iter()
        .chain(sub)
        .chain(sup)
        .fold(0.0f64, |a, v| a.max(v.abs()));
    if !(scale > 0.0) || !scale.is_finite() {
        return None;
    }
    for i in 0..m.saturating_sub(1) {
        // the row below holds sub[i] in column i, diag[i+1] in i+1, sup[i+1] in i+2
        let (mut below0, mut below1, mut below2) =
            (sub[i], u0[i + 1], if i + 2 < m { u1[i + 1] } else { 0.0 });
        if below0.abs() > u0[i].abs() {
            // swap row i and row i + 1
            std::mem::swap(&mut u0[i], &mut below0);
            std::mem::swap(&mut u1[i], &mut below1);
            std::mem::swap(&mut u2[i], &mut below2);
            for r in rhs.iter_mut() {
                r.swap(i, i + 1);
            }
        }
        if u0[i].abs() <= f64::EPSILON * scale * 1e-3 {
            return None;
        }
        let f = below0 / u0[i];
        u0[i + 1] = below1 - f * u1[i];
        if i + 2 < m {
            u1[i + 1] = below2 - f * u2[i];
        }
        for r in rhs.iter_mut() {
            r[i + 1] -= f * r[i];
        }
    }
    if u0[m - 1].abs() <= f64::EPSILON * scale * 1e-3 {
        return None;
    }
    for r in rhs.iter_mut() {
        for i in (0..m).rev() {
            let mut v = r[i];
            if i + 1 < m {
                v -= u1[i] * r[i + 1];
            }
            if i + 2 < m {
                v -= u2[i] * r[i + 2];
            }
            r[i] = v / u0[i];
        }
    }
    Some(rhs)
}

/// Solves the symmetric bordered system `[[T, Gᵀ], [G, 0]] (x, y) = (f, g)` for the
/// tridiagonal `T = (diag, off)` and the two rows `G`, through the Schur complement
/// (two extra tridiagonal solves); `None` when `T` or the complement is singular.
pub(crate) fn bordered_solve(
    diag: &[f64],
    off: &[f64],
    rows: [&[f64]; 2],
    f: &[f64],
    g: [f64; 2],
) -> Option<(Vec<f64>, [f64; 2])> {
    let sol = match symmetric_solve(diag, off, &[f, rows[0], rows[1]]) {
        Some(s) => s,
        None => tridiagonal_solve(off, diag, off, &[f, rows[0], rows[1]])?,
    };
    let (u, x0, x1) = (&sol[0], &sol[1], &sol[2]);
    // G x = g with x = u − X y: (G X) y = G u − g
    let s = [
        [dot(rows[0], x0), dot(rows[0], x1)],
        [dot(rows[1], x0), dot(rows[1], x1)],
    ];
    let r = [dot(rows[0], u) - g[0], dot(rows[1], u) - g[1]];
    let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
    let size = s.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    if !(det.abs() > 1e-14 * size * size) || !det.is_finite() {
        return None;
    }
    let y = [
        (r[0] * s[1][1] - r[1] * s[0][1]) / det,
        (s[0][0] * r[1] - s[1][0] * r[0]) / det,
    ];
    let x = (0..diag.len())
        .map(|i| u[i] - x0[i] * y[0] - x1[i] * y[1])
        .collect();
    Some((x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A deterministic pseudo-random sequence in [−1, 1).
    fn noise(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    fn dense(p: &Pencil) -> DMatrix<f64> {
        let m = p.len();
        DMatrix::from_fn(m, m, |i, j| {
            if i == j {
                p.diag[i]
            } else if i + 1 == j {
                p.off[i]
            } else if j + 1 == i {
                p.off[j]
            } else {
                0.0
            }
        })
    }

    /// The restricted eigenvalues by a dense eigen-decomposition in an orthonormal basis
    /// of the rows' complement.
    fn dense_restricted(p: &Pencil) -> Vec<f64> {
        let m = p.len();
        let r = p.rows.len();
        let g = DMatrix::from_fn(r, m, |a, i| p.rows[a][i]);
        // complement by the full SVD of Gᵀ's projector
        let proj = DMatrix::identity(m, m) - g.transpose() * &g;
        let eig = proj.symmetric_eigen();
        let cols: Vec<DVector<f64>> = (0..m)
            .filter(|&i| eig.eigenvalues[i] > 0.5)
            .map(|i| eig.eigenvectors.column(i).into_owned())
            .collect();
        let z = DMatrix::from_columns(&cols);
        let reduced = z.transpose() * dense(p) * &z;
        let mut e: Vec<f64> = reduced
            .symmetric_eigen()
            .eigenvalues
            .iter()
            .copied()
            .collect();
        e.sort_by(f64::total_cmp);
        e
    }

    #[test]
    fn counts_and_smallest_match_a_dense_eigen_decomposition() {
        let mut rnd = noise(7);
        for m in [3, 5, 12, 40] {
            for _ in 0..20 {
                let diag: Vec<f64> = (0..m).map(|_| 3.0 * rnd()).collect();
                let off: Vec<f64> = (0..m - 1).map(|_| rnd()).collect();
                let rows = [
                    (0..m).map(|_| rnd()).collect(),
                    (0..m).map(|_| rnd()).collect(),
                ];
                let p = Pencil::new(diag, off, rows);
                let e = dense_restricted(&p);
                for k in 0..e.len() {
                    // between two eigenvalues the count is exact
                    let nu = if k + 1 < e.len() {
                        0.5 * (e[k] + e[k + 1])
                    } else {
                        e[k] + 1.0
                    };
                    assert_eq!(p.count_below(nu), k + 1, "m {m} k {k}");
                }
                assert_eq!(p.count_below(e[0] - 1e-6), 0);
                let s = p.smallest(1e-13).unwrap();
                assert!((s - e[0]).abs() < 1e-10, "{s} vs {}", e[0]);
            }
        }
    }

    #[test]
    fn a_dependent_row_is_dropped() {
        let m = 6;
        let diag = vec![2.0; m];
        let off = vec![-1.0; m - 1];
        let row: Vec<f64> = vec![1.0; m];
        let p = Pencil::new(
            diag,
            off,
            [row.clone(), row.iter().map(|v| -2.0 * v).collect()],
        );
        assert_eq!(p.rows.len(), 1);
        let e = dense_restricted(&p);
        assert_eq!(e.len(), m - 1);
        assert!((p.smallest(1e-14).unwrap() - e[0]).abs() < 1e-11);
    }

    #[test]
    fn bordered_solve_matches_a_dense_solve() {
        let mut rnd = noise(11);
        for m in [3, 8, 30] {
            let diag: Vec<f64> = (0..m).map(|_| 2.0 * rnd()).collect();
            let off: Vec<f64> = (0..m - 1).map(|_| rnd()).collect();
            let r0: Vec<f64> = (0..m).map(|_| rnd()).collect();
            let r1: Vec<f64> = (0..m).map(|_| rnd()).collect();
            let f: Vec<f64> = (0..m).map(|_| rnd()).collect();
            let g = [rnd(), rnd()];
            let (x, y) = bordered_solve(&diag, &off, [&r0, &r1], &f, g).unwrap();
            let n = m + 2;
            let k = DMatrix::from_fn(n, n, |i, j| match (i < m, j < m) {
                (true, true) => {
                    if i == j {
                        diag[i]
                    } else if i + 1 == j {
                        off[i]
                    } else if j + 1 == i {
                        off[j]
                    } else {
                        0.0
                    }
                }
                (true, false) => [&r0, &r1][j - m][i],
                (false, true) => [&r0, &r1][i - m][j],
                (false, false) => 0.0,
            });
            let mut rhs = f.clone();
            rhs.extend(g);
            let want = k.lu().solve(&DVector::from_vec(rhs)).unwrap();
            for i in 0..m {
                assert!((x[i] - want[i]).abs() < 1e-9, "m {m} x{i}");
            }
            assert!((y[0] - want[m]).abs() < 1e-9 && (y[1] - want[m + 1]).abs() < 1e-9);
        }
    }
}
