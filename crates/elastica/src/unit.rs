//! The two normalized elastica of the papers, in arc length σ:
//!
//! - inflectional `ζ(σ) = (2E(σ|k²) − σ, 2k(1 − cn(σ|k²)))`, tangent angle
//!   `θ = 2 atan2(k sn, dn)`, curvature `2k cn`, k ∈ [0, 1];
//! - non-inflectional `γ(σ) = ((1 − 2/k²)σ + (2/k)E(σ/k|k²), (2/k)(1 − dn(σ/k|k²)))`,
//!   tangent angle `θ = 2 am(σ/k)`, curvature `(2/k) dn(σ/k)`, k ∈ (0, 1].
//!
//! The non-inflectional x-coordinate cancels terms of size σ/k² down to O(k); it is
//! evaluated as `σ − 2k D(σ/k)` with `D = ∫ sn²` ([`crate::elliptic::JacobiValues::d`])
//! and `1 − dn = m sn²/(1 + dn)`, which keeps full accuracy for small k. Both curves
//! pass through the origin with tangent angle 0 at σ = 0 and turn left (κ > 0 there).

use crate::elliptic::{Elliptic, EllipticError};

/// The two closed-form families of non-circular elastica.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
pub enum Family {
    /// Curvature changes sign (κ = 2k cn); k ∈ [0, 1].
    Inflectional,
    /// Curvature keeps its sign (κ = (2/k) dn); k ∈ (0, 1].
    #[cfg_attr(feature = "serde", serde(rename = "noninflectional"))]
    NonInflectional,
}

/// A point of a normalized elastica with its first-order geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitPoint {
    /// Position.
    pub p: [f64; 2],
    /// Unit tangent (cos θ, sin θ).
    pub t: [f64; 2],
    /// Tangent angle θ, continuous in σ.
    pub theta: f64,
    /// Curvature dθ/dσ.
    pub kappa: f64,
}

/// A normalized elastica of one family and modulus k, ready to evaluate.
#[derive(Clone, Debug)]
pub struct UnitElastica {
    family: Family,
    k: f64,
    ell: Elliptic,
}

