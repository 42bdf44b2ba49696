//! Results do not depend on where the model sits: the mesh facade (jobs/models/facade.obj,
//! millimetres) moved rigidly by 10⁶ of its units along every axis, written as OBJ text
//! and read back, gives the same sections (lengths, inflections, curvature maxima) and the
//! same Trace segmentation (pieces, their parts' arc-length ranges), with the blocks moved
//! by the translation.
//!
//! Tolerance, derived: a coordinate near 10⁶ carries a rounding error of
//! 10⁶ · 2⁻⁵² ≈ 2.2·10⁻¹⁰ mm (in the OBJ text and in every product with the plane frame).
//! Section points are ~7 mm apart and a section is ~1.2 m long; lengths summed over ~200
//! chords and the smoothing fit's residuals stay within 10⁻⁷ mm, so arc lengths and part
//! ends agree within 10⁻⁶ mm, curvature maxima (second derivatives over ~7 mm, error
//! ≲ 10⁻⁹/7² per mm) within 10⁻⁹ /mm. Reading the OBJ in f32, as hotcut once did, moves
//! each vertex by up to 0.06 mm and fails every one of these.

use facade_seg::trace::{trace, TraceParams};
use facade_seg::{Constraints, Facade};
use geom::fit::SmoothingParams;
use geom::mesh::TriMesh;
use geom::surface::{SectionParams, Surface};
use nalgebra::Vector3;

const SHIFT: f64 = 1e6;

fn facade(obj: &std::path::Path) -> Facade {
    let mesh = TriMesh::load_obj(obj).unwrap();
    let (frame, sections) = Surface::Mesh(mesh)
        .sections(
            &SectionParams {
                direction: Vector3::new(1.0, 0.0, 0.0),
                count: 12,
                smoothing: SmoothingParams {
                    tolerance: 0.05,
                    ..SmoothingParams::default()
                },
                ..SectionParams::default()
            },
            &|| {},
        )
        .unwrap();
    Facade::new(frame, &sections).unwrap()
}

#[test]
fn a_mesh_moved_by_a_million_units_gives_the_same_segmentation() {
    let original =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/models/facade.obj");
    let text = std::fs::read_to_string(&original).unwrap();
    let mut moved = String::new();
    for line in text.lines() {
        match line.strip_prefix("v ") {
            Some(rest) => {
                let v: Vec<f64> = rest
                    .split_whitespace()
                    .map(|t| t.parse().unwrap())
                    .collect();
                moved += &format!("v {} {} {}\n", v[0] + SHIFT, v[1] + SHIFT, v[2] + SHIFT);
            }
            None => {
                moved += line;
                moved.push('\n');
            }
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("moved.obj");
    std::fs::write(&path, moved).unwrap();
    let (a, b) = (facade(&original), facade(&path));
    assert_eq!(a.sections.len(), b.sections.len());
    let (mut length, mut curvature, mut ends) = (0.0f64, 0.0f64, 0.0f64);
    for (p, q) in a.sections.iter().zip(&b.sections) {
        assert_eq!(
            p.inflections.len(),
            q.inflections.len(),
            "plane {}",
            p.index
        );
        length = length.max((p.length - q.length).abs());
        for (s, t) in p.inflections.iter().zip(&q.inflections) {
            ends = ends.max((s - t).abs());
        }
        let n = 200;
        curvature = curvature.max(
            (p.max_abs_curvature(0.0, p.length, n) - q.max_abs_curvature(0.0, q.length, n)).abs(),
        );
    }
    let c = Constraints {
        block: [600.0, 500.0, 400.0],
        blade_length: 700.0,
        max_curvature: 0.011,
        max_inflections: 1,
        tolerance_rms: 0.5,
        tolerance_max: 2.0,
    };
    let (sa, sb) = (
        trace(&a, &c, &TraceParams::default(), &|| {}).unwrap(),
        trace(&b, &c, &TraceParams::default(), &|| {}).unwrap(),
    );
    assert_eq!(sa.pieces.len(), sb.pieces.len());
    let mut origin = 0.0f64;
    for (p, q) in sa.pieces.iter().zip(&sb.pieces) {
        assert_eq!(p.parts.len(), q.parts.len(), "piece {}", p.id);
        for (x, y) in p.parts.iter().zip(&q.parts) {
            ends = ends
                .max((x.s[0] - y.s[0]).abs())
                .max((x.s[1] - y.s[1]).abs());
        }
        for k in 0..3 {
            origin = origin.max((p.block.origin[k] + SHIFT - q.block.origin[k]).abs());
        }
    }
    println!(
        "moved by {SHIFT}: {} pieces; section lengths differ ≤ {length:.2e} mm, part ends and inflections ≤ {ends:.2e} mm, max |κ| ≤ {curvature:.2e} /mm, block origins ≤ {origin:.2e} mm",
        sa.pieces.len()
    );
    assert!(length <= 1e-6, "{length}");
    assert!(ends <= 1e-6, "{ends}");
    assert!(curvature <= 1e-9, "{curvature}");
    assert!(origin <= 1e-6, "{origin}");
}
