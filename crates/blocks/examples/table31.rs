//! Reproduces thesis Table 3.1 (and, with `ablation`, Table 3.2) on the shared meshes:
//! for each model, a block edge is searched so that the initial grid is within ±10 % of
//! the paper's "No B Init", then the full algorithm runs with `RESTARTS` restarts.
//!
//! `cargo run --release -p blocks --example table31 -- [RESTARTS] [ablation] [MODEL…]`

use std::path::Path;
use std::time::Instant;

use blocks::{segment, Operation, Params};
use geom::mesh::TriMesh;

/// (file, model, paper's initial blocks, paper's result, paper's reduction %).
const PAPER: [(&str, &str, usize, usize, u32); 9] = [
    ("torus.obj", "Torus", 52, 33, 37),
    ("octopus.obj", "Octopus", 115, 68, 41),
    ("neptune.obj", "Neptun", 107, 76, 29),
    ("neptune.obj", "Neptun2-3", 143, 103, 28),
    ("neptune.obj", "Neptun3-2", 87, 61, 30),
    ("fertility.obj", "Fertility", 222, 200, 10),
    ("dancer.obj", "Dancer", 60, 31, 48),
    ("hand.obj", "Hand", 147, 96, 35),
    ("armadillo.obj", "Armadillo", 148, 117, 20),
];

/// Table 3.2 rows we have: (model, initial, translation, rotation, both, full).
const PAPER_ABLATION: [(&str, [usize; 5]); 3] = [
    ("Octopus", [115, 73, 88, 78, 68]),
    ("Armadillo", [148, 121, 137, 123, 117]),
    ("Neptun", [107, 94, 94, 76, 76]),
];

fn initial(mesh: &TriMesh, edge: f64) -> Result<usize, blocks::BlockError> {
    let p = Params {
        block_size: [edge; 3],
        operations: vec![Operation::Translate],
        max_iterations: 1,
        ..Params::default()
    };
    Ok(segment(mesh, &p, &|_| {})?.initial_blocks)
}

/// A block edge whose initial grid is within ±10 % (aiming at ±3 %) of `target`.
fn edge_for(mesh: &TriMesh, target: usize) -> Result<(f64, usize), blocks::BlockError> {
    let s = mesh.aabb().size();
    let mut edge = (s.x * s.y * s.z / target as f64).cbrt();
    let mut best = (edge, initial(mesh, edge)?);
    for _ in 0..12 {
        let n = initial(mesh, edge)?;
        let err = |n: usize| (n as f64 / target as f64 - 1.0).abs();
        if err(n) < err(best.1) {
            best = (edge, n);
        }
        if err(n) <= 0.03 {
            break;
        }
        edge *= (n as f64 / target as f64).powf(0.4);
    }
    // The count jumps with the edge (grid layers appear and vanish); scan around.
    let err = |n: usize| (n as f64 / target as f64 - 1.0).abs();
    if err(best.1) > 0.05 {
        let centre = best.0;
        for k in 0..=40 {
            let e = centre * (0.8 + 0.01 * k as f64);
            let n = initial(mesh, e)?;
            if err(n) < err(best.1) {
                best = (e, n);
            }
        }
    }
    Ok(best)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let restarts: u32 = args.first().map_or(Ok(4), |s| s.parse())?;
    let ablation = args.iter().any(|a| a == "ablation");
    let only: Vec<&String> = args.iter().skip(1).filter(|a| *a != "ablation").collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes");
    if !ablation {
        println!("| Model | file | block edge | init (paper) | result (paper) | reduction % (paper) | lower bound | wall time (s) |");
        println!("|---|---|---|---|---|---|---|---|");
    }
    for (file, model, init_paper, result_paper, red_paper) in PAPER {
        if !only.is_empty() && !only.iter().any(|m| m.as_str() == model) {
            continue;
        }
        let mesh = TriMesh::load_obj(&dir.join(file))?;
        let (edge, init) = edge_for(&mesh, init_paper)?;
        let base = Params {
            block_size: [edge; 3],
            restarts,
            seed: 1,
            ..Params::default()
        };
        if ablation {
            let Some((_, paper)) = PAPER_ABLATION.iter().find(|(m, _)| *m == model) else {
                continue;
            };
            let mut row = format!("| {model} | {init} ({}) |", paper[0]);
            for (k, ops) in [
                vec![Operation::Translate],
                vec![Operation::Rotate],
                vec![Operation::Translate, Operation::Rotate],
                vec![Operation::Translate, Operation::Rotate, Operation::Align],
            ]
            .into_iter()
            .enumerate()
            {
                let t = Instant::now();
                let seg = segment(
                    &mesh,
                    &Params {
                        operations: ops,
                        ..base.clone()
                    },
                    &|_| {},
                )?;
                row += &format!(
                    " {} ({}) {:.0} s |",
                    seg.final_blocks,
                    paper[k + 1],
                    t.elapsed().as_secs_f64()
                );
            }
            println!("{row}");
            continue;
        }
        let t = Instant::now();
        let seg = segment(&mesh, &base, &|_| {})?;
        println!(
            "| {model} | {file} | {edge:.4} | {} ({init_paper}) | {} ({result_paper}) | {:.1} ({red_paper}) | {} | {:.1} |",
            seg.initial_blocks,
            seg.final_blocks,
            seg.reduction_percent,
            seg.lower_bound,
            t.elapsed().as_secs_f64()
        );
        assert_eq!(seg.initial_blocks, init);
    }
    Ok(())
}
