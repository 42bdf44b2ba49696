//! Benchmarks of the three segmentation algorithms on the meandering wavy facade of the
//! `seg-wavy-*` jobs (`40*sin((y + 120*sin(x/300))/90) + 20*cos(x/300)` over 1.2 m × 2.4 m,
//! cut along x; blocks 600 × 600 × 400 mm, blade 800 mm, tolerance 0.5 / 2 mm), with 26
//! and with 200 sections. Sectioning is done once outside the timed code; what is timed
//! is the algorithm alone (`inflection_points`, `trace`, `longest_elastica` with their
//! default parameters), including the per-part checks of its pieces.
//!
//! Run: `cargo bench -p hotcut-facade-seg --bench segment`.

use std::sync::OnceLock;

use facade_seg::inflection::{inflection_points, InflectionParams};
use facade_seg::longest::{longest_elastica, LongestParams};
use facade_seg::trace::{trace, TraceParams};
use facade_seg::{Constraints, Facade};
use geom::expr::Expr;
use geom::heightfield::HeightField;
use geom::surface::{SectionParams, Surface};
use nalgebra::Vector3;

fn main() {
    divan::main();
}

const SECTIONS: [usize; 2] = [26, 200];

fn facade(count: usize) -> &'static Facade {
    static F: OnceLock<Vec<(usize, Facade)>> = OnceLock::new();
    let all = F.get_or_init(|| {
        SECTIONS
            .iter()
            .map(|&n| {
                let h = HeightField::try_new(
                    Expr::parse("40*sin((y + 120*sin(x/300))/90) + 20*cos(x/300)")
                        .expect("expression parses"),
                    (0.0, 1200.0),
                    (0.0, 2400.0),
                )
                .expect("height field");
                let (frame, sections) = Surface::HeightField(h)
                    .sections(
                        &SectionParams {
                            direction: Vector3::x(),
                            count: n,
                            ..SectionParams::default()
                        },
                        &|| {},
                    )
                    .expect("sections");
                (n, Facade::new(frame, &sections).expect("facade"))
            })
            .collect()
    });
    &all.iter()
        .find(|(n, _)| *n == count)
        .expect("a benchmarked count")
        .1
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

#[divan::bench(args = SECTIONS, sample_count = 5, sample_size = 1)]
fn inflection(n: usize) -> usize {
    let seg = inflection_points(
        facade(n),
        &constraints(),
        &InflectionParams::default(),
        &|| {},
    )
    .expect("segments");
    seg.pieces.len()
}

#[divan::bench(args = SECTIONS, sample_count = 5, sample_size = 1)]
fn trace_algorithm(n: usize) -> usize {
    let seg = trace(facade(n), &constraints(), &TraceParams::default(), &|| {}).expect("segments");
    seg.pieces.len()
}

#[divan::bench(args = SECTIONS, sample_count = 3, sample_size = 1)]
fn longest(n: usize) -> usize {
    let seg = longest_elastica(facade(n), &constraints(), &LongestParams::default(), &|| {})
        .expect("segments");
    seg.pieces.len()
}
