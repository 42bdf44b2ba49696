//! The independent checker of `RuledBlocks` (issue 39): runs every `ruled-*` job of
//! `jobs/` and, from its written files only — `report.json`, `rationalized.obj`, the G-code
//! programs and the job's own model — with its own readers and mesh queries
//! (`tests/ruled/mesh.rs`, nothing shared with hotcut's algorithms):
//! - replays every program as wire lines: each tower's (along, up) mapped back into the
//!   model by the mount its header states and the block's placement in the report, the
//!   wire between them;
//! - heated moves: no sampled wire point lies inside the rationalized model and inside the
//!   block deeper than the tolerance (from the model's surface and the block's faces);
//! - rapids: the cold wire never meets the block;
//! - a height field's slab, written as `model`, is the job's field closed down to a floor;
//! - the wire never enters the job's own model deeper than the reported largest
//!   deviation plus the tolerance (what the cut keeps holds the model but for what the
//!   report declares);
//! - the reported deviation is recomputed from the model's vertices and face centroids to
//!   the written rationalized mesh, and agrees.

#[path = "ruled/mesh.rs"]
mod mesh;

use geom::surface::Surface;
use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::NoProgress;
use hotcut_workspace_tests::root;
use mesh::{read_obj, Soup, P};
use serde_json::Value;

/// What a program's header says.
struct Header {
    axes: [char; 4],
    block: usize,
    mount: [(usize, f64); 3],
    towers_mm: f64,
    origin_mm: [f64; 2],
}

fn header(text: &str) -> Header {
    let comment = |start: &str| -> String {
        text.lines()
            .filter_map(|l| l.strip_prefix('(').and_then(|l| l.strip_suffix(')')))
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no header line {start:?}"))
            .to_string()
    };
    let profile = comment("profile");
    // "tower A X along Y up, tower B U along V up": the letters after "tower A"/"tower B"
    let after = |tag: &str| -> [char; 2] {
        let rest = profile.split(tag).nth(1).unwrap();
        let w: Vec<&str> = rest.split_whitespace().collect();
        [w[0].chars().next().unwrap(), w[2].chars().next().unwrap()]
    };
    let (a, b) = (after("tower A "), after("tower B "));
    let mount = comment("mount block");
    let words: Vec<&str> = mount.split_whitespace().collect();
    let block: usize = words[2].trim_end_matches(':').parse().unwrap();
    let axis = |w: &str| {
        let w = w.trim_end_matches(',');
        let s = if w.starts_with('-') { -1.0 } else { 1.0 };
        (
            ["x", "y", "z"]
                .iter()
                .position(|&n| w.ends_with(n))
                .unwrap(),
            s,
        )
    };
    // "mount block 1: its +y axis along the cut, +x towards tower B, -z up"
    let m = [axis(words[4]), axis(words[9]), axis(words[13])];
    let towers = comment("block centred between the towers");
    let towers_mm: f64 = towers
        .split_whitespace()
        .rev()
        .nth(2)
        .unwrap()
        .trim_end_matches(',')
        .parse()
        .unwrap();
    let origin = comment(&format!("{} {} =", a[0], b[0]));
    let nums: Vec<f64> = origin
        .split_whitespace()
        .filter_map(|w| w.trim_end_matches(',').parse().ok())
        .collect();
    Header {
        axes: [a[0], a[1], b[0], b[1]],
        block,
        mount: m,
        towers_mm,
        origin_mm: [nums[0], nums[1]],
    }
}

/// The moves of a program: (heated, [a_along, a_up, b_along, b_up] in mm).
fn moves(text: &str, axes: [char; 4]) -> Vec<(bool, [f64; 4])> {
    let mut at = [f64::NAN; 4];
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('(').next().unwrap().trim();
        let mut words = line.split_whitespace();
        let Some(code) = words.next() else { continue };
        let heated = match code {
            "G0" => false,
            "G1" => true,
            _ => continue,
        };
        for w in words {
            let (letter, value) = w.split_at(1);
            if let Some(k) = axes.iter().position(|c| c.to_string() == letter) {
                at[k] = value.parse().unwrap();
            }
        }
        out.push((heated, at));
    }
    out
}

