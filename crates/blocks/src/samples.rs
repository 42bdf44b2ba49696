//! The model as points: vertices, surface samples and interior grid samples, stored in
//! cell order with a uniform-grid index for box queries.
//!
//! Spacing (with `g` the interior grid spacing, a fraction of the block's shortest edge):
//! - every mesh vertex;
//! - surface samples at most `g / 2` apart: every edge divided evenly, every triangle's
//!   interior on a barycentric lattice;
//! - `Solid` coverage: the centres of a `g`-grid in the model's bounding-box frame that
//!   lie inside the mesh (ray parity along the frame's z axis, one ray per grid column).
//!
//! A block covers a sample when the sample lies in the block shrunk by the margin (`g`
//! for `Solid`, `g / 2` for `Surface`), no less than the distance from any model point
//! to its nearest sample; so a union of blocks that covers every sample this way covers
//! the model itself, not only the samples.

use geom::mesh::TriMesh;
use nalgebra::{Matrix3, Vector3};

use crate::cuboid::Cuboid;
use crate::error::{BlockError, Result};
use crate::obb::BoxFit;

/// What the blocks must cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum Coverage {
    /// The model's volume lies in the union of blocks.
    #[default]
    Solid,
    /// Only the model's surface lies in the union of blocks.
    Surface,
}

/// The sample set and its index.
#[derive(Debug, Clone)]
pub struct Samples {
    /// Sample positions, sorted by index cell.
    pub points: Vec<Vector3<f64>>,
    /// How many samples are mesh vertices, surface samples and interior samples.
    pub counts: SampleCounts,
    /// Interior grid spacing `g`.
    pub spacing: f64,
    /// Margin by which blocks are shrunk when testing coverage.
    pub margin: f64,
    index: Index,
}

/// Sample counts by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SampleCounts {
    /// Mesh vertices.
    pub vertices: usize,
    /// Samples on edges and triangles.
    pub surface: usize,
    /// Interior grid samples (0 for `Surface` coverage).
    pub interior: usize,
}

/// About how many samples [`sample`] takes at spacing `g`: surface samples at `g/2` (two
/// per cell of area) and, for `Solid`, one per `g³` of volume.
pub fn estimate(mesh: &TriMesh, g: f64, coverage: Coverage) -> f64 {
    let s = g / 2.0;
    2.0 * mesh.area() / (s * s)
        + if coverage == Coverage::Solid {
            mesh.volume().abs() / (g * g * g)
        } else {
            0.0
        }
}

/// Samples a closed mesh. `frame` is the model's bounding box (interior grid axes),
/// `spacing` the interior grid spacing `g`; `cap` bounds the sample count.
///
/// # Errors
/// [`BlockError::TooManySamples`] past the cap (checked first against [`estimate`]),
/// [`BlockError::Model`] for a mesh whose
/// interior grid finds no sample inside (not closed, or thinner than the spacing
/// everywhere).
pub fn sample(
    mesh: &TriMesh,
    frame: &BoxFit,
    spacing: f64,
    coverage: Coverage,
    cap: usize,
    index_cell: f64,
) -> Result<Samples> {
    let g = spacing;
    let s = g / 2.0;
    let estimate = estimate(mesh, g, coverage);
    if estimate > cap as f64 {
        return Err(BlockError::TooManySamples {
            samples: estimate as usize,
            cap,
        });
    }
    let mut points: Vec<Vector3<f64>> = mesh.vertices().to_vec();
    let vertices = points.len();
    surface_samples(mesh, s, &mut points);
    let surface = points.len() - vertices;
    let interior = if coverage == Coverage::Solid {
        let before = points.len();
        interior_samples(mesh, frame, g, &mut points);
        let n = points.len() - before;
        if n == 0 {
            return Err(BlockError::Model(format!(
                "no interior grid point (spacing {g:.4}) lies inside the mesh"
            )));
        }
        n
    } else {
        0
    };
    if points.len() > cap {
        return Err(BlockError::TooManySamples {
            samples: points.len(),
            cap,
        });
    }
    let (index, points) = Index::build(points, index_cell);
    Ok(Samples {
        points,
        counts: SampleCounts {
            vertices,
            surface,
            interior,
        },
        spacing: g,
        margin: if coverage == Coverage::Solid { g } else { s },
        index,
    })
}

impl Samples {
    /// Calls `f` with every sample block `b` covers (inside it shrunk by the margin).
    pub fn for_each_covered(&self, b: &Cuboid, mut f: impl FnMut(usize)) {
        let (lo, hi) = b.aabb();
        self.for_each_near(&lo, &hi, |id| {
            if b.contains(&self.points[id], self.margin) {
                f(id);
            }
        });
    }

