//! Nearly straight curves under tension: the closed form near the separatrix, solved in
//! unknowns centred on the pendulum's top.
//!
//! Under a strong pull (λL² ≫ 1) a nearly straight elastica bends only in boundary layers
//! at its ends; in between its tangent hugs the force direction, the pendulum's unstable
//! top, where the angle off the top grows like `k′ cosh(σ − σ_top)`. Shooting from the
//! start amplifies errors like `e^{√λ L}` there, and the closed form's `(k, s₀, ℓ)` couple
//! badly (the top, the quarter period `K ≈ ln(4/k′)`, moves with `k`). The unknowns
//! `(q, τ₀, ℓ)` — `q = −ln(1 − k)` with `1 − k` kept exactly
//! ([`ElasticaParams::one_minus_k`]), `τ₀ = s₀ − σ_top` the start's distance from the top,
//! and the normalized length — make the end angles `≈ k′ cosh τ` smooth and well scaled.

use elastica::elliptic::Elliptic;
use elastica::segment::{ElasticaParams, Segment};
use elastica::unit::Family;

use super::{damped_newton, norm, segment_residuals, EndData, TOLERANCE};

/// Relative step of the Jacobian's differences in `(q, τ₀, ℓ)`.
const TAUT_STEP: f64 = 1e-4;

/// Where the top lies on the normalized curve of `family` with `1 − k = c`: σ = ±K
/// (inflectional, sn = ±1) or ±kK (non-inflectional, am = ±π/2), on the side `sign`.
fn top(family: Family, c: f64, sign: f64) -> Option<f64> {
    let kk = Elliptic::from_complement(c).ok()?.k();
    let at = match family {
        Family::Inflectional => kk,
        Family::NonInflectional => (1.0 - c) * kk,
    };
    at.is_finite().then_some(sign * at)
}

/// The closed form of `(family, 1 − k = c, s₀, ℓ)` between `d`'s end points.
fn shape(d: &EndData, family: Family, c: f64, s0: f64, l: f64) -> Option<Segment> {
    let unit = Segment::Elastica(ElasticaParams {
        family,
        k: 1.0 - c,
        s0,
        l,
        scale: 1.0,
        phi: 0.0,
        x0: 0.0,
        y0: 0.0,
        one_minus_k: Some(c),
    });
    unit.with_ends(d.start, d.end)
}

/// Damped Newton in `(q, τ₀, ℓ)` from the closed form `seg` (whose `1 − k` is small):
/// the segment, its residuals ([`super::residuals`]'s) and the iterations.
pub(super) fn newton_taut(d: &EndData, seg: &Segment) -> Option<(Segment, [f64; 3], usize)> {
    let Segment::Elastica(p) = seg else {
        return None;
    };
    let c0 = p.one_minus_k.unwrap_or(1.0 - p.k);
    if !(c0 > 0.0 && c0 < 0.5) {
        return None;
    }
    let family = p.family;
    // about the top nearest the window's middle first, then the other
    let near = if p.s0 + 0.5 * p.l >= 0.0 { 1.0 } else { -1.0 };
    let mut best: Option<(Segment, [f64; 3], usize)> = None;
    for sign in [near, -near] {
        let res = |y: [f64; 3]| {
            let c = (-y[0]).exp();
            let s0 = top(family, c, sign)? + y[1];
            segment_residuals(d, shape(d, family, c, s0, y[2])?)
        };
        let Some(t) = top(family, c0, sign) else {
            continue;
        };
        let y = [-c0.ln(), p.s0 - t, p.l];
        // the length depends on the tension only through the slack (≈ ℓ·δ): differences
        // wide enough to see it above rounding
        if let Some(found) = damped_newton(&res, y, [-(0.5f64.ln()), 700.0], TAUT_STEP) {
            if best.as_ref().is_none_or(|b| norm(&found.1) < norm(&b.1)) {
                best = Some(found);
            }
        }
        if best.as_ref().is_some_and(|b| norm(&b.1) <= TOLERANCE) {
            break;
        }
    }
    best
}
