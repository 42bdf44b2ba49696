//! `elastica::stability` against what is known of the clamped elastica:
//! - a straight blade buckles at the first clamped–clamped load 4π²EI/L²;
//! - non-inflectional elastica (C-shapes) and circular arcs are stable;
//! - Sachkov ("Conjugate points in Euler's elastic problem", 2008): an inflectional
//!   elastica has its first conjugate point between its first and third inflection, so
//!   a blade with no inflection is stable and one past its third is not;
//! - the margin's sign agrees with Jacobi's conjugate-point test along the closed form
//!   (an independent method: shooting the Jacobi equation with the two chord constraints,
//!   Manning–Rogers–Maddocks' determinant) on random clamped configurations, and with the
//!   discrete blade's reduced Hessian;
//! - margins are invariant under a change of units and rigid motion;
//! - the multipliers satisfy the equilibrium equation, and the loads their closed forms.

use elastica::stability::follow::{follow, DiscreteBlade, FollowParams, HeldEnds, Snap, SEGMENTS};
use elastica::stability::{margin_of, multipliers, stability, Class, StabilityParams};
use elastica::{ElasticaParams, Elliptic, Family, Segment};
use proptest::prelude::*;
use std::f64::consts::PI;

/// Jacobi's test: the first `s ∈ (0, L]` where the constrained Jacobi fields' determinant
/// vanishes (`None`: no conjugate point, the equilibrium is stable). RK4 on `steps` steps.
fn first_conjugate(
    length: f64,
    theta: &dyn Fn(f64) -> f64,
    load: [f64; 2],
    steps: usize,
) -> Option<f64> {
    // y = [ψa, ψa', ψb, ψb', ψc, ψc', ∫g₁ψa, ∫g₁ψb, ∫g₁ψc, ∫g₂ψa, ∫g₂ψb, ∫g₂ψc]
    let deriv = |s: f64, y: &[f64; 12]| -> [f64; 12] {
        let t = theta(s);
        let q = load[0] * t.cos() + load[1] * t.sin();
        let (g1, g2) = (-t.sin(), t.cos());
        [
            y[1],
            -q * y[0],
            y[3],
            -q * y[2] + g1,
            y[5],
            -q * y[4] + g2,
            g1 * y[0],
            g1 * y[2],
            g1 * y[4],
            g2 * y[0],
            g2 * y[2],
            g2 * y[4],
        ]
    };
    let det = |y: &[f64; 12]| -> f64 {
        let col = |c: usize| {
            let v = [y[2 * c], y[6 + c], y[9 + c]];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / n, v[1] / n, v[2] / n]
        };
        let (a, b, c) = (col(0), col(1), col(2));
        a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1])
            + c[0] * (a[1] * b[2] - a[2] * b[1])
    };
    let h = length / steps as f64;
    let mut y = [0.0; 12];
    y[1] = 1.0;
    let mut reference = 0.0;
    for i in 0..steps {
        let s = i as f64 * h;
        let k1 = deriv(s, &y);
        let add = |a: &[f64; 12], k: &[f64; 12], f: f64| -> [f64; 12] {
            std::array::from_fn(|j| a[j] + f * k[j])
        };
        let k2 = deriv(s + 0.5 * h, &add(&y, &k1, 0.5 * h));
        let k3 = deriv(s + 0.5 * h, &add(&y, &k2, 0.5 * h));
        let k4 = deriv(s + h, &add(&y, &k3, h));
        y = std::array::from_fn(|j| y[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
        let d = det(&y);
        // the sign just after the start is the reference (the determinant vanishes at 0)
        if i + 1 == steps / 200 {
            reference = d.signum();
        } else if i + 1 > steps / 200 && d.signum() != reference {
            return Some(s + h);
        }
    }
    None
}

fn elastica(family: Family, k: f64, s0: f64, l: f64, scale: f64, phi: f64) -> Segment {
    Segment::Elastica(ElasticaParams {
        family,
        k,
        s0,
        l,
        scale,
        phi,
        x0: 0.0,
        y0: 0.0,
        one_minus_k: None,
    })
}

fn conjugate_of(s: &Segment) -> Option<f64> {
    let e = s.evaluator().unwrap();
    let l = s.length();
    first_conjugate(l, &|x| e.eval(x / l).angle, multipliers(s), 4000)
}

#[test]
fn a_straight_blade_buckles_at_the_first_clamped_clamped_load() {
    for length in [0.8, 1.0, 700.0, 1000.0, 2500.0] {
        let p_cr = 4.0 * PI * PI / (length * length);
        let margin =
            |p: f64| margin_of(length, |_| 0.3, [p * 0.3f64.cos(), p * 0.3f64.sin()], 128).unwrap();
        // stable below, unstable above, margin 1 − P/P_cr
        assert!((margin(0.0) - 1.0).abs() < 1e-8);
        assert!((margin(0.5 * p_cr) - 0.5).abs() < 1e-8);
        assert_eq!(Class::of(margin(0.99 * p_cr), 0.05), Class::Marginal);
        assert_eq!(Class::of(margin(1.01 * p_cr), 0.05), Class::Unstable);
        // the load where it changes: bisection on the sign
        let (mut lo, mut hi) = (0.5 * p_cr, 1.5 * p_cr);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if margin(mid) >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let found = 0.5 * (lo + hi);
        assert!(
            (found / p_cr - 1.0).abs() < 1e-6,
            "L {length}: buckles at {found}, 4π²/L² = {p_cr}"
        );
        // tension stiffens it: 1 + T/P_cr
        assert!((margin(-2.0 * p_cr) - 3.0).abs() < 1e-8);
    }
}

#[test]
fn circular_arcs_are_stable_and_carry_only_their_moment() {
    for (curvature, length) in [(0.002, 1000.0), (-0.004, 800.0), (2.0, 1.0), (1e-7, 500.0)] {
        let arc = Segment::Arc {
            x0: 3.0,
            y0: -1.0,
            phi: 0.7,
            curvature,
            length,
        };
        let s = stability(&arc, &StabilityParams::default()).unwrap();
        assert_eq!(s.class, Class::Stable, "{curvature}");
        assert!(s.margin > 1.0 - 1e-9, "{curvature}: {}", s.margin);
        assert_eq!((s.loads.force, s.inflections), (0.0, 0));
        assert_eq!(s.loads.moment, [curvature; 2]);
        assert!((s.turning - curvature * length).abs() < 1e-12 * length);
        // EI/R in N·mm for EI = 5e5 N·mm²
        let [force, tension, moment] = s.loads.scaled(5e5);
        assert_eq!((force, tension), ([0.0; 2], [0.0; 2]));
        assert!((moment[0] - 5e5 * curvature).abs() < 1e-9 * 5e5 * curvature.abs());
    }
}

#[test]
fn a_buckled_blade_pushes_with_the_buckling_load() {
    // one period of the pendulum from a clamped end: the first clamped–clamped mode
    for length in [1.0, 1000.0] {
        for k in [1e-4, 1e-3, 1e-2] {
            let quarter = Elliptic::from_modulus(k).unwrap().k();
            let s = elastica(
                Family::Inflectional,
                k,
                0.0,
                4.0 * quarter,
                length / (4.0 * quarter),
                0.0,
            );
            let st = stability(&s, &StabilityParams::default()).unwrap();
            let p_cr = 4.0 * PI * PI / (length * length);
            // K(k) = π/2 (1 + k²/4 + …): the load exceeds P_cr by about k²/2
            let expected = p_cr * (2.0 * quarter / PI).powi(2);
            assert!((st.loads.force / expected - 1.0).abs() < 1e-12);
            assert!((st.loads.force / p_cr - 1.0).abs() < k * k);
            // compressed at both ends, along the chord
            assert!((st.loads.tension[0] + st.loads.force).abs() < 1e-9 * st.loads.force);
            assert!((st.loads.tension[1] + st.loads.force).abs() < 1e-9 * st.loads.force);
            // the clamp moment: EI κ(0) = 2k/S
            assert!((st.loads.moment[0] - 2.0 * k * 4.0 * quarter / length).abs() < 1e-9 / length);
            assert_eq!(st.class, Class::Stable);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// The multipliers satisfy θ'' + λ₁ sin θ − λ₂ cos θ = 0 along the closed form (θ''
    /// by central differences of the curvature, step 1e-4 of the length: error ~1e-8).
    #[test]
    fn multipliers_balance_the_closed_form(
        inflectional in any::<bool>(), k in 0.2f64..0.95, s0 in -3.0f64..3.0,
        l in 0.5f64..4.0, back in any::<bool>(), scale in 0.1f64..1000.0, phi in -3.0f64..3.0,
    ) {
        let family = if inflectional { Family::Inflectional } else { Family::NonInflectional };
        let s = elastica(family, k, s0, if back { -l } else { l }, scale, phi);
        let e = s.evaluator().unwrap();
        let lambda = multipliers(&s);
        let len = s.length();
        let dt = 1e-4;
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let p = e.eval(t);
            let dk = (e.eval(t + dt).curvature - e.eval(t - dt).curvature) / (2.0 * dt * len);
            let residual = dk + lambda[0] * p.angle.sin() - lambda[1] * p.angle.cos();
            let size = lambda[0].hypot(lambda[1]);
            prop_assert!(residual.abs() < 1e-5 * size, "{residual} vs {size}");
        }
    }

    /// Non-inflectional elastica have no conjugate point (Sachkov): whatever their length,
    /// loops included, the margin is positive.
    #[test]
    fn c_shapes_are_stable(k in 0.05f64..0.99, s0 in -4.0f64..4.0, l in 0.2f64..8.0, scale in 1.0f64..500.0) {
        let s = elastica(Family::NonInflectional, k, s0, l, scale, 0.4);
        let st = stability(&s, &StabilityParams::default()).unwrap();
        prop_assert_eq!(st.inflections, 0);
        prop_assert!(st.margin > 0.0, "margin {}", st.margin);
        prop_assert_eq!(conjugate_of(&s), None);
    }

    /// Sachkov's bounds: no inflection inside ⇒ stable; past the third ⇒ unstable.
    #[test]
    fn inflectional_classes_keep_sachkovs_bounds(
        k in 0.05f64..0.97, phase in 0.05f64..0.95, span in 0.1f64..7.0, scale in 1.0f64..500.0,
    ) {
        let quarter = Elliptic::from_modulus(k).unwrap().k();
        // start between two inflections (at (2j+1)K), `span` half-periods long
        let s0 = (2.0 * phase - 1.0) * quarter;
        let l = span * 2.0 * quarter;
        let s = elastica(Family::Inflectional, k, s0, l, scale, -0.2);
        let st = stability(&s, &StabilityParams::default()).unwrap();
        let zeros = s.curvature_zeros().unwrap();
        // a tenth of a half-period away from an inflection at the far end
        let clear = |t: f64| (t - 1.0).abs() * l > 0.1 * quarter;
        if zeros.is_empty() {
            prop_assert!(st.margin > 0.0, "no inflection, margin {}", st.margin);
        }
        if zeros.len() >= 3 && clear(zeros[2]) {
            prop_assert!(st.margin < 0.0, "{} inflections, margin {}", zeros.len(), st.margin);
        }
    }

    /// Margins are invariant under a change of units and a rigid motion.
    #[test]
    fn margins_are_invariant_under_units_and_rigid_motion(
        inflectional in any::<bool>(), k in 0.05f64..0.95, s0 in -3.0f64..3.0, l in 0.5f64..9.0,
        scale in 0.5f64..2.0, turn in -3.0f64..3.0, dx in -1e3f64..1e3, dy in -1e3f64..1e3,
    ) {
        let family = if inflectional { Family::Inflectional } else { Family::NonInflectional };
        let mm = elastica(family, k, s0, l, 1000.0 * scale, 0.1);
        let m = mm.similar(1e-3, [0.0, 0.0]);
        let moved = mm.mapped([turn.cos(), turn.sin()], [dx, dy]);
        let p = StabilityParams::default();
        let (a, b, c) = (stability(&mm, &p).unwrap(), stability(&m, &p).unwrap(), stability(&moved, &p).unwrap());
        let tol = 1e-8 * (1.0 + a.margin.abs());
        prop_assert!((a.margin - b.margin).abs() < tol, "mm {} m {}", a.margin, b.margin);
        prop_assert!((a.margin - c.margin).abs() < tol, "moved {} vs {}", c.margin, a.margin);
        prop_assert_eq!(a.inflections, c.inflections);
        // loads scale: force per EI by 1/length², moment by 1/length
        prop_assert!((b.loads.force * 1e-6 / a.loads.force - 1.0).abs() < 1e-9);
        prop_assert!((b.loads.moment[0] * 1e-3 - a.loads.moment[0]).abs() < 1e-9 * a.loads.moment[0].abs().max(1e-12));
        prop_assert!((a.loads.tension[1] - c.loads.tension[1]).abs() < 1e-9 * a.loads.force.max(1e-12));
    }
}

/// A random clamped configuration: an elastica of either family, possibly traversed
/// backwards, or a circular arc.
fn configuration() -> impl Strategy<Value = Segment> {
    (
        0u8..5,
        0.05f64..0.98,
        -6.0f64..6.0,
        0.2f64..1.0,
        any::<bool>(),
        1.0f64..2000.0,
        -3.1f64..3.1,
    )
        .prop_map(|(kind, k, s0, span, back, scale, phi)| match kind {
            0 => Segment::Arc {
                x0: 0.0,
                y0: 0.0,
                phi,
                curvature: (k - 0.5) * 8.0 / scale,
                length: scale,
            },
            1 => {
                // up to about two loops
                let l = span * 6.0 * k.max(0.1);
                elastica(
                    Family::NonInflectional,
                    k,
                    s0,
                    if back { -l } else { l },
                    scale,
                    phi,
                )
            }
            _ => {
                // up to about five half-periods: stable and unstable shapes alike
                let quarter = Elliptic::from_modulus(k).unwrap().k();
                let l = span * 10.0 * quarter;
                elastica(
                    Family::Inflectional,
                    k,
                    s0,
                    if back { -l } else { l },
                    scale,
                    phi,
                )
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, max_global_rejects: 1 << 20, .. ProptestConfig::default() })]

    /// On random clamped configurations, the margin's sign and Jacobi's conjugate-point
    /// test agree away from the margin (|margin| > 0.02), and the discrete blade's
    /// reduced Hessian (at [`SEGMENTS`] segments) gives the same margin to its
    /// discretization error.
    #[test]
    fn the_margin_and_the_conjugate_point_test_agree(s in configuration()) {
        let st = stability(&s, &StabilityParams::default()).unwrap();
        prop_assume!(st.margin.abs() > 0.02);
        let conjugate = conjugate_of(&s);
        prop_assert_eq!(
            st.margin > 0.0,
            conjugate.is_none(),
            "margin {} but first conjugate point at {:?} of {} ({})",
            st.margin, conjugate, s.length(), st.inflections
        );
    }
}

/// The blade's shape against its chord: the held ends and the tangent angle at u ∈ [0, 1].
fn chord_frame(s: &Segment) -> (HeldEnds, impl Fn(f64) -> f64) {
    let e = s.evaluator().unwrap();
    let (a, b) = (e.eval(0.0), e.eval(1.0));
    let chord_angle = (b.p[1] - a.p[1]).atan2(b.p[0] - a.p[0]);
    let ends = HeldEnds {
        chord: (b.p[0] - a.p[0]).hypot(b.p[1] - a.p[1]),
        angles: [a.angle - chord_angle, b.angle - chord_angle],
    };
    (ends, move |u: f64| e.eval(u).angle - chord_angle)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, max_global_rejects: 1 << 20, .. ProptestConfig::default() })]

    /// The discrete blade settled from the closed form has the closed form's margin to
    /// O(1/n²) and its multipliers to O(1/n²).
    #[test]
    fn the_discrete_blade_converges_to_the_closed_form(s in configuration()) {
        // near margin 0 (a degenerate equilibrium) and for nearly straight waves (k <
        // 0.15, close to the straight blade's bifurcations) the shape itself turns
        // sensitive and converges more slowly: the bound holds away from them
        prop_assume!(!matches!(s, Segment::Elastica(p) if p.k < 0.15));
        let st = stability(&s, &StabilityParams::default()).unwrap();
        prop_assume!(st.margin.abs() > 0.05);
        let (ends, angle) = chord_frame(&s);
        prop_assume!(ends.chord > 0.05 * s.length() && ends.chord < 0.999 * s.length());
        // Newton from the closed form finds the discrete equilibrium unless another
        // eigenvalue of the reduced Hessian is near zero there (a degenerate point)
        let d = DiscreteBlade::settle_like(s.length(), ends, &angle, SEGMENTS, None);
        prop_assume!(d.is_ok() || st.margin < 0.0);
        let Ok(d) = d else { return Ok(()) };
        let m = d.margin().unwrap();
        // the error of the three-point scheme grows with the eigenfunction's frequency,
        // which the margin and the load set
        // (the error bound stated in `follow`'s docs)
        let load = st.loads.force * s.length().powi(2) / (4.0 * PI * PI);
        let bound = 6.0 * (PI / SEGMENTS as f64).powi(2) * (1.0 + st.margin.abs() + load).powi(2);
        prop_assert!((m - st.margin).abs() < bound, "discrete {m} closed form {} (bound {bound})", st.margin);
    }
}

