//! Thesis Table 2.1 on five height fields of different character (and the bump cut in
//! two directions): volumes normalised by the block, and how much more our cuts remove
//! than the convex hull and the bounding box.
//!
//! `cargo run --release -p hotcut-ruled --example table21`

use std::time::Instant;

use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
use ruled::{pre_cut, Block, Params};

/// (name, z(x, y) over [−1, 1]², directions).
const SURFACES: [(&str, &str, &[[f64; 2]]); 6] = [
    ("bump", "0.35 + 0.35*exp(-3*(x*x + y*y))", &[[1.0, 0.0]]),
    ("saddle", "0.5 + 0.25*(x*x - y*y)", &[[1.0, 0.0]]),
    ("depression", "0.45 + 0.3*exp(-6*((abs(x)-0.6)^2 + y*y)) + 0.3*exp(-6*(x*x + (abs(y)-0.6)^2)) - 0.25*exp(-8*(x*x + y*y))", &[[1.0, 0.0]]),
    ("ridge", "0.2 + 0.55*exp(-6*(x - 0.3*y)^2)", &[[1.0, 0.0]]),
    ("wavy", "0.5 + 0.12*sin(3*x)*cos(2*y) + 0.1*x", &[[1.0, 0.0]]),
    ("bump, two directions", "0.35 + 0.35*exp(-3*(x*x + y*y))", &[[1.0, 0.0], [0.0, 1.0]]),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("| surface | directions | model | ruled | convex hull | more than hull % | bounding box | more than box % | wall time (s) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, z, dirs) in SURFACES {
        let h = HeightField::try_new(Expr::parse(z)?, (-1.0, 1.0), (-1.0, 1.0))?;
        let block = Block {
            min: [-1.0, -1.0, 0.0],
            max: [1.0, 1.0, 1.0],
        };
        let params = Params {
            directions: dirs.to_vec(),
            ..Params::default()
        };
        let t = Instant::now();
        let cut = pre_cut(&Surface::HeightField(h), &block, &params, &|_| {})?;
        let v = cut.volumes;
        println!(
            "| {name} | {} | {:.4} | {:.4} | {:.4} | {:.0} | {:.4} | {:.0} | {:.1} |",
            dirs.len(),
            v.model,
            v.ruled,
            v.convex_hull,
            v.more_than_hull_percent,
            v.bounding_box,
            v.more_than_box_percent,
            t.elapsed().as_secs_f64()
        );
        for d in &cut.directions {
            eprintln!(
                "  rounds {} qps {} constraints {} clearance {:.2e} objective {:?}",
                d.rounds,
                d.qps,
                d.constraint_points,
                d.clearance,
                d.objective_history
                    .iter()
                    .map(|o| format!("{o:.4}"))
                    .collect::<Vec<_>>()
            );
        }
    }
    Ok(())
}
