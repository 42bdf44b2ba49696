//! The numerical spline approach ("Hot Blade Cuttings" §5.2, eq. 13) on the shared curves
//! (`testdata::curves_json`): the result stays within ε of the input, lowers the bending
//! energy, keeps what it is told to keep, and is compared with the analytic elastica fit
//! (`cargo test -p hotcut-design --test numerical -- --nocapture` prints the BENCHMARKS.md table).

use std::time::Instant;

use design::numerical::{numerical_spline, NumericalParams};
use elastica::fit::{fit_points, FitParams};

fn curves() -> Vec<(String, String, Vec<[f64; 2]>)> {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(testdata::curves_json()).unwrap()).unwrap();
    v["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let pts = c["points"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
                .collect();
            (
                c["id"].as_str().unwrap().to_string(),
                c["class"].as_str().unwrap().to_string(),
                pts,
            )
        })
        .collect()
}

/// Largest distance from `a`'s points to the polyline `b`.
fn distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .map(|p| {
            b.windows(2)
                .map(|w| {
                    let (d, e) = (
                        [w[1][0] - w[0][0], w[1][1] - w[0][1]],
                        [p[0] - w[0][0], p[1] - w[0][1]],
                    );
                    let t = ((d[0] * e[0] + d[1] * e[1]) / (d[0] * d[0] + d[1] * d[1]).max(1e-300))
                        .clamp(0.0, 1.0);
                    (e[0] - t * d[0]).hypot(e[1] - t * d[1])
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

#[test]
fn results_stay_within_epsilon_and_lower_the_energy() {
    let eps = 0.002; // 2 mm on curves of 0.5–3 m
    println!("| curve | class | fixed | active | max dist. to input (mm) | energy before → after | eq. (11) residual | dist. to analytic fit (mm) | numerical (ms) | analytic (ms) |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (id, class, pts) in curves().iter().step_by(6) {
        for (fix_tangents, fix_length) in [(false, false), (true, true)] {
            let p = NumericalParams {
                epsilon: eps,
                control_points: 24,
                fix_tangents,
                fix_length,
            };
            let t0 = Instant::now();
            let r = numerical_spline(pts, &p).unwrap();
            let numerical_ms = t0.elapsed().as_secs_f64() * 1e3;
            // within ε of the input spline (control points in discs), so within ε plus
            // the refinement's own error of the input points
            assert!(
                r.max_control_offset <= eps * (1.0 + 1e-9),
                "{id}: {}",
                r.max_control_offset
            );
            assert!(
                r.max_distance <= eps + r.input_fit_distance + 1e-12,
                "{id}: {} vs {}",
                r.max_distance,
                r.input_fit_distance
            );
            assert!(
                r.energy_after <= r.energy_before * (1.0 + 1e-9),
                "{id}: {} → {}",
                r.energy_before,
                r.energy_after
            );
            assert_eq!(r.control[0], r.input_control[0]);
            assert_eq!(r.control[23], r.input_control[23]);
            if fix_length {
                assert!(
                    (r.length / r.input_length - 1.0).abs() < 1e-6,
                    "{id}: {} vs {}",
                    r.length,
                    r.input_length
                );
            }
            if fix_tangents {
                let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
                    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
                    (u[0] * v[1] - u[1] * v[0]) / (u[0].hypot(u[1]) * v[0].hypot(v[1])).max(1e-300)
                };
                let (x, y) = (&r.input_control, &r.control);
                if (y[1][0] - x[0][0]).hypot(y[1][1] - x[0][1]) > 1e-9 {
                    assert!(cross(x[0], x[1], y[1]).abs() < 1e-9, "{id}");
                }
            }
            {
                let t1 = Instant::now();
                let fit = fit_points(pts, &FitParams::default());
                let analytic_ms = t1.elapsed().as_secs_f64() * 1e3;
                let to_fit = fit
                    .ok()
                    .and_then(|f| f.segment.sample(2000).ok())
                    .map_or(f64::NAN, |s| distance(&r.samples, &s));
                println!(
                    "| {id} | {class} | {} | {} | {:.3} | {:.3} → {:.3} | {:.4} | {:.3} | {:.1} | {:.1} |",
                    if fix_length { "ends, tangents, length" } else { "ends" },
                    r.active_constraints,
                    r.max_distance * 1e3,
                    r.energy_before,
                    r.energy_after,
                    r.eq11_residual,
                    to_fit * 1e3,
                    numerical_ms,
                    analytic_ms
                );
            }
        }
    }
}

#[test]
fn an_exact_elastica_needs_no_active_constraint_with_a_loose_epsilon() {
    // the spline of an elastica is already near least energy: a generous ε leaves room
    let (_, _, pts) = curves()
        .into_iter()
        .find(|c| c.1 == "elastica_exact")
        .unwrap();
    let p = NumericalParams {
        epsilon: 0.05,
        control_points: 24,
        fix_tangents: true,
        fix_length: true,
    };
    let r = numerical_spline(&pts, &p).unwrap();
    assert!(r.eq11_residual < 0.05, "{}", r.eq11_residual);
    assert!(r.max_control_offset < 0.05);
}

#[test]
fn bad_settings_are_refused() {
    let pts: Vec<[f64; 2]> = (0..10).map(|i| [i as f64, 0.0]).collect();
    let p = NumericalParams {
        epsilon: 0.1,
        control_points: 6,
        fix_tangents: false,
        fix_length: false,
    };
    assert!(numerical_spline(&pts[..3], &p).is_err());
    assert!(numerical_spline(&pts, &NumericalParams { epsilon: 0.0, ..p }).is_err());
    assert!(numerical_spline(
        &pts,
        &NumericalParams {
            control_points: 11,
            ..p
        }
    )
    .is_err());
    assert!(numerical_spline(&[[1.0, 1.0]; 10], &p).is_err());
}

#[test]
fn results_are_invariant_under_units_and_rigid_motion() {
    // mm instead of m, and a turn plus a shift: the same curve, so the same result mapped
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    let motion = |q: &[f64; 2]| [c * q[0] - s * q[1] + 3.0, s * q[0] + c * q[1] - 7.0];
    let mut worst = 0.0f64;
    for (id, _, pts) in curves().iter().step_by(6) {
        for (fix_tangents, fix_length) in [(false, false), (true, true)] {
            let p = NumericalParams {
                epsilon: 0.002,
                control_points: 24,
                fix_tangents,
                fix_length,
            };
            let r = numerical_spline(pts, &p).unwrap();
            assert!(r.converged, "{id}: {} steps", r.iterations);
            let mm: Vec<[f64; 2]> = pts.iter().map(|q| [q[0] * 1e3, q[1] * 1e3]).collect();
            let rm = numerical_spline(&mm, &NumericalParams { epsilon: 2.0, ..p }).unwrap();
            let moved: Vec<[f64; 2]> = pts.iter().map(motion).collect();
            let rr = numerical_spline(&moved, &p).unwrap();
            assert_eq!(r.active_constraints, rm.active_constraints, "{id} mm");
            assert_eq!(r.active_constraints, rr.active_constraints, "{id} moved");
            for ((a, b), d) in r.control.iter().zip(&rm.control).zip(&rr.control) {
                let ma = motion(a);
                let e = ((a[0] - b[0] * 1e-3).hypot(a[1] - b[1] * 1e-3))
                    .max((ma[0] - d[0]).hypot(ma[1] - d[1]))
                    / p.epsilon;
                worst = worst.max(e);
                assert!(e < 1e-7, "{id} {fix_length}: {e:e} of ε");
            }
        }
    }
    println!("worst difference {worst:e} of ε");
}

#[test]
fn extreme_epsilons_neither_panic_nor_leave_their_discs() {
    // ε from far below rounding to far beyond the curve's size (a 1 m curve)
    let (_, _, pts) = curves().into_iter().nth(6).unwrap();
    for eps in [1e-12, 1e-6, 0.5, 10.0, 1e6] {
        for (fix_tangents, fix_length) in [(false, false), (true, true)] {
            let p = NumericalParams {
                epsilon: eps,
                control_points: 24,
                fix_tangents,
                fix_length,
            };
            let r = numerical_spline(&pts, &p).unwrap();
            assert!(r.max_control_offset <= eps * (1.0 + 1e-9), "{eps}");
            assert!(r.energy_after.is_finite() && r.length.is_finite(), "{eps}");
            assert!(r.energy_after <= r.energy_before * (1.0 + 1e-9), "{eps}");
        }
    }
}
