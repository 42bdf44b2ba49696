//! The rationalized model as a closed solid: each region's ruled strips tessellated along
//! the axis, closed at its ends by a cone to the model's tip beyond its last section or,
//! where the region meets another (its loops split or merge), by a flat cap halfway to the
//! next section; and each strip's rulings in the order a wire follows them.

use geom::bbox::Aabb;
use geom::index::TriangleIndex;
use geom::TriMesh;
use nalgebra::Vector3;

use crate::error::{Error, Result};
use crate::regions::Region;

/// Rows of the tessellation per gap between sections: one, the sections themselves — between
/// two rows the surface is the bilinear patch of their rulings, which is what a wire moved
/// linearly from one ruling to the next cuts.
pub const ROWS_PER_GAP: usize = 1;
/// Wire positions across a cap, from its rim to its tip.
pub const CAP_STEPS: usize = 4;

/// How a region ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum End {
    /// A cone to the model's tip beyond the end section.
    Tip(Vector3<f64>),
    /// The end loop moved along the axis to this offset, and a flat cap there.
    Flat(f64),
}

/// One wire position: the ruling from `a` to `b` (a point of the cut surface and its
/// direction) and the cut surface's outward unit normal there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ruling {
    /// Start of the ruling (on rail `j`).
    pub a: Vector3<f64>,
    /// End (on rail `j + 1`).
    pub b: Vector3<f64>,
    /// Unit direction (kept where the ruling shrinks to a point at a tip).
    pub dir: Vector3<f64>,
    /// Outward unit normal.
    pub normal: Vector3<f64>,
}

/// One strip of a region: its rulings from the start tip or cap over the rails to the end.
#[derive(Debug, Clone, PartialEq)]
pub struct Strip {
    /// The region.
    pub region: usize,
    /// The strip around the region (between rails `index` and `index + 1`).
    pub index: usize,
    /// Wire positions in order along the axis.
    pub rulings: Vec<Ruling>,
}

/// The rationalized solid.
#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    /// The closed mesh: every region's strips and ends.
    pub mesh: TriMesh,
    /// The region of each face.
    pub face_region: Vec<usize>,
    /// The ruling direction on each face (unit): the rows' direction on a strip, the rim's
    /// on a cap.
    pub face_ruling: Vec<Vector3<f64>>,
    /// Every strip of every region.
    pub strips: Vec<Strip>,
    /// The axis.
    pub axis: Vector3<f64>,
}

