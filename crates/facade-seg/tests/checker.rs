//! The segmentation algorithms on a wavy facade, checked from outside their bookkeeping:
//! every part of every piece is re-measured on the section curve itself (inflections by
//! sign changes of the sampled curvature, length by quadrature of the sampled polyline,
//! extent in the block, for `LongestElastica` a fresh elastica fit), and the parts of each
//! section tile it exactly once.

use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams};
use facade_seg::inflection::{inflection_points, InflectionParams};
use facade_seg::longest::{longest_elastica, LongestParams};
use facade_seg::trace::{trace, TraceParams};
use facade_seg::{Constraints, Facade, Segmentation};
use geom::expr::Expr;
use geom::heightfield::HeightField;
use geom::planar::{signed_curvature, PlanarCurve};
use geom::surface::{SectionParams, Surface};
use nalgebra::Vector3;

fn wavy(amplitude: f64, period: f64, count: usize) -> Facade {
    let h = HeightField::try_new(
        Expr::parse(&format!("{amplitude}*sin(y/{period}) + 20*cos(x/300)")).unwrap(),
        (0.0, 1200.0),
        (0.0, 2400.0),
    )
    .unwrap();
    let (frame, sections) = Surface::HeightField(h)
        .sections(
            &SectionParams {
                direction: Vector3::x(),
                count,
                ..SectionParams::default()
            },
            &|| {},
        )
        .unwrap();
    Facade::new(frame, &sections).unwrap()
}

fn constraints() -> Constraints {
    Constraints {
        block: [600.0, 600.0, 400.0],
        blade_length: 800.0,
        max_curvature: 0.011,
        max_inflections: 2,
        tolerance_rms: 0.5,
        tolerance_max: 2.0,
    }
}

/// Checks `seg` against the constraints on the curves themselves; `fitted`: also the
/// elastica fit and the blade length (the category-a guarantee).
fn check(facade: &Facade, c: &Constraints, seg: &Segmentation, fitted: bool) {
    println!(
        "{}: {} bands, {} rows, {} pieces",
        seg.algorithm,
        seg.bands,
        seg.rows,
        seg.pieces.len()
    );
    for piece in &seg.pieces {
        let (mut ulo, mut uhi) = (f64::INFINITY, f64::NEG_INFINITY);
        for part in &piece.parts {
            let sec = facade
                .sections
                .iter()
                .find(|s| s.index == part.plane)
                .unwrap();
            let m = 400;
            let ts: Vec<f64> = (0..=m)
                .map(|i| {
                    let s = part.s[0] + (part.s[1] - part.s[0]) * i as f64 / m as f64;
                    sec.t_at(s)
                })
                .collect();
            let pts: Vec<[f64; 2]> = ts
                .iter()
                .map(|&t| {
                    let q = sec.curve.point(t);
                    [q.x, q.y]
                })
                .collect();
            // inflections: sign changes of the curvature, ignoring the two end samples
            let signs: Vec<f64> = ts[1..m]
                .iter()
                .map(|&t| signed_curvature(&sec.curve.jet(t)))
                .filter(|k| k.abs() > 1e-12)
                .collect();
            let changes = signs.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
            assert!(
                changes <= 2,
                "piece {} plane {}: {changes} inflections",
                piece.id,
                part.plane
            );
            let length: f64 = pts
                .windows(2)
                .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                .sum();
            assert!(
                length <= c.blade_length + 1e-6,
                "piece {}: length {length}",
                piece.id
            );
            for q in &pts {
                ulo = ulo.min(q[0]);
                uhi = uhi.max(q[0]);
            }
            let ss: Vec<f64> = pts
                .iter()
                .scan((0.0, pts[0]), |(acc, prev), q| {
                    *acc += (q[0] - prev[0]).hypot(q[1] - prev[1]);
                    *prev = *q;
                    Some(*acc)
                })
                .collect();
            if !fitted {
                continue;
            }
            let fit = fit_points_with_arclength(
                &pts,
                &ss,
                &FitParams {
                    constraint: FitConstraint::EndPoints,
                    ..FitParams::default()
                },
            )
            .unwrap();
            assert!(
                fit.rms <= c.tolerance_rms && fit.max <= c.tolerance_max,
                "piece {} plane {}: fit rms {} max {}",
                piece.id,
                part.plane,
                fit.rms,
                fit.max
            );
        }
        assert!(
            uhi - ulo <= c.block[1] + 1e-6,
            "piece {} is {} wide",
            piece.id,
            uhi - ulo
        );
        assert!(
            piece.verdicts.all(),
            "piece {}: {:?}",
            piece.id,
            piece.verdicts
        );
    }
    // every section covered exactly once
    for sec in &facade.sections {
        let mut parts: Vec<[f64; 2]> = seg
            .pieces
            .iter()
            .flat_map(|p| p.parts.iter())
            .filter(|p| p.plane == sec.index)
            .map(|p| p.s)
            .collect();
        parts.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_eq!(parts[0][0], 0.0);
        for w in parts.windows(2) {
            assert_eq!(w[0][1], w[1][0], "plane {}: gap or overlap", sec.index);
        }
        assert!((parts.last().unwrap()[1] - sec.length).abs() < 1e-9 * sec.length);
    }
}

