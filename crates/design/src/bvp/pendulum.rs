//! The pendulum side of the boundary-value problem: an elastica as the solution of
//! θ'' = λ₂ cos θ − λ₁ sin θ ("Hot Blade Cuttings" eq. 3) from its start point, start angle
//! and start curvature κ₀, given by its pendulum data `u = (κ₀, λ₁, λ₂)`. Shooting on those
//! data, their estimate from the discrete elastica, and the closed form they define.

use std::f64::consts::PI;

use elastica::elliptic::Elliptic;
use elastica::segment::{ElasticaParams, Segment};
use elastica::unit::{Family, UnitElastica};

use crate::bezier::wrap;

use super::{jacobian, norm, other, residuals, EndData};

/// Steps of the shooting integration (RK4; its error, O(h⁴), is far below the
/// tolerances on a unit chord).
const SHOOT_STEPS: usize = 2000;
/// Residual at which shooting stops: its solution only starts the closed form's Newton,
/// which converges from far rougher starts.
const SHOOT_ENOUGH: f64 = 1e-6;

/// The end of the elastica from the start of `d` with start curvature `u[0]` and
/// multipliers `(λ₁, λ₂) = (u[1], u[2])` (θ'' = λ₂ cos θ − λ₁ sin θ, "Hot Blade Cuttings"
/// eq. 3), integrated over the length: `(x, y, θ)`.
fn shoot_end(d: &EndData, u: [f64; 3]) -> [f64; 3] {
    let f = |y: [f64; 4]| {
        let (s, c) = y[2].sin_cos();
        [c, s, y[3], u[2] * c - u[1] * s]
    };
    let h = d.length / SHOOT_STEPS as f64;
    let mut y = [d.start[0], d.start[1], d.start_angle, u[0]];
    let add = |a: [f64; 4], b: [f64; 4], w: f64| std::array::from_fn(|i| a[i] + w * b[i]);
    for _ in 0..SHOOT_STEPS {
        let k1 = f(y);
        let k2 = f(add(y, k1, 0.5 * h));
        let k3 = f(add(y, k2, 0.5 * h));
        let k4 = f(add(y, k3, h));
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    [y[0], y[1], y[2]]
}

/// The start curvature and the multipliers `(κ₀, λ₁, λ₂)` of the discrete elastica, from
/// the eq. (11) fit κ = λ₂x − λ₁y + α of its turning angles: the pendulum data of the
/// solution to the discretization's error.
pub(super) fn discrete_pendulum(
    d: &EndData,
    discrete: &elastica::discrete::DiscreteElastica,
) -> Option<[f64; 3]> {
    let h = d.length / discrete.angles.len() as f64;
    let (mut a, mut b) = (nalgebra::Matrix3::zeros(), nalgebra::Vector3::zeros());
    for j in 1..discrete.angles.len() {
        let p = discrete.points[j];
        let v = nalgebra::Vector3::new(p[0] - d.start[0], -(p[1] - d.start[1]), 1.0);
        a += v * v.transpose();
        b += v * ((discrete.angles[j] - discrete.angles[j - 1]) / h);
    }
    let g = a.lu().solve(&b)?;
    Some([g[2], g[1], g[0]])
}

/// The pendulum data `(κ₀, λ₁, λ₂)` of a closed-form segment: θ'' = −λ sin(θ − φ) with
/// λ = 1/S² and φ the segment's rotation (turned by π when it runs backwards).
pub(super) fn pendulum_of(seg: &Segment) -> Option<[f64; 3]> {
    let Segment::Elastica(p) = seg else {
        return None;
    };
    let e = seg.evaluator().ok()?;
    let lambda = 1.0 / (p.scale * p.scale);
    let phi = p.phi + if p.l < 0.0 { std::f64::consts::PI } else { 0.0 };
    Some([
        e.eval(0.0).curvature,
        lambda * phi.cos(),
        lambda * phi.sin(),
    ])
}

/// [`shoot`] from `u`: Levenberg–Marquardt on the end point and the end angle.
pub(super) fn shoot_from(d: &EndData, mut u: [f64; 3]) -> Option<[f64; 3]> {
    let res = |u: [f64; 3]| {
        let e = shoot_end(d, u);
        [e[0] - d.end[0], e[1] - d.end[1], e[2] - d.end_angle]
    };
    // Levenberg–Marquardt: robust from a rough start
    let mut r = res(u);
    let mut mu = 1e-3;
    for _ in 0..200 {
        if norm(&r) <= SHOOT_ENOUGH {
            return Some(u);
        }
        let mut jac = nalgebra::Matrix3::zeros();
        for j in 0..3 {
            let e = 1e-7 * u[j].abs().max(1.0);
            let (mut up, mut down) = (u, u);
            up[j] += e;
            down[j] -= e;
            let (ru, rd) = (res(up), res(down));
            for i in 0..3 {
                jac[(i, j)] = (ru[i] - rd[i]) / (2.0 * e);
            }
        }
        let jt = jac.transpose();
        let (jtj, jtr) = (jt * jac, jt * nalgebra::Vector3::from(r));
        let mut accepted = false;
        for _ in 0..40 {
            let m = jtj + nalgebra::Matrix3::identity() * (mu * jtj.diagonal().max().max(1e-300));
            if let Some(step) = m.lu().solve(&jtr) {
                let trial = [u[0] - step[0], u[1] - step[1], u[2] - step[2]];
                let rt = res(trial);
                if rt.iter().all(|v| v.is_finite()) && norm(&rt) < norm(&r) {
                    (u, r, accepted) = (trial, rt, true);
                    mu = (mu / 3.0).max(1e-15);
                    break;
                }
            }
            mu *= 4.0;
        }
        if !accepted {
            break;
        }
    }
    // a start for the closed form's Newton, which polishes it
    (norm(&r) <= 1e-4).then_some(u)
}

/// Closed-form starts from the shooting solution `u = (κ₀, λ₁, λ₂)`: the family and
/// modulus from the pendulum's first integral (κ²/2 − λ cos(θ − φ) constant, so
/// k̂² = (κ₀²/(2λ) − cos(θ₀ − φ) + 1)/2; inflectional when k̂ < 1, else modulus 1/k̂), the
/// normalized length √λ·L, and the start on the normalized curve searched on a grid for
/// the smallest residual, both ways along it.
pub(super) fn closed_form_starts(d: &EndData, u: [f64; 3]) -> Vec<(Family, [f64; 3])> {
    let lambda = u[1].hypot(u[2]);
    if !(lambda > 1e-12) {
        return Vec::new();
    }
    let phi = u[2].atan2(u[1]);
    let khat2 = (u[0] * u[0] / (2.0 * lambda) - (d.start_angle - phi).cos() + 1.0) / 2.0;
    let (family, k) = if khat2 < 1.0 {
        (Family::Inflectional, khat2.max(0.0).sqrt())
    } else {
        (Family::NonInflectional, 1.0 / khat2.sqrt())
    };
    let k = k.clamp(1e-9, 1.0);
    let l = lambda.sqrt() * d.length;
    // near the separatrix, the other family's neighbour too
    let mut shapes = vec![(family, k)];
    if k > 0.999 {
        shapes.push((other(family), k));
    }
    let mut out = Vec::new();
    for (family, k) in shapes {
        let mut best: Option<(f64, [f64; 3])> = None;
        // a grid of s₀ ∈ [−80, 80] spaced 0.2 (a normalized curve's features are about
        // 1 long), then two finer grids about the best
        let (mut centre, mut half, steps) = (0.0, 80.0, 800);
        for _ in 0..3 {
            for sign in [1.0, -1.0] {
                for i in 0..=steps {
                    let s0 = centre - half + 2.0 * half * i as f64 / steps as f64;
                    let x = [k, s0, sign * l];
                    if let Some((_, r)) = residuals(d, family, x) {
                        if best.is_none_or(|b| norm(&r) < b.0) {
                            best = Some((norm(&r), x));
                        }
                    }
                }
            }
            let Some(b) = best else { break };
            (centre, half) = (b.1[1], 4.0 * half / steps as f64);
        }
        out.extend(best.map(|b| (family, b.1)));
    }
    out
}

/// Below this `1 − k` a closed form carries its modulus by its complement
/// ([`ElasticaParams::one_minus_k`]).
const SEPARATRIX: f64 = 1e-3;

/// Below this `λL²` the force is too weak to bend the curve measurably: the elastica is a
/// circular arc (or a line) to `O(λL²)` in its tangent angle.
const NO_FORCE: f64 = 1e-14;

/// The closed-form segment that leaves `start` at `start_angle` with curvature `u[0]`
/// under the multipliers `(λ₁, λ₂) = (u[1], u[2])`, `length` long: the pendulum
/// `θ'' = −λ sin(θ − φ)` (λ = |(λ₁, λ₂)|, φ = arg(λ₁, λ₂)) in the normalized arc length
/// `σ = √λ s`, whose first integral `ψ'²/4 + sin²(ψ/2) = k̂²` (ψ = θ − φ) gives the family
/// (inflectional when k̂ < 1, modulus k̂; else modulus 1/k̂) and the start `s₀` on the
/// normalized curve by the incomplete integral F of its amplitude. A curve bending left
/// runs forwards; a non-inflectional one bending right runs backwards (ℓ < 0) on the
/// curve turned by π. `None` at the unstable rest (ψ = π, κ₀ = 0) and for non-finite data.
///
/// Unlike `(k, s₀, ℓ)`, the data `u` are well conditioned for nearly straight curves
/// (angles → 0, where the closed form's window shrinks or its modulus tends to 1), so the
/// near-straight solve runs Newton on them ([`newton_pendulum`]).
pub(super) fn segment_of_pendulum(
    start: [f64; 2],
    start_angle: f64,
    u: [f64; 3],
    length: f64,
) -> Option<Segment> {
    if !u.iter().all(|v| v.is_finite()) {
        return None;
    }
    let lambda = u[1].hypot(u[2]);
    if !(lambda * length * length > NO_FORCE) {
        return Some(Segment::Arc {
            x0: start[0],
            y0: start[1],
            phi: start_angle,
            curvature: u[0],
            length,
        });
    }
    let phi = u[2].atan2(u[1]);
    let scale = 1.0 / lambda.sqrt();
    let half = 0.5 * wrap(start_angle - phi);
    let c = u[0] * scale;
    let khat2 = 0.25 * c * c + half.sin().powi(2);
    // 1 − k̂² = cos²(ψ/2) − c²/4 as a product: exact to rounding as k̂ → 1 (the
    // separatrix, where a nearly straight curve under tension lives)
    let (ch, hc) = (half.cos(), 0.5 * c.abs());
    let gap = (ch - hc) * (ch + hc);
    let khat = khat2.sqrt();
    let (family, one_minus_k) = if gap >= 0.0 {
        (Family::Inflectional, gap / (1.0 + khat))
    } else {
        (Family::NonInflectional, -gap / (khat * (1.0 + khat)))
    };
    let k = 1.0 - one_minus_k;
    // the complement is kept where k alone would lose its digits
    let precise = (one_minus_k < SEPARATRIX).then_some(one_minus_k);
    let (unit, ell) = match precise {
        Some(c) => (
            UnitElastica::with_complement(family, c).ok()?,
            Elliptic::from_complement(c).ok()?,
        ),
        None => (
            UnitElastica::new(family, k).ok()?,
            Elliptic::from_modulus(k).ok()?,
        ),
    };
    let (s0, l, turn) = match family {
        Family::Inflectional => {
            // sn(s₀) = sin(ψ/2)/k, cn(s₀) = c/(2k): the amplitude is atan2 of the two
            let am = if khat > 0.0 {
                half.sin().atan2(0.5 * c)
            } else {
                0.0
            };
            (ell.f(am), length / scale, phi)
        }
        Family::NonInflectional => {
            // am(s₀/k) = ψ/2, curvature (2/k)·dn > 0
            let s0 = k * ell.f(half);
            if c >= 0.0 {
                (s0, length / scale, phi)
            } else {
                (s0, -length / scale, phi - PI)
            }
        }
    };
    if !s0.is_finite() {
        return None;
    }
    let f0 = unit.eval(s0).p;
    let (sin, cos) = turn.sin_cos();
    Some(Segment::Elastica(ElasticaParams {
        one_minus_k: precise,
        family,
        k,
        s0,
        l,
        scale,
        phi: turn,
        x0: start[0] - scale * (cos * f0[0] - sin * f0[1]),
        y0: start[1] - scale * (sin * f0[0] + cos * f0[1]),
    }))
}

/// The end of [`segment_of_pendulum`] against `d`: end point (relative to the length)
/// and total turning.
fn pendulum_residuals(d: &EndData, u: [f64; 3]) -> Option<(Segment, [f64; 3])> {
    let seg = segment_of_pendulum(d.start, d.start_angle, u, d.length)?;
    let e = seg.evaluator().ok()?;
    let (a, b) = (e.eval(0.0), e.eval(1.0));
    let r = [
        (b.p[0] - d.end[0]) / d.length,
        (b.p[1] - d.end[1]) / d.length,
        (b.angle - a.angle) - (d.end_angle - d.start_angle),
    ];
    r.iter().all(|v| v.is_finite()).then_some((seg, r))
}

/// `(κ₀, λ₂)` from `u` meeting the end's height and the turning with `λ₁` held at
/// `lambda1` (Newton on two unknowns, at most 50 steps), and the end's remaining
/// residual along the chord; `None` where it does not converge.
fn across_at(d: &EndData, u: [f64; 3], lambda1: f64) -> Option<([f64; 3], f64)> {
    let mut u = [u[0], lambda1, u[2]];
    let two = |u: [f64; 3]| pendulum_residuals(d, u).map(|(_, r)| r);
    let mut r = two(u)?;
    for _ in 0..50 {
        if r[1].abs().max(r[2].abs()) <= 1e-15 {
            break;
        }
        let h = [1e-7 * u[0].abs().max(1.0), 1e-7 * u[2].abs().max(1.0)];
        let a = two([u[0] + h[0], u[1], u[2]])?;
        let b = two([u[0], u[1], u[2] + h[1]])?;
        let j = nalgebra::Matrix2::new(
            (a[1] - r[1]) / h[0],
            (b[1] - r[1]) / h[1],
            (a[2] - r[2]) / h[0],
            (b[2] - r[2]) / h[1],
        );
        let step = j.lu().solve(&nalgebra::Vector2::new(r[1], r[2]))?;
        let next = [u[0] - step[0], u[1], u[2] - step[1]];
        let rn = two(next)?;
        if rn[1].abs().max(rn[2].abs()) >= r[1].abs().max(r[2].abs()) {
            break;
        }
        (u, r) = (next, rn);
    }
    (r[1].abs().max(r[2].abs()) <= 1e-12).then_some((u, r[0]))
}

/// Pendulum data for `d` found by following `λ₁` alone, from `u` (a Newton that stalled
/// near a buckling load: the end short of the chord by the slack a buckled mode takes)
/// towards tension, each `λ₁` meeting the end's height and the turning
/// ([`across_at`]), to where the end meets the chord: the first sign change of that
/// residual over `λ₁ = u₁ − 10ʲ` (j = −3 … 8), then bisection (at most 100 halvings).
/// `None` when it does not change sign.
pub(super) fn along_tension(d: &EndData, u: [f64; 3]) -> Option<[f64; 3]> {
    let (mut lo, mut r_lo) = across_at(d, u, u[1])?;
    let mut hi = None;
    for j in -3..=8 {
        let l1 = u[1] - 10f64.powi(j);
        let Some((v, r)) = across_at(d, lo, l1) else {
            continue;
        };
        if r.signum() != r_lo.signum() {
            hi = Some((v, r));
            break;
        }
        (lo, r_lo) = (v, r);
    }
    let (mut hi, _) = hi?;
    for _ in 0..100 {
        let mid = 0.5 * (lo[1] + hi[1]);
        if !(mid > hi[1].min(lo[1]) && mid < hi[1].max(lo[1])) {
            break;
        }
        let (v, r) = across_at(d, lo, mid)?;
        if r == 0.0 {
            return Some(v);
        }
        if r.signum() == r_lo.signum() {
            (lo, r_lo) = (v, r);
        } else {
            hi = v;
        }
    }
    Some(lo)
}

/// Levenberg–Marquardt iterations at most on the pendulum data.
const MAX_PENDULUM: usize = 100;

/// The elastica of `d` (on a unit chord) by Levenberg–Marquardt on its pendulum data from
/// `u`, with the closed form ([`segment_of_pendulum`]) as the exact integrator: the
/// residuals are the end point and the turning. Returns the segment, its residuals and
/// the iterations; `None` when no step lowers the residual.
///
/// The end point's component along the chord depends on `λ₁` only at second order in the
/// angles (the slack `L − chord ≈ ½∫θ²`), so for nearly straight curves that column of
/// the Jacobian is small; the damping keeps the steps bounded where it drowns in rounding,
/// and the residual, not `λ₁`, decides convergence.
pub(super) fn newton_pendulum(
    d: &EndData,
    mut u: [f64; 3],
    tolerance: f64,
) -> Option<(Segment, [f64; 3], usize)> {
    let (mut seg, mut r) = pendulum_residuals(d, u)?;
    let mut mu = 1e-6;
    for it in 0..MAX_PENDULUM {
        if norm(&r) <= tolerance {
            return Some((seg, r, it));
        }
        let jac = jacobian(&|x| pendulum_residuals(d, x).map(|v| v.1), u, r, &|v| {
            1e-5 * v.abs().max(1.0)
        })?;
        let jt = jac.transpose();
        let (jtj, jtr) = (jt * jac, jt * nalgebra::Vector3::from(r));
        let mut accepted = false;
        for _ in 0..40 {
            let mut m = jtj;
            for i in 0..3 {
                m[(i, i)] += mu * jtj[(i, i)].max(1e-30);
            }
            if let Some(step) = m.lu().solve(&jtr) {
                let trial = [u[0] - step[0], u[1] - step[1], u[2] - step[2]];
                if let Some((s, rt)) = pendulum_residuals(d, trial) {
                    if norm(&rt) < norm(&r) {
                        (u, seg, r, accepted) = (trial, s, rt, true);
                        mu = (mu / 10.0).max(1e-15);
                        break;
                    }
                }
            }
            mu *= 10.0;
        }
        if !accepted {
            break;
        }
    }
    Some((seg, r, MAX_PENDULUM))
}
