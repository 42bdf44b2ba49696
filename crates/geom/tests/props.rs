//! Property and reference tests of the geometry kernel.

use std::f64::consts::PI;

use geom::analysis::{analyze_curve, CurveAnalysisParams};
use geom::bspline::{basis_function, clamped_uniform_knots, BSplineCurve};
use geom::expr::Expr;
use geom::heightfield::HeightField;
use geom::mesh::TriMesh;
use geom::planar::{signed_curvature, Jet2, PlanarCurve, SplineCurve2};
use geom::slice::{slice_mesh, PlaneFrame};
use geom::surface::{SectionParams, Surface};
use nalgebra::{Vector2, Vector3};
use proptest::prelude::*;

/// Strategy: a degree, a valid (possibly repeated-knot) knot vector and control points.
fn spline2() -> impl Strategy<Value = BSplineCurve<2>> {
    (1usize..=5, 0usize..6)
        .prop_flat_map(|(p, extra)| {
            let n = p + 1 + extra;
            (
                Just(p),
                prop::collection::vec(0.0f64..1.0, n - p - 1),
                prop::collection::vec((-10.0f64..10.0, -10.0f64..10.0), n),
            )
        })
        .prop_map(|(p, mut interior, ctrl)| {
            interior.sort_by(f64::total_cmp);
            let mut knots = vec![0.0; p + 1];
            knots.extend(interior);
            knots.extend(vec![1.0; p + 1]);
            let ctrl = ctrl.into_iter().map(|(x, y)| Vector2::new(x, y)).collect();
            BSplineCurve::try_new(p, knots, ctrl).expect("valid by construction")
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn basis_is_a_partition_of_unity(c in spline2(), t in 0.0f64..0.999_999) {
        let n = c.control_points().len();
        let sum: f64 = (0..n).map(|i| basis_function(c.knots(), i, c.degree(), t)).sum();
        prop_assert!((sum - 1.0).abs() < 1e-12, "sum = {sum}");
        let (_, b) = c.basis_at(t);
        prop_assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        prop_assert!(b.iter().all(|&v| v >= -1e-15));
    }

    #[test]
    fn derivative_matches_finite_differences(c in spline2(), t in 0.05f64..0.95) {
        let h = 1e-6;
        let knots = c.knots();
        // stay off knots, where one-sided derivatives of low-continuity splines differ
        prop_assume!(knots.iter().all(|k| (k - t).abs() > 2.0 * h));
        let d = c.derivative().eval(t);
        let fd = (c.eval(t + h) - c.eval(t - h)) / (2.0 * h);
        let scale = 1.0 + d.norm();
        prop_assert!((d - fd).norm() < 1e-5 * scale, "{d} vs {fd}");
    }

    #[test]
    fn knot_insertion_preserves_the_curve(c in spline2(), u in 0.01f64..0.99, t in 0.0f64..1.0) {
        if let Ok(d) = c.insert_knot(u) {
            prop_assert!((c.eval(t) - d.eval(t)).norm() < 1e-9);
        }
    }

    #[test]
    fn circles_have_curvature_one_over_r(r in 0.01f64..1e4, t in 0.0f64..6.0) {
        struct C(f64);
        impl PlanarCurve for C {
            fn domain(&self) -> (f64, f64) { (0.0, 2.0 * PI) }
            fn jet(&self, t: f64) -> Jet2 {
                let r = self.0;
                Jet2 {
                    p: Vector2::new(r * t.cos(), r * t.sin()),
                    d1: Vector2::new(-r * t.sin(), r * t.cos()),
                    d2: Vector2::new(-r * t.cos(), -r * t.sin()),
                }
            }
        }
        let k = signed_curvature(&C(r).jet(t));
        prop_assert!((k * r - 1.0).abs() < 1e-12);
        // clockwise circle: negative curvature; and a height-field cap sqrt(R² − y²): −1/R
        let e = Expr::parse(&format!("sqrt({r}^2 - y^2)")).unwrap();
        let j = e.eval_along((0.0, 0.0), (0.0, 1.0), 0.3 * r * (t / 6.0));
        let jet = Jet2 { p: Vector2::new(0.0, j.v), d1: Vector2::new(1.0, j.d1), d2: Vector2::new(0.0, j.d2) };
        prop_assert!((signed_curvature(&jet) * r + 1.0).abs() < 1e-9);
    }

    #[test]
    fn lines_have_zero_curvature(a in -5.0f64..5.0, b in -5.0f64..5.0, c in -100.0f64..100.0) {
        let hf = HeightField::try_new(Expr::parse(&format!("{a}*x + {b}*y + {c}")).unwrap(), (0.0, 100.0), (0.0, 50.0)).unwrap();
        let (_, secs) = Surface::HeightField(hf).sections(&SectionParams { count: 3, ..Default::default() }, &|| {}).unwrap();
        for s in &secs {
            let an = analyze_curve(&s.curve, &CurveAnalysisParams::default()).unwrap();
            prop_assert_eq!(an.max_abs_curvature.curvature, 0.0);
            prop_assert!(an.inflections.is_empty());
            prop_assert!((an.length - 50.0 * (1.0 + b * b).sqrt()).abs() < 1e-9);
        }
    }

    #[test]
    fn inflections_of_sin_are_at_multiples_of_pi(y0 in -10.0f64..0.0, len in 3.5f64..20.0, tol_exp in 4i32..12) {
        let tol = 10f64.powi(-tol_exp);
        let hf = HeightField::try_new(Expr::parse("sin(y)").unwrap(), (0.0, 1.0), (y0, y0 + len)).unwrap();
        let (_, secs) = Surface::HeightField(hf).sections(&SectionParams { count: 1, ..Default::default() }, &|| {}).unwrap();
        let params = CurveAnalysisParams { samples: 4000, bisection_tolerance: tol, min_lobe_turning: 0.0, ..Default::default() };
        let an = analyze_curve(&secs[0].curve, &params).unwrap();
        let expect: Vec<f64> = ((y0 / PI).floor() as i64..=((y0 + len) / PI).ceil() as i64)
            .map(|k| k as f64 * PI)
            .filter(|&y| y > y0 && y < y0 + len)
            .collect();
        // an inflection 0.01 from an end bounds a lobe departing from its chord by ~2e-7:
        // above the noise floor (f64 rounding, ~1e-9 here); one closer may be below it
        prop_assume!(expect.iter().all(|&y| y > y0 + 0.01 && y < y0 + len - 0.01));
        prop_assert_eq!(an.inflections.len(), expect.len());
        for (p, y) in an.inflections.iter().zip(&expect) {
            prop_assert!((p.t - y).abs() <= tol, "{} vs {y}", p.t);
        }
    }

    #[test]
    fn sphere_sections_have_perimeter_two_pi_r(r in 1.0f64..1000.0, frac in -0.9f64..0.9) {
        let (mesh, h) = uv_sphere(r, 96, 192);
        let c = frac * r;
        let chains = slice_mesh(&mesh, &Vector3::x(), c);
        prop_assert_eq!(chains.len(), 1);
        prop_assert!(chains[0].closed);
        let pts = chains[0].points(&mesh);
        let perim: f64 = (0..pts.len()).map(|i| (pts[(i + 1) % pts.len()] - pts[i]).norm()).sum();
        let rho = (r * r - c * c).sqrt();
        // an inscribed polyline loses at most the chordal error: relative (h/ρ)²/8 per unit,
        // with h the mesh edge length (the facets also sit inside the sphere by h²/(8r))
        let rel = (h / rho).powi(2) / 8.0 + h * h / (8.0 * r * rho);
        prop_assert!(perim <= 2.0 * PI * rho * (1.0 + 1e-12));
        prop_assert!((perim - 2.0 * PI * rho).abs() <= 2.0 * PI * rho * 2.0 * rel, "{perim} vs {}", 2.0 * PI * rho);
    }
}

/// A UV sphere of radius `r` with `nlat` × `nlon` cells and its largest edge length.
fn uv_sphere(r: f64, nlat: usize, nlon: usize) -> (TriMesh, f64) {
    let mut v = vec![Vector3::new(0.0, 0.0, r)];
    for i in 1..nlat {
        let th = PI * i as f64 / nlat as f64;
        for j in 0..nlon {
            let ph = 2.0 * PI * j as f64 / nlon as f64;
            v.push(Vector3::new(
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            ));
        }
    }
    v.push(Vector3::new(0.0, 0.0, -r));
    let last = (v.len() - 1) as u32;
    let idx = |i: usize, j: usize| (1 + (i - 1) * nlon + j % nlon) as u32;
    let mut f = Vec::new();
    for j in 0..nlon {
        f.push([0, idx(1, j), idx(1, j + 1)]);
        f.push([last, idx(nlat - 1, j + 1), idx(nlat - 1, j)]);
    }
    for i in 1..nlat - 1 {
        for j in 0..nlon {
            f.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            f.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    let m = TriMesh::try_new(v, f).unwrap();
    let h = m
        .faces()
        .iter()
        .enumerate()
        .map(|(fi, _)| {
            let [a, b, c] = m.triangle(fi);
            (a - b).norm().max((b - c).norm()).max((c - a).norm())
        })
        .fold(0.0, f64::max);
    (m, h)
}

#[test]
fn sphere_mesh_is_closed_with_the_right_volume() {
    let (m, _) = uv_sphere(2.0, 64, 128);
    assert!(m.validate(true).unwrap().is_empty());
    let v = 4.0 / 3.0 * PI * 8.0;
    assert!((m.volume() - v).abs() / v < 2e-3);
}

#[test]
fn smoothing_fit_of_a_noisy_circle_recovers_its_curvature() {
    // a circle arc of radius 500 sampled every ~5 units with ±0.02 deterministic noise
    let pts: Vec<Vector2<f64>> = (0..=200)
        .map(|i| {
            let a = 1.0 * i as f64 / 200.0;
            let noise = 0.02 * (((i * 7919) % 17) as f64 / 8.0 - 1.0);
            Vector2::new((500.0 + noise) * a.cos(), (500.0 + noise) * a.sin())
        })
        .collect();
    let fit = geom::fit::fit_smoothing(
        &pts,
        None,
        &geom::fit::SmoothingParams {
            tolerance: 0.05,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(fit.max_error <= 0.05);
    let an = analyze_curve(
        &SplineCurve2::new(fit.curve),
        &CurveAnalysisParams::default(),
    )
    .unwrap();
    assert!(an.inflections.is_empty(), "{:?}", an.inflections);
    assert!((an.max_abs_curvature.curvature - 1.0 / 500.0).abs() < 2e-4);
}

#[test]
fn clamped_uniform_knots_shape() {
    assert_eq!(
        clamped_uniform_knots(2, 5, 0.0, 1.0),
        vec![0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
    );
}

#[test]
fn plane_frame_sections_of_a_tilted_direction_lie_in_their_planes() {
    let (m, _) = uv_sphere(10.0, 32, 64);
    let d = Vector3::new(1.0, 2.0, 3.0);
    let f = PlaneFrame::from_direction(d).unwrap();
    let surf = Surface::Mesh(m);
    let (frame, secs) = surf
        .sections(
            &SectionParams {
                direction: d,
                count: 5,
                smoothing: geom::fit::SmoothingParams {
                    tolerance: 0.01,
                    ..Default::default()
                },
                ..Default::default()
            },
            &|| {},
        )
        .unwrap();
    assert_eq!(frame, f);
    assert_eq!(secs.len(), 5);
    assert!(secs.iter().all(|s| s.closed));
}

/// The benchmark meshes load, are closed, and have the volume and area recorded in
/// `testdata::meshes_json` (the torus is vendored; the others are third-party data, skipped
/// loudly when absent).
#[test]
fn benchmark_meshes_match_their_recorded_volume_and_area() {
    let facts: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(testdata::meshes_json()).unwrap()).unwrap();
    for name in ["torus.obj", "fertility.obj", "hand.obj"] {
        let Some(path) = testdata::mesh(
            name,
            "benchmark_meshes_match_their_recorded_volume_and_area",
        ) else {
            continue;
        };
        let entry = facts
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["file"] == name)
            .unwrap();
        let m = TriMesh::load_obj(&path).unwrap();
        assert!(m.validate(true).is_ok(), "{name}");
        let t = m.topology();
        assert_eq!(t.components, 1);
        assert_eq!(m.faces().len() as u64, entry["faces"].as_u64().unwrap());
        let (v, a) = (
            entry["volume"].as_f64().unwrap(),
            entry["area"].as_f64().unwrap(),
        );
        assert!(
            (m.volume() - v).abs() / v < 1e-6,
            "{name}: volume {} vs {v}",
            m.volume()
        );
        assert!(
            (m.area() - a).abs() / a < 1e-6,
            "{name}: area {} vs {a}",
            m.area()
        );
        let hull = geom::hull::convex_hull(m.vertices()).unwrap();
        assert!(hull.volume() >= m.volume());
        assert_eq!(hull.topology().boundary_edges, 0);
    }
}

/// Points where the old rounded hull failed: a box's corners, points on its edges and faces
/// (clipping a solid to a block makes such sets), duplicates, and a curved top inside it,
/// all turned and moved so that no coordinate is exact.
fn boxed_points(
    half: [f64; 3],
    turn: (Vector3<f64>, f64),
    shift: Vector3<f64>,
    params: &[(u8, f64, f64)],
) -> Vec<Vector3<f64>> {
    let rot = nalgebra::Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(turn.0 + Vector3::new(0.0, 0.0, 1e-3)),
        turn.1,
    );
    let h = Vector3::from(half);
    let mut local = Vec::new();
    for &(kind, s, t) in params {
        let (s2, t2) = (2.0 * s - 1.0, 2.0 * t - 1.0);
        let k = (kind % 3) as usize;
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut p = Vector3::zeros();
        match kind / 3 % 4 {
            // on an edge along axis k
            0 => {
                p[k] = s2 * h[k];
                p[i] = if t < 0.5 { -h[i] } else { h[i] };
                p[j] = if (s * 7.0).fract() < 0.5 { -h[j] } else { h[j] };
            }
            // on a face normal to k
            1 => {
                p[k] = if (s * 5.0).fract() < 0.5 { -h[k] } else { h[k] };
                p[i] = s2 * h[i];
                p[j] = t2 * h[j];
            }
            // a corner
            2 => {
                p = Vector3::new(
                    if s < 0.5 { -h.x } else { h.x },
                    if t < 0.5 { -h.y } else { h.y },
                    if (s * 3.0 + t).fract() < 0.5 {
                        -h.z
                    } else {
                        h.z
                    },
                );
            }
            // a gently curved top inside the box, clipped at its walls
            _ => {
                p.x = s2 * h.x;
                p.y = t2 * h.y;
                p.z = h.z * (0.2 + 0.3 * (2.0 * s2).sin() * (1.5 * t2).cos());
            }
        }
        // noise as a clipped solid's points carry, from none to a millionth of the box
        let noise = [0.0, 1e-12, 1e-9, 1e-6][(kind / 12 % 4) as usize];
        let wobble = |x: f64| noise * h.norm() * ((x * 97.0).fract() - 0.5);
        p += Vector3::new(wobble(s + t), wobble(s * 3.0 + t), wobble(s + 5.0 * t));
        local.push(p);
        // duplicates, as clipping writes them
        if (s * 11.0).fract() < 0.3 {
            local.push(p);
        }
    }
    local.iter().map(|p| rot * p + shift).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The hull holds every point (no point outside any face's plane, exactly) and is
    /// closed, whatever the coplanar, collinear and repeated points.
    #[test]
    fn convex_hull_holds_every_point_of_degenerate_sets(
        half in prop::array::uniform3(0.05f64..3.0),
        axis in prop::array::uniform3(-1.0f64..1.0),
        angle in 0.0f64..6.3,
        shift in prop::array::uniform3(-100.0f64..100.0),
        params in prop::collection::vec((any::<u8>(), 0.0f64..1.0, 0.0f64..1.0), 40..3000),
    ) {
        let mut pts = boxed_points(half, (Vector3::from(axis), angle), Vector3::from(shift), &params);
        // the box's corners make it three-dimensional
        pts.extend(boxed_points(half, (Vector3::from(axis), angle), Vector3::from(shift), &[
            (6, 0.1, 0.1), (6, 0.9, 0.1), (6, 0.1, 0.9), (6, 0.9, 0.9),
            (6, 0.2, 0.2), (6, 0.8, 0.2), (6, 0.2, 0.8), (6, 0.8, 0.8),
        ]));
        let hull = geom::hull::convex_hull(&pts).unwrap();
        // exactly: no point strictly outside any face's plane (Shewchuk's predicate: a
        // positive orientation puts the point below the outward face)
        let c = |q: &Vector3<f64>| robust::Coord3D { x: q.x, y: q.y, z: q.z };
        for f in 0..hull.faces().len() {
            let [a, b, d] = hull.triangle(f);
            for p in &pts {
                let o = robust::orient3d(c(&a), c(&b), c(&d), c(p));
                prop_assert!(o >= 0.0, "a point outside face {f}: {p:?} ({o:e})");
            }
        }
        let t = hull.topology();
        prop_assert_eq!((t.boundary_edges, t.nonmanifold_edges), (0, 0));
    }
}
