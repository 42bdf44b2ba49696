//! Independent check of the no-over-cut guarantee: on a sampling 4× denser than the
//! optimizer's in each direction, jittered with its own seed, every design point lies on
//! or below every leg's line extended across the whole block (so below the cut surface
//! too) up to 1e-6 of the block size. The cut surface is rebuilt from the result's
//! B-spline data with `geom`'s de Boor evaluation, and mesh heights by brute force over
//! all triangles — not the optimizer's code paths.

use geom::{expr::Expr, heightfield::HeightField, mesh::TriMesh, surface::Surface};
use nalgebra::{Vector2, Vector3};
use ruled::search::search_directions;
use ruled::{pre_cut, Block, Params, PreCut};

mod common;
use common::check_in;

const SURFACES: [(&str, &str); 5] = [
    ("bump", "0.35 + 0.35*exp(-3*(x*x + y*y))"),
    ("saddle", "0.5 + 0.25*(x*x - y*y)"),
    ("depression", "0.45 + 0.3*exp(-6*((abs(x)-0.6)^2 + y*y)) + 0.3*exp(-6*(x*x + (abs(y)-0.6)^2)) - 0.25*exp(-8*(x*x + y*y))"),
    ("ridge", "0.2 + 0.55*exp(-6*(x - 0.3*y)^2)"),
    ("wavy", "0.5 + 0.12*sin(3*x)*cos(2*y) + 0.1*x"),
];

fn block() -> Block {
    Block {
        min: [-1.0, -1.0, 0.0],
        max: [1.0, 1.0, 1.0],
    }
}

/// Checks `cut` against `design` on a jittered grid 4N × 4M per direction over the whole
/// block; returns (points checked, largest excess of design over a leg).
fn check(cut: &PreCut, params: &Params, design: &dyn Fn(f64, f64) -> Option<f64>) -> (usize, f64) {
    check_in(&block(), cut, params, design)
}

fn params(directions: Vec<[f64; 2]>) -> Params {
    Params {
        directions,
        sections: 16,
        samples: 16,
        controls: 6,
        ..Params::default()
    }
}

#[test]
fn no_design_point_above_any_extended_ruling() {
    let tol = 1e-6 * block().scale();
    for (name, z) in SURFACES {
        let expr = Expr::parse(z).unwrap();
        let h = HeightField::try_new(expr.clone(), (-1.0, 1.0), (-1.0, 1.0)).unwrap();
        for dirs in [vec![[1.0, 0.0]], vec![[1.0, 0.6]]] {
            let p = params(dirs.clone());
            let cut = pre_cut(&Surface::HeightField(h.clone()), &block(), &p, &|_| {}).unwrap();
            let (count, worst) = check(&cut, &p, &|x, y| Some(expr.eval(x, y)));
            println!(
                "{name} {dirs:?}: {count} points, largest excess {worst:.3e}, hull {:.0} % more",
                cut.volumes.more_than_hull_percent
            );
            assert!(count >= 16 * 16 * 16 / 2, "{name}: {count}");
            assert!(
                worst <= tol,
                "{name} {dirs:?}: design {worst:.3e} above a ruling"
            );
            // The cuts do remove material.
            assert!(cut.volumes.ruled < cut.volumes.bounding_box, "{name}");
        }
    }
}

/// Brute-force highest triangle over (x, y).
fn mesh_height(mesh: &TriMesh, x: f64, y: f64) -> Option<f64> {
    let p = Vector2::new(x, y);
    (0..mesh.faces().len())
        .filter_map(|f| {
            let [a, b, c]: [Vector3<f64>; 3] = mesh.triangle(f);
            let d = (b - a).xy().perp(&(c - a).xy());
            if d.abs() < 1e-300 {
                return None;
            }
            let l1 = (p - a.xy()).perp(&(c - a).xy()) / d;
            let l2 = (b - a).xy().perp(&(p - a.xy())) / d;
            let l0 = 1.0 - l1 - l2;
            (l0 >= -1e-12 && l1 >= -1e-12 && l2 >= -1e-12).then(|| l0 * a.z + l1 * b.z + l2 * c.z)
        })
        .reduce(f64::max)
}

