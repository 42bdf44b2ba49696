//! Independent coverage checker: after a segmentation, points of the model drawn at
//! random (a different generator and seed from the optimizer's grid), more densely than
//! the optimizer's samples, must each lie in some final block, tested exactly (no margin).
//!
//! `Solid`: random points inside the mesh, by ray parity along the model's x axis (the
//! optimizer casts along its bounding box's z axis), plus random points on every triangle
//! and every vertex. `Surface`: the points on triangles and the vertices.
//!
//! Run on every benchmark mesh (`testdata`: the vendored torus, the third-party meshes
//! when present).

use std::path::{Path, PathBuf};

use blocks::{segment, Coverage, Cuboid, Params, Segmentation};
use geom::mesh::TriMesh;
use nalgebra::Vector3;

/// The benchmark mesh `file`, or `None` (after a loud SKIPPED line) when it is
/// third-party data that is absent.
fn mesh_path(file: &str, test: &str) -> Option<PathBuf> {
    testdata::mesh(file, test)
}

/// A small deterministic generator (SplitMix64), deliberately not the optimizer's.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Points inside the mesh: uniform in its bounding box, kept when a ray along +x crosses
/// the surface an odd number of times (triangles binned by their y–z bounds).
fn inside_points(mesh: &TriMesh, n: usize, rng: &mut Rng) -> Vec<Vector3<f64>> {
    let bb = mesh.aabb();
    let size = bb.size();
    let bins = 64usize;
    let bin = |y: f64, z: f64| -> usize {
        let by = (((y - bb.min.y) / size.y * bins as f64) as usize).min(bins - 1);
        let bz = (((z - bb.min.z) / size.z * bins as f64) as usize).min(bins - 1);
        by * bins + bz
    };
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); bins * bins];
    for (f, _) in mesh.faces().iter().enumerate() {
        let [a, b, c] = mesh.triangle(f);
        let (y0, y1) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        let (z0, z1) = (a.z.min(b.z).min(c.z), a.z.max(b.z).max(c.z));
        let (lo, hi) = (bin(y0, z0), bin(y1, z1));
        for by in lo / bins..=hi / bins {
            for bz in lo % bins..=hi % bins {
                grid[by * bins + bz].push(f);
            }
        }
    }
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let p = bb.min
            + Vector3::new(
                rng.next() * size.x,
                rng.next() * size.y,
                rng.next() * size.z,
            );
        let mut crossings = 0;
        for &f in &grid[bin(p.y, p.z)] {
            let [a, b, c] = mesh.triangle(f);
            // Where the line through p along x meets the triangle's plane, if inside it
            // (barycentric coordinates in the y–z projection).
            let d = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
            if d == 0.0 {
                continue;
            }
            let u = ((p.y - a.y) * (c.z - a.z) - (c.y - a.y) * (p.z - a.z)) / d;
            let v = ((b.y - a.y) * (p.z - a.z) - (p.y - a.y) * (b.z - a.z)) / d;
            if u < 0.0 || v < 0.0 || u + v > 1.0 {
                continue;
            }
            let x = a.x + u * (b.x - a.x) + v * (c.x - a.x);
            if x > p.x {
                crossings += 1;
            }
        }
        if crossings % 2 == 1 {
            out.push(p);
        }
    }
    out
}

/// Uniform random points on the surface (triangles chosen by area).
fn surface_points(mesh: &TriMesh, n: usize, rng: &mut Rng) -> Vec<Vector3<f64>> {
    let mut cum = Vec::with_capacity(mesh.faces().len());
    let mut total = 0.0;
    for f in 0..mesh.faces().len() {
        let [a, b, c] = mesh.triangle(f);
        total += (b - a).cross(&(c - a)).norm();
        cum.push(total);
    }
    (0..n)
        .map(|_| {
            let t = rng.next() * total;
            let f = cum.partition_point(|&c| c < t).min(cum.len() - 1);
            let [a, b, c] = mesh.triangle(f);
            let (mut u, mut v) = (rng.next(), rng.next());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            a + (b - a) * u + (c - a) * v
        })
        .collect()
}

/// Points of `pts` in no block (exact containment, rounding slack 1e-9 of the block).
fn uncovered(blocks: &[Cuboid], pts: &[Vector3<f64>]) -> usize {
    pts.iter()
        .filter(|p| !blocks.iter().any(|b| b.contains(p, -1e-9 * b.half.norm())))
        .count()
}

