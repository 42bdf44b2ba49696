//! The least-squares piecewise ruled fit (eq. 4.1) against surfaces whose answer is known:
//! ruled surfaces come back exactly, curved ones converge at the order of their spline,
//! and the fit moves, turns and scales with its samples.

use nalgebra::{Rotation3, Vector3};
use proptest::prelude::*;
use ruled_blocks::fit::{fit_piecewise_ruled, FitError, GridSamples, RuledFitParams};

fn grid(nu: usize, nv: usize, f: impl Fn(f64, f64) -> [f64; 3]) -> GridSamples {
    let u: Vec<f64> = (0..nu).map(|i| i as f64 / (nu - 1) as f64).collect();
    let v: Vec<f64> = (0..nv).map(|j| j as f64 / (nv - 1) as f64).collect();
    let points = v
        .iter()
        .flat_map(|&y| u.iter().map(|&x| f(x, y)).collect::<Vec<_>>())
        .collect();
    GridSamples { u, v, points }
}

/// A surface `(u, v) ↦ point`.
type Surface = fn(f64, f64) -> [f64; 3];

fn params(strips: usize, controls: usize) -> RuledFitParams {
    RuledFitParams {
        strips,
        degree: 3,
        controls,
    }
}

/// A spherical cap of radius 1 over 90° × 90°: curved both ways.
fn cap(u: f64, v: f64) -> [f64; 3] {
    let (a, b) = ((u - 0.5) * 1.5, (v - 0.5) * 1.5);
    [a.sin() * b.cos(), b.sin(), a.cos() * b.cos()]
}

#[test]
fn ruled_surfaces_come_back_exactly() {
    // a hyperbolic paraboloid, a cone and a helicoid are ruled along v
    let cases: [(&str, Surface); 3] = [
        ("paraboloid", |x, y| [x, y, 3.0 * x * y]),
        ("cone", |u, v| {
            let a = 2.0 * u;
            [v * a.cos(), v * a.sin(), 1.0 - v]
        }),
        ("helicoid", |u, v| [v * u.cos(), v * u.sin(), 0.5 * u]),
    ];
    for (name, f) in cases {
        // the cone's and helicoid's rails are circles and helices: exact only as the
        // controls grow, so measure them against a straight-v fit of many controls
        let fit = fit_piecewise_ruled(&grid(60, 7, f), &params(1, 30)).unwrap();
        let tol = if name == "paraboloid" { 1e-12 } else { 1e-6 };
        assert!(fit.max_residual < tol, "{name}: {}", fit.max_residual);
    }
}

#[test]
fn rails_converge_at_the_fourth_order_and_strips_at_the_second() {
    let s = grid(200, 65, cap);
    let err = |strips, controls| {
        fit_piecewise_ruled(&s, &params(strips, controls))
            .unwrap()
            .max_residual
    };
    // along u (many strips, so the error is the rails'): cubic splines, O(h⁴)
    let (a, b) = (err(64, 8), err(64, 16));
    assert!(a / b > 10.0, "rails: {a:e} → {b:e}");
    // across (many controls): straight rulings between rails, O(h²)
    let (c, d) = (err(4, 40), err(8, 40));
    assert!(c / d > 3.0 && c / d < 5.0, "strips: {c:e} → {d:e}");
}

#[test]
fn distances_are_to_the_closest_point() {
    // a paraboloid is fitted exactly; points moved δ along its unit normal lie δ from it
    // (δ far below its radius of curvature, ≥ 1/6 here)
    let f = |x: f64, y: f64| [x, y, 3.0 * x * y];
    let fit = fit_piecewise_ruled(&grid(20, 6, f), &params(1, 4)).unwrap();
    let delta = 1e-3;
    for &(x, y) in &[(0.2, 0.3), (0.5, 0.5), (0.9, 0.1), (0.35, 0.8)] {
        let n = Vector3::new(-3.0 * y, -3.0 * x, 1.0).normalize();
        let q = Vector3::from(f(x, y)) + n * delta;
        // searched from a point well off the foot
        let (d, (u, v)) = ruled_blocks::fit::closest_point(&fit.surface, q, (x + 0.1, y - 0.1));
        assert!((d - delta).abs() < 1e-9, "{d} at ({x}, {y})");
        assert!((u - x).abs() < 1e-6 && (v - y).abs() < 1e-6, "({u}, {v})");
    }
    // on a curved model the distances are at most the residuals, and some are less
    let s = grid(40, 17, cap);
    let fit = fit_piecewise_ruled(&s, &params(2, 6)).unwrap();
    assert!(fit
        .distances
        .iter()
        .zip(&fit.residuals)
        .all(|(d, r)| *d <= *r));
    assert!(fit.rms_distance < fit.rms && fit.max_distance <= fit.max_residual);
}

