//! Block segmentation wall time on two shared meshes (torus, octopus) at a fixed
//! iteration cap, and the exact overlap volume of two rotated blocks.
//! `cargo bench -p blocks --bench segment`.

use std::path::Path;

use blocks::{cuboid::overlap_volume, segment, Cuboid, Params};
use geom::mesh::TriMesh;
use nalgebra::{UnitQuaternion, Vector3};

fn main() {
    divan::main();
}

fn mesh(name: &str) -> TriMesh {
    TriMesh::load_obj(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../../shared/data/meshes")
            .join(name),
    )
    .expect("shared mesh")
}

#[divan::bench(args = [("torus.obj", 0.55), ("octopus.obj", 0.12)], sample_count = 3)]
fn segment_20_iterations(bencher: divan::Bencher, (name, edge): (&str, f64)) {
    let m = mesh(name);
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
