//! Jacobi elliptic functions sn, cn, dn, am, the Jacobi epsilon function E(u|m) and the
//! complete integrals K(m), E(m), for the parameter m = k² ∈ [0, 1].
//!
//! # Algorithm
//!
//! 1. **Argument reduction.** `u = 2jK + r` with `|r| ≤ K`, then `sn(u) = (−1)^j sn(r)`,
//!    `cn(u) = (−1)^j cn(r)`, `dn(u) = dn(r)`, `am(u) = jπ + am(r)` and
//!    `E(u) = 2jE(m) + E(r)` (DLMF 22.4, 22.16.27). K is computed by the arithmetic–geometric
//!    mean in double-double arithmetic and `r = (u − 2jK_hi) − 2jK_lo` with a fused
//!    multiply-add, so `r` carries no error from K even for |u| = 10³.
//! 2. **Half-period reflection.** For `|r| > K/2` the functions are evaluated at
//!    `v = K − |r|` and mapped back with `sn(K−v) = cn v/dn v`, `cn(K−v) = k′ sn v/dn v`,
//!    `dn(K−v) = k′/dn v` (DLMF 22.4.3) and the addition formula
//!    `E(K−v) = E(m) − E(v) + m sn v sn(K−v)` (DLMF 22.16.27). Near the quarter period with
//!    m → 1 this keeps cn and dn *relatively* accurate, which is where the textbook
//!    descending-Landen / AGM recurrence (A&S 16.4) loses half its digits through
//!    `asin(x ≈ 1)`.
//! 3. **Descending Landen transformation** (DLMF 22.7.1–3) in its rational form,
//!    `k₁ = k²/(1+k′)²`, `sn(z|k) = (1+k₁) s/(1+k₁s²)`, `cn = c d/(1+k₁s²)`,
//!    `dn = ((1−k₁) + k₁c²)/(1+k₁s²)` with `s, c, d` at `z/(1+k₁)` and modulus `k₁`; the
//!    moduli fall quadratically (at most 9 steps for m = 1 − 2⁻⁵³), and at the bottom
//!    (m < 3·10⁻⁹) the first-order series of A&S 16.13 is exact to rounding. The chain of
//!    moduli depends on m only and is computed once per [`Elliptic`](crate::elliptic::Elliptic).
//! 4. **Epsilon function.** `E(v) = v − m·D(v)` with `D(v) = (v − E(v))/m = ∫₀^v sn²`,
//!    climbed up the same Landen chain as sn, cn, dn: at the bottom D is the integral of
//!    the first-order series, and each level applies
//!    `D(u|k) = (1+k₁)/2 · (u₁ − s c d/(1 + k₁s²) + k₁ D(u₁|k₁))` (derived in
//!    `scd_small`). Writing E through D avoids the cancellation in `v − E(v)` for small m
//!    that the non-inflectional elastica needs, and costs a few multiplications per level
//!    (Carlson's R_D, `D = sn³ R_D(cn², dn², 1)/3` by DLMF 19.25.9, gives the same values
//!    at about twice the price of the whole evaluation).
//! 5. **Complete integrals.** `K = π / (2 AGM(1, k′))` (double-double), and
//!    `E(m) = K − m R_D(0, 1−m, 1)/3` (DLMF 19.25.1).
//!
//! m = 1 is handled in closed form (sn = tanh, cn = dn = sech, am = gd, E(u) = tanh u,
//! K = ∞) and never overflows for large u. Accuracy against 60-digit references
//! (`tests/elliptic_reference.rs`, generated with mpmath): see
//! `BENCHMARKS.md` (repository root) for the measured maxima.

use crate::carlson::carlson_rd;
use crate::dd::{Dd, PI};

/// Errors of the elliptic-function layer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EllipticError {
    /// The parameter m = k² must be finite and in [0, 1].
    #[error("elliptic parameter m = {0} is outside [0, 1]")]
    Parameter(f64),
}