/// A block from the report: centre, axes (columns), half sizes, and the half-spaces
/// `n · x ≤ c` its share of overlaps lies in.
struct Block {
    center: P,
    axes: [P; 3],
    half: P,
    keeps: Vec<(P, f64)>,
}

fn block(v: &Value) -> Block {
    let p = &v["placement"];
    let f = |x: &Value| x.as_f64().unwrap();
    let c = [0, 1, 2].map(|k| f(&p["center"][k]));
    let q = [0, 1, 2, 3].map(|k| f(&p["rotation"][k]));
    let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
    let n = (w * w + x * x + y * y + z * z).sqrt();
    let (w, x, y, z) = (w / n, x / n, y / n, z / n);
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    let axes = [0, 1, 2].map(|k| [r[0][k], r[1][k], r[2][k]]);
    let keeps = v["keeps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| ([0, 1, 2].map(|k| f(&h["normal"][k])), f(&h["offset"])))
        .collect();
    Block {
        center: c,
        axes,
        half: [0, 1, 2].map(|k| f(&p["size"][k]) / 2.0),
        keeps,
    }
}

impl Block {
    fn local(&self, p: P) -> P {
        let d = [
            p[0] - self.center[0],
            p[1] - self.center[1],
            p[2] - self.center[2],
        ];
        self.axes.map(|a| a[0] * d[0] + a[1] * d[1] + a[2] * d[2])
    }
    /// How far inside the block `p` lies (negative outside).
    fn depth(&self, p: P) -> f64 {
        let l = self.local(p);
        (0..3)
            .map(|k| self.half[k] - l[k].abs())
            .fold(f64::INFINITY, f64::min)
    }
    /// How far inside the block's share `p` lies: its depth in the block and below each
    /// half-space's plane.
    fn share_depth(&self, p: P) -> f64 {
        self.keeps
            .iter()
            .map(|(n, c)| c - (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]))
            .fold(self.depth(p), f64::min)
    }
}

/// The wire's two tower points in model coordinates.
fn wire(b: &Block, h: &Header, mm_per_unit: f64, q: [f64; 4]) -> (P, P) {
    let e = |(k, s): (usize, f64)| b.axes[k].map(|v| v * s);
    let (ea, ew, eu) = (e(h.mount[0]), e(h.mount[1]), e(h.mount[2]));
    let (ha, hu) = (b.half[h.mount[0].0], b.half[h.mount[2].0]);
    let point = |along_mm: f64, up_mm: f64, w_mm: f64| -> P {
        let along = (along_mm - h.origin_mm[0]) / mm_per_unit - ha;
        let up = (up_mm - h.origin_mm[1]) / mm_per_unit - hu;
        let w = w_mm / mm_per_unit;
        [0, 1, 2].map(|k| b.center[k] + ea[k] * along + ew[k] * w + eu[k] * up)
    };
    (
        point(q[0], q[1], -h.towers_mm / 2.0),
        point(q[2], q[3], h.towers_mm / 2.0),
    )
}