#[test]
fn longest_elastica_pieces_meet_every_constraint() {
    let facade = wavy(60.0, 150.0, 12);
    let c = constraints();
    let seg = longest_elastica(&facade, &c, &LongestParams::default(), &|| {}).unwrap();
    assert!(seg.bands > 2, "a 2.4 m wavy facade needs several bands");
    check(&facade, &c, &seg, true);
}

#[test]
fn inflection_pieces_hold_at_most_two_inflections() {
    let c = constraints();
    // inflections every 471 mm, and every 141 mm (4 or 5 per 600 mm block: moves needed)
    for (facade, symmetric) in [
        (wavy(60.0, 150.0, 12), false),
        (wavy(60.0, 150.0, 12), true),
        (wavy(10.0, 45.0, 12), false),
        (wavy(10.0, 45.0, 12), true),
    ] {
        let p = InflectionParams {
            symmetric,
            ..InflectionParams::default()
        };
        let seg = inflection_points(&facade, &c, &p, &|| {}).unwrap();
        check(&facade, &c, &seg, false);
        if symmetric {
            // every row has the same blocks
            let bands: Vec<usize> = (0..seg.rows)
                .map(|r| seg.pieces.iter().filter(|q| q.row == r).count())
                .collect();
            assert!(bands.windows(2).all(|w| w[0] == w[1]), "{bands:?}");
        }
    }
}

#[test]
fn trace_pieces_hold_at_most_two_inflections() {
    let c = constraints();
    for facade in [wavy(60.0, 150.0, 12), wavy(10.0, 45.0, 12)] {
        let seg = trace(&facade, &c, &TraceParams::default(), &|| {}).unwrap();
        assert!(!seg.seams.is_empty());
        check(&facade, &c, &seg, false);
    }
}

/// The three algorithms cut the same wavy facade differently: their seams sit at different
/// places on the sections.
#[test]
fn the_algorithms_segment_the_wavy_facade_differently() {
    let facade = wavy(60.0, 150.0, 12);
    let c = constraints();
    let ends = |seg: &Segmentation| {
        let mut v: Vec<i64> = seg
            .pieces
            .iter()
            .flat_map(|p| p.parts.iter())
            .filter(|p| p.plane == facade.sections[0].index)
            .map(|p| p.s[1].round() as i64)
            .collect();
        v.sort();
        v
    };
    let a = ends(&inflection_points(&facade, &c, &InflectionParams::default(), &|| {}).unwrap());
    let b = ends(&trace(&facade, &c, &TraceParams::default(), &|| {}).unwrap());
    let l = ends(&longest_elastica(&facade, &c, &LongestParams::default(), &|| {}).unwrap());
    println!("part ends on the first section: inflection {a:?}, trace {b:?}, longest {l:?}");
    assert!(a != b && b != l && a != l);
}

#[test]
fn bad_constraints_are_rejected() {
    let facade = wavy(60.0, 150.0, 4);
    for bad in [
        Constraints {
            blade_length: -1.0,
            ..constraints()
        },
        Constraints {
            tolerance_max: f64::NAN,
            ..constraints()
        },
        Constraints {
            block: [600.0, 0.0, 400.0],
            ..constraints()
        },
    ] {
        assert!(longest_elastica(&facade, &bad, &LongestParams::default(), &|| {}).is_err());
    }
    let p = LongestParams {
        precision: 0.0,
        ..LongestParams::default()
    };
    assert!(longest_elastica(&facade, &constraints(), &p, &|| {}).is_err());
}
