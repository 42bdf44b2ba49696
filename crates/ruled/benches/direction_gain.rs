//! Issue 19 item 7: the gain of `Auto(8)` over the convex hull. Nine non-convex surfaces
//! of our own in a 1000 × 1000 × 600 mm block (the jobs of `benches/precut-auto/`),
//! default parameters: each kept cut passes the independent over-cut check of
//! `tests/common`, no search leaves more than cutting along x, and the mean gain over the
//! convex hull is at least 60 %. Prints the table of BENCHMARKS.md; exits non-zero when a
//! check fails.
//!
//! `cargo bench -p hotcut-ruled --bench direction_gain` (72 default pre-cuts: about 11 minutes
//! on the 2-core VM).

use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
use ruled::search::search_directions;
use ruled::{Block, Params};

#[path = "../tests/common/mod.rs"]
mod common;

const SURFACES: [(&str, &str); 9] = [
    ("bump-field", "150 + 120*exp(-((x-250)^2+(y-200)^2)/30000) + 150*exp(-((x+200)^2+(y+250)^2)/40000) + 100*exp(-((x+150)^2+(y-280)^2)/20000) + 90*exp(-((x-300)^2+(y+250)^2)/25000)"),
    ("crater", "200 + 250*exp(-(x^2+y^2)/120000) - 180*exp(-(x^2+y^2)/25000)"),
    ("crossing-ridges", "120 + 200*exp(-8*((x - y)/700)^2) + 200*exp(-8*((x + 0.4*y)/600)^2)"),
    ("oblique-ridge", "120 + 330*exp(-6*(x/500 - 0.6*y/500)^2)"),
    ("oblique-valley", "450 - 300*exp(-5*((x + 0.8*y)/500)^2)"),
    ("oblique-waves", "300 + 120*sin(2*pi*(x*0.6 + y*0.8)/450)"),
    ("s-step", "300 + 150*(1 - 2/(exp(2*(4*((x*0.8 + y*0.6)/500 - 0.3*sin(3*(y*0.8 - x*0.6)/500)))) + 1))"),
    ("saddle", "300 + 250*((x/500)^2 - (y/500)^2)"),
    ("twisted-valleys", "300 + 100*cos(2*pi*x/700)*cos(2*pi*y/900) + 80*x*y/250000"),
];

fn main() {
    // `cargo test --benches` and `cargo bench -- --list` pass flags; run only as a bench
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let b = Block {
        min: [-500.0, -500.0, 0.0],
        max: [500.0, 500.0, 600.0],
    };
    let tol = 1e-6 * b.scale();
    let p = Params::default();
    let mut gains = Vec::new();
    let mut failures = Vec::new();
    println!("| surface | along x % | Auto(8) % | kept | points checked | largest excess (mm) |");
    println!("|---|---|---|---|---|---|");
    for (name, z) in SURFACES {
        let expr = Expr::parse(z).expect("expression");
        let h = Surface::HeightField(
            HeightField::try_new(expr.clone(), (-500.0, 500.0), (-500.0, 500.0))
                .expect("height field"),
        );
        let (cut, search) = match search_directions(&h, &b, &p, 8, &|_| {}) {
            Ok(r) => r,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let (count, worst) = common::check_in(&b, &cut, &p, &|x, y| Some(expr.eval(x, y)));
        let gain = cut.volumes.more_than_hull_percent;
        let along_x = search.candidates[0]
            .more_than_hull_percent
            .unwrap_or(f64::NAN);
        println!(
            "| {name} | {along_x:.1} | {gain:.1} | {}° | {count} | {worst:.2e} |",
            search.candidates[search.best].degrees
        );
        if count == 0 || worst > tol {
            failures.push(format!("{name}: design {worst:.3e} above a ruling"));
        }
        if !(gain >= along_x) {
            failures.push(format!("{name}: {gain} % < {along_x} % along x"));
        }
        gains.push(gain);
    }
    let mean = gains.iter().sum::<f64>() / gains.len().max(1) as f64;
    println!("mean {mean:.1} % more removed than the hull");
    if mean < 60.0 {
        failures.push(format!("mean {mean:.1} % < 60 %"));
    }
    if !failures.is_empty() {
        eprintln!("{failures:#?}");
        std::process::exit(1);
    }
}
