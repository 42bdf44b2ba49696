//! Identities of the Jacobi functions over the whole parameter range m ∈ [0, 1] and
//! arguments up to |u| = 10³.

use elastica::elliptic::Elliptic;
use proptest::prelude::*;

fn param() -> impl Strategy<Value = f64> {
    prop_oneof![
        0.0f64..1.0,
        (1.0f64..16.0).prop_map(|e| 1.0 - 10f64.powf(-e)),
        (1.0f64..16.0).prop_map(|e| 10f64.powf(-e)),
        Just(0.0),
        Just(1.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn pythagorean_identities(m in param(), u in -1000.0f64..1000.0) {
        let v = Elliptic::new(m).unwrap().eval(u);
        prop_assert!((v.sn * v.sn + v.cn * v.cn - 1.0).abs() < 4e-15);
        prop_assert!((v.dn * v.dn + m * v.sn * v.sn - 1.0).abs() < 4e-15);
        // am is large here: its own rounding (ulp(am)) limits the comparison
        let tol = 1e-15 + 4.0 * f64::EPSILON * v.am.abs();
        prop_assert!((v.am.sin() - v.sn).abs() < tol && (v.am.cos() - v.cn).abs() < tol);
        prop_assert!(((u - v.eps) - m * v.d).abs() < 1e-12 * (1.0 + u.abs()));
    }

    /// Central differences against the derivative formulas (DLMF 22.13.1–3, 22.16.1/14).
    /// The tolerance is derived, not tuned: truncation h²/6·max|f‴| (≤ 2·10⁻¹⁰ with
    /// |f‴| ≤ 10 for m ≤ 1) plus the rounding of the two values, a few ulp of |f| each,
    /// divided by the step. The step is the one actually taken, (u + h) − (u − h) (exact),
    /// not 2h: at |u| = 90 the two differ by an ulp of u, 7·10⁻¹⁰ of the quotient.
    #[test]
    fn derivatives_in_u(m in param(), u in -100.0f64..100.0) {
        let e = Elliptic::new(m).unwrap();
        let h = 1e-5;
        let (lo, hi) = (u - h, u + h);
        let step = hi - lo;
        let (a, b, c) = (e.eval(lo), e.eval(hi), e.eval(u));
        let fd = |x: f64, y: f64| (y - x) / step;
        let tol = |x: f64, y: f64| 2e-10 + 8.0 * f64::EPSILON * x.abs().max(y.abs()) / step;
        prop_assert!((fd(a.sn, b.sn) - c.cn * c.dn).abs() < tol(a.sn, b.sn));
        prop_assert!((fd(a.cn, b.cn) + c.sn * c.dn).abs() < tol(a.cn, b.cn));
        prop_assert!((fd(a.dn, b.dn) + m * c.sn * c.cn).abs() < tol(a.dn, b.dn));
        prop_assert!((fd(a.am, b.am) - c.dn).abs() < tol(a.am, b.am));
        prop_assert!((fd(a.eps, b.eps) - c.dn * c.dn).abs() < tol(a.eps, b.eps));
        // D = ∫ sn² is computed on its own (Landen recursion), not as (u − E)/m
        prop_assert!((fd(a.d, b.d) - c.sn * c.sn).abs() < tol(a.d, b.d));
    }

    /// D(u|m) = ∫₀ᵘ sn² matches its m = 0 limit (u − sin u cos u)/2 to first order in m.
    #[test]
    fn d_small_parameter(m in 0.0f64..1e-6, u in -20.0f64..20.0) {
        let v = Elliptic::new(m).unwrap().eval(u);
        let d0 = 0.5 * (u - u.sin() * u.cos());
        prop_assert!((v.d - d0).abs() < 1e-13 + m * u.abs().powi(2));
    }

    /// Addition formulas (DLMF 22.8.1–3 and 22.16.27 for E).
    #[test]
    fn addition_formulas(m in param(), u in -50.0f64..50.0, w in -50.0f64..50.0) {
        let e = Elliptic::new(m).unwrap();
        let (a, b, s) = (e.eval(u), e.eval(w), e.eval(u + w));
        let den = 1.0 - m * a.sn * a.sn * b.sn * b.sn;
        prop_assume!(den > 1e-6);
        let sn = (a.sn * b.cn * b.dn + b.sn * a.cn * a.dn) / den;
        let cn = (a.cn * b.cn - a.sn * a.dn * b.sn * b.dn) / den;
        let dn = (a.dn * b.dn - m * a.sn * a.cn * b.sn * b.cn) / den;
        // the formulas themselves lose accuracy where `den` is small (m → 1, |sn| → 1)
        let tol = 1e-12 / den;
        prop_assert!((s.sn - sn).abs() < tol, "sn {} vs {}", s.sn, sn);
        prop_assert!((s.cn - cn).abs() < tol);
        prop_assert!((s.dn - dn).abs() < tol);
        let eps = a.eps + b.eps - m * a.sn * b.sn * s.sn;
        prop_assert!((s.eps - eps).abs() < 1e-12 * (1.0 + u.abs() + w.abs()));
    }

    /// 4K periodicity of sn and cn, 2K of dn, quasi-periodicity E(u + 2K) = E(u) + 2E(m).
    #[test]
    fn periods(m in 0.0f64..0.999_999, u in -300.0f64..300.0, j in -20i32..20) {
        let e = Elliptic::new(m).unwrap();
        let kk = e.k();
        let a = e.eval(u);
        let b = e.eval(u + 4.0 * kk * j as f64);
        let c = e.eval(u + 2.0 * kk);
        let tol = 1e-13 * (1.0 + u.abs() + (4.0 * kk * j as f64).abs()) / (1.0 + kk);
        prop_assert!((a.sn - b.sn).abs() < tol && (a.cn - b.cn).abs() < tol && (a.dn - b.dn).abs() < tol);
        prop_assert!((a.dn - c.dn).abs() < 1e-12 && (a.sn + c.sn).abs() < 1e-12);
        prop_assert!((c.eps - a.eps - 2.0 * e.e()).abs() < 1e-12 * (1.0 + u.abs()));
    }

    /// Derivatives with respect to m against central differences.
    #[test]
    fn derivatives_in_m(m in 0.0f64..0.99, u in -20.0f64..20.0) {
        let h = 1e-6;
        let (lo, hi) = ((m - h).max(0.0), m + h);
        let e = Elliptic::new(m).unwrap();
        let v = e.eval(u);
        let d = e.dm(u, &v);
        let (a, b) = (Elliptic::new(lo).unwrap().eval(u), Elliptic::new(hi).unwrap().eval(u));
        let fd = |x: f64, y: f64| (y - x) / (hi - lo);
        let tol = |x: f64| 1e-5 * (1.0 + x.abs());
        prop_assert!((fd(a.sn, b.sn) - d.sn).abs() < tol(d.sn), "sn {} {}", fd(a.sn, b.sn), d.sn);
        prop_assert!((fd(a.cn, b.cn) - d.cn).abs() < tol(d.cn));
        prop_assert!((fd(a.dn, b.dn) - d.dn).abs() < tol(d.dn));
        prop_assert!((fd(a.am, b.am) - d.am).abs() < tol(d.am));
        prop_assert!((fd(a.eps, b.eps) - d.eps).abs() < tol(d.eps));
    }
}

/// The point where a random seed once failed `derivatives_in_u` (m = 3.5·10⁻⁸, u = −90.9):
/// am itself is right there (60-digit mpmath values of am(u ± 10⁻⁵) and dn(u)); the old
/// tolerance was what was wrong.
#[test]
#[allow(clippy::excessive_precision)] // the reference values as mpmath printed them
fn amplitude_at_a_former_failure() {
    let e = Elliptic::new(3.527401176162884e-8).unwrap();
    let cases = [
        (-90.9075984310215, -90.907_597_627_646_986_250_966_03),
        (-90.9075884310215, -90.907_587_627_646_989_941_845_1),
        (-90.90757843102149, -90.907_577_627_646_993_633_406_44),
    ];
    for (u, am) in cases {
        assert!((e.eval(u).am - am).abs() <= 2.0 * 1.5e-14, "{u}");
    }
    assert!((e.eval(-90.9075884310215).dn - 0.999_999_999_313_464_329_375_683_9).abs() < 1e-16);
}

#[test]
fn limits_and_traps() {
    // m = 0: circular functions
    let e0 = Elliptic::new(0.0).unwrap();
    let v = e0.eval(2.0);
    assert!((v.sn - 2f64.sin()).abs() < 1e-16 && (v.dn - 1.0).abs() == 0.0);
    // m = 1: hyperbolic functions, no overflow at |u| = 1000
    let e1 = Elliptic::new(1.0).unwrap();
    let v = e1.eval(1000.0);
    assert_eq!((v.sn, v.cn, v.dn, v.eps), (1.0, 0.0, 0.0, 1.0));
    assert!((v.am - std::f64::consts::FRAC_PI_2).abs() < 1e-16);
    // m → 1 beyond the quarter period: sn(3K) = −1, dn(K) = k′
    let m = 1.0 - 1e-14;
    let e = Elliptic::new(m).unwrap();
    let v = e.eval(3.0 * e.k());
    assert!((v.sn + 1.0).abs() < 1e-15 && v.cn.abs() < 1e-13);
    let q = e.eval(e.k());
    assert!((q.dn - e.kprime()).abs() < 1e-15);
    // bad parameters are errors, not NaN
    assert!(Elliptic::new(1.5).is_err() && Elliptic::new(f64::NAN).is_err());
    assert!(Elliptic::new(-1e-300).is_err());
    assert!(e.eval(f64::NAN).sn.is_nan());
}