#[test]
fn bad_input_is_refused_with_its_field() {
    let s = grid(10, 5, cap);
    let field = |p: RuledFitParams| match fit_piecewise_ruled(&s, &p) {
        Err(FitError::Params { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    assert_eq!(field(params(0, 4)), "strips");
    assert_eq!(field(params(5, 4)), "strips"); // 6 rails from 5 samples across
    assert_eq!(field(params(1, 11)), "controls");
    assert_eq!(
        field(RuledFitParams {
            degree: 0,
            ..params(1, 4)
        }),
        "degree"
    );
    let mut nan = s.clone();
    nan.points[7][2] = f64::NAN;
    assert!(matches!(
        fit_piecewise_ruled(&nan, &params(1, 4)),
        Err(FitError::Samples(_))
    ));
    let mut back = s.clone();
    back.u.swap(2, 3);
    assert!(matches!(
        fit_piecewise_ruled(&back, &params(1, 4)),
        Err(FitError::Samples(_))
    ));
    let mut short = s.clone();
    short.points.pop();
    assert!(matches!(
        fit_piecewise_ruled(&short, &params(1, 4)),
        Err(FitError::Samples(_))
    ));
    // ten samples along u, nine of them clumped near the start: the knots are placed among
    // the samples (every span holds some), so all six control points are still pinned
    let mut clumped = s.clone();
    clumped.u = (0..10)
        .map(|i| if i < 9 { i as f64 * 1e-3 } else { 1.0 })
        .collect();
    assert!(fit_piecewise_ruled(&clumped, &params(1, 6)).is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Moved, turned and scaled samples give the moved, turned and scaled fit: its
    /// residuals scale with the samples, and the surface maps with them. The tolerance is
    /// a few hundred roundings of the coordinates' size, far above the fit's own rounding
    /// and far below any residual the fit could change by.
    #[test]
    fn the_fit_follows_rigid_motion_and_scale(
        axis in (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0),
        angle in -3.0f64..3.0,
        shift in (-1e3f64..1e3, -1e3f64..1e3, -1e3f64..1e3),
        log_scale in -3.0f64..3.0,
        strips in 1usize..5,
        controls in 4usize..10,
    ) {
        let s = grid(30, 9, cap);
        let base = fit_piecewise_ruled(&s, &params(strips, controls)).unwrap();
        let rot = Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(axis.0, axis.1, axis.2)),
            angle,
        );
        let scale = 10f64.powf(log_scale);
        let t = Vector3::new(shift.0, shift.1, shift.2) * scale;
        let map = |p: Vector3<f64>| rot * p * scale + t;
        let moved = GridSamples {
            points: s.points.iter().map(|p| map(Vector3::from(*p)).into()).collect(),
            ..s.clone()
        };
        let fit = fit_piecewise_ruled(&moved, &params(strips, controls)).unwrap();
        let size = scale * (1.0 + shift.0.abs().max(shift.1.abs()).max(shift.2.abs()));
        let tol = 1e-12 * size;
        prop_assert!((fit.rms - scale * base.rms).abs() <= tol);
        prop_assert!((fit.max_residual - scale * base.max_residual).abs() <= tol);
        prop_assert!((fit.rms_distance - scale * base.rms_distance).abs() <= 1e-9 * scale);
        for &(u, v) in &[(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.77, 1.0)] {
            let d = (fit.surface.eval(u, v) - map(base.surface.eval(u, v))).norm();
            prop_assert!(d <= tol, "{d:e} at ({u}, {v})");
        }
    }
}
