//! The checker's own mesh queries (no code shared with hotcut's algorithms): an OBJ
//! reader, inside tests by ray parity along +z, and distances through a uniform grid.

use std::collections::HashMap;

pub type P = [f64; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: P) -> f64 {
    dot(a, a).sqrt()
}

/// Objects of an OBJ file by name: vertices and triangles (indices into its vertices).
pub fn read_obj(text: &str) -> HashMap<String, (Vec<P>, Vec<[usize; 3]>)> {
    let mut all: Vec<P> = Vec::new();
    let mut out: HashMap<String, (Vec<P>, Vec<[usize; 3]>)> = HashMap::new();
    let mut current = String::from("default");
    let mut faces: HashMap<String, Vec<[usize; 3]>> = HashMap::new();
    for line in text.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("o") => current = w.next().unwrap_or("").to_string(),
            Some("v") => {
                let v: Vec<f64> = w.take(3).map(|x| x.parse().unwrap()).collect();
                all.push([v[0], v[1], v[2]]);
            }
            Some("f") => {
                let ix: Vec<usize> = w
                    .map(|x| x.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                    .collect();
                for k in 1..ix.len() - 1 {
                    faces
                        .entry(current.clone())
                        .or_default()
                        .push([ix[0], ix[k], ix[k + 1]]);
                }
            }
            _ => {}
        }
    }
    for (name, fs) in faces {
        // each object's own vertices, renumbered
        let mut map = HashMap::new();
        let mut verts = Vec::new();
        let tris = fs
            .iter()
            .map(|f| {
                f.map(|i| {
                    *map.entry(i).or_insert_with(|| {
                        verts.push(all[i]);
                        verts.len() - 1
                    })
                })
            })
            .collect();
        out.insert(name, (verts, tris));
    }
    out
}

/// A triangle soup with a uniform grid over it.
pub struct Soup {
    tris: Vec<[P; 3]>,
    lo: P,
    cell: f64,
    n: [usize; 3],
    cells: HashMap<[usize; 3], Vec<usize>>,
    columns: HashMap<[usize; 2], Vec<usize>>,
}

impl Soup {
    pub fn new(verts: &[P], faces: &[[usize; 3]], cell: f64) -> Self {
        let tris: Vec<[P; 3]> = faces.iter().map(|f| f.map(|i| verts[i])).collect();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for t in &tris {
            for p in t {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let n = [0, 1, 2].map(|k| (((hi[k] - lo[k]) / cell).floor() as usize + 1).max(1));
        let mut s = Self {
            tris,
            lo,
            cell,
            n,
            cells: HashMap::new(),
            columns: HashMap::new(),
        };
        for (i, t) in s.tris.iter().enumerate() {
            let a = [0, 1, 2].map(|k| t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
            let b = [0, 1, 2].map(|k| t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max));
            let (ca, cb) = (s.cell_of(a), s.cell_of(b));
            for x in ca[0]..=cb[0] {
                for y in ca[1]..=cb[1] {
                    s.columns.entry([x, y]).or_default().push(i);
                    for z in ca[2]..=cb[2] {
                        s.cells.entry([x, y, z]).or_default().push(i);
                    }
                }
            }
        }
        s
    }

    fn cell_of(&self, p: P) -> [usize; 3] {
        [0, 1, 2].map(|k| {
            (((p[k] - self.lo[k]) / self.cell).floor().max(0.0) as usize).min(self.n[k] - 1)
        })
    }

    /// Inside by the parity of crossings of the ray from `p` along +z.
    pub fn inside(&self, p: P) -> bool {
        let c = self.cell_of(p);
        let Some(list) = self.columns.get(&[c[0], c[1]]) else {
            return false;
        };
        let mut odd = false;
        for &i in list {
            let [a, b, cc] = self.tris[i];
            // barycentric in xy
            let d = (b[1] - cc[1]) * (a[0] - cc[0]) + (cc[0] - b[0]) * (a[1] - cc[1]);
            if d == 0.0 {
                continue;
            }
            let l1 = ((b[1] - cc[1]) * (p[0] - cc[0]) + (cc[0] - b[0]) * (p[1] - cc[1])) / d;
            let l2 = ((cc[1] - a[1]) * (p[0] - cc[0]) + (a[0] - cc[0]) * (p[1] - cc[1])) / d;
            let l3 = 1.0 - l1 - l2;
            if l1 < 0.0 || l2 < 0.0 || l3 < 0.0 || (l1 == 0.0 || l2 == 0.0 || l3 == 0.0) && d < 0.0
            {
                continue;
            }
            let z = l1 * a[2] + l2 * b[2] + l3 * cc[2];
            if z > p[2] {
                odd = !odd;
            }
        }
        odd
    }

    /// The distance from `p` to the soup, searched out to `reach` (beyond: `None`).
    pub fn distance_within(&self, p: P, reach: f64) -> Option<f64> {
        let r = (reach / self.cell).ceil() as isize;
        let c = self.cell_of(p);
        let mut best = f64::INFINITY;
        let mut seen = std::collections::HashSet::new();
        for dx in -r..=r {
            for dy in -r..=r {
                for dz in -r..=r {
                    let q = [c[0] as isize + dx, c[1] as isize + dy, c[2] as isize + dz];
                    if q.iter().any(|&v| v < 0) {
                        continue;
                    }
                    if let Some(list) = self.cells.get(&q.map(|v| v as usize)) {
                        for &i in list {
                            if seen.insert(i) {
                                best = best.min(point_triangle(p, self.tris[i]));
                            }
                        }
                    }
                }
            }
        }
        (best <= reach).then_some(best)
    }

    /// The distance from `p` to the soup.
    pub fn distance(&self, p: P) -> f64 {
        let mut reach = self.cell;
        loop {
            if let Some(d) = self.distance_within(p, reach) {
                return d;
            }
            reach *= 2.0;
            assert!(reach < 1e12, "no triangle");
        }
    }
}

/// Distance from a point to a triangle (by its plane, else its edges).
pub fn point_triangle(p: P, [a, b, c]: [P; 3]) -> f64 {
    let n = cross(sub(b, a), sub(c, a));
    let nn = norm(n);
    if nn > 0.0 {
        let h = dot(sub(p, a), n) / nn;
        let q = sub(p, n.map(|v| v * h / nn));
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| dot(cross(sub(v, u), sub(q, u)), n) >= 0.0);
        if inside {
            return h.abs();
        }
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| {
            let e = sub(v, u);
            let l = dot(e, e);
            let t = if l > 0.0 {
                (dot(sub(p, u), e) / l).clamp(0.0, 1.0)
            } else {
                0.0
            };
            norm(sub(p, [u[0] + e[0] * t, u[1] + e[1] * t, u[2] + e[2] * t]))
        })
        .fold(f64::INFINITY, f64::min)
}