#[test]
fn mesh_surface_is_never_overcut() {
    let expr = Expr::parse(SURFACES[0].1).unwrap();
    let mesh = HeightField::try_new(expr, (-1.0, 1.0), (-1.0, 1.0))
        .unwrap()
        .to_mesh(24, 24)
        .unwrap();
    let p = params(vec![[1.0, 0.0], [0.0, 1.0]]);
    let cut = pre_cut(&Surface::Mesh(mesh.clone()), &block(), &p, &|_| {}).unwrap();
    let (count, worst) = check(&cut, &p, &|x, y| mesh_height(&mesh, x, y));
    println!("mesh bump: {count} points, largest excess {worst:.3e}");
    assert!(count > 0);
    assert!(worst <= 1e-6 * block().scale(), "{worst:.3e}");
}

/// The check can fail: lowering every leg by 1 % of the block puts design points above.
#[test]
fn checker_detects_a_lowered_cut() {
    let expr = Expr::parse(SURFACES[0].1).unwrap();
    let h = HeightField::try_new(expr.clone(), (-1.0, 1.0), (-1.0, 1.0)).unwrap();
    let p = params(vec![[1.0, 0.0]]);
    let mut cut = pre_cut(&Surface::HeightField(h), &block(), &p, &|_| {}).unwrap();
    for leg in &mut cut.directions[0].legs {
        for a in &mut leg.a {
            *a -= 0.01;
        }
    }
    let (_, worst) = check(&cut, &p, &|x, y| Some(expr.eval(x, y)));
    assert!(worst > 0.005, "{worst}");
}

/// Oblique travelling waves (crests neither along nor across the cut, several wavelengths
/// over the block): the exchange's local searches once walked along the troughs at a
/// tiny step for hours. Now every direction ends within its QP budget, with its constraint
/// set bounded (one point per basin), and the cut is still never above the design.
#[test]
fn oblique_waves_end_within_budget_and_are_never_overcut() {
    let tol = 1e-6 * block().scale();
    let waves = [
        "0.5 + 0.15*sin((0.866*x + 0.5*y)*8)",
        "0.5 + 0.2*sin((0.6*x - 0.8*y)*5) + 0.05*cos((0.9*x + 0.44*y)*14)",
    ];
    for z in waves {
        let expr = Expr::parse(z).unwrap();
        let h = HeightField::try_new(expr.clone(), (-1.0, 1.0), (-1.0, 1.0)).unwrap();
        for dirs in [vec![[1.0, 0.0]], vec![[0.5, 0.866]]] {
            let p = params(dirs.clone());
            let cut = pre_cut(&Surface::HeightField(h.clone()), &block(), &p, &|_| {}).unwrap();
            let (_, worst) = check(&cut, &p, &|x, y| Some(expr.eval(x, y)));
            for d in &cut.directions {
                println!(
                    "{z} {dirs:?}: {} rounds, {} QPs, {} constraint points",
                    d.rounds, d.qps, d.constraint_points
                );
                assert!(d.qps <= 3 * p.max_rounds + 51, "{z}: {} QPs", d.qps);
                assert!(d.constraint_points <= 20 * p.sections * p.samples, "{z}");
            }
            assert!(
                worst <= tol,
                "{z} {dirs:?}: design {worst:.3e} above a ruling"
            );
        }
    }
}

/// `Auto(n)` (ruled::search): the kept direction leaves the least material of all
/// candidates, +x is a candidate (so the search never does worse than cutting along x),
/// the kept cuts are never above the design, and the choice is the same on one thread.
#[test]
fn the_direction_search_keeps_the_best_candidate_and_never_overcuts() {
    let tol = 1e-6 * block().scale();
    for (name, z) in [SURFACES[3], SURFACES[1]] {
        let expr = Expr::parse(z).unwrap();
        let h = Surface::HeightField(
            HeightField::try_new(expr.clone(), (-1.0, 1.0), (-1.0, 1.0)).unwrap(),
        );
        let p = Params {
            sections: 8,
            samples: 8,
            controls: 5,
            ..params(vec![[1.0, 0.0]])
        };
        let (cut, search) = search_directions(&h, &block(), &p, 4, &|_| {}).unwrap();
        let best = search.candidates[search.best].left_for_milling.unwrap();
        for c in &search.candidates {
            println!("{name}: {:5.1}° leaves {:?}", c.degrees, c.left_for_milling);
            assert!(
                c.left_for_milling.is_some_and(|v| v >= best),
                "{name}: {c:?}"
            );
        }
        assert_eq!(cut.volumes.ruled, best);
        let d = search.candidates[search.best].direction;
        assert_eq!(cut.directions.len(), 1);
        assert!((cut.directions[0].direction[0] - d[0]).abs() < 1e-12);
        let along_x = pre_cut(&h, &block(), &p, &|_| {}).unwrap();
        assert_eq!(search.candidates[0].degrees, 0.0);
        assert_eq!(
            search.candidates[0].left_for_milling,
            Some(along_x.volumes.ruled)
        );
        let (count, worst) = check(&cut, &p, &|x, y| Some(expr.eval(x, y)));
        assert!(
            count > 0 && worst <= tol,
            "{name}: design {worst:.3e} above a ruling"
        );
        if name != "ridge" {
            continue;
        }
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| search_directions(&h, &block(), &p, 4, &|_| {}))
            .unwrap();
        assert_eq!(one.1, search, "{name}: thread count changed the search");
        assert_eq!(one.0, cut);
    }
}

