//! Carlson's symmetric elliptic integrals R_F and R_D by the duplication theorem.
//!
//! Algorithm: B. C. Carlson, "Numerical computation of real or complex elliptic
//! integrals", Numer. Algorithms 10 (1995), with the series of DLMF §19.36(i). The
//! duplication step `x ← (x + λ)/4` shrinks the spread of the arguments by 4 each time;
//! once it is below 1.5e-3 the truncated Taylor series (to the 7th order for R_F, the 5th
//! for R_D) is exact to well below one rounding. Arguments must be finite and ≥ 0 with at
//! most one of them zero; the callers in this crate guarantee that.

/// Carlson's R_F(x, y, z) = ½∫₀^∞ dt / √((t+x)(t+y)(t+z)).
///
/// ```
/// use elastica::carlson::carlson_rf;
/// use elastica::ellip_k;
/// // R_F(x, x, x) = 1/√x, and K(m) = R_F(0, 1 − m, 1)
/// assert!((carlson_rf(4.0, 4.0, 4.0) - 0.5).abs() < 1e-15);
/// let m = 0.45;
/// assert!((carlson_rf(0.0, 1.0 - m, 1.0) - ellip_k(m)?).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    let (mut x, mut y, mut z) = (x, y, z);
    let mut a = (x + y + z) / 3.0;
    loop {
        let dx = 1.0 - x / a;
        let dy = 1.0 - y / a;
        let dz = 1.0 - z / a;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1.5e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            let s = 1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0
                - 3.0 * e2 * e3 / 44.0
                - 5.0 * e2 * e2 * e2 / 208.0
                + 3.0 * e3 * e3 / 104.0
                + e2 * e2 * e3 / 16.0;
            return s / a.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        a = 0.25 * (a + lambda);
    }
}

/// Carlson's R_D(x, y, z) = 3/2 ∫₀^∞ dt / (√((t+x)(t+y)) (t+z)^{3/2}).
///
/// ```
/// use elastica::carlson::carlson_rd;
/// use elastica::{ellip_e, ellip_k};
/// // R_D(x, x, x) = x^(−3/2), and K(m) − E(m) = m/3 · R_D(0, 1 − m, 1)
/// assert!((carlson_rd(4.0, 4.0, 4.0) - 0.125).abs() < 1e-15);
/// let m = 0.45;
/// let lhs = ellip_k(m)? - ellip_e(m)?;
/// assert!((lhs - m / 3.0 * carlson_rd(0.0, 1.0 - m, 1.0)).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    let (mut x, mut y, mut z) = (x, y, z);
    let mut a = (x + y + 3.0 * z) / 5.0;
    let mut sum = 0.0;
    let mut fac = 1.0;
    loop {
        let dx = 1.0 - x / a;
        let dy = 1.0 - y / a;
        let dz = 1.0 - z / a;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1.5e-3 {
            // DLMF 19.36.2 with X = dx, Y = dy, Z = −(X + Y)/3 (= dz up to rounding)
            let zz = -(dx + dy) / 3.0;
            let xy = dx * dy;
            let z2 = zz * zz;
            let e2 = xy - 6.0 * z2;
            let e3 = (3.0 * xy - 8.0 * z2) * zz;
            let e4 = 3.0 * (xy - z2) * z2;
            let e5 = xy * z2 * zz;
            let s = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
                - 3.0 * e4 / 22.0
                - 9.0 * e2 * e3 / 52.0
                + 3.0 * e5 / 26.0;
            return 3.0 * sum + fac * s / (a * a.sqrt());
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        sum += fac / (sz * (z + lambda));
        fac *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        a = 0.25 * (a + lambda);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn known_values() {
        // DLMF 19.20.1: R_F(x, x, x) = x^{-1/2}; R_F(0, 1, 1) = π/2; R_D(0, 1, 1) = 3π/4
        assert!(rel(carlson_rf(4.0, 4.0, 4.0), 0.5) < 1e-15);
        assert!(rel(carlson_rf(0.0, 1.0, 1.0), std::f64::consts::FRAC_PI_2) < 1e-15);
        assert!(rel(carlson_rd(0.0, 1.0, 1.0), 0.75 * std::f64::consts::PI) < 1e-15);
        // Carlson (1995) test values
        assert!(rel(carlson_rf(1.0, 2.0, 0.0), 1.311_028_777_146_059_9) < 1e-15);
        assert!(rel(carlson_rd(0.0, 2.0, 1.0), 1.797_210_352_103_388_4) < 1e-15);
        assert!(rel(carlson_rd(2.0, 3.0, 4.0), 0.165_105_272_942_610_53) < 1e-15);
    }
}
