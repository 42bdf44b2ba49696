//! Block segmentation wall time on two benchmark meshes (torus, octopus; the octopus is
//! third-party data, skipped loudly when absent, see `testdata`) at a fixed
//! iteration cap, and the exact overlap volume of two rotated blocks.
//! `cargo bench -p hotcut-blocks --bench segment`.

use blocks::{cuboid::overlap_volume, segment, Cuboid, Params};
use geom::mesh::TriMesh;
use nalgebra::{UnitQuaternion, Vector3};

fn main() {
    divan::main();
}

fn mesh(name: &str) -> Option<TriMesh> {
    let path = testdata::mesh(name, "cargo bench -p hotcut-blocks --bench segment")?;
    Some(TriMesh::load_obj(&path).expect("benchmark mesh"))
}

#[divan::bench(args = [("torus.obj", 0.55), ("octopus.obj", 0.12)], sample_count = 3)]
fn segment_20_iterations(bencher: divan::Bencher, (name, edge): (&str, f64)) {
    let Some(m) = mesh(name) else {
        return;
    };
    let params = Params {
        block_size: [edge; 3],
        max_iterations: 20,
        ..Params::default()
    };
    bencher.bench(|| segment(&m, &params, &|_| {}).expect("segments"));
}

#[divan::bench]
fn overlap_of_rotated_blocks(bencher: divan::Bencher) {
    let a = Cuboid::new(
        Vector3::zeros(),
        UnitQuaternion::from_euler_angles(0.3, 0.2, 0.1),
        Vector3::repeat(0.5),
    );
    let b = Cuboid::new(
        Vector3::new(0.4, 0.3, 0.2),
        UnitQuaternion::from_euler_angles(-0.5, 0.7, 0.2),
        Vector3::repeat(0.5),
    );
    bencher.bench(|| overlap_volume(divan::black_box(&a), divan::black_box(&b)));
}