#[test]
fn a_search_needs_1_to_36_candidates() {
    let h = Surface::HeightField(
        HeightField::try_new(
            Expr::parse(SURFACES[0].1).unwrap(),
            (-1.0, 1.0),
            (-1.0, 1.0),
        )
        .unwrap(),
    );
    for n in [0, 37] {
        let e = search_directions(&h, &block(), &params(vec![[1.0, 0.0]]), n, &|_| {}).unwrap_err();
        assert!(e.to_string().contains("1–36"), "{e}");
    }
}

/// The optimization runs in the block's unit frame: moved far from the origin and
/// scaled, the same job gives the same cut mapped by the same similarity, every number of
/// the result (ranges, knots, legs, polygons, lines, clearance) back in model units.
#[test]
fn results_come_back_in_model_units_wherever_the_block_is() {
    let p = Params {
        sections: 8,
        samples: 8,
        ..params(vec![[1.0, 0.0], [0.6, 0.8]])
    };
    let z = SURFACES[0].1;
    let unit = pre_cut(
        &Surface::HeightField(
            HeightField::try_new(Expr::parse(z).unwrap(), (-1.0, 1.0), (-1.0, 1.0)).unwrap(),
        ),
        &block(),
        &p,
        &|_| {},
    )
    .unwrap();
    // x ↦ 250·x + (4000, −3000, 120), exact in floating point for the inputs below
    let (s, o) = (250.0, [4000.0, -3000.0, 120.0]);
    // (the surfaces' only function name, `exp`, holds an `x`)
    let moved = format!("{o2} + {s}*({z})", o2 = o[2])
        .replace("exp", "E")
        .replace('x', &format!("((X - {})/{s})", o[0]))
        .replace('y', &format!("((Y - ({}))/{s})", o[1]))
        .replace('X', "x")
        .replace('Y', "y")
        .replace('E', "exp");
    let far = Block {
        min: [o[0] - s, o[1] - s, o[2]],
        max: [o[0] + s, o[1] + s, o[2] + s],
    };
    let h = HeightField::try_new(
        Expr::parse(&moved).unwrap(),
        (far.min[0], far.max[0]),
        (far.min[1], far.max[1]),
    )
    .unwrap();
    let cut = pre_cut(&Surface::HeightField(h.clone()), &far, &p, &|_| {}).unwrap();
    assert_eq!(cut.volumes, unit.volumes);
    let close = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() <= 1e-9 * s * (1.0 + b.abs() / s),
            "{what}: {a} vs {b}"
        );
    };
    let map = |v: f64, k: usize| o[k] + s * v;
    for (d, e) in cut.directions.iter().zip(&unit.directions) {
        let (du, dw) = (
            d.direction[0] * o[0] + d.direction[1] * o[1],
            d.across[0] * o[0] + d.across[1] * o[1],
        );
        close(d.u.0, du + s * e.u.0, "u");
        close(d.w.1, dw + s * e.w.1, "w");
        close(d.w_mid, dw + s * e.w_mid, "w_mid");
        close(d.w_half, s * e.w_half, "w_half");
        close(d.clearance, s * e.clearance, "clearance");
        for (a, b) in d.knots.iter().zip(&e.knots) {
            close(*a, du + s * b, "knot");
        }
        for (a, b) in d.legs.iter().zip(&e.legs) {
            for (x, y) in a.a.iter().zip(&b.a) {
                close(*x, map(*y, 2), "leg a");
            }
            for (x, y) in a.m.iter().zip(&b.m) {
                close(*x, s * y, "leg m");
            }
        }
        for (a, b) in d.sections.iter().zip(&e.sections) {
            close(a.offset, du + s * b.offset, "offset");
            for (p, q) in a.polygon.iter().zip(&b.polygon) {
                (0..3).for_each(|k| close(p[k], map(q[k], k), "polygon"));
            }
        }
        for (a, b) in d.lines.iter().flatten().zip(e.lines.iter().flatten()) {
            close(a.a, map(b.a, 2), "line a");
            close(a.m, s * b.m, "line m");
        }
    }
    let design = |x: f64, y: f64| far.covers(x, y).then(|| h.expr().eval(x, y));
    let (_, worst) = check_in(&far, &cut, &p, &design);
    assert!(worst <= 1e-6 * s, "over-cut by {worst}");
}