/// Segments `file` with blocks of `edge`, then checks it with `factor ×` the optimizer's
/// sample counts. Returns the segmentation for further checks.
fn check(path: &Path, edge: f64, coverage: Coverage, factor: usize) -> Segmentation {
    let file = path.file_name().unwrap_or_default().to_string_lossy();
    let mesh = TriMesh::load_obj(path).unwrap();
    let params = Params {
        block_size: [edge; 3],
        coverage,
        sample_spacing: 0.1,
        max_iterations: 8,
        seed: 3,
        ..Params::default()
    };
    let seg = segment(&mesh, &params, &|_| {}).unwrap();
    let blocks: Vec<Cuboid> = seg.blocks.iter().map(|p| p.cuboid()).collect();
    let mut rng = Rng(0xC0FFEE ^ file.len() as u64);
    let c = seg.sampling.counts;
    let on = surface_points(&mesh, factor * (c.surface + c.vertices), &mut rng);
    let mut missed = uncovered(&blocks, &on) + uncovered(&blocks, mesh.vertices());
    let mut checked = on.len() + mesh.vertices().len();
    if coverage == Coverage::Solid {
        let inner = inside_points(&mesh, factor * c.interior, &mut rng);
        missed += uncovered(&blocks, &inner);
        checked += inner.len();
    }
    assert_eq!(
        missed, 0,
        "{file}: {missed} of {checked} checker points lie in no block"
    );
    assert!(seg.final_blocks <= seg.initial_blocks);
    assert!(seg.final_blocks >= seg.lower_bound || coverage == Coverage::Surface);
    eprintln!(
        "{file}: {} → {} blocks, {checked} checker points ({factor}× the optimizer's {} samples), all covered",
        seg.initial_blocks,
        seg.final_blocks,
        c.vertices + c.surface + c.interior
    );
    seg
}

/// Block edge giving a few dozen blocks: a quarter of the bounding box's longest side.
fn edge_for(path: &Path) -> f64 {
    let mesh = TriMesh::load_obj(path).unwrap();
    mesh.aabb().size().max() / 4.0
}

#[test]
fn every_benchmark_mesh_is_covered_solid() {
    let test = "every_benchmark_mesh_is_covered_solid";
    let mut files: Vec<PathBuf> = testdata::VENDORED_MESHES
        .iter()
        .filter_map(|n| mesh_path(n, test))
        .collect();
    files.extend(testdata::third_party_meshes(test).unwrap_or_default());
    for f in &files {
        check(f, edge_for(f), Coverage::Solid, 2);
    }
}

#[test]
fn surface_coverage_is_checked_on_the_surface() {
    for name in ["torus.obj", "octopus.obj", "fertility.obj"] {
        let Some(f) = mesh_path(name, "surface_coverage_is_checked_on_the_surface") else {
            continue;
        };
        let f = f.as_path();
        let solid = check(f, edge_for(f), Coverage::Solid, 2);
        let surface = check(f, edge_for(f), Coverage::Surface, 3);
        assert!(
            surface.initial_blocks <= solid.initial_blocks,
            "{name}: surface {} vs solid {}",
            surface.initial_blocks,
            solid.initial_blocks
        );
    }
}

/// The segmentation runs in a unit frame: the model in other units and moved far from the
/// origin (×1000, then translated) gives the same blocks, mapped by the same similarity,
/// every length of the result back in model units.
#[test]
fn results_come_back_in_model_units_in_any_unit_and_place() {
    let torus = mesh_path("torus.obj", "results_come_back_in_model_units").unwrap();
    let mesh = TriMesh::load_obj(&torus).unwrap();
    let edge = edge_for(&torus);
    let (s, o) = (1000.0, Vector3::new(5000.0, -7000.0, 300.0));
    let moved = TriMesh::try_new(
        mesh.vertices().iter().map(|v| v * s + o).collect(),
        mesh.faces().to_vec(),
    )
    .unwrap();
    let params = |edge: f64| Params {
        block_size: [edge; 3],
        sample_spacing: 0.1,
        max_iterations: 6,
        seed: 5,
        ..Params::default()
    };
    let a = segment(&mesh, &params(edge), &|_| {}).unwrap();
    let b = segment(&moved, &params(edge * s), &|_| {}).unwrap();
    assert_eq!(a.final_blocks, b.final_blocks);
    assert_eq!(a.history, b.history);
    assert_eq!(a.energy, b.energy);
    let close = |x: f64, y: f64, what: &str| {
        assert!(
            (x - y).abs() <= 1e-9 * (y.abs() + s * edge),
            "{what}: {x} vs {y}"
        );
    };
    let placed = |p: &blocks::Placement, q: &blocks::Placement| {
        (0..3).for_each(|k| close(q.center[k], p.center[k] * s + o[k], "centre"));
        (0..3).for_each(|k| close(q.size[k], p.size[k] * s, "size"));
        (0..4).for_each(|k| assert!((q.rotation[k] - p.rotation[k]).abs() < 1e-9));
    };
    for (p, q) in a.blocks.iter().zip(&b.blocks) {
        placed(p, q);
    }
    placed(&a.bounding_box, &b.bounding_box);
    let cube = s * s * s;
    assert!((b.model_volume - a.model_volume * cube).abs() <= 1e-9 * b.model_volume);
    assert!((b.block_volume - a.block_volume * cube).abs() <= 1e-9 * b.block_volume);
    close(b.sampling.spacing, a.sampling.spacing * s, "spacing");
    close(b.sampling.margin, a.sampling.margin * s, "margin");
    assert!((a.model_volume - mesh.volume().abs()).abs() <= 1e-6 * a.model_volume);
}