impl UnitElastica {
    /// The normalized curve of `family` with modulus `k` (k ∈ [0, 1] inflectional,
    /// k ∈ (0, 1] non-inflectional).
    ///
    /// ```
    /// use elastica::{jacobi, Family, UnitElastica};
    /// // ζ(σ) = (2E(σ|k²) − σ, 2k(1 − cn(σ|k²))) with curvature 2k·cn
    /// let k = 0.7;
    /// let z = UnitElastica::new(Family::Inflectional, k)?;
    /// let sigma = 1.1;
    /// let (p, v) = (z.eval(sigma), jacobi(sigma, k * k)?);
    /// assert!((p.p[0] - (2.0 * v.eps - sigma)).abs() < 1e-14);
    /// assert!((p.p[1] - 2.0 * k * (1.0 - v.cn)).abs() < 1e-14);
    /// assert!((p.kappa - 2.0 * k * v.cn).abs() < 1e-14);
    /// // the non-inflectional family needs k > 0
    /// assert!(UnitElastica::new(Family::NonInflectional, 0.0).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(family: Family, k: f64) -> Result<Self, EllipticError> {
        let ok = match family {
            Family::Inflectional => (0.0..=1.0).contains(&k),
            Family::NonInflectional => k > 0.0 && k <= 1.0,
        };
        if !ok {
            return Err(EllipticError::Parameter(k * k));
        }
        Ok(UnitElastica {
            family,
            k,
            ell: Elliptic::from_modulus(k)?,
        })
    }

    /// The normalized curve of `family` with modulus `k = 1 − one_minus_k`, given by its
    /// distance from 1 ([`Elliptic::from_complement`]): for shapes near the separatrix,
    /// whose `1 − k` is below what `k` in `f64` resolves.
    pub fn with_complement(family: Family, one_minus_k: f64) -> Result<Self, EllipticError> {
        if family == Family::NonInflectional && !(one_minus_k < 1.0) {
            return Err(EllipticError::Parameter(one_minus_k));
        }
        Ok(UnitElastica {
            family,
            k: 1.0 - one_minus_k,
            ell: Elliptic::from_complement(one_minus_k)?,
        })
    }

    /// The family.
    pub fn family(&self) -> Family {
        self.family
    }

    /// The modulus k.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// The elliptic parameter data (m = k²).
    pub fn elliptic(&self) -> &Elliptic {
        &self.ell
    }

    /// Position, tangent, angle and curvature at arc length σ.
    pub fn eval(&self, sigma: f64) -> UnitPoint {
        self.eval_impl(sigma, false, true).0
    }

    /// [`UnitElastica::eval`] plus the derivative of the position with respect to k.
    pub fn eval_dk(&self, sigma: f64) -> (UnitPoint, [f64; 2]) {
        self.eval_impl(sigma, true, true)
    }

    /// Position, unit tangent and ∂position/∂k without the tangent angle (which costs
    /// `atan2`s the fitting loops do not need).
    pub(crate) fn eval_fit(&self, sigma: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let (u, dk) = self.eval_impl(sigma, true, false);
        (u.p, u.t, dk)
    }

    #[inline(always)]
    fn eval_impl(&self, sigma: f64, want_dk: bool, want_theta: bool) -> (UnitPoint, [f64; 2]) {
        let k = self.k;
        let m = k * k;
        let jacobi = |u: f64| {
            if want_theta {
                self.ell.eval(u)
            } else {
                self.ell.eval_no_am(u)
            }
        };
        match self.family {
            Family::Inflectional => {
                let v = jacobi(sigma);
                let one_minus_cn = if v.cn > 0.0 {
                    v.sn * v.sn / (1.0 + v.cn)
                } else {
                    1.0 - v.cn
                };
                let p = [2.0 * v.eps - sigma, 2.0 * k * one_minus_cn];
                let t = [1.0 - 2.0 * m * v.sn * v.sn, 2.0 * k * v.sn * v.dn];
                let theta = if want_theta {
                    2.0 * (k * v.sn).atan2(v.dn)
                } else {
                    f64::NAN
                };
                let up = UnitPoint {
                    p,
                    t,
                    theta,
                    kappa: 2.0 * k * v.cn,
                };
                let dk = if want_dk {
                    let d = self.ell.dm(sigma, &v);
                    [4.0 * k * d.eps, 2.0 * one_minus_cn - 4.0 * m * d.cn]
                } else {
                    [0.0; 2]
                };
                (up, dk)
            }
            Family::NonInflectional => {
                let u = sigma / k;
                let v = jacobi(u);
                let s2 = v.sn * v.sn;
                let p = [sigma - 2.0 * k * v.d, 2.0 * k * s2 / (1.0 + v.dn)];
                let t = [v.cn * v.cn - s2, 2.0 * v.sn * v.cn];
                let up = UnitPoint {
                    p,
                    t,
                    theta: 2.0 * v.am,
                    kappa: 2.0 * v.dn / k,
                };
                let dk = if want_dk {
                    let d = self.ell.dm(u, &v);
                    let dx = 2.0 * u * s2 + 4.0 * v.dn * d.am;
                    let dy = -2.0 * s2 / (1.0 + v.dn) - 2.0 * u * v.sn * v.cn - 4.0 * d.dn;
                    [dx, dy]
                } else {
                    [0.0; 2]
                };
                (up, dk)
            }
        }
    }

    /// Arc lengths σ ∈ (a, b) (either order) where the curvature vanishes: σ = (2j+1)K for
    /// the inflectional family, none for the other.
    pub fn inflections_between(&self, a: f64, b: f64) -> Vec<f64> {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let kk = self.ell.k();
        if self.family == Family::NonInflectional || !kk.is_finite() || self.k == 0.0 {
            return Vec::new();
        }
        // in floating point: far out (|σ| ≫ K) an integer index would overflow
        let mut j = ((lo / kk - 1.0) / 2.0).ceil();
        let mut out = Vec::new();
        // at most 100 001 inflections, whatever the range
        for _ in 0..=100_001 {
            let s = (2.0 * j + 1.0) * kk;
            if !(s < hi) {
                break;
            }
            if s > lo {
                out.push(s);
            }
            j += 1.0;
            if out.len() > 100_000 {
                break;
            }
        }
        out
    }

    /// max |κ| over σ ∈ [a, b] (either order).
    pub fn max_abs_curvature_between(&self, a: f64, b: f64) -> f64 {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let k = self.k;
        // |cn| (inflectional) and dn (non-inflectional) peak at even multiples of K.
        let (scale, lo_u, hi_u) = match self.family {
            Family::Inflectional => (2.0 * k, lo, hi),
            Family::NonInflectional => (2.0 / k, lo / k, hi / k),
        };
        let kk = self.ell.k();
        let contains_peak = if kk.is_finite() {
            let j = (lo_u / (2.0 * kk)).ceil();
            2.0 * kk * j <= hi_u
        } else {
            lo_u <= 0.0 && hi_u >= 0.0
        };
        if contains_peak {
            return scale;
        }
        let at = |u: f64| {
            let v = self.ell.eval(u);
            match self.family {
                Family::Inflectional => v.cn.abs(),
                Family::NonInflectional => v.dn,
            }
        };
        scale * at(lo_u).max(at(hi_u))
    }
}