/// Landen steps at most; m = 1 − 2⁻⁵³ needs 9.
const MAX_LANDEN: usize = 12;
/// Below this parameter the first-order series in m is exact to rounding on |w| ≤ π/4.
const SERIES_M: f64 = 3e-9;

/// Values of the Jacobi functions at one argument.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct JacobiValues {
    /// sn(u|m).
    pub sn: f64,
    /// cn(u|m).
    pub cn: f64,
    /// dn(u|m).
    pub dn: f64,
    /// The amplitude am(u|m), continuous and increasing in u.
    pub am: f64,
    /// The Jacobi epsilon function E(u|m) = ∫₀ᵘ dn²(t|m) dt.
    pub eps: f64,
    /// D(u|m) = ∫₀ᵘ sn²(t|m) dt = (u − E(u|m))/m, without the cancellation for small m.
    pub d: f64,
}

/// Partial derivatives of the Jacobi functions with respect to the parameter m at fixed u.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct JacobiDm {
    /// ∂sn/∂m.
    pub sn: f64,
    /// ∂cn/∂m.
    pub cn: f64,
    /// ∂dn/∂m.
    pub dn: f64,
    /// ∂am/∂m.
    pub am: f64,
    /// ∂E(u|m)/∂m.
    pub eps: f64,
}

/// The elliptic parameter m with everything that depends on it alone precomputed: the
/// quarter period K (double-double), E(m), and the chain of Landen moduli. Evaluate many
/// arguments with one `Elliptic`.
///
/// ```
/// use elastica::elliptic::Elliptic;
/// let e = Elliptic::new(0.5).unwrap();
/// let v = e.eval(1.0);
/// assert!((v.sn * v.sn + v.cn * v.cn - 1.0).abs() < 1e-15);
/// assert!((e.k() - 1.854_074_677_301_372).abs() < 1e-14); // K(1/2)
/// // quarter period: sn(K) = 1, cn(K) = 0, dn(K) = k′
/// let q = e.eval(e.k());
/// assert!((q.sn - 1.0).abs() < 1e-15 && q.cn.abs() < 1e-15);
/// assert!((q.dn - 0.5f64.sqrt()).abs() < 1e-15);
/// ```
#[derive(Clone, Debug)]
pub struct Elliptic {
    m: f64,
    m1: f64,
    kp: f64,
    k: Dd,
    e: f64,
    /// (K − E)/m = R_D(0, 1 − m, 1)/3, finite at m = 0.
    dk: f64,
    /// Landen moduli k₁, k₂, … and 1 − kₙ.
    chain: [(f64, f64); MAX_LANDEN],
    levels: usize,
    /// Π 1/(1 + kₙ): the argument scale at the bottom of the chain.
    bottom_scale: f64,
    /// Parameter at the bottom of the chain.
    bottom_m: f64,
    /// 1 − m is 0: the functions are hyperbolic (m itself may round to 1 with 1 − m > 0).
    at_one: bool,
}

impl Elliptic {
    /// Precompute for parameter `m ∈ [0, 1]`.
    pub fn new(m: f64) -> Result<Self, EllipticError> {
        if !(0.0..=1.0).contains(&m) {
            return Err(EllipticError::Parameter(m));
        }
        // 1 − m is exact in f64 for m ≥ 1/2 and the error-free sum covers m < 1/2.
        let one_minus_m = Dd::from_f64(1.0).add(Dd::from_f64(-m));
        Ok(Self::with_complement(m, m.sqrt(), one_minus_m))
    }

