//! Closed test models.
#![allow(dead_code)]

use geom::TriMesh;
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The upper half of a sphere of radius `r` closed by its disk, `n` segments around.
pub fn half_sphere(r: f64, n: usize) -> TriMesh {
    let rings = n / 4;
    let mut v = vec![Vector3::new(0.0, 0.0, r)];
    for i in 1..=rings {
        let phi = PI / 2.0 * i as f64 / rings as f64;
        for k in 0..n {
            let th = 2.0 * PI * k as f64 / n as f64;
            v.push(Vector3::new(
                r * phi.sin() * th.cos(),
                r * phi.sin() * th.sin(),
                r * phi.cos(),
            ));
        }
    }
    let centre = v.len() as u32;
    v.push(Vector3::zeros());
    let id = |i: usize, k: usize| (1 + (i - 1) * n + k % n) as u32;
    let mut f = Vec::new();
    for k in 0..n {
        f.push([0, id(1, k), id(1, k + 1)]);
    }
    for i in 1..rings {
        for k in 0..n {
            f.push([id(i, k), id(i + 1, k), id(i + 1, k + 1)]);
            f.push([id(i, k), id(i + 1, k + 1), id(i, k + 1)]);
        }
    }
    for k in 0..n {
        f.push([centre, id(rings, k + 1), id(rings, k)]);
    }
    TriMesh::try_new(v, f).unwrap()
}

/// A torus (major radius `a`, tube `b`), `n × m` segments.
pub fn torus(a: f64, b: f64, n: usize, m: usize) -> TriMesh {
    let mut v = Vec::new();
    for i in 0..n {
        let th = 2.0 * PI * i as f64 / n as f64;
        for j in 0..m {
            let ph = 2.0 * PI * j as f64 / m as f64;
            let r = a + b * ph.cos();
            v.push(Vector3::new(r * th.cos(), r * th.sin(), b * ph.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let mut f = Vec::new();
    for i in 0..n {
        for j in 0..m {
            f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::try_new(v, f).unwrap()
}
