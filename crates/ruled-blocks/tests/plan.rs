//! The whole chain on closed models: the deviation within the tolerance, the rationalized
//! solid's volume close to the model's, a convex model's blocks cut by their strips, both
//! strategies compared; the result follows a rigid motion and a change of scale.

mod common;

use geom::TriMesh;
use nalgebra::{Rotation3, Vector3};
use ruled_blocks::compare::figures;
use ruled_blocks::{per_block, run, Params};

fn params(tol: f64, block: f64, axis: [f64; 3]) -> Params {
    Params {
        axis,
        sections: 24,
        tolerance: tol,
        max_strips: 48,
        blocks: blocks::Params {
            block_size: [block; 3],
            max_iterations: 10,
            sample_spacing: 0.1,
            seed: 1,
            ..blocks::Params::default()
        },
        kerf: 0.0,
        lead: 20.0,
    }
}

#[test]
fn a_half_sphere_is_rationalized_within_the_tolerance_and_its_blocks_are_cut() {
    let m = common::half_sphere(500.0, 64);
    let p = params(5.0, 600.0, [1.0, 0.0, 0.0]);
    let r = run(&m, &p, &|_| {}).unwrap();
    assert_eq!(r.regions.len(), 1);
    // the flat base is one strip, the rest of the half disc's outline the others
    assert_eq!(r.regions[0].region.side_strips[0], 1);
    assert!(r.deviation.max <= 5.0, "{:?}", r.deviation);
    assert!(r.deviation.samples >= m.vertices().len() + m.faces().len());
    let (v, w) = (r.solid.mesh.volume(), m.volume());
    assert!((v - w).abs() <= 0.02 * w, "volume {v} vs {w}");
    // convex: most blocks are cut by their strips
    let cuttable = r.blocks.iter().filter(|b| b.cuttable).count();
    assert!(
        2 * cuttable > r.blocks.len(),
        "{cuttable} of {}",
        r.blocks.len()
    );
    assert!(r
        .blocks
        .iter()
        .filter(|b| b.cuttable)
        .all(|b| b.added_volume == 0.0));
    // the whole model's blocks share one surface: no gap, no jump; per block they differ
    let solids: Vec<_> = r.blocks.iter().map(|_| Some(&r.solid)).collect();
    let whole = figures(&m, &r.blocks, &solids, r.deviation, p.tolerance);
    assert!(whole.seams > 0);
    assert_eq!((whole.max_gap, whole.max_jump_deg), (0.0, 0.0));
    let pb = per_block::run(&m, &p).unwrap();
    let solids: Vec<_> = pb
        .rational
        .iter()
        .map(|x| x.as_ref().map(|x| &x.solid))
        .collect();
    let per = figures(&m, &pb.blocks, &solids, pb.deviation, p.tolerance);
    assert!(
        per.seams > 0 && per.max_gap > 0.0 && per.max_jump_deg > 0.0,
        "{per:?}"
    );
}

#[test]
fn a_torus_splits_into_regions_where_its_sections_split() {
    let m = common::torus(1000.0, 350.0, 48, 24);
    let mut p = params(20.0, 800.0, [1.0, 0.0, 0.0]);
    p.sections = 48;
    let r = run(&m, &p, &|_| {}).unwrap();
    // one loop at the ends, two between: at least the two ends and the two tubes
    assert!(r.regions.len() >= 4, "{}", r.regions.len());
    assert!(r.deviation.max <= 20.0, "{:?}", r.deviation);
    // the hole's side is concave: some blocks go to their hulls, and say why
    assert!(r
        .blocks
        .iter()
        .any(|b| !b.cuttable && b.reason.is_some() && b.added_volume > 0.0));
}

fn moved(m: &TriMesh, f: impl Fn(Vector3<f64>) -> Vector3<f64>) -> TriMesh {
    TriMesh::try_new(
        m.vertices().iter().map(|p| f(*p)).collect(),
        m.faces().to_vec(),
    )
    .unwrap()
}

#[test]
fn a_rigid_motion_and_a_change_of_scale_move_the_result_with_the_model() {
    let m = common::half_sphere(500.0, 48);
    let p = params(5.0, 600.0, [1.0, 0.0, 0.0]);
    let a = run(&m, &p, &|_| {}).unwrap();
    let rot = Rotation3::from_euler_angles(0.3, -0.2, 0.7);
    let shift = Vector3::new(1234.5, -250.0, 80.0);
    let s = 2.0_f64.powi(-5);
    let m2 = moved(&m, |v| (rot * v + shift) * s);
    let mut p2 = params(5.0 * s, 600.0 * s, (rot * Vector3::x()).into());
    p2.lead = 20.0 * s;
    let b = run(&m2, &p2, &|_| {}).unwrap();
    assert_eq!(a.regions.len(), b.regions.len());
    assert_eq!(a.regions[0].region.strips, b.regions[0].region.strips);
    let close = |x: f64, y: f64| (x * s - y).abs() <= 1e-6 * x * s + 1e-9;
    assert!(
        close(a.deviation.max, b.deviation.max),
        "{} vs {}",
        a.deviation.max,
        b.deviation.max
    );
    assert!(close(a.deviation.rms, b.deviation.rms));
    assert_eq!(a.solid.mesh.faces().len(), b.solid.mesh.faces().len());
}