    /// Precompute for the modulus `k ∈ [0, 1]` (m = k²). The complementary parameter
    /// 1 − m = (1 − k)(1 + k) is formed exactly from k, so K, E and the functions keep
    /// full relative accuracy in 1 − m as k → 1: forming m = k² first rounds away up to
    /// 1.1·10⁻¹⁶ of 1 − m, which is a relative error of 10⁻⁶ at 1 − m = 10⁻¹⁰.
    ///
    /// ```
    /// use elastica::elliptic::Elliptic;
    /// let k = 1.0 - 1e-10;
    /// let e = Elliptic::from_modulus(k).unwrap();
    /// // K = ln(4/k′) + O(k′²) with k′² = (1 − k)(1 + k) ≈ 2·10⁻¹⁰
    /// let kp2 = (1.0 - k) * (1.0 + k);
    /// assert!((e.k() - (4.0 / kp2.sqrt()).ln()).abs() < 1e-9);
    /// ```
    pub fn from_modulus(k: f64) -> Result<Self, EllipticError> {
        if !(0.0..=1.0).contains(&k) {
            return Err(EllipticError::Parameter(k * k));
        }
        let one = Dd::from_f64(1.0);
        let one_minus_m = one.add(Dd::from_f64(-k)).mul(one.add(Dd::from_f64(k)));
        Ok(Self::with_complement(k * k, k, one_minus_m))
    }

    /// Precompute for the modulus `k = 1 − one_minus_k` given by its distance from 1,
    /// `one_minus_k ∈ [0, 1]`: near 1 this keeps what `k` in `f64` cannot — every digit of
    /// 1 − k below 1.1·10⁻¹⁶ (an elastica under strong tension has 1 − k ≈ 10⁻²⁰, which
    /// rounds k to 1) — and 1 − m = (1 − k)(1 + k) is formed from it exactly.
    ///
    /// ```
    /// use elastica::elliptic::Elliptic;
    /// let e = Elliptic::from_complement(1e-20).unwrap();
    /// // K = ln(4/k′) with k′² = 1 − m ≈ 2·10⁻²⁰, although k rounds to 1
    /// assert!((e.k() - (4.0 / 2e-20f64.sqrt()).ln()).abs() < 1e-12);
    /// assert_eq!(e.m(), 1.0);
    /// ```
    pub fn from_complement(one_minus_k: f64) -> Result<Self, EllipticError> {
        if !(0.0..=1.0).contains(&one_minus_k) {
            return Err(EllipticError::Parameter(one_minus_k));
        }
        let c = Dd::from_f64(one_minus_k);
        let one_minus_m = c.mul(Dd::from_f64(2.0).add(Dd::from_f64(-one_minus_k)));
        let k = 1.0 - one_minus_k;
        Ok(Self::with_complement(k * k, k, one_minus_m))
    }

    /// Precompute from m, k = √m and 1 − m in double-double (m ∈ [0, 1] checked).
    fn with_complement(m: f64, k: f64, one_minus_m: Dd) -> Self {
        let m1 = one_minus_m.hi;
        let mut s = Elliptic {
            m,
            m1,
            kp: one_minus_m.sqrt().hi,
            k: Dd::from_f64(f64::INFINITY),
            e: 1.0,
            dk: f64::INFINITY,
            chain: [(0.0, 1.0); MAX_LANDEN],
            levels: 0,
            bottom_scale: 1.0,
            bottom_m: m,
            at_one: false,
        };
        if m1 == 0.0 {
            s.m = 1.0;
            s.at_one = true;
            return s;
        }
        // K by the AGM in double-double.
        let (mut a, mut b) = (Dd::from_f64(1.0), one_minus_m.sqrt());
        for _ in 0..40 {
            if (a.hi - b.hi).abs() <= 1e-17 * a.hi && (a.add(b.scale(-1.0))).hi.abs() < 1e-32 {
                break;
            }
            let an = a.add(b).scale(0.5);
            b = a.mul(b).sqrt();
            a = an;
        }
        s.k = PI.div(a.scale(2.0));
        s.dk = carlson_rd(0.0, m1, 1.0) / 3.0;
        s.e = s.k.hi - m * s.dk;
        // Landen chain
        let (mut k, mut kp) = (k, s.kp);
        let mut mm = m;
        while mm >= SERIES_M && s.levels < MAX_LANDEN {
            let k1 = (k / (1.0 + kp)).powi(2);
            let one_minus_k1 = 2.0 * kp / (1.0 + kp);
            let kp1 = 2.0 * kp.sqrt() / (1.0 + kp);
            s.chain[s.levels] = (k1, one_minus_k1);
            s.levels += 1;
            s.bottom_scale /= 1.0 + k1;
            k = k1;
            kp = kp1;
            mm = k1 * k1;
        }
        s.bottom_m = mm;
        s
    }