fn lerp(a: P, b: P, t: f64) -> P {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

/// The job's model as the checker reads it: a mesh job's own OBJ (its one object); for a
/// height field, the slab the run wrote (`model` in `rationalized.obj`), checked here
/// against the job's height field first ([`check_slab`]).
fn model_of(
    name: &str,
    job: &hotcut::load::ResolvedJob,
    written: &std::collections::HashMap<String, (Vec<P>, Vec<[usize; 3]>)>,
) -> (Vec<P>, Vec<[usize; 3]>) {
    let text = std::fs::read_to_string(root().join("jobs").join(name)).unwrap();
    if let Some(rest) = text.split("Mesh(path: \"").nth(1) {
        let path = rest.split('"').next().unwrap();
        let obj = std::fs::read_to_string(root().join("jobs").join(path)).unwrap();
        return read_obj(&obj).into_values().next().unwrap();
    }
    let (v, f) = written
        .get("model")
        .unwrap_or_else(|| panic!("{name}: rationalized.obj has no `model` (the slab)"))
        .clone();
    check_slab(name, job, &v, &f);
    (v, f)
}

/// A written slab is the job's height field (as the job loader parses it: the input, not
/// the algorithm) closed down to a floor, meshed on the job's `grid`: its top vertices are
/// the `(grid + 1)²` grid points, each on the field, the others on the floor (its lowest
/// plane); every vertex inside the field's rectangle; and its enclosed volume (divergence
/// theorem over its triangles) is the integral of height minus floor (midpoint rule on a
/// grid four times finer), within the error of linear interpolation on the grid's cells:
/// (cell diagonal)² / 8 · the largest second difference found, times the rectangle's
/// area, doubled. Coordinates carry the OBJ's rounding, half a unit of its 6th decimal, in
/// each of x, y and z; a height read at a rounded (x, y) is off by the field's slope times
/// that.
fn check_slab(name: &str, job: &hotcut::load::ResolvedJob, v: &[P], f: &[[usize; 3]]) {
    let Some(Surface::HeightField(hf)) = &job.context.surface else {
        panic!("{name}: not a height field")
    };
    let task = serde_json::to_value(&job.task).unwrap();
    let grid = task["RuledBlocks"]["grid"]
        .as_u64()
        .expect("RuledBlocks' grid") as usize;
    let z = |x: f64, y: f64| hf.expr().eval(x, y);
    let ((x0, x1), (y0, y1)) = (hf.x_range(), hf.y_range());
    let (dx, dy) = ((x1 - x0) / grid as f64, (y1 - y0) / grid as f64);
    let floor = v.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    // the field's steepest slope and sharpest bend, on a grid four times finer than the slab's
    let (nx, ny) = (4 * grid, 4 * grid);
    let (hx, hy) = ((x1 - x0) / nx as f64, (y1 - y0) / ny as f64);
    let (mut integral, mut curv, mut slope) = (0.0, 0.0f64, 0.0f64);
    for i in 0..nx {
        for j in 0..ny {
            let (x, y) = (x0 + (i as f64 + 0.5) * hx, y0 + (j as f64 + 0.5) * hy);
            integral += (z(x, y) - floor) * hx * hy;
            let fxx = (z(x + hx, y) - 2.0 * z(x, y) + z(x - hx, y)) / (hx * hx);
            let fyy = (z(x, y + hy) - 2.0 * z(x, y) + z(x, y - hy)) / (hy * hy);
            let fxy = (z(x + hx, y + hy) - z(x + hx, y - hy) - z(x - hx, y + hy)
                + z(x - hx, y - hy))
                / (4.0 * hx * hy);
            curv = curv.max(fxx.abs() + fyy.abs() + 2.0 * fxy.abs());
            let gx = (z(x + hx, y) - z(x - hx, y)) / (2.0 * hx);
            let gy = (z(x, y + hy) - z(x, y - hy)) / (2.0 * hy);
            slope = slope.max(gx.hypot(gy));
        }
    }
    // the OBJ's rounding (absolute) through the slope, and a margin for the finite differences
    let eps = 5e-7 * (1.0 + 2.0 * std::f64::consts::SQRT_2 * slope) * 2.0;
    let mut top = 0;
    for p in v {
        assert!(
            p[0] >= x0 - eps && p[0] <= x1 + eps && p[1] >= y0 - eps && p[1] <= y1 + eps,
            "{name}: slab vertex {p:?} outside the field"
        );
        if (p[2] - floor).abs() <= eps {
            continue;
        }
        top += 1;
        assert!(
            (p[2] - z(p[0], p[1])).abs() <= eps,
            "{name}: slab vertex {p:?} neither on the field ({}) nor on the floor {floor}",
            z(p[0], p[1])
        );
        // on the job's grid
        let (i, j) = ((p[0] - x0) / dx, (p[1] - y0) / dy);
        assert!(
            (i - i.round()).abs() * dx <= eps && (j - j.round()).abs() * dy <= eps,
            "{name}: slab vertex {p:?} off the {grid}-cell grid"
        );
    }
    assert_eq!(
        top,
        (grid + 1) * (grid + 1),
        "{name}: the slab's top vertices"
    );
    let volume: f64 = f
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| v[i]);
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum();
    let area = (x1 - x0) * (y1 - y0);
    let bound = 2.0 * (dx * dx + dy * dy) / 8.0 * curv * area + eps * area;
    assert!(
        (volume - integral).abs() <= bound,
        "{name}: the slab holds {volume}, the field over its floor {integral} (bound {bound})"
    );
}

