//! Segmentation versus rationalization on a 30k-face closed mesh (Neptune, 29 636
//! triangles, third-party data: skipped loudly when absent, see `testdata`): the whole-model
//! strategy (rationalize, segment, plan every block) and the per-block one, each once, in
//! the settings of BENCHMARKS.md. `cargo bench -p hotcut-ruled-blocks --bench plan`.

use geom::mesh::TriMesh;
use ruled_blocks::{per_block, run, Params};

fn main() {
    divan::main();
}

fn neptune() -> Option<TriMesh> {
    let path = testdata::mesh(
        "neptune.obj",
        "cargo bench -p hotcut-ruled-blocks --bench plan",
    )?;
    Some(TriMesh::load_obj(&path).expect("benchmark mesh"))
}

/// Neptune (1 m tall, in metres), sections along its height, 0.25 m blocks, 20 mm.
fn params() -> Params {
    Params {
        axis: [0.0, 1.0, 0.0],
        sections: 80,
        tolerance: 0.02,
        max_strips: 48,
        blocks: blocks::Params {
            block_size: [0.25; 3],
            max_iterations: 20,
            sample_spacing: 0.1,
            ..blocks::Params::default()
        },
        kerf: 0.0015,
        lead: 0.02,
    }
}

#[divan::bench(sample_count = 1)]
fn neptune_whole_model(bencher: divan::Bencher) {
    let Some(m) = neptune() else {
        return;
    };
    let p = params();
    bencher.bench(|| run(&m, &p, &|_| {}).expect("rationalizes"));
}

#[divan::bench(sample_count = 1)]
fn neptune_per_block(bencher: divan::Bencher) {
    let Some(m) = neptune() else {
        return;
    };
    let p = params();
    bencher.bench(|| per_block::run(&m, &p).expect("rationalizes"));
}