    /// The parameter m.
    pub fn m(&self) -> f64 {
        self.m
    }

    /// The complementary modulus k′ = √(1 − m).
    pub fn kprime(&self) -> f64 {
        self.kp
    }

    /// The quarter period K(m) (∞ at m = 1).
    pub fn k(&self) -> f64 {
        self.k.hi
    }

    /// The complete integral of the second kind E(m).
    pub fn e(&self) -> f64 {
        self.e
    }

    /// (K(m) − E(m))/m, finite at m = 0 (π/4) and ∞ at m = 1.
    pub fn k_minus_e_over_m(&self) -> f64 {
        self.dk
    }

    /// sn, cn, dn and D = ∫₀^v sn² at `v` with |v| ≤ K/2: scaled down to the bottom of the
    /// Landen chain, evaluated by the first-order series in m there, climbed back up;
    /// returns relatively accurate (s, c, d) and D to absolute accuracy.
    ///
    /// D climbs with the Landen transformation of ∫ sn² (derived for this crate from
    /// `m sn²(u|k) = 4y s²/(1 + y s²)²` and `d/du [s c d/(1 + y s²)]`, with s, c, d at
    /// `u/(1+y)` and modulus y = k₁): `D(u|k) = (1+y)/2 · (u₁ − s c d/(1 + y s²) + y D(u₁|y))`.
    /// It costs a few multiplications per level, against the ~5 duplication steps (15 square
    /// roots) of Carlson's R_D.
    fn scd_small(&self, v: f64) -> (f64, f64, f64, f64) {
        let w = v * self.bottom_scale;
        let (sw, cw) = w.sin_cos();
        let mb = self.bottom_m;
        let corr = 0.25 * mb * (w - sw * cw);
        let mut s = sw - corr * cw;
        let mut c = cw + corr * sw;
        let mut d = 1.0 - 0.5 * mb * sw * sw;
        // ∫₀^w sn²(t|m_b) to first order in m_b (A&S 16.13 integrated)
        let (s2w, c2w) = (2.0 * sw * cw, (cw - sw) * (cw + sw));
        let mut dint = 0.5 * (w - sw * cw)
            - 0.5 * mb * (-0.25 * w * c2w + 0.125 * s2w - 0.125 * w + 0.0625 * s2w * c2w);
        let mut u = w;
        for &(k1, one_minus_k1) in self.chain[..self.levels].iter().rev() {
            let den = 1.0 + k1 * s * s;
            let inv = 1.0 / den;
            dint = 0.5 * (1.0 + k1) * (u - s * c * d * inv + k1 * dint);
            u *= 1.0 + k1;
            let s_up = (1.0 + k1) * s * inv;
            let c_up = c * d * inv;
            // 1 − k₁s² written without cancellation on either side of s² = ½
            let d_up = if s * s < 0.5 {
                (1.0 - k1 * s * s) * inv
            } else {
                (one_minus_k1 + k1 * c * c) * inv
            };
            s = s_up;
            c = c_up;
            d = d_up;
        }
        (s, c, d, dint)
    }