/// Tessellates the regions (`ends[r]`: how region `r` starts and ends).
///
/// # Errors
/// [`Error::Model`] for a degenerate result.
pub fn build(regions: &[Region], ends: &[(End, End)], axis: Vector3<f64>) -> Result<Solid> {
    let mut v: Vec<Vector3<f64>> = Vec::new();
    let mut f: Vec<[u32; 3]> = Vec::new();
    let mut face_region = Vec::new();
    let mut face_ruling = Vec::new();
    let mut strips = Vec::new();
    let unit = |w: Vector3<f64>| {
        let l = w.norm();
        if l > 0.0 {
            w / l
        } else {
            axis
        }
    };
    for (r, (reg, &(start, end))) in regions.iter().zip(ends).enumerate() {
        let n = reg.strips;
        let mut rows: Vec<Vec<Vector3<f64>>> = Vec::new();
        let o = &reg.offsets;
        for i in 0..o.len() {
            let subs = if i + 1 < o.len() { ROWS_PER_GAP } else { 1 };
            for s in 0..subs {
                let u = if s == 0 {
                    o[i]
                } else {
                    o[i] + (o[i + 1] - o[i]) * s as f64 / ROWS_PER_GAP as f64
                };
                rows.push((0..n).map(|j| reg.rail(u, j)).collect());
            }
        }
        if let End::Flat(t) = start {
            let shift = axis * (t - o[0]);
            rows.insert(0, rows[0].iter().map(|p| p + shift).collect());
        }
        if let End::Flat(t) = end {
            let last = &rows[rows.len() - 1];
            let shift = axis * (t - o[o.len() - 1]);
            let moved = last.iter().map(|p| p + shift).collect();
            rows.push(moved);
        }
        let tip = |e: End, row: &[Vector3<f64>]| match e {
            End::Tip(p) => p,
            End::Flat(_) => row.iter().sum::<Vector3<f64>>() / row.len() as f64,
        };
        let (t0, t1) = (tip(start, &rows[0]), tip(end, &rows[rows.len() - 1]));
        let base = v.len() as u32;
        let idx = |row: usize, j: usize| base + (row * n + j % n) as u32;
        for row in &rows {
            v.extend(row.iter().copied());
        }
        let (i0, i1) = (v.len() as u32, v.len() as u32 + 1);
        v.push(t0);
        v.push(t1);
        let last = rows.len() - 1;
        for row in 0..last {
            for j in 0..n {
                f.push([idx(row, j), idx(row, j + 1), idx(row + 1, j + 1)]);
                f.push([idx(row, j), idx(row + 1, j + 1), idx(row + 1, j)]);
                face_region.extend([r, r]);
                let d = (rows[row][(j + 1) % n] - rows[row][j])
                    + (rows[row + 1][(j + 1) % n] - rows[row + 1][j]);
                face_ruling.extend([unit(d), unit(d)]);
            }
        }
        for j in 0..n {
            f.push([i0, idx(0, j + 1), idx(0, j)]);
            f.push([i1, idx(last, j), idx(last, j + 1)]);
            face_region.extend([r, r]);
            face_ruling.push(unit(rows[0][(j + 1) % n] - rows[0][j]));
            face_ruling.push(unit(rows[last][(j + 1) % n] - rows[last][j]));
        }
        for j in 0..n {
            strips.push(strip_rulings(r, j, &rows, (t0, t1), axis));
        }
    }
    let mesh = TriMesh::try_new(v, f).map_err(|e| Error::Model(e.to_string()))?;
    Ok(Solid {
        mesh,
        face_region,
        face_ruling,
        strips,
        axis,
    })
}

/// The rulings of strip `j`: across the start cap from its tip, along the rows, across the
/// end cap to its tip.
fn strip_rulings(
    region: usize,
    j: usize,
    rows: &[Vec<Vector3<f64>>],
    (t0, t1): (Vector3<f64>, Vector3<f64>),
    axis: Vector3<f64>,
) -> Strip {
    let n = rows[0].len();
    let (a, b) = (
        |row: usize| rows[row][j],
        |row: usize| rows[row][(j + 1) % n],
    );
    let last = rows.len() - 1;
    let unit = |w: Vector3<f64>, fallback: Vector3<f64>| {
        let l = w.norm();
        if l > 0.0 && l.is_finite() {
            w / l
        } else {
            fallback
        }
    };
    let mut out = Vec::new();
    // a cap: the triangle (tip, a, b), its rulings parallel to a→b
    let cap = |row: usize, tip: Vector3<f64>, outward: Vector3<f64>, rev: bool| {
        let (pa, pb) = (a(row), b(row));
        let dir = unit(pb - pa, axis.cross(&outward));
        let mut nrm = unit((pa - tip).cross(&(pb - tip)), outward);
        if nrm.dot(&outward) < 0.0 {
            nrm = -nrm;
        }
        let mut cs: Vec<Ruling> = (0..=CAP_STEPS)
            .map(|k| {
                let s = k as f64 / CAP_STEPS as f64;
                Ruling {
                    a: pa + (tip - pa) * s,
                    b: pb + (tip - pb) * s,
                    dir,
                    normal: nrm,
                }
            })
            .collect();
        if !rev {
            cs.reverse();
        }
        cs
    };
    let mut start = cap(0, t0, -axis, false);
    start.pop(); // the rim is the first row's ruling
    out.extend(start);
    for row in 0..=last {
        let (pa, pb) = (a(row), b(row));
        let along = (rows[(row + 1).min(last)][j] - rows[row.saturating_sub(1)][j])
            + (rows[(row + 1).min(last)][(j + 1) % n] - rows[row.saturating_sub(1)][(j + 1) % n]);
        let along = unit(along, axis);
        let dir = unit(pb - pa, axis.cross(&Vector3::z()));
        out.push(Ruling {
            a: pa,
            b: pb,
            dir,
            normal: unit(dir.cross(&along), Vector3::z()),
        });
    }
    let mut end = cap(last, t1, axis, true);
    end.remove(0);
    out.extend(end);
    Strip {
        region,
        index: j,
        rulings: out,
    }
}

