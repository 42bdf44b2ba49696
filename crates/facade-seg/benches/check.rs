//! One section checked while it is drawn (`facade_seg::check::check_section`), the call
//! behind the Python bindings' `hotcut.check_section`: a 200-point section (a sine arch
//! 600 mm wide, 40 mm high), blade 1200 mm, |κ| ≤ 0.01/mm, tolerance 0.5 / 2 mm, and its
//! parts — the smoothing spline, the curvature analysis, the elastica fit. The target of
//! issue 41 is 1 ms per call.
//!
//! Run: `cargo bench -p hotcut-facade-seg --bench check`.

use facade_seg::check::{check_section, CheckParams};
use facade_seg::survey::SurveyParams;
use geom::analysis::{analyze_curve, CurveAnalysisParams};
use geom::fit::SmoothingParams;
use geom::surface::Section;
use nalgebra::Vector2;

fn main() {
    divan::main();
}

fn points() -> Vec<[f64; 2]> {
    (0..200)
        .map(|i| {
            let x = 3.0 * i as f64;
            [x, 40.0 * (x / 100.0).sin()]
        })
        .collect()
}

/// The points as a section's plane coordinates.
fn vectors() -> Vec<Vector2<f64>> {
    points().iter().map(|p| Vector2::new(p[0], p[1])).collect()
}

/// The smoothing spline of the `Analyze` task's sections, 0.05 mm.
fn smoothing() -> SmoothingParams {
    SmoothingParams {
        degree: 3,
        tolerance: 0.05,
        max_control: 400,
        chordal: false,
    }
}

fn params(samples: usize) -> CheckParams {
    CheckParams {
        survey: SurveyParams {
            curve: CurveAnalysisParams {
                samples,
                ..Default::default()
            },
            blade_length: 1200.0,
            max_curvature: 0.01,
            max_inflections: 2,
            block: None,
        },
        smoothing: 0.05,
        rms: 0.5,
        max: 2.0,
        min_margin: elastica::stability::MARGINAL,
    }
}

/// With the default samples of a 200-point section (400), and with the `Analyze` task's
/// 2000.
#[divan::bench(args = [400, 2000])]
fn check(bencher: divan::Bencher, samples: usize) {
    let (pts, p) = (points(), params(samples));
    bencher.bench(|| check_section(divan::black_box(&pts), &p).map(|c| c.cuttable));
}

#[divan::bench]
fn smoothing_spline(bencher: divan::Bencher) {
    let (pts, s) = (vectors(), smoothing());
    bencher.bench(|| {
        Section::from_points(divan::black_box(pts.clone()), None, false, &s).map(|s| s.fit_rms)
    });
}

#[divan::bench(args = [400, 2000])]
fn analysis(bencher: divan::Bencher, samples: usize) {
    let (pts, s) = (vectors(), smoothing());
    let section = Section::from_points(pts, None, false, &s).expect("a section");
    let p = section.analysis_params(&CurveAnalysisParams {
        samples,
        ..Default::default()
    });
    bencher.bench(|| analyze_curve(divan::black_box(&section.curve), &p).map(|a| a.length));
}

#[divan::bench]
fn analysis_params(bencher: divan::Bencher) {
    let (pts, s) = (vectors(), smoothing());
    let section = Section::from_points(pts, None, false, &s).expect("a section");
    bencher.bench(|| {
        section
            .analysis_params(&CurveAnalysisParams::default())
            .samples
    });
}

#[divan::bench]
fn elastica_fit(bencher: divan::Bencher) {
    let pts = points();
    bencher
        .bench(|| elastica::fit_points(divan::black_box(&pts), &Default::default()).map(|f| f.rms));
}
