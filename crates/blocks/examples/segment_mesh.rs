//! Segments one mesh and prints the counts: `cargo run --release -p hotcut-blocks --example
//! segment_mesh -- MESH EDGE [RESTARTS] [OPS: any of t r a] [MAX_ITERATIONS] [SPACING]`.

use std::time::Instant;

use blocks::{segment, Operation, Params};
use geom::mesh::TriMesh;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: segment_mesh MESH EDGE [RESTARTS] [OPS] [MAX_ITERATIONS]";
    let mesh = TriMesh::load_obj(args.first().ok_or(usage)?.as_ref())?;
    let edge: f64 = args.get(1).ok_or(usage)?.parse()?;
    let restarts: u32 = args.get(2).map_or(Ok(1), |s| s.parse())?;
    let ops = args.get(3).map_or("tra", String::as_str);
    let max_iterations: u32 = args.get(4).map_or(Ok(200), |s| s.parse())?;
    let sample_spacing: f64 = args.get(5).map_or(Ok(0.05), |s| s.parse())?;
    let operations = [
        ('t', Operation::Translate),
        ('r', Operation::Rotate),
        ('a', Operation::Align),
    ]
    .into_iter()
    .filter(|(c, _)| ops.contains(*c))
    .map(|(_, o)| o)
    .collect();
    let params = Params {
        block_size: [edge; 3],
        restarts,
        operations,
        max_iterations,
        sample_spacing,
        ..Params::default()
    };
    let t = Instant::now();
    let seg = segment(&mesh, &params, &|_| {})?;
    println!(
        "init {} final {} reduction {:.1}% lower bound {} samples {:?} iterations {:?} accepted {:?} time {:.1}s",
        seg.initial_blocks,
        seg.final_blocks,
        seg.reduction_percent,
        seg.lower_bound,
        seg.sampling.counts,
        seg.restarts.iter().map(|r| (r.blocks, r.iterations)).collect::<Vec<_>>(),
        seg.accepted,
        t.elapsed().as_secs_f64()
    );
    Ok(())
}