#[test]
fn every_ruled_blocks_program_keeps_what_its_block_keeps() {
    let mut jobs: Vec<_> = std::fs::read_dir(root().join("jobs"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("ruled-") && n.ends_with(".ron"))
        .collect();
    jobs.sort();
    assert!(jobs.len() >= 3, "{jobs:?}");
    for name in jobs {
        check_job(&name);
    }
}

fn check_job(name: &str) {
    let job = load_job(&root().join("jobs").join(name)).unwrap();
    let out = tempfile::tempdir().unwrap();
    let run = run_job(&job, out.path(), &NoProgress).unwrap();
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(run.dir.join("report.json")).unwrap())
            .unwrap();
    let mm_per_unit = if report["units"] == "Metre" {
        1000.0
    } else {
        1.0
    };
    let tol = report["tolerance"].as_f64().unwrap();
    let dev_max = report["deviation"]["max"].as_f64().unwrap();
    let objs = read_obj(&std::fs::read_to_string(run.dir.join("rationalized.obj")).unwrap());
    let diag = report["model"]["diagonal"].as_f64().unwrap();
    let cell = (diag / 64.0).max(tol);
    // what each block keeps: the one rationalized model, or (per block) its own
    let whole = objs.get("rationalized").map(|(v, f)| Soup::new(v, f, cell));
    let own: Vec<Option<Soup>> = (1..=report["blocks"].as_array().unwrap().len())
        .map(|i| {
            objs.get(&format!("rationalized_{i}"))
                .map(|(v, f)| Soup::new(v, f, cell))
        })
        .collect();
    let kept = |b: usize| whole.as_ref().or(own[b - 1].as_ref());
    let (v, f) = model_of(name, &job, &objs);
    let m = Soup::new(&v, &f, cell);
    let blocks: Vec<Block> = report["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(block)
        .collect();
    let (mut programs, mut samples, mut deepest, mut model_deepest) =
        (0usize, 0usize, 0.0f64, 0.0f64);
    let mut files: Vec<_> = std::fs::read_dir(&run.dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "gcode"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{name}: no program");
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let h = header(&text);
        let b = &blocks[h.block - 1];
        let mv = moves(&text, h.axes);
        programs += 1;
        for w in mv.windows(2) {
            let ((_, from), (heated, to)) = (w[0], w[1]);
            if from.iter().any(|v| v.is_nan()) {
                continue;
            }
            for s in 0..4 {
                let t = (s + 1) as f64 / 4.0;
                let q = [0, 1, 2, 3].map(|k| from[k] + (to[k] - from[k]) * t);
                let (pa, pb) = wire(b, &h, mm_per_unit, q);
                let len = mesh::point_triangle(pa, [pb, pb, pb]);
                let n = ((len / tol).ceil() as usize).clamp(2, 4000);
                for i in 0..=n {
                    let p = lerp(pa, pb, i as f64 / n as f64);
                    let inside_block = b.depth(p);
                    if !heated {
                        assert!(
                            inside_block < 0.0,
                            "{name} {}: the cold wire meets block {} at {p:?}",
                            file.display(),
                            h.block
                        );
                        continue;
                    }
                    // what the block keeps: its share of the rationalized model
                    let inside_block = b.share_depth(p);
                    if inside_block <= tol {
                        continue;
                    }
                    samples += 1;
                    let Some(solid) = kept(h.block) else {
                        panic!("{name}: block {} keeps nothing but has a program", h.block)
                    };
                    if solid.inside(p) {
                        let d = solid.distance_within(p, 4.0 * tol).unwrap_or(4.0 * tol);
                        let depth = d.min(inside_block);
                        deepest = deepest.max(depth);
                        assert!(
                            depth <= tol,
                            "{name} {}: the wire enters what block {} keeps {depth} deep at {p:?}",
                            file.display(),
                            h.block
                        );
                    }
                    if m.inside(p) {
                        let reach = dev_max + 2.0 * tol;
                        let d = m.distance_within(p, reach).unwrap_or(reach);
                        model_deepest = model_deepest.max(d.min(inside_block));
                        assert!(
                            d.min(inside_block) <= dev_max + tol,
                            "{name} {}: the wire enters the model {d} deep at {p:?} (deviation {dev_max})",
                            file.display()
                        );
                    }
                }
            }
        }
    }
    let listed: usize = report["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["cuts"].as_array().unwrap().len())
        .sum();
    assert_eq!(programs, listed, "{name}: a program per cut");
    // the blocks' shares cover the model: every vertex lies in one (to a thousandth of the
    // tolerance)
    {
        for p in &v {
            assert!(
                blocks.iter().any(|b| b.share_depth(*p) >= -1e-3 * tol),
                "{name}: no block keeps the model's vertex {p:?}"
            );
        }
    }
    // the deviation from the written mesh: the model's vertices and face centroids
    {
        // the report's rule (README): the vertices, then per face a barycentric lattice
        // dividing its edges into k = ⌈longest edge / tolerance⌉ parts (1 to 4), corners
        // left out, the centroid alone for k ≤ 2
        let mut pts: Vec<P> = v.clone();
        for t in &f {
            let [a, b, c] = t.map(|i| v[i]);
            let len = |p: P, q: P| mesh::point_triangle(p, [q, q, q]);
            let longest = len(a, b).max(len(b, c)).max(len(c, a));
            let k = ((longest / tol).ceil() as usize).clamp(1, 4);
            if k <= 2 {
                pts.push([0, 1, 2].map(|m| (a[m] + b[m] + c[m]) / 3.0));
                continue;
            }
            for i in 0..=k {
                for j in 0..=(k - i) {
                    if (i, j) == (0, 0) || (i, j) == (k, 0) || (i, j) == (0, k) {
                        continue;
                    }
                    let (x, y) = (i as f64 / k as f64, j as f64 / k as f64);
                    pts.push([0, 1, 2].map(|m| a[m] + (b[m] - a[m]) * x + (c[m] - a[m]) * y));
                }
            }
        }
        // each sample's distance to the surface of the one model, or of the nearest of the
        // blocks holding it
        let d: Vec<f64> = pts
            .iter()
            .filter_map(|p| match &whole {
                Some(s) => Some(s.distance(*p)),
                None => blocks
                    .iter()
                    .zip(&own)
                    .filter(|(b, s)| s.is_some() && b.depth(*p) >= -1e-9 * diag)
                    .map(|(_, s)| s.as_ref().map_or(f64::INFINITY, |s| s.distance(*p)))
                    .reduce(f64::min),
            })
            .collect();
        let max = d.iter().copied().fold(0.0, f64::max);
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
        let rep_rms = report["deviation"]["rms"].as_f64().unwrap();
        // the OBJ holds 6 decimals
        let slack = 1e-5 * diag;
        assert!(
            (max - dev_max).abs() <= slack,
            "{name}: deviation max {max} vs the report's {dev_max}"
        );
        assert!(
            (rms - rep_rms).abs() <= slack,
            "{name}: deviation RMS {rms} vs the report's {rep_rms}"
        );
        assert_eq!(
            pts.len(),
            report["deviation"]["samples"].as_u64().unwrap() as usize
        );
    }
    eprintln!(
        "{name}: {programs} programs, {samples} wire points in blocks, deepest into kept material {deepest:.3e}, into the model {model_deepest:.3e} (tolerance {tol}, deviation {dev_max})"
    );
}
