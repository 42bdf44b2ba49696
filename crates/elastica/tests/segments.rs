//! Elastica segments: identities of the closed forms, derivatives against finite
//! differences, and agreement with the independent generator of the test curves (`testdata::curves_json`).

use elastica::segment::{ElasticaParams, ElasticaSegment, Segment};
use elastica::unit::{Family, UnitElastica};
use proptest::prelude::*;

fn family() -> impl Strategy<Value = Family> {
    prop_oneof![Just(Family::Inflectional), Just(Family::NonInflectional)]
}

fn params() -> impl Strategy<Value = ElasticaParams> {
    (
        family(),
        0.05f64..0.98,
        -8.0f64..8.0,
        prop_oneof![-6.0f64..-0.2, 0.2f64..6.0],
        0.2f64..3.0,
        -3.0f64..3.0,
        -2.0f64..2.0,
        -2.0f64..2.0,
    )
        .prop_map(|(family, k, s0, l, scale, phi, x0, y0)| ElasticaParams {
            one_minus_k: None,
            family,
            k,
            s0,
            l,
            scale,
            phi,
            x0,
            y0,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// |γ'| = 1 in arc length: the derivative of the normalized curve is its unit tangent,
    /// and the curvature is the derivative of the tangent angle.
    #[test]
    fn unit_speed_and_curvature(fam in family(), k in 0.05f64..0.99, s in -20.0f64..20.0) {
        let u = UnitElastica::new(fam, k).unwrap();
        // curvature up to 2/k: scale the step so that h·κ stays small
        let h = match fam { Family::Inflectional => 1e-5, Family::NonInflectional => 1e-5 * k };
        let a = u.eval(s - h);
        let b = u.eval(s + h);
        let c = u.eval(s);
        let d = [(b.p[0] - a.p[0]) / (2.0 * h), (b.p[1] - a.p[1]) / (2.0 * h)];
        prop_assert!((d[0] - c.t[0]).abs() < 1e-8 && (d[1] - c.t[1]).abs() < 1e-8, "{d:?} vs {:?}", c.t);
        prop_assert!(((c.t[0].hypot(c.t[1])) - 1.0).abs() < 1e-14);
        // θ grows with |s|/k: its own rounding (ulp θ) limits the comparison
        let tol = 1e-13 + 4.0 * f64::EPSILON * c.theta.abs();
        prop_assert!((c.t[0] - c.theta.cos()).abs() < tol && (c.t[1] - c.theta.sin()).abs() < tol);
        let dtheta = (b.theta - a.theta) / (2.0 * h);
        prop_assert!((dtheta - c.kappa).abs() < 1e-7 * (1.0 + c.kappa.abs()), "{dtheta} vs {}", c.kappa);
        // both families solve the normalized pendulum equation θ'' = −sin θ
        let ddtheta = (b.kappa - a.kappa) / (2.0 * h);
        let expect = -c.theta.sin();
        prop_assert!((ddtheta - expect).abs() < 1e-6 * (1.0 + expect.abs()) / (k * k), "{ddtheta} vs {expect}");
    }

    /// The same identities for moduli near 1 (1 − k² log-uniform in [10⁻¹⁶, 10⁻³]) and arc
    /// lengths up to 100, where the curve runs close to the separatrix. Tolerances derived:
    /// truncation h²/6·max|f‴| (|p‴| ≤ |κ′| + κ² ≤ 6, |κ‴| ≤ 20 there) plus, over the step
    /// actually taken, a few ulp of the values and of the argument σ times |f′| ≤ 2 (an
    /// ulp of σ = 100 moves every function by ~10⁻¹⁴).
    #[test]
    fn unit_speed_and_curvature_near_k_one(fam in family(), x in -16.0f64..-3.0, s in -100.0f64..100.0) {
        let k = (1.0 - 10f64.powf(x)).sqrt();
        prop_assume!(k < 1.0);
        let u = UnitElastica::new(fam, k).unwrap();
        let h = 1e-5;
        let (lo, hi) = (s - h, s + h);
        let step = hi - lo;
        let (a, b, c) = (u.eval(lo), u.eval(hi), u.eval(s));
        let tol = |x: f64, y: f64, f3: f64| {
            f3 * h * h / 6.0 + 8.0 * f64::EPSILON * x.abs().max(y.abs()).max(2.0 * s.abs()) / step
        };
        for i in 0..2 {
            let d = (b.p[i] - a.p[i]) / step;
            prop_assert!((d - c.t[i]).abs() < tol(a.p[i], b.p[i], 6.0), "{d} vs {:?}", c.t);
        }
        prop_assert!(((c.t[0].hypot(c.t[1])) - 1.0).abs() < 1e-14);
        let t = 1e-13 + 4.0 * f64::EPSILON * c.theta.abs();
        prop_assert!((c.t[0] - c.theta.cos()).abs() < t && (c.t[1] - c.theta.sin()).abs() < t);
        let dtheta = (b.theta - a.theta) / step;
        prop_assert!((dtheta - c.kappa).abs() < tol(a.theta, b.theta, 6.0), "{dtheta} vs {}", c.kappa);
        let ddtheta = (b.kappa - a.kappa) / step;
        let expect = -c.theta.sin();
        prop_assert!((ddtheta - expect).abs() < tol(a.kappa, b.kappa, 20.0), "{ddtheta} vs {expect}");
    }

    /// The derivative with respect to every standard parameter matches central differences.
    #[test]
    fn gradient_matches_finite_differences(p in params(), t in 0.0f64..1.0) {
        let seg = ElasticaSegment::new(p).unwrap();
        let (x, g) = seg.point_gradient(t);
        let e = seg.eval(t).p;
        prop_assert!((x[0] - e[0]).abs() < 1e-14 * (1.0 + e[0].abs()));
        for (i, gi) in g.iter().enumerate() {
            let h = 1e-6;
            let bump = |d: f64| {
                let mut q = p;
                match i { 0 => q.k += d, 1 => q.s0 += d, 2 => q.l += d, 3 => q.scale += d,
                          4 => q.phi += d, 5 => q.x0 += d, _ => q.y0 += d }
                ElasticaSegment::new(q).unwrap().eval(t).p
            };
            // Richardson extrapolation of two central differences: truncation O(h⁴). A plain
            // central difference has h²/6·|∂³p/∂k³|, which at k = 0.05 (arguments σ/k of a
            // few hundred) is 10⁻⁵ relative at h = 10⁻⁶.
            let (a, b) = (bump(-h), bump(h));
            let (a2, b2) = (bump(-0.5 * h), bump(0.5 * h));
            for c in 0..2 {
                let fd = (4.0 * (b2[c] - a2[c]) / h - (b[c] - a[c]) / (2.0 * h)) / 3.0;
                let tol = 1e-5 * (1.0 + fd.abs().max(gi[c].abs()));
                prop_assert!((fd - gi[c]).abs() < tol, "param {i} coord {c}: fd {fd} analytic {}", gi[c]);
            }
        }
    }

    /// Extending a segment keeps the curve: the original points sit at the mapped parameters.
    #[test]
    fn extension_keeps_the_curve(p in params(), before in 0.0f64..1.0, after in 0.0f64..1.0, t in 0.0f64..1.0) {
        let s = Segment::Elastica(p);
        let e = s.extended(before, after);
        let len = s.length();
        prop_assert!((e.length() - (len + before + after)).abs() < 1e-12 * (1.0 + len));
        let te = (before + t * len) / (len + before + after);
        let a = s.eval(t).unwrap();
        let b = e.eval(te).unwrap();
        prop_assert!((a.p[0] - b.p[0]).abs() < 1e-11 && (a.p[1] - b.p[1]).abs() < 1e-11);
        prop_assert!((a.curvature - b.curvature).abs() < 1e-9 * (1.0 + a.curvature.abs()));
    }
}

#[test]
fn backwards_traversal_mirrors_the_turning_direction() {
    let p = ElasticaParams {
        one_minus_k: None,
        family: Family::NonInflectional,
        k: 0.8,
        s0: 0.3,
        l: 1.0,
        scale: 1.0,
        phi: 0.0,
        x0: 0.0,
        y0: 0.0,
    };
    let fwd = Segment::Elastica(p);
    let bwd = Segment::Elastica(ElasticaParams {
        s0: p.s0 + p.l,
        l: -p.l,
        ..p
    });
    let a = fwd.eval(0.25).unwrap();
    let b = bwd.eval(0.75).unwrap();
    assert!((a.p[0] - b.p[0]).abs() < 1e-15 && (a.p[1] - b.p[1]).abs() < 1e-15);
    assert!(a.curvature > 0.0 && (a.curvature + b.curvature).abs() < 1e-14);
    assert!((a.tangent[0] + b.tangent[0]).abs() < 1e-15);
}

#[test]
fn lines_and_arcs_evaluate_in_closed_form() {
    let arc = Segment::Arc {
        x0: 1.0,
        y0: 0.0,
        phi: std::f64::consts::FRAC_PI_2,
        curvature: 1.0,
        length: std::f64::consts::PI,
    };
    let end = arc.eval(1.0).unwrap();
    assert!((end.p[0] + 1.0).abs() < 1e-15 && end.p[1].abs() < 1e-15);
    assert_eq!(arc.max_abs_curvature().unwrap(), 1.0);
    assert!(arc.inflections().unwrap().is_empty());
    let line = Segment::Line {
        x0: 0.0,
        y0: 0.0,
        phi: 0.0,
        length: 2.0,
    };
    assert_eq!(line.eval(0.5).unwrap().p, [1.0, 0.0]);
    let flat = Segment::Arc {
        x0: 0.0,
        y0: 0.0,
        phi: 0.0,
        curvature: 1e-12,
        length: 2.0,
    };
    assert!((flat.eval(1.0).unwrap().p[0] - 2.0).abs() < 1e-15);
}

/// The test curves (`testdata::curves_json`) were generated by an independent
/// implementation (`elastica_ref.py`); evaluating their true parameters here must reproduce
/// the stored points to float precision, and the stated inflections and max |κ|.
#[test]
fn reproduces_the_shared_exact_curves() {
    let text = std::fs::read_to_string(testdata::curves_json()).unwrap();
    let data: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut checked = 0;
    for c in data["curves"].as_array().unwrap() {
        if c["class"] != "elastica_exact" {
            continue;
        }
        let t = &c["truth"];
        let pr = &t["params"];
        let f = |n: &str| pr[n].as_f64().unwrap();
        let family = match t["family"].as_str().unwrap() {
            "inflectional" => Family::Inflectional,
            _ => Family::NonInflectional,
        };
        let seg = Segment::Elastica(ElasticaParams {
            one_minus_k: None,
            family,
            k: f("k"),
            s0: f("s0"),
            l: f("l"),
            scale: f("S"),
            phi: f("phi"),
            x0: f("x0"),
            y0: f("y0"),
        });
        let pts = c["points"].as_array().unwrap();
        let n = pts.len();
        let ev = seg.evaluator().unwrap();
        let mut worst: f64 = 0.0;
        for (i, q) in pts.iter().enumerate() {
            let p = ev.eval(i as f64 / (n - 1) as f64).p;
            let dx = p[0] - q[0].as_f64().unwrap();
            let dy = p[1] - q[1].as_f64().unwrap();
            worst = worst.max(dx.hypot(dy));
        }
        assert!(worst < 1e-12, "{}: {worst:e}", c["id"]);
        let infl = seg.inflections().unwrap();
        assert_eq!(
            infl.len() as u64,
            t["n_inflections"].as_u64().unwrap(),
            "{}",
            c["id"]
        );
        for (a, b) in infl.iter().zip(t["inflection_t"].as_array().unwrap()) {
            assert!((a - b.as_f64().unwrap()).abs() < 1e-10, "{}", c["id"]);
        }
        let kmax = seg.max_abs_curvature().unwrap();
        let kref = t["max_abs_curvature"].as_f64().unwrap();
        assert!(
            (kmax - kref).abs() < 1e-6 * kref,
            "{}: {kmax} vs {kref}",
            c["id"]
        );
        checked += 1;
    }
    assert_eq!(checked, 24);
}

#[test]
fn blade_extends_along_the_elastica_and_counts_inflections() {
    use elastica::blade::{extend_to_blade, BladeError, BladeParams};
    // one full inflection inside the section, another one in the lead-out
    let p = ElasticaParams {
        one_minus_k: None,
        family: Family::Inflectional,
        k: 0.7,
        s0: 0.2,
        l: 2.5,
        scale: 0.4,
        phi: 0.3,
        x0: 1.0,
        y0: -1.0,
    };
    let section = Segment::Elastica(p);
    assert_eq!(section.inflections().unwrap().len(), 1);
    let params = BladeParams {
        length: 3.0,
        lead_in_share: 0.25,
        max_curvature: Some(2.0),
        max_inflections: Some(1),
        ..BladeParams::new(3.0)
    };
    let blade = extend_to_blade(&section, &params).unwrap();
    assert!((blade.segment.length() - 3.0).abs() < 1e-12);
    assert!((blade.lead_in - 0.25 * (3.0 - 1.0)).abs() < 1e-12);
    // the section's own points lie on the blade
    let mid = section.eval(0.5).unwrap().p;
    let tb = (blade.lead_in + 0.5 * section.length()) / 3.0;
    let on = blade.segment.eval(tb).unwrap().p;
    assert!((mid[0] - on[0]).abs() < 1e-12 && (mid[1] - on[1]).abs() < 1e-12);
    assert!(blade.inflections >= 2 && !blade.inflections_ok);
    // max |κ| = 2k/S = 3.5 is reached on the blade
    assert!((blade.max_abs_curvature - 3.5).abs() < 1e-12 && !blade.curvature_ok);
    let start = blade.segment.eval(0.0).unwrap();
    assert_eq!(blade.ends[0].position, start.p);
    assert!(matches!(
        extend_to_blade(&section, &BladeParams::new(0.5)),
        Err(BladeError::TooShort { .. })
    ));
    assert!(extend_to_blade(&section, &BladeParams::new(f64::NAN)).is_err());
}

/// The discrete elastica with the boundary data of a closed-form segment converges to it at
/// second order in the segment length (the error drops ~4× when n doubles). The last two
/// cases are nearly taut S-shaped blades (length/chord − 1 of 1e-5 and 3e-6), where Newton on
/// the KKT system alone stalls and the augmented-Lagrangian fallback takes over.
#[test]
fn discrete_elastica_converges_to_the_closed_form() {
    use elastica::discrete::{discrete_elastica, DiscreteParams};
    for (family, k, s0, l) in [
        (Family::Inflectional, 0.6, -0.4, 2.4),
        (Family::NonInflectional, 0.9, 0.2, 1.5),
        (Family::Inflectional, 0.004, -1.5, 5.0),
        (Family::Inflectional, 0.002, -1.0, 6.0),
    ] {
        let seg = Segment::Elastica(ElasticaParams {
            one_minus_k: None,
            family,
            k,
            s0,
            l,
            scale: 0.8,
            phi: 0.4,
            x0: 0.5,
            y0: 0.1,
        });
        let (a, b) = (seg.eval(0.0).unwrap(), seg.eval(1.0).unwrap());
        let slack = seg.length() / (b.p[0] - a.p[0]).hypot(b.p[1] - a.p[1]) - 1.0;
        let mut errors = Vec::new();
        let mut fallbacks = 0;
        for n in [16usize, 32, 64, 128] {
            let d = discrete_elastica(&DiscreteParams {
                segments: n,
                start: a.p,
                start_angle: a.angle,
                end: b.p,
                end_angle: b.angle,
                length: seg.length(),
                max_iterations: 100,
            })
            .unwrap();
            fallbacks += usize::from(d.fallback);
            let err = d
                .points
                .iter()
                .enumerate()
                .map(|(j, v)| {
                    let q = seg.eval(j as f64 / n as f64).unwrap().p;
                    (v[0] - q[0]).hypot(v[1] - q[1])
                })
                .fold(0.0, f64::max);
            errors.push(err);
        }
        println!("{family:?} k {k} (slack {slack:.1e}): {errors:?}");
        for w in errors.windows(2) {
            let rate = (w[0] / w[1]).log2();
            assert!(rate > 1.8, "{family:?}: order {rate} ({errors:?})");
        }
        assert!(errors[3] < 1e-4 * seg.length());
        // the taut cases exercise the fallback (at the finer resolutions at least)
        assert_eq!(
            fallbacks > 0,
            slack < 1e-4,
            "{family:?} k {k}: {fallbacks} fallbacks"
        );
    }
}