/// Issue 35 item 6: travelling waves in a 4 × 3 m block (millimetres), oblique and
/// axis-aligned, under `Auto(6)`. Every leg's line, extended across the whole block, is
/// checked against the exact surface on a grid that includes the block's end faces and
/// the ends of every chord (where an over-cut once hid: the samples stopped short of the
/// end sections), whatever direction the search keeps.
#[test]
fn auto_directions_never_overcut_anywhere_in_the_block_end_faces_included() {
    let b = Block {
        min: [0.0, 0.0, 0.0],
        max: [4000.0, 3000.0, 1000.0],
    };
    let tol = 1e-6 * b.scale();
    let waves = [
        ("oblique", "500 + 150*sin(x/400 + y/250)"),
        (
            "oblique-steep",
            "450 + 120*sin(0.8*x/300 - 0.6*y/300) + 60*cos(y/500)",
        ),
        ("along-x", "500 + 140*sin(x/350)"),
        ("along-y", "500 + 140*sin(y/300)"),
    ];
    for (name, z) in waves {
        let expr = Expr::parse(z).unwrap();
        let h = HeightField::try_new(expr.clone(), (0.0, 4000.0), (0.0, 3000.0)).unwrap();
        let p = Params {
            sections: 12,
            samples: 12,
            controls: 6,
            ..Params::default()
        };
        let (cut, search) =
            search_directions(&Surface::HeightField(h), &b, &p, 6, &|_| {}).unwrap();
        let kept = search.candidates[search.best].degrees;
        let (count, worst) = check_everywhere(&b, &cut, &|x, y| expr.eval(x, y));
        println!("{name}: Auto(6) kept {kept}°, {count} points, largest excess {worst:.3e} mm");
        assert!(count > 0);
        assert!(
            worst <= tol,
            "{name} (kept {kept}°): design {worst:.3e} mm above a leg"
        );
    }
}

/// The largest excess of the design over any leg's line on a grid of every direction's
/// frame that includes both end faces (`u` at its ends) and both ends of every chord:
/// `(points, excess)`. Points are clamped onto the block's footprint (a rotated frame's
/// end face lies on the block's edge to rounding).
fn check_everywhere(b: &Block, cut: &PreCut, design: &dyn Fn(f64, f64) -> f64) -> (usize, f64) {
    let mut worst = f64::NEG_INFINITY;
    let mut count = 0;
    let n = 200;
    for d in &cut.directions {
        let curves = common::leg_curves(d);
        let along = Vector2::new(d.direction[0], d.direction[1]);
        let across = Vector2::new(d.across[0], d.across[1]);
        for i in 0..=n {
            let u = d.u.0 + (d.u.1 - d.u.0) * i as f64 / n as f64;
            for k in 0..=n {
                let w = d.w.0 + (d.w.1 - d.w.0) * k as f64 / n as f64;
                let p = along * u + across * w;
                let (x, y) = (p.x.clamp(b.min[0], b.max[0]), p.y.clamp(b.min[1], b.max[1]));
                // outside the block (a rotated frame's corners): not part of the cut
                if (x - p.x).abs() + (y - p.y).abs() > 1e-9 * b.scale() {
                    continue;
                }
                let f = design(x, y);
                count += 1;
                for c in &curves {
                    worst = worst.max(f - common::leg_z(c, d, u, w));
                }
            }
        }
    }
    (count, worst)
}