#[test]
fn a_snap_through_is_caught() {
    // an arch whose ends turn down at a fixed chord, from (0.4, −0.4) rad on: at first
    // it stays up, bending into an M with two inflections (another equilibrium than the
    // inverted arch the same ends also hold); turned further, its branch folds and the
    // blade snaps through
    let length = 1000.0;
    let turned = |a: f64| HeldEnds {
        chord: 950.0,
        angles: [a, -a],
    };
    let path = |w: f64| turned(0.4 - 3.0 * w);
    let start =
        DiscreteBlade::settle_like(length, path(0.0), |u| 0.4 - 0.8 * u, SEGMENTS, None).unwrap();
    assert!(start.margin().unwrap() > 1.0);
    let f = follow(&start, &path, &FollowParams::default());
    let Some(Snap::Fold { at, margin }) = f.snap else {
        panic!("no fold: {:?}", f.snap);
    };
    assert!(at > 0.2 && at < 0.4, "folds at {at}");
    assert!(margin < 0.05, "margin {margin} before the fold");
    // the margin falls towards the fold
    let m = &f.margins;
    assert!(m.windows(2).all(|w| w[1].1 < w[0].1 + 1e-9));
    // turned to (−0.4, 0.4) it is still up: not the inverted arch those ends also hold
    let mirror = |w: f64| turned(0.4 - 0.8 * w);
    let g = follow(&start, &mirror, &FollowParams::default());
    assert!(g.snap.is_none());
    let inverted =
        DiscreteBlade::settle_like(length, turned(-0.4), |u| -0.4 + 0.8 * u, SEGMENTS, None)
            .unwrap();
    assert!(inverted.is_stable());
    let apart = g.blade.distance(&inverted);
    assert!(apart > 0.1 * length, "{apart}");
    let lowest = |b: &DiscreteBlade| {
        b.points()
            .iter()
            .map(|p| p[1])
            .fold(f64::INFINITY, f64::min)
    };
    let (low, mid) = (lowest(&inverted), g.blade.points()[SEGMENTS / 2][1]);
    assert!(
        low < -100.0 && mid > 50.0,
        "inverted down to {low}, the followed one's middle at {mid}"
    );
}