/// Inside and depth queries on a closed solid whose faces belong to regions (closed shells
/// that may touch): a point is inside when a ray from it crosses some region's shell an odd
/// number of times (majority of three rays along the axes).
pub struct Probe<'m> {
    mesh: &'m TriMesh,
    index: TriangleIndex<'m>,
    region: &'m [usize],
    regions: usize,
    bounds: Aabb,
}

impl<'m> Probe<'m> {
    /// The probe of `solid`.
    pub fn new(solid: &'m Solid) -> Self {
        let regions = solid.face_region.iter().copied().max().map_or(0, |m| m + 1);
        Self {
            mesh: &solid.mesh,
            index: TriangleIndex::new(&solid.mesh),
            region: &solid.face_region,
            regions,
            bounds: solid.mesh.aabb(),
        }
    }

    /// Whether `p` lies inside.
    pub fn inside(&self, p: &Vector3<f64>) -> bool {
        if !self.bounds.contains(p) {
            return false;
        }
        let votes = (0..3).filter(|&k| self.ray_inside(p, k)).count();
        votes >= 2
    }

    /// The distance from `p` to the surface.
    pub fn distance(&self, p: &Vector3<f64>) -> f64 {
        self.index
            .closest_point(p)
            .map_or(f64::INFINITY, |c| c.distance)
    }

    /// The closest face to `p` and its distance.
    pub fn closest(&self, p: &Vector3<f64>) -> Option<(usize, f64)> {
        self.index.closest_point(p).map(|c| (c.face, c.distance))
    }

    /// The closest face to `p` and the closest point on it.
    pub fn closest_point(&self, p: &Vector3<f64>) -> Option<(usize, Vector3<f64>)> {
        self.index.closest_point(p).map(|c| (c.face, c.point))
    }

    /// How deep `p` lies inside (positive) or how far outside (negative).
    pub fn depth(&self, p: &Vector3<f64>) -> f64 {
        let d = self.distance(p);
        if self.inside(p) {
            d
        } else {
            -d
        }
    }

    fn ray_inside(&self, p: &Vector3<f64>, k: usize) -> bool {
        let mut hi = *p;
        hi[k] = self.bounds.max[k] + 1.0 + self.bounds.size()[k];
        let column = Aabb { min: *p, max: hi };
        let mut parity = vec![false; self.regions];
        for f in self.index.triangles_in(&column) {
            let [a, b, c] = self.mesh.triangle(f);
            if crosses(p, k, &a, &b, &c) {
                parity[self.region[f]] ^= true;
            }
        }
        parity.iter().any(|&x| x)
    }
}

/// Whether the ray from `p` along axis `k` crosses triangle `abc` (half-open edge rules so
/// that a ray through a shared edge counts once).
fn crosses(
    p: &Vector3<f64>,
    k: usize,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> bool {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    // 2D point-in-triangle in the plane of the other two axes, by edge functions with a
    // tie rule
    let e = |p0: &Vector3<f64>, p1: &Vector3<f64>| {
        let w = (p1[i] - p0[i]) * (p[j] - p0[j]) - (p1[j] - p0[j]) * (p[i] - p0[i]);
        if w != 0.0 {
            w
        } else if p1[j] != p0[j] {
            // on the edge: count it for edges going one way only
            if p1[j] > p0[j] {
                1e-300
            } else {
                -1e-300
            }
        } else if p1[i] < p0[i] {
            1e-300
        } else {
            -1e-300
        }
    };
    let (w0, w1, w2) = (e(b, c), e(c, a), e(a, b));
    let same = (w0 > 0.0 && w1 > 0.0 && w2 > 0.0) || (w0 < 0.0 && w1 < 0.0 && w2 < 0.0);
    if !same {
        return false;
    }
    let s = w0 + w1 + w2;
    let h = (w0 * a[k] + w1 * b[k] + w2 * c[k]) / s;
    h > p[k]
}