    /// Whether some sample block `b` covers satisfies `pred` (stops at the first).
    pub fn any_covered(&self, b: &Cuboid, mut pred: impl FnMut(usize) -> bool) -> bool {
        let (lo, hi) = b.aabb();
        self.try_each_near(&lo, &hi, |id| {
            b.contains(&self.points[id], self.margin) && pred(id)
        })
    }

    /// Calls `f` with every sample index whose index cell meets the box `lo..hi`.
    pub fn for_each_near(&self, lo: &Vector3<f64>, hi: &Vector3<f64>, mut f: impl FnMut(usize)) {
        self.try_each_near(lo, hi, |id| {
            f(id);
            false
        });
    }

    /// Like [`Samples::for_each_near`], stopping when `f` returns true; whether it did.
    fn try_each_near(
        &self,
        lo: &Vector3<f64>,
        hi: &Vector3<f64>,
        mut f: impl FnMut(usize) -> bool,
    ) -> bool {
        let ix = &self.index;
        let cell = |p: &Vector3<f64>, k: usize| -> usize {
            (((p[k] - ix.origin[k]) / ix.cell).floor().max(0.0) as usize).min(ix.dims[k] - 1)
        };
        let (a, b) = (
            [0, 1, 2].map(|k| cell(lo, k)),
            [0, 1, 2].map(|k| cell(hi, k)),
        );
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                let row = (z * ix.dims[1] + y) * ix.dims[0];
                let (s, e) = (ix.start[row + a[0]], ix.start[row + b[0] + 1]);
                if (s as usize..e as usize).any(&mut f) {
                    return true;
                }
            }
        }
        false
    }
}

/// A uniform grid over the samples; samples are stored cell by cell.
#[derive(Debug, Clone)]
struct Index {
    origin: Vector3<f64>,
    cell: f64,
    dims: [usize; 3],
    /// Start of each cell's samples (x fastest), plus the end.
    start: Vec<u32>,
}

impl Index {
    fn build(points: Vec<Vector3<f64>>, cell: f64) -> (Self, Vec<Vector3<f64>>) {
        let (lo, hi) = points.iter().fold(
            (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let dims = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / cell).floor() as usize + 1).min(4096));
        let key = |p: &Vector3<f64>| -> usize {
            let c = [0, 1, 2].map(|k| (((p[k] - lo[k]) / cell).floor() as usize).min(dims[k] - 1));
            (c[2] * dims[1] + c[1]) * dims[0] + c[0]
        };
        let ncell = dims[0] * dims[1] * dims[2];
        let mut keyed: Vec<(usize, Vector3<f64>)> =
            points.into_iter().map(|p| (key(&p), p)).collect();
        // Stable: samples in a cell keep their generation order (deterministic).
        keyed.sort_by_key(|(k, _)| *k);
        let mut start = vec![0u32; ncell + 1];
        for (k, _) in &keyed {
            start[k + 1] += 1;
        }
        for i in 0..ncell {
            start[i + 1] += start[i];
        }
        let index = Self {
            origin: lo,
            cell,
            dims,
            start,
        };
        (index, keyed.into_iter().map(|(_, p)| p).collect())
    }
}

