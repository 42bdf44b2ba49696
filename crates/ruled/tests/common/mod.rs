//! The independent over-cut check shared by `tests/checker.rs` and
//! `benches/direction_gain.rs`: design points on a jittered grid 4× denser than the
//! optimizer's, against every leg's line rebuilt from the result's B-spline data with
//! `geom`'s de Boor evaluation (not the optimizer's code paths).

use geom::bspline::BSplineCurve;
use nalgebra::Vector2;
use ruled::{Block, DirectionCut, Params, PreCut};

/// SplitMix64 in [0, 1).
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Every leg's `(a, m)` curve along the cut, rebuilt from the result.
pub fn leg_curves(d: &DirectionCut) -> Vec<BSplineCurve<2>> {
    d.legs
        .iter()
        .map(|l| {
            let ctrl =
                l.a.iter()
                    .zip(&l.m)
                    .map(|(a, m)| nalgebra::Vector2::new(*a, *m))
                    .collect();
            BSplineCurve::try_new(d.degree, d.knots.clone(), ctrl).unwrap()
        })
        .collect()
}

/// The height of the leg `c` (one of [`leg_curves`] of `d`) at frame point `(u, w)`, its
/// line extended across the whole block.
pub fn leg_z(c: &BSplineCurve<2>, d: &DirectionCut, u: f64, w: f64) -> f64 {
    let am = c.eval(u);
    am[0] + am[1] * (w - d.w_mid) / d.w_half
}

/// Checks `cut` against `design` on a jittered grid 4N × 4M per direction over the whole
/// block `b`; returns (points checked, largest excess of design over a leg).
pub fn check_in(
    b: &Block,
    cut: &PreCut,
    params: &Params,
    design: &dyn Fn(f64, f64) -> Option<f64>,
) -> (usize, f64) {
    let mut rng = Rng(0xC0FFEE);
    let (n, m) = (4 * params.sections, 4 * params.samples);
    let mut worst = f64::NEG_INFINITY;
    let mut count = 0;
    for d in &cut.directions {
        let curves = leg_curves(d);
        let along = Vector2::new(d.direction[0], d.direction[1]);
        let across = Vector2::new(d.across[0], d.across[1]);
        for i in 0..n {
            let u = d.u.0 + (d.u.1 - d.u.0) * (i as f64 + rng.next()) / n as f64;
            for k in 0..m {
                let w = d.w.0 + (d.w.1 - d.w.0) * (k as f64 + rng.next()) / m as f64;
                let p = along * u + across * w;
                if !(b.covers(p.x, p.y)) {
                    continue;
                }
                let Some(f) = design(p.x, p.y) else { continue };
                count += 1;
                for c in &curves {
                    worst = worst.max(f - leg_z(c, d, u, w));
                }
            }
        }
    }
    (count, worst)
}
