//! What a block keeps, rebuilt from the job's own surface and the report's block
//! placements (issue 37), for the replay's heated moves: the material below the design
//! surface inside the block — for a facade's piece, only across the piece's own part of
//! each section (the rest of its block's width belongs to no design of this piece). A
//! point of the blade there, deeper than the tolerance, is a gouge. Nothing here uses the
//! planner's clearance code: the surface is the job's height field (evaluated) or mesh
//! (cast vertically, on a bucket grid written here).

use std::collections::HashMap;

use geom::surface::Surface;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Heights of the design surface, mm.
#[derive(Clone)]
enum Height {
    /// `z = f(x, y)` over `[x0, x1] × [y0, y1]` (job units, `per_mm`).
    Field {
        f: geom::expr::Expr,
        x: (f64, f64),
        y: (f64, f64),
        per_mm: f64,
    },
    /// Triangles (mm) in square buckets of `cell` mm from `origin`.
    Mesh {
        triangles: Vec<[Vector3<f64>; 3]>,
        buckets: HashMap<(i64, i64), Vec<usize>>,
        cell: f64,
    },
}

impl Height {
    /// The surface's height above `(x, y)` (mm), the highest where a mesh has several;
    /// `None` off the surface.
    fn at(&self, x: f64, y: f64) -> Option<f64> {
        match self {
            Height::Field {
                f,
                x: xr,
                y: yr,
                per_mm,
            } => {
                let (xs, ys) = (x * per_mm, y * per_mm);
                let inside = xs >= xr.0 && xs <= xr.1 && ys >= yr.0 && ys <= yr.1;
                inside.then(|| f.eval(xs, ys) / per_mm)
            }
            Height::Mesh {
                triangles,
                buckets,
                cell,
            } => {
                let key = ((x / cell).floor() as i64, (y / cell).floor() as i64);
                buckets
                    .get(&key)?
                    .iter()
                    .filter_map(|&i| vertical_hit(&triangles[i], x, y))
                    .fold(None, |a: Option<f64>, z| Some(a.map_or(z, |a| a.max(z))))
            }
        }
    }
}

/// Where the vertical line through `(x, y)` meets triangle `t` (barycentric, edges
/// included), its `z`.
fn vertical_hit(t: &[Vector3<f64>; 3], x: f64, y: f64) -> Option<f64> {
    let (a, b, c) = (t[0], t[1], t[2]);
    let det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if det.abs() < 1e-12 {
        return None;
    }
    let l1 = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
    let l2 = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
    let eps = -1e-9;
    (l1 >= eps && l2 >= eps && 1.0 - l1 - l2 >= eps)
        .then(|| a.z + l1 * (b.z - a.z) + l2 * (c.z - a.z))
}

/// A block's placement in the design frame: min corner (mm) and axes.
#[derive(Clone)]
struct Placement {
    origin: Vector3<f64>,
    axes: Matrix3<f64>,
}

/// A facade piece's part on one section: its start and end (design frame, mm).
type Part = (Vector3<f64>, Vector3<f64>);

/// The kept material of every block of a run.
#[derive(Clone)]
pub struct Kept {
    height: Height,
    blocks: HashMap<usize, Placement>,
    /// A facade's pieces: per block, each part's start and end (design frame, mm).
    parts: Option<HashMap<usize, Vec<Part>>>,
    /// How deep below the surface a blade point may be (mm): the fit's largest-distance
    /// tolerance (measured along the normal; half as much again vertically on slopes of
    /// 48°), and 0.5 mm for the facets of a mesh and the blade rebuilt on 128 chords
    /// (measured: at most 0.71 mm on the shipped jobs).
    pub tolerance: f64,
    /// How far the rebuilt blade may miss the cut and still be taken as the blade the
    /// program holds (mm): a nearly taut blade has two equilibria with the same ends.
    pub consistency: f64,
}