/// Edge and triangle-interior samples, at most `s` apart.
fn surface_samples(mesh: &TriMesh, s: f64, out: &mut Vec<Vector3<f64>>) {
    let v = mesh.vertices();
    let mut edges: Vec<(u32, u32)> = mesh
        .faces()
        .iter()
        .flat_map(|f| [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    for (a, b) in edges {
        let (p, q) = (v[a as usize], v[b as usize]);
        let n = crate::moves::cells((q - p).norm(), s);
        for m in 1..n {
            out.push(p + (q - p) * (m as f64 / n as f64));
        }
    }
    for f in mesh.faces() {
        let [a, b, c] = f.map(|i| v[i as usize]);
        let longest = (b - a).norm().max((c - b).norm()).max((a - c).norm());
        let n = crate::moves::cells(longest, s);
        for i in 1..n {
            for j in 1..n - i {
                out.push(a + (b - a) * (i as f64 / n as f64) + (c - a) * (j as f64 / n as f64));
            }
        }
    }
}

/// Grid-cell centres inside the mesh, by ray parity along the frame's z axis per column.
fn interior_samples(mesh: &TriMesh, frame: &BoxFit, g: f64, out: &mut Vec<Vector3<f64>>) {
    let axes: Matrix3<f64> = frame.axes();
    let lo = -frame.size / 2.0;
    let dims = [0, 1, 2].map(|k| ((frame.size[k] / g).ceil() as usize).max(1));
    // Columns are offset by a small irrational fraction of the spacing so that no ray
    // runs exactly through a mesh edge of a model drawn on a round grid.
    let jitter = [g * 1.234_567e-4, g * 7.654_321e-5];
    let col_x = |i: usize| lo.x + (i as f64 + 0.5) * g + jitter[0];
    let col_y = |j: usize| lo.y + (j as f64 + 0.5) * g + jitter[1];
    let local: Vec<Vector3<f64>> = mesh
        .vertices()
        .iter()
        .map(|p| axes.tr_mul(&(p - frame.center)))
        .collect();
    let mut crossings: Vec<Vec<f64>> = vec![Vec::new(); dims[0] * dims[1]];
    for f in mesh.faces() {
        let [a, b, c] = f.map(|i| local[i as usize]);
        let (xmin, xmax) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
        let (ymin, ymax) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        let i0 = (((xmin - lo.x - jitter[0]) / g - 0.5).ceil().max(0.0)) as usize;
        let j0 = (((ymin - lo.y - jitter[1]) / g - 0.5).ceil().max(0.0)) as usize;
        for i in i0..dims[0] {
            let x = col_x(i);
            if x > xmax {
                break;
            }
            for j in j0..dims[1] {
                let y = col_y(j);
                if y > ymax {
                    break;
                }
                if let Some(z) = ray_hit(&a, &b, &c, x, y) {
                    crossings[j * dims[0] + i].push(z);
                }
            }
        }
    }
    for j in 0..dims[1] {
        for i in 0..dims[0] {
            let zs = &mut crossings[j * dims[0] + i];
            if zs.is_empty() {
                continue;
            }
            zs.sort_by(f64::total_cmp);
            // An odd count means the ray grazed an edge or vertex: the column is skipped
            // (surface samples still cover that part of the model).
            if zs.len() % 2 == 1 {
                continue;
            }
            for pair in zs.chunks(2) {
                let k0 = (((pair[0] - lo.z) / g - 0.5).ceil().max(0.0)) as usize;
                let mut k = k0;
                while k < dims[2] {
                    let z = lo.z + (k as f64 + 0.5) * g;
                    if z > pair[1] {
                        break;
                    }
                    out.push(frame.center + axes * Vector3::new(col_x(i), col_y(j), z));
                    k += 1;
                }
            }
        }
    }
}

/// Where the vertical line through `(x, y)` meets triangle `abc`, if it does.
fn ray_hit(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>, x: f64, y: f64) -> Option<f64> {
    let orient =
        |p: &Vector3<f64>, q: &Vector3<f64>| (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
    let (w0, w1, w2) = (orient(b, c), orient(c, a), orient(a, b));
    let sum = w0 + w1 + w2;
    let inside = (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0);
    if !inside || sum == 0.0 {
        return None;
    }
    Some((w0 * a.z + w1 * b.z + w2 * c.z) / sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    /// A closed axis-aligned cube mesh of edge `e` with its min corner at the origin.
    pub(crate) fn cube_mesh(e: f64) -> TriMesh {
        let v: Vec<Vector3<f64>> = (0..8)
            .map(|i| Vector3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64) * e)
            .collect();
        let f = vec![
            [0, 2, 3],
            [0, 3, 1],
            [4, 5, 7],
            [4, 7, 6],
            [0, 1, 5],
            [0, 5, 4],
            [2, 6, 7],
            [2, 7, 3],
            [0, 4, 6],
            [0, 6, 2],
            [1, 3, 7],
            [1, 7, 5],
        ];
        TriMesh::try_new(v, f).unwrap()
    }

    #[test]
    fn cube_interior_grid_is_complete_and_inside() {
        let mesh = cube_mesh(1.0);
        let frame = BoxFit {
            center: Vector3::repeat(0.5),
            rotation: UnitQuaternion::identity(),
            size: Vector3::repeat(1.0),
        };
        let s = sample(&mesh, &frame, 0.1, Coverage::Solid, 1_000_000, 0.25).unwrap();
        assert_eq!(s.counts.interior, 1000);
        assert_eq!(s.counts.vertices, 8);
        assert!(s
            .points
            .iter()
            .all(|p| p.iter().all(|&c| (-1e-12..=1.0 + 1e-12).contains(&c))));
        // Surface samples at most 0.05 apart: each face has its diagonal and edges cut into 20–29 parts.
        assert!(s.counts.surface > 6 * 19 * 19 / 2, "{}", s.counts.surface);
        let mut n = 0;
        s.for_each_near(&Vector3::repeat(-1.0), &Vector3::repeat(2.0), |_| n += 1);
        assert_eq!(n, s.points.len());
        let surf = sample(&mesh, &frame, 0.1, Coverage::Surface, 1_000_000, 0.25).unwrap();
        assert_eq!(surf.counts.interior, 0);
        assert_eq!(surf.margin, 0.05);
        assert!(matches!(
            sample(&mesh, &frame, 0.001, Coverage::Solid, 1_000_000, 0.25),
            Err(BlockError::TooManySamples { .. })
        ));
    }
}