    /// Evaluate sn, cn, dn, am, E(u|m) and D(u|m) at `u`. Non-finite `u` gives NaN.
    ///
    /// ```
    /// use elastica::Elliptic;
    /// let m = 0.6;
    /// let e = Elliptic::new(m)?;
    /// for u in [-2.0, 0.3, 1.0, 5.0] {
    ///     let v = e.eval(u);
    ///     assert!((v.sn * v.sn + v.cn * v.cn - 1.0).abs() < 1e-15);
    ///     assert!((v.dn * v.dn + m * v.sn * v.sn - 1.0).abs() < 1e-15);
    ///     assert!((v.sn - v.am.sin()).abs() < 1e-15); // sn = sin am
    /// }
    /// // E(K|m) is the complete integral E(m)
    /// assert!((e.eval(e.k()).eps - e.e()).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn eval(&self, u: f64) -> JacobiValues {
        self.eval_inner(u, true)
    }

    /// [`Elliptic::eval`] without the amplitude (`am` is NaN): saves an `atan2` where only
    /// sn, cn, dn, E and D are needed (the fitting loops).
    pub(crate) fn eval_no_am(&self, u: f64) -> JacobiValues {
        self.eval_inner(u, false)
    }

    #[inline(always)]
    fn eval_inner(&self, u: f64, want_am: bool) -> JacobiValues {
        if !u.is_finite() {
            return JacobiValues {
                sn: f64::NAN,
                cn: f64::NAN,
                dn: f64::NAN,
                am: f64::NAN,
                eps: f64::NAN,
                d: f64::NAN,
            };
        }
        if self.at_one {
            let t = u.tanh();
            let sech = 1.0 / u.cosh();
            return JacobiValues {
                sn: t,
                cn: sech,
                dn: sech,
                am: if want_am { u.sinh().atan() } else { f64::NAN },
                eps: t,
                d: u - t,
            };
        }
        let kk = self.k.hi;
        let j = (u / (2.0 * kk)).round();
        let r = (-j).mul_add(2.0 * kk, u) - j * (2.0 * self.k.lo);
        let sign = if r < 0.0 { -1.0 } else { 1.0 };
        let a = r.abs().min(kk);
        let (mut sn, mut cn, dn, mut am, mut eps, mut d);
        if a <= 0.5 * kk {
            let (s, c, dd, dv) = self.scd_small(a);
            sn = s;
            cn = c;
            dn = dd;
            am = if want_am { s.atan2(c) } else { f64::NAN };
            d = dv;
            eps = a - self.m * dv;
        } else {
            let v = ((kk - a) + self.k.lo).max(0.0);
            let (s, c, dd, dv) = self.scd_small(v);
            let ev = v - self.m * dv;
            sn = c / dd;
            cn = self.kp * s / dd;
            dn = self.kp / dd;
            am = if want_am { sn.atan2(cn) } else { f64::NAN };
            eps = self.e - ev + self.m * s * sn;
            d = self.dk - dv - s * sn;
        }
        sn *= sign;
        am *= sign;
        eps *= sign;
        d *= sign;
        if j != 0.0 {
            if (j as i64) % 2 != 0 {
                sn = -sn;
                cn = -cn;
            }
            am += j * std::f64::consts::PI;
            eps += 2.0 * j * self.e;
            d += 2.0 * j * self.dk;
        }
        JacobiValues {
            sn,
            cn,
            dn,
            am,
            eps,
            d,
        }
    }

    /// Derivatives of sn, cn, dn, am and E(u|m) with respect to m at fixed u, from the
    /// values `v = self.eval(u)` (closed form: ∂am/∂m = (sn cn − dn (u − D))/(2(1−m)), from
    /// ∂F(φ|m)/∂m, DLMF 19.4.1; at m = 1 its limit −¼(sinh u − u sech u)). Loses digits
    /// like ε/(1 − m) as m → 1, where the functions themselves become that sensitive.
    ///
    /// ```
    /// use elastica::Elliptic;
    /// // against central differences in m
    /// let (u, m, h) = (0.7, 0.4, 1e-6);
    /// let e = Elliptic::new(m)?;
    /// let d = e.dm(u, &e.eval(u));
    /// let (hi, lo) = (Elliptic::new(m + h)?.eval(u), Elliptic::new(m - h)?.eval(u));
    /// assert!((d.sn - (hi.sn - lo.sn) / (2.0 * h)).abs() < 1e-8);
    /// assert!((d.dn - (hi.dn - lo.dn) / (2.0 * h)).abs() < 1e-8);
    /// assert!((d.eps - (hi.eps - lo.eps) / (2.0 * h)).abs() < 1e-8);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn dm(&self, u: f64, v: &JacobiValues) -> JacobiDm {
        let am = if self.at_one {
            -0.25 * (u.sinh() - u / u.cosh())
        } else {
            (v.sn * v.cn - v.dn * (u - v.d)) / (2.0 * self.m1)
        };
        let dn = if v.dn > 0.0 {
            -(v.sn * v.sn + 2.0 * self.m * v.sn * v.cn * am) / (2.0 * v.dn)
        } else {
            0.0
        };
        JacobiDm {
            sn: v.cn * am,
            cn: -v.sn * am,
            dn,
            am,
            eps: -0.5 * v.d + v.dn * am,
        }
    }

    /// The incomplete integral of the first kind F(φ|m) = ∫₀^φ dθ/√(1 − m sin²θ) for any
    /// real φ (quasi-periodic: F(φ + jπ) = F(φ) + 2jK). Infinite at m = 1, |φ| ≥ π/2.
    ///
    /// ```
    /// use elastica::Elliptic;
    /// let e = Elliptic::new(0.8)?;
    /// // F inverts the amplitude: F(am(u|m)|m) = u
    /// let u = 1.3;
    /// assert!((e.f(e.eval(u).am) - u).abs() < 1e-14);
    /// // F(π/2) = K, and a half turn more adds 2K
    /// assert!((e.f(std::f64::consts::FRAC_PI_2) - e.k()).abs() < 1e-14);
    /// assert!((e.f(1.5 * std::f64::consts::PI) - 3.0 * e.k()).abs() < 1e-13);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn f(&self, phi: f64) -> f64 {
        let j = (phi / std::f64::consts::PI).round();
        let psi = phi - j * std::f64::consts::PI;
        let (s, c) = psi.sin_cos();
        // 1 − m sin² = cos² + (1 − m) sin², without cancellation as m → 1
        let base = s * crate::carlson::carlson_rf(c * c, c * c + self.m1 * s * s, 1.0);
        if j == 0.0 {
            base
        } else {
            base + 2.0 * j * self.k.hi
        }
    }
}