fn vec3(v: &serde_json::Value) -> Vector3<f64> {
    Vector3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

impl Kept {
    /// A facade's pieces (judged across their parts only).
    pub fn is_facade(&self) -> bool {
        self.parts.is_some()
    }

    /// From a run's job and report: `HotBlade` and `FacadeSegmentation` on a height field
    /// or a mesh; `None` for other tasks and surfaces.
    pub fn of(job: &hotcut::load::ResolvedJob, report: &serde_json::Value) -> Option<Kept> {
        let per_mm = job.context.per_mm();
        let height = match job.context.surface.as_ref()? {
            Surface::HeightField(h) => Height::Field {
                f: h.expr().clone(),
                x: h.x_range(),
                y: h.y_range(),
                per_mm,
            },
            Surface::Mesh(m) => {
                let triangles: Vec<[Vector3<f64>; 3]> = (0..m.faces().len())
                    .map(|f| m.triangle(f).map(|p| p / per_mm))
                    .collect();
                let cell = 50.0;
                let mut buckets: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
                for (i, t) in triangles.iter().enumerate() {
                    let lo = |k: usize| t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
                    let hi = |k: usize| t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
                    let (x0, x1) = ((lo(0) / cell).floor() as i64, (hi(0) / cell).floor() as i64);
                    let (y0, y1) = ((lo(1) / cell).floor() as i64, (hi(1) / cell).floor() as i64);
                    for bx in x0..=x1 {
                        for by in y0..=y1 {
                            buckets.entry((bx, by)).or_default().push(i);
                        }
                    }
                }
                Height::Mesh {
                    triangles,
                    buckets,
                    cell,
                }
            }
            Surface::Spline(_) => return None,
        };
        let mut blocks = HashMap::new();
        let mut parts = None;
        match report["task"].as_str()? {
            "HotBlade" => {
                let g = &report["grid"];
                let axes = Matrix3::from_columns(&[
                    vec3(&g["axis_d"]),
                    vec3(&g["axis_u"]),
                    vec3(&g["axis_v"]),
                ]);
                for b in report["blocks"].as_array()? {
                    let n = b["block"].as_u64()? as usize;
                    let origin = vec3(&b["origin"]) / per_mm;
                    blocks.insert(n, Placement { origin, axes });
                }
            }
            "FacadeSegmentation" => {
                let mut by_block = HashMap::new();
                for p in report["pieces"].as_array()? {
                    let b = &p["block"];
                    let n = b["number"].as_u64()? as usize;
                    let q: Vec<f64> = (0..4).map(|i| b["rotation"][i].as_f64().unwrap()).collect();
                    let r =
                        UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]));
                    let origin = vec3(&b["origin"]) / per_mm;
                    blocks.insert(
                        n,
                        Placement {
                            origin,
                            axes: *r.to_rotation_matrix().matrix(),
                        },
                    );
                    let ends = p["sections"]
                        .as_array()?
                        .iter()
                        .map(|s| (vec3(&s["start"]) / per_mm, vec3(&s["end"]) / per_mm))
                        .collect();
                    by_block.insert(n, ends);
                }
                parts = Some(by_block);
            }
            _ => return None,
        }
        Some(Kept {
            height,
            blocks,
            parts,
            tolerance: 1.5 * job.context.tolerance.max / per_mm + 0.5,
            consistency: 0.25,
        })
    }

    /// The blade `points` (block frame, mm) of a heated move's target on `block` with its
    /// plane's `normal` (block frame): the deepest any point inside the block (`size`) and
    /// within the design's footprint lies below the surface (negative: above it), and how
    /// far the rebuilt blade misses the cut — for a facade's piece the farther of its
    /// part's two ends from the blade's polygon, else the nearest any point inside comes to
    /// the surface. `None`: no point inside.
    pub fn below(
        &self,
        block: usize,
        size: &[f64; 3],
        normal: &Vector3<f64>,
        points: &[Vector3<f64>],
    ) -> Result<Option<(f64, f64)>, String> {
        let p = self
            .blocks
            .get(&block)
            .ok_or(format!("block {block} is not in the report"))?;
        let design: Vec<Vector3<f64>> = points.iter().map(|l| p.origin + p.axes * l).collect();
        // a facade's piece: its part on this plane, the one whose start lies on it
        let part = match &self.parts {
            None => None,
            Some(parts) => {
                let n = p.axes * normal;
                let found = parts
                    .get(&block)
                    .ok_or(format!("block {block} has no parts"))?
                    .iter()
                    .find(|(s, _)| n.dot(&(s - design[0])).abs() < 0.5)
                    .copied();
                match found {
                    Some(f) => Some(f),
                    // no part of this piece on this plane: the blade leaves the block
                    None => return Ok(None),
                }
            }
        };
        // across the cut (the block's second axis), between the part's ends
        let across = p.axes.column(1).into_owned();
        let within = |q: &Vector3<f64>| match part {
            None => true,
            Some((s, e)) => {
                let t = (q - s).dot(&across) / (e - s).dot(&across);
                t > 0.0 && t < 1.0
            }
        };
        let inside = |l: &Vector3<f64>| (0..3).all(|i| l[i] > 0.5 && l[i] < size[i] - 0.5);
        let mut found: Option<(f64, f64)> = None;
        for (l, q) in points.iter().zip(&design) {
            if !inside(l) || !within(q) {
                continue;
            }
            let Some(z) = self.height.at(q.x, q.y) else {
                continue;
            };
            let below = z - q.z;
            found = Some(match found {
                None => (below, below.abs()),
                Some((d, n)) => (d.max(below), n.min(below.abs())),
            });
        }
        Ok(found.map(|(deepest, nearest)| match part {
            Some((s, e)) => (
                deepest,
                to_polygon(&s, &design).max(to_polygon(&e, &design)),
            ),
            None => (deepest, nearest),
        }))
    }
}

/// Distance from `p` to the polygon through `points`.
fn to_polygon(p: &Vector3<f64>, points: &[Vector3<f64>]) -> f64 {
    points
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let t = ((p - w[0]).dot(&d) / d.norm_squared().max(1e-300)).clamp(0.0, 1.0);
            (p - w[0] - d * t).norm()
        })
        .fold(f64::INFINITY, f64::min)
}
