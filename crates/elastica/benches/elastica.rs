//! Benchmarks: one Jacobi evaluation (sn, cn, dn, am, E together) and fitting one
//! 200-point test curve (`testdata::curves_json`) with each constraint option, and the generic
//! 7-parameter baseline fit.
//! Run: `cargo bench -p hotcut-elastica`.

use elastica::elliptic::Elliptic;
use elastica::fit::{fit_points, FitConstraint, FitParams};
use std::sync::OnceLock;

fn main() {
    divan::main();
}

#[divan::bench(args = [0.1, 0.5, 0.9, 0.999_999])]
fn jacobi_eval(bencher: divan::Bencher, m: f64) {
    let e = Elliptic::new(m).unwrap();
    let mut u = 0.1;
    bencher.bench_local(|| {
        u = if u > 50.0 { 0.1 } else { u + 0.37 };
        divan::black_box(e.eval(divan::black_box(u)))
    });
}

#[divan::bench]
fn elliptic_new(bencher: divan::Bencher) {
    bencher.bench_local(|| Elliptic::new(divan::black_box(0.7)).unwrap().k());
}

fn curves() -> &'static Vec<(String, Vec<[f64; 2]>)> {
    static C: OnceLock<Vec<(String, Vec<[f64; 2]>)>> = OnceLock::new();
    C.get_or_init(|| {
        let text = std::fs::read_to_string(testdata::curves_json()).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
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
                (c["class"].as_str().unwrap().to_string(), pts)
            })
            .collect()
    })
}

const OPTIONS: [FitConstraint; 3] = [
    FitConstraint::Free,
    FitConstraint::EndPoints,
    FitConstraint::EndPointsAndLength,
];

/// One fit per sample, cycling through all 72 curves ten times (720 samples): divan's median
/// is the median over the curves.
#[divan::bench(args = OPTIONS, sample_count = 720)]
fn fit_200_points(bencher: divan::Bencher, constraint: FitConstraint) {
    let cs = curves();
    let params = FitParams {
        constraint,
        ..Default::default()
    };
    let mut i = 0;
    bencher.bench_local(|| {
        i = (i + 1) % cs.len();
        divan::black_box(fit_points(&cs[i].1, &params).ok())
    });
}

/// The generic 7-parameter Levenberg–Marquardt baseline (forward-difference Jacobian, same
/// §5.1 guess, same curves); compare with `fit_200_points` Free.
#[divan::bench(sample_count = 720)]
fn baseline_fit_200_points(bencher: divan::Bencher) {
    let cs = curves();
    let mut i = 0;
    bencher.bench_local(|| {
        i = (i + 1) % cs.len();
        divan::black_box(elastica::fit::baseline::fit_points_baseline(&cs[i].1, 200).ok())
    });
}

/// A 1000 mm blade of each kind a facade poses: an arch (non-inflectional), an S with one
/// inflection, a wave with three (unstable).
fn blades() -> [elastica::Segment; 3] {
    use elastica::{ElasticaParams, Family, Segment};
    let e = |family, k: f64, s0: f64, l: f64| {
        Segment::Elastica(ElasticaParams {
            family,
            k,
            s0,
            l,
            scale: 1000.0 / l,
            phi: 0.2,
            x0: 0.0,
            y0: 0.0,
            one_minus_k: None,
        })
    };
    [
        e(Family::NonInflectional, 0.9, -0.4, 0.8),
        e(Family::Inflectional, 0.3, -1.0, 2.5),
        e(Family::Inflectional, 0.3, 0.5, 7.0),
    ]
}

/// The margin, class, inflections and loads of one held blade (`elastica::stability`),
/// moved along x by a new amount each time so that `stability`'s memo does not answer.
#[divan::bench(args = [0, 1, 2])]
fn stability_of_blade(bencher: divan::Bencher, which: usize) {
    let b = blades()[which];
    let p = elastica::StabilityParams::default();
    let mut shift = 0.0;
    bencher.bench_local(|| {
        shift += 1.0;
        let moved = b.mapped([1.0, 0.0], [shift, 0.0]);
        elastica::stability(divan::black_box(&moved), &p)
            .unwrap()
            .margin
    });
}

/// Following the discrete blade (128 segments) through one move that turns an arch's ends
/// by 0.1 rad and closes the chord by 1 %.
#[divan::bench]
fn follow_one_move(bencher: divan::Bencher) {
    use elastica::stability::follow::{follow, DiscreteBlade, FollowParams, HeldEnds, SEGMENTS};
    let at = |w: f64| HeldEnds {
        chord: 950.0 - 10.0 * w,
        angles: [0.3 + 0.1 * w, -0.3 - 0.1 * w],
    };
    let start =
        DiscreteBlade::settle_like(1000.0, at(0.0), |u| 0.3 - 0.6 * u, SEGMENTS, None).unwrap();
    let p = FollowParams::default();
    bencher.bench_local(|| follow(divan::black_box(&start), &at, &p).min_margin());
}

/// One blade carried to the next plane's (`stability::follow::transition`): an arch
/// flattening slightly, as between two neighbouring cutting planes.
#[divan::bench]
fn transition_between_planes(bencher: divan::Bencher) {
    use elastica::Segment;
    let arc = |c: f64| Segment::Arc {
        x0: 0.0,
        y0: 0.0,
        phi: 0.5 * c * 1000.0,
        curvature: -c,
        length: 1000.0,
    };
    let (a, b) = (arc(4e-4), arc(3.9e-4));
    bencher.bench_local(|| {
        elastica::stability::follow::transition(divan::black_box(&a), &b)
            .unwrap()
            .snap
    });
}