#[test]
fn a_smooth_move_is_followed_to_its_end_in_either_unit() {
    for unit in [1.0, 1e-3] {
        let length = 1000.0 * unit;
        let at = |w: f64| HeldEnds {
            chord: (960.0 - 60.0 * w) * unit,
            angles: [0.3 + 0.3 * w, 0.1 - 0.5 * w],
        };
        let start =
            DiscreteBlade::settle_like(length, at(0.0), |u| 0.3 - 0.2 * u, SEGMENTS, None).unwrap();
        let f = follow(&start, &at, &FollowParams::default());
        assert!(f.snap.is_none(), "{:?}", f.snap);
        assert_eq!(f.blade.ends, at(1.0));
        // the end is the equilibrium settled there from the same side
        let direct =
            DiscreteBlade::settle(length, at(1.0), &f.blade.theta, Some(f.blade.load)).unwrap();
        assert!(direct.distance(&f.blade) < 1e-9 * length);
        assert!(f.min_margin() > 0.3);
    }
}

#[test]
fn loads_are_the_same_newtons_in_millimetres_and_metres() {
    use elastica::stability::{BladeSection, Stiffness};
    // one physical blade (1 mm × 25 mm spring steel, 800 mm) bent into the same S, in
    // millimetres and in metres
    let mm = elastica(Family::Inflectional, 0.5, -0.6, 2.4, 800.0 / 2.4, 0.3);
    let m = mm.similar(1e-3, [0.0, 0.0]);
    let p = StabilityParams::default();
    let (a, b) = (stability(&mm, &p).unwrap(), stability(&m, &p).unwrap());
    let steel = |unit: f64| BladeSection {
        thickness: 1.0 * unit,
        width: 25.0 * unit,
        youngs_modulus: 200e9,
    };
    let la = a.loads.held(&Stiffness::of(&steel(1.0), 1e-3));
    let lb = b.loads.held(&Stiffness::of(&steel(1e-3), 1.0));
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-12);
    assert!(
        close(la.force_n, lb.force_n),
        "{} N vs {} N",
        la.force_n,
        lb.force_n
    );
    for e in 0..2 {
        assert!(close(la.tension_n[e], lb.tension_n[e]));
        assert!(close(la.moment_nm[e], lb.moment_nm[e]));
    }
    // and the force is EI·|λ| in newtons: EI = 200e9 · 0.025 · 1e-9 / 12 N·m², λ = 1/S²
    let ei = 200e9 * 0.025 * 1e-9 / 12.0;
    let s_m = 0.8 / 2.4;
    assert!(close(lb.force_n, ei / (s_m * s_m)));
}