/// The complete elliptic integral of the first kind K(m).
///
/// ```
/// use elastica::ellip_k;
/// // K(m) = π / (2·AGM(1, √(1 − m))), here with the AGM iterated by hand
/// let m: f64 = 0.7;
/// let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
/// for _ in 0..8 {
///     (a, b) = ((a + b) / 2.0, (a * b).sqrt());
/// }
/// assert!((ellip_k(m)? - std::f64::consts::PI / (2.0 * a)).abs() < 1e-14);
/// // no quarter period outside m ∈ [0, 1]
/// assert!(ellip_k(1.5).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn ellip_k(m: f64) -> Result<f64, EllipticError> {
    Ok(Elliptic::new(m)?.k())
}

/// The complete elliptic integral of the second kind E(m).
///
/// ```
/// use elastica::{ellip_e, ellip_k};
/// use std::f64::consts::FRAC_PI_2;
/// // Legendre's relation E·K′ + E′·K − K·K′ = π/2 (primes: at 1 − m)
/// let (m, m1) = (0.3, 0.7);
/// let (k, e, k1, e1) = (ellip_k(m)?, ellip_e(m)?, ellip_k(m1)?, ellip_e(m1)?);
/// assert!((e * k1 + e1 * k - k * k1 - FRAC_PI_2).abs() < 1e-14);
/// // E(0) = π/2 (a circle's quarter) and E(1) = 1
/// assert!((ellip_e(0.0)? - FRAC_PI_2).abs() < 1e-15);
/// assert!((ellip_e(1.0)? - 1.0).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn ellip_e(m: f64) -> Result<f64, EllipticError> {
    Ok(Elliptic::new(m)?.e())
}

/// sn, cn, dn, am and E(u|m) at one point (precompute an [`Elliptic`] for many points).
///
/// ```
/// let v = elastica::elliptic::jacobi(0.3, 0.0).unwrap();
/// assert!((v.sn - 0.3f64.sin()).abs() < 1e-16 && (v.eps - 0.3).abs() < 1e-16);
/// ```
pub fn jacobi(u: f64, m: f64) -> Result<JacobiValues, EllipticError> {
    Ok(Elliptic::new(m)?.eval(u))
}
