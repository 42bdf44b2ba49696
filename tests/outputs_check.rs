//! Checks of every job's output files, run by `jobs.rs` on each job's first run: the glTF
//! is in metres and its bounds are the report's `model_bounds`, and every JSON file
//! validates against its committed schema, which rejects unknown keys.

use std::path::Path;

use serde_json::Value;

/// The schema file of a JSON output `name` (`report.json` by the report's task).
fn schema_for(name: &str, value: &Value) -> String {
    match name {
        "targets.json" => "targets.schema.json".into(),
        "blocks.json" => "blocks.schema.json".into(),
        "precut.json" => "precut.schema.json".into(),
        "report.json" => {
            let task = value["task"].as_str().expect("a report names its task");
            hotcut::schema_files()
                .into_iter()
                .find(|f| f.task == Some(task))
                .unwrap_or_else(|| panic!("no report schema for task {task}"))
                .file
                .into()
        }
        other => panic!("{other}: a JSON output without a schema"),
    }
}

/// Every object of `v`, depth first, as JSON pointers.
fn objects(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Object(o) => {
            out.push(at.clone());
            for (k, x) in o {
                objects(
                    x,
                    format!("{at}/{}", k.replace('~', "~0").replace('/', "~1")),
                    out,
                );
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                objects(x, format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
}

/// Every `.json` file in `dir` validates against its schema in `schemas/`, and adding an
/// unknown key to any of its objects (up to 64 of them, spread evenly) makes it invalid.
pub fn json_files_validate(dir: &Path, root: &Path, what: &str) {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    names.sort();
    assert!(
        names.contains(&"report.json".to_string()),
        "{what}: no report"
    );
    for name in names {
        let value: Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(&name)).unwrap()).unwrap();
        let schema_file = schema_for(&name, &value);
        let schema: Value = serde_json::from_str(
            &std::fs::read_to_string(root.join("schemas").join(&schema_file)).unwrap(),
        )
        .unwrap();
        let validator = jsonschema::validator_for(&schema).unwrap();
        let errors: Vec<String> = validator
            .iter_errors(&value)
            .take(5)
            .map(|e| format!("{} at {}", e, e.instance_path()))
            .collect();
        assert!(
            errors.is_empty(),
            "{what}: {name} does not validate against schemas/{schema_file}: {errors:?}"
        );
        let mut all = Vec::new();
        objects(&value, String::new(), &mut all);
        let step = all.len().div_ceil(64).max(1);
        for at in all.iter().step_by(step) {
            let mut bad = value.clone();
            bad.pointer_mut(at)
                .and_then(Value::as_object_mut)
                .unwrap()
                .insert("hotcut_unknown_key".into(), Value::Null);
            assert!(
                !validator.is_valid(&bad),
                "{what}: schemas/{schema_file} accepts an unknown key at {name}{at}"
            );
        }
    }
}

/// A unit quaternion `[x, y, z, w]` as a rotation matrix (rows).
fn rotation(q: &[f64]) -> [[f64; 3]; 3] {
    let (x, y, z, w) = (q[0], q[1], q[2], q[3]);
    [
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
    ]
}

/// `model.gltf`'s scene bounds in metres, y up (every mesh node's accessor box, its
/// corners moved by the rotations and scales of the nodes above it), and the report's
/// `model_bounds` moved the same way glTF says a z-up job is turned (checked separately:
/// the root node is the −90° turn about x) agree to single precision.
pub fn gltf_bounds_match_the_report(dir: &Path, what: &str) {
    let path = dir.join("model.gltf");
    if !path.exists() {
        return;
    }
    let g: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let metres = match report["units"].as_str().unwrap() {
        "Millimetre" => 1e-3,
        "Metre" => 1.0,
        u => panic!("{what}: unit {u}"),
    };
    assert_eq!(
        g["asset"]["extras"]["source_units"], report["units"],
        "{what}"
    );
    assert_eq!(
        g["asset"]["extras"]["metres_per_source_unit"].as_f64(),
        Some(metres),
        "{what}"
    );
    let nodes = g["nodes"].as_array().unwrap();
    // each node's transform: rotation then scale (no node translates)
    let transform = |n: &Value| {
        assert!(
            n.get("translation").is_none() && n.get("matrix").is_none(),
            "{what}"
        );
        let r = n["rotation"]
            .as_array()
            .map(|q| rotation(&q.iter().map(|v| v.as_f64().unwrap()).collect::<Vec<_>>()))
            .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let s: Vec<f64> = n["scale"]
            .as_array()
            .map(|s| s.iter().map(|v| v.as_f64().unwrap()).collect())
            .unwrap_or(vec![1.0; 3]);
        move |p: [f64; 3]| -> [f64; 3] {
            let q = [p[0] * s[0], p[1] * s[1], p[2] * s[2]];
            std::array::from_fn(|i| (0..3).map(|k| r[i][k] * q[k]).sum())
        }
    };
    let parent = |i: usize| {
        nodes.iter().position(|n| {
            n["children"]
                .as_array()
                .is_some_and(|c| c.iter().any(|x| x.as_u64() == Some(i as u64)))
        })
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (i, n) in nodes.iter().enumerate() {
        let Some(mesh) = n["mesh"].as_u64() else {
            continue;
        };
        for prim in g["meshes"][mesh as usize]["primitives"].as_array().unwrap() {
            let acc = &g["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize];
            let v = |k: &str| -> Vec<f64> {
                acc[k]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect()
            };
            let (a, b) = (v("min"), v("max"));
            for c in 0..8 {
                let mut p = [
                    if c & 1 == 0 { a[0] } else { b[0] },
                    if c & 2 == 0 { a[1] } else { b[1] },
                    if c & 4 == 0 { a[2] } else { b[2] },
                ];
                p = transform(n)(p);
                let mut up = parent(i);
                let mut depth = 0;
                while let Some(j) = up {
                    p = transform(&nodes[j])(p);
                    up = parent(j);
                    depth += 1;
                    assert!(depth < nodes.len(), "{what}: node cycle");
                }
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
    }
    let b = &report["model_bounds"];
    let r = |k: &str| -> Vec<f64> {
        b[k].as_array()
            .unwrap_or_else(|| panic!("{what}: report has no model_bounds"))
            .iter()
            .map(|x| x.as_f64().unwrap() * metres)
            .collect()
    };
    let (min, max) = (r("min"), r("max"));
    // z up to y up: (x, y, z) → (x, z, −y)
    let want_lo = [min[0], min[2], -max[1]];
    let want_hi = [max[0], max[2], -min[1]];
    let size = (0..3)
        .map(|k| want_hi[k].abs().max(want_lo[k].abs()))
        .fold(0.0, f64::max);
    // f32 positions (6e-8 relative) and the report's 9 digits
    let tol = 1e-6 * size.max(1e-3);
    for k in 0..3 {
        assert!(
            (lo[k] - want_lo[k]).abs() <= tol && (hi[k] - want_hi[k]).abs() <= tol,
            "{what}: glTF bounds {lo:?}..{hi:?} m, report {want_lo:?}..{want_hi:?} m"
        );
    }
}

/// The value of attribute `name` in an element's text.
fn attr<'a>(el: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = el.find(&key)? + key.len();
    let j = el[i..].find('"')? + i;
    Some(&el[i..j])
}

fn num(el: &str, name: &str) -> f64 {
    attr(el, name).and_then(|v| v.parse().ok()).unwrap_or(0.0)
}

/// Whether segment `a`–`b` meets the box `(x0, y0, x1, y1)` (Liang–Barsky clipping).
fn segment_meets_box(a: (f64, f64), b: (f64, f64), bx: (f64, f64, f64, f64)) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - bx.0),
        (dx, bx.2 - a.0),
        (-dy, a.1 - bx.1),
        (dy, bx.3 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// What a reader of the drawings in `dir` would trip on, by a simple honest proxy of
/// "text overdrawn by geometry": every text's box (0.6 em per character wide, from 0.8 em
/// above its baseline to 0.2 em below) must lie on the page, clear of every other text's
/// box and of every drawn segment (polyline and polygon edges, rectangle edges, circles as
/// their boxes). The page's white background and a text's own halo are not geometry.
/// Every drawing must also carry a scale (`<g class="scale-bar">` or
/// `<g class="chart-axes">`), its axes (`<g class="axes">` or a chart's) and a legend
/// (`<g class="legend">`), as `export::svg` draws them.
pub fn svg_problems(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
        .collect();
    names.sort();
    for path in names {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(&path).unwrap();
        let svg = text.lines().find(|l| l.starts_with("<svg")).unwrap_or("");
        let (w, h) = (num(svg, "width"), num(svg, "height"));
        let mut boxes: Vec<(String, (f64, f64, f64, f64))> = Vec::new();
        let mut segments: Vec<((f64, f64), (f64, f64))> = Vec::new();
        for (i, el) in text.lines().enumerate() {
            if let Some(rest) = el.strip_prefix("<text") {
                let size = num(rest, "font-size");
                let content = rest
                    .split_once('>')
                    .map(|(_, c)| c.trim_end_matches("</text>"))
                    .unwrap_or("");
                let chars = content
                    .replace("&amp;", "&")
                    .replace("&lt;", "<")
                    .replace("&gt;", ">")
                    .replace("&quot;", "\"")
                    .chars()
                    .count() as f64;
                let (x, y) = (num(rest, "x"), num(rest, "y"));
                let width = 0.6 * size * chars;
                let x0 = match attr(rest, "text-anchor") {
                    Some("middle") => x - width / 2.0,
                    Some("end") => x - width,
                    _ => x,
                };
                boxes.push((
                    content.to_string(),
                    (x0, y - 0.8 * size, x0 + width, y + 0.2 * size),
                ));
            } else if el.starts_with("<polyline") || el.starts_with("<polygon") {
                let pts: Vec<(f64, f64)> = attr(el, "points")
                    .unwrap_or("")
                    .split_whitespace()
                    .filter_map(|p| {
                        let (a, b) = p.split_once(',')?;
                        Some((a.parse().ok()?, b.parse().ok()?))
                    })
                    .collect();
                for s in pts.windows(2) {
                    segments.push((s[0], s[1]));
                }
                if el.starts_with("<polygon") && pts.len() > 2 {
                    segments.push((pts[pts.len() - 1], pts[0]));
                }
            } else if el.starts_with("<rect") && i > 2 {
                // (the first element, on line 3, is the page's white background)
                let (x, y, rw, rh) = (
                    num(el, "x"),
                    num(el, "y"),
                    num(el, "width"),
                    num(el, "height"),
                );
                let c = [(x, y), (x + rw, y), (x + rw, y + rh), (x, y + rh)];
                for k in 0..4 {
                    segments.push((c[k], c[(k + 1) % 4]));
                }
            } else if el.starts_with("<circle") {
                let (x, y, r) = (num(el, "cx"), num(el, "cy"), num(el, "r"));
                segments.push(((x - r, y), (x + r, y)));
                segments.push(((x, y - r), (x, y + r)));
            }
        }
        // what makes a drawing readable: a scale (a scale bar in job units, or a chart's
        // axes with values), the axes' directions (or the chart's), and a legend
        let has = |class: &str| text.contains(&format!("<g class=\"{class}\">"));
        if !has("scale-bar") && !has("chart-axes") {
            out.push(format!("{name}: no scale bar and no chart axes"));
        }
        if !has("axes") && !has("chart-axes") {
            out.push(format!("{name}: no axis labels"));
        }
        if !has("legend") {
            out.push(format!("{name}: no legend"));
        }
        for (k, (t, b)) in boxes.iter().enumerate() {
            if b.0 < -0.5 || b.1 < -0.5 || b.2 > w + 0.5 || b.3 > h + 0.5 {
                out.push(format!("{name}: text {t:?} runs off the page"));
            }
            if let Some((u, _)) = boxes[..k]
                .iter()
                .find(|(_, c)| b.0 < c.2 && c.0 < b.2 && b.1 < c.3 && c.1 < b.3)
            {
                out.push(format!("{name}: texts {u:?} and {t:?} overlap"));
            }
            let inner = (b.0 + 0.5, b.1 + 0.5, b.2 - 0.5, b.3 - 0.5);
            if let Some(s) = segments
                .iter()
                .find(|(p, q)| segment_meets_box(*p, *q, inner))
            {
                out.push(format!(
                    "{name}: text {t:?} is overdrawn by a line through {:?}",
                    s.0
                ));
            }
        }
    }
    out
}
