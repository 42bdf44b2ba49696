//! Unit and scale invariance: every job of `jobs/` is run as written and again in the
//! other unit (millimetres ↔ metres: every length of the job and of its input files
//! divided or multiplied by 1000, the same geometry). The two `report.json` must agree:
//! the same counts, pieces, blocks, verdicts and inflections, and every number either
//! equal or scaled by a power of 1000 (lengths, curvatures, areas, volumes).

use std::path::{Path, PathBuf};

use hotcut::job::{Job, MillingStock, Process, TaskSpec};
use hotcut::load::{parse_job, resolve};
use hotcut::run::run_job;
use hotcut::spec::{SurfaceSpec, Units};
use hotcut::NoProgress;
use hotcut_workspace_tests::{root, third_party_jobs};
use serde_json::Value;

/// `x` scaled by `f`.
fn sc(x: f64, f: f64) -> f64 {
    x * f
}

fn sc3(p: (f64, f64, f64), f: f64) -> (f64, f64, f64) {
    (p.0 * f, p.1 * f, p.2 * f)
}

/// The expression `z(x, y)` of a height field in the new unit: `f · z(x/f, y/f)`.
fn scale_expression(z: &str, f: f64) -> String {
    let mut out = String::new();
    let mut ident = String::new();
    let flush = |ident: &mut String, out: &mut String| {
        match ident.as_str() {
            "x" | "y" => out.push_str(&format!("({ident}/{f})")),
            _ => out.push_str(ident),
        }
        ident.clear();
    };
    for c in z.chars() {
        if c.is_ascii_alphanumeric() || c == '_' || (c == '.' && !ident.is_empty()) {
            // digits after a letter belong to the identifier; a number starts with a digit
            if ident.is_empty() && (c.is_ascii_digit() || c == '.') {
                out.push(c);
            } else {
                ident.push(c);
            }
        } else {
            flush(&mut ident, &mut out);
            out.push(c);
        }
    }
    flush(&mut ident, &mut out);
    format!("({out})*{f}")
}

/// Writes `src` (an OBJ mesh, a spline grid or a curves file) scaled by `f` into `dir`.
fn scale_file(src: &Path, f: f64, dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(src).unwrap();
    let name = src.file_name().unwrap();
    let out = dir.join(name);
    let scaled = match src.extension().and_then(|e| e.to_str()) {
        Some("obj") => text
            .lines()
            .map(|l| match l.strip_prefix("v ") {
                Some(rest) => {
                    let v: Vec<String> = rest
                        .split_whitespace()
                        .map(|c| format!("{:e}", c.parse::<f64>().unwrap() * f))
                        .collect();
                    format!("v {}", v.join(" "))
                }
                None => l.to_string(),
            })
            .collect::<Vec<_>>()
            .join("\n"),
        Some("json") => {
            let mut v: Value = serde_json::from_str(&text).unwrap();
            let scale_points = |p: &mut Value| scale_numbers(p, f);
            if let Some(points) = v.get_mut("points") {
                scale_points(points);
            }
            if v.get("cuts").is_some() {
                scale_design(&mut v, f);
            }
            if let Some(curves) = v.get_mut("curves").and_then(Value::as_array_mut) {
                for c in curves {
                    scale_points(c.get_mut("points").unwrap());
                }
            }
            v.to_string()
        }
        other => panic!("no scaling for {other:?} files"),
    };
    std::fs::write(&out, scaled).unwrap();
    out
}

/// A design file's lengths: the blocks' corners (or the grid's origin and size) and the
/// curves' points; not the grid's counts or the stations' fractions.
fn scale_design(v: &mut Value, f: f64) {
    let blocks = &mut v["blocks"];
    if let Some(list) = blocks.get_mut("List").and_then(Value::as_array_mut) {
        for b in list {
            scale_numbers(&mut b["min"], f);
            scale_numbers(&mut b["max"], f);
        }
    }
    if let Some(g) = blocks.get_mut("Grid") {
        scale_numbers(&mut g["origin"], f);
        scale_numbers(&mut g["size"], f);
    }
    for c in v["cuts"].as_array_mut().unwrap() {
        for s in c["stations"].as_array_mut().unwrap() {
            scale_numbers(&mut s["curve"], f);
        }
    }
}

fn scale_numbers(v: &mut Value, f: f64) {
    match v {
        Value::Number(n) => *v = Value::from(n.as_f64().unwrap() * f),
        Value::Array(a) => a.iter_mut().for_each(|x| scale_numbers(x, f)),
        Value::Object(o) => o.values_mut().for_each(|x| scale_numbers(x, f)),
        _ => {}
    }
}

/// Every length default written out, in the job's units (so that scaling the job keeps
/// them when its units do not change).
fn with_defaults(job: &Job) -> Job {
    use hotcut::spec::{defaults as d, BladeSpec};
    let mut j = job.clone();
    let u = job.units.per_mm();
    // the robot cell has a size of its own (an arm does not shrink with the job): no
    // robot programs here; the mm/m test checks the cell
    j.cell = None;
    j.outputs
        .retain(|o| !matches!(o, hotcut::spec::OutputSpec::Rapid));
    let b = j.blade.get_or_insert(BladeSpec {
        length: d::BLADE_LENGTH_MM * u,
        max_curvature: d::BLADE_MAX_CURVATURE_PER_MM / u,
        max_inflections: 2,
        kerf: None,
        kerf_table: None,
        max_blade_inflections: None,
        thickness: None,
        width: None,
        youngs_modulus: None,
        min_margin: None,
    });
    b.thickness.get_or_insert(d::BLADE_THICKNESS_MM * u);
    b.width.get_or_insert(d::BLADE_WIDTH_MM * u);
    if let Some(w) = j.wire.as_mut() {
        w.speed.get_or_insert(d::WIRE_SPEED_MM_PER_MIN * u);
        w.lead.get_or_insert(d::WIRE_LEAD_MM * u);
        w.clearance.get_or_insert(d::WIRE_CLEARANCE_MM * u);
    }
    let t = &mut j.tolerance;
    t.rms.get_or_insert(d::RMS_MM * u);
    t.max.get_or_insert(d::MAX_MM * u);
    t.smoothing.get_or_insert(d::SMOOTHING_MM * u);
    t.bisection.get_or_insert(d::BISECTION_MM * u);
    task_defaults(&mut j.task, u);
    j
}

/// The length defaults of a task written out (`u`: job units per mm); a comparison's
/// processes each as their own task, its tools and length rates too.
fn task_defaults(task: &mut TaskSpec, u: f64) {
    use hotcut::spec::defaults as d;
    match task {
        TaskSpec::HotBlade(h) => {
            h.speed.get_or_insert(d::BLADE_SPEED_MM_PER_S * u);
            h.approach.get_or_insert(d::APPROACH_MM * u);
        }
        TaskSpec::FacadeSegmentation(s) => {
            s.speed.get_or_insert(d::BLADE_SPEED_MM_PER_S * u);
            s.approach.get_or_insert(d::APPROACH_MM * u);
            if let hotcut::facade_segmentation::SegAlgorithmSpec::LongestElastica {
                precision,
                ..
            } = &mut s.algorithm
            {
                precision.get_or_insert(d::PRECISION_MM * u);
            }
        }
        TaskSpec::Design(t) => {
            t.speed.get_or_insert(d::BLADE_SPEED_MM_PER_S * u);
            t.approach.get_or_insert(d::APPROACH_MM * u);
        }
        TaskSpec::RuledBlocks(r) => {
            r.floor.get_or_insert(d::RULED_FLOOR_MM * u);
        }
        TaskSpec::Compare(c) => {
            use hotcut::spec::compare::{RATE_DEFAULTS, STEPOVER_MM, TOOL_DIAMETER_MM};
            for p in &mut c.processes {
                each_process_task(p, |t| task_defaults(t, u));
                if let Some(t) = process_tool(p) {
                    t.diameter.get_or_insert(TOOL_DIAMETER_MM * u);
                    t.stepover.get_or_insert(STEPOVER_MM * u);
                }
            }
            let r = &mut c.rates;
            let fields = [
                &mut r.removal_rate,
                &mut r.finishing_feed,
                &mut r.wire_speed,
                &mut r.blade_speed,
            ];
            for (x, name) in fields.into_iter().zip([
                "removal_rate",
                "finishing_feed",
                "wire_speed",
                "blade_speed",
            ]) {
                let dflt = RATE_DEFAULTS.iter().find(|d| d.field == name).unwrap();
                x.get_or_insert(dflt.value * u.powi(dflt.length_power));
            }
        }
        _ => {}
    }
}

/// The job in `units`, every length scaled by `f` (new units per old unit), its input
/// files scaled into `dir`.
fn convert(job: &Job, base: &Path, units: Units, f: f64, dir: &Path) -> Job {
    let mut j = job.clone();
    j.units = units;
    j.surface = job.surface.as_ref().map(|s| match s {
        SurfaceSpec::HeightField { z, x, y } => SurfaceSpec::HeightField {
            z: scale_expression(z, f),
            x: (sc(x.0, f), sc(x.1, f)),
            y: (sc(y.0, f), sc(y.1, f)),
        },
        SurfaceSpec::Mesh { path, closed } => SurfaceSpec::Mesh {
            path: scale_file(&base.join(path), f, dir).display().to_string(),
            closed: *closed,
        },
        SurfaceSpec::Spline { path } => SurfaceSpec::Spline {
            path: scale_file(&base.join(path), f, dir).display().to_string(),
        },
    });
    if let Some(b) = j.block.as_mut() {
        b.size = sc3(b.size, f);
        b.origin = b.origin.map(|o| sc3(o, f));
    }
    if let Some(b) = j.blade.as_mut() {
        b.length *= f;
        b.max_curvature /= f;
        b.thickness = b.thickness.map(|v| v * f);
        b.width = b.width.map(|v| v * f);
        b.kerf = b.kerf.map(|k| sc(k, f));
        b.kerf_table = b
            .kerf_table
            .as_ref()
            .map(|t| t.iter().map(|&(v, k)| (sc(v, f), sc(k, f))).collect());
    }
    if let Some(w) = j.wire.as_mut() {
        w.tower_distance *= f;
        for x in [
            &mut w.kerf,
            &mut w.speed,
            &mut w.lead,
            &mut w.clearance,
            &mut w.max_speed,
        ] {
            *x = x.map(|v| v * f);
        }
        let pair = |p: (f64, f64)| (p.0 * f, p.1 * f);
        w.origin = w.origin.map(pair);
        if let Some(t) = w.kerf_table.as_mut() {
            t.iter_mut().for_each(|r| *r = pair(*r));
        }
        if let Some(t) = w.travel.as_mut() {
            t.along = pair(t.along);
            t.up = pair(t.up);
            t.b_along = t.b_along.map(pair);
            t.b_up = t.b_up.map(pair);
        }
    }
    if let Some(c) = j.cutting.curve.as_mut() {
        c.iter_mut().for_each(|p| *p = (p.0 * f, p.1 * f));
    }
    if let Some(c) = j.cell.as_mut() {
        scale_cell(c, f);
    }
    let t = &mut j.tolerance;
    for x in [&mut t.rms, &mut t.max, &mut t.smoothing, &mut t.bisection] {
        *x = x.map(|v| v * f);
    }
    convert_task(&mut j.task, base, f, dir);
    j
}

/// Every length of a task scaled by `f`, its input files scaled into `dir`.
fn convert_task(task: &mut TaskSpec, base: &Path, f: f64, dir: &Path) {
    match task {
        TaskSpec::HotBlade(h) => {
            h.speed = h.speed.map(|v| v * f);
            h.approach = h.approach.map(|v| v * f);
        }
        TaskSpec::FacadeSegmentation(s) => {
            s.speed = s.speed.map(|v| v * f);
            s.approach = s.approach.map(|v| v * f);
            use hotcut::facade_segmentation::SegAlgorithmSpec as A;
            match &mut s.algorithm {
                A::Inflection { .. } => {}
                A::Trace {
                    link_distance,
                    merge_distance,
                    ..
                } => {
                    *link_distance = link_distance.map(|v| v * f);
                    *merge_distance = merge_distance.map(|v| v * f);
                }
                A::LongestElastica {
                    precision,
                    max_step,
                } => {
                    *precision = precision.map(|v| v * f);
                    *max_step = max_step.map(|v| v * f);
                }
            }
        }
        TaskSpec::Design(d) => {
            d.speed = d.speed.map(|v| v * f);
            d.approach = d.approach.map(|v| v * f);
            d.design = scale_file(&base.join(&d.design), f, dir)
                .display()
                .to_string();
        }
        TaskSpec::FitCurves(c) => {
            if let hotcut::fit_curves::FitMethod::NumericalSpline { epsilon, .. } = &mut c.method {
                *epsilon *= f;
            }
            c.input = c
                .input
                .as_ref()
                .map(|p| scale_file(&base.join(p), f, dir).display().to_string());
        }
        TaskSpec::RuledBlocks(r) => r.floor = r.floor.map(|v| v * f),
        // no lengths: sample counts, fractions of the block, angles
        TaskSpec::Analyze(_) | TaskSpec::BlockSegmentation(_) | TaskSpec::PreCut(_) => {}
        TaskSpec::Compare(c) => {
            for p in &mut c.processes {
                each_process_task(p, |t| convert_task(t, base, f, dir));
                if let Some(t) = process_tool(p) {
                    for x in [&mut t.diameter, &mut t.stepover, &mut t.feed] {
                        *x = x.map(|v| v * f);
                    }
                    t.removal_rate = t.removal_rate.map(|v| v * f * f * f);
                }
            }
            let r = &mut c.rates;
            r.removal_rate = r.removal_rate.map(|v| v * f * f * f);
            for x in [&mut r.finishing_feed, &mut r.wire_speed, &mut r.blade_speed] {
                *x = x.map(|v| v * f);
            }
        }
    }
}

/// Calls `g` with a comparison's process as its own task (`TaskSpec`), and keeps what
/// `g` changed.
fn each_process_task(p: &mut Process, g: impl Fn(&mut TaskSpec)) {
    macro_rules! via {
        ($v:expr, $variant:ident) => {{
            let mut t = TaskSpec::$variant($v.clone());
            g(&mut t);
            if let TaskSpec::$variant(x) = t {
                *$v = x;
            }
        }};
    }
    match p {
        Process::Milling(m) => {
            if let MillingStock::BlockSegmentation(b) = &mut m.stock {
                via!(b, BlockSegmentation)
            }
        }
        Process::PreCutThenMilling(c) => via!(&mut c.pre_cut, PreCut),
        Process::HotWireRuled(r) => via!(r, RuledBlocks),
        Process::HotBlade(h) => via!(h, HotBlade),
        Process::FacadeSegmentation(s) => via!(s, FacadeSegmentation),
    }
}

/// A process's milling tool.
fn process_tool(p: &mut Process) -> Option<&mut hotcut::spec::compare::ToolSpec> {
    match p {
        Process::Milling(m) => Some(&mut m.tool),
        Process::PreCutThenMilling(c) => Some(&mut c.tool),
        _ => None,
    }
}

/// Every length of a `cell:` scaled by `f`.
fn scale_cell(c: &mut hotcut::spec::CellSpec, f: f64) {
    use hotcut::spec::ModelSpec;
    let frame = |fr: &mut hotcut::spec::FrameSpec| fr.origin = sc3(fr.origin, f);
    for r in c.robots.iter_mut().flatten() {
        frame(&mut r.base);
        if let ModelSpec::Custom(m) = &mut r.model {
            for v in [
                &mut m.a1, &mut m.a2, &mut m.b, &mut m.c1, &mut m.c2, &mut m.c3, &mut m.c4,
            ] {
                *v *= f;
            }
        }
    }
    for h in c.blade_holders.iter_mut().flatten() {
        if let Some(t) = h.tcp.as_mut() {
            frame(t);
        }
        h.cog = h.cog.map(|p| sc3(p, f));
    }
    if let Some(fx) = c.fixture.as_mut() {
        frame(fx);
    }
    if let Some(k) = c.block_carrier.as_mut() {
        frame(&mut k.grip);
        frame(&mut k.station);
    }
    c.air_speed = c.air_speed.map(|v| v * f);
    c.clearance = c.clearance.map(|v| v * f);
}

/// Compares report `a` with report `b` of the same job with every length multiplied by
/// `f` (< 1), at `path`: numbers equal (counts, fractions, angles) or scaled as a length
/// (×f), a curvature (÷f), an area, a volume, or an L2 distance along a curve (f^1.5).
fn compare(a: &Value, b: &Value, path: &str, f: f64, errors: &mut Vec<String>) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            let ok = [1.0, f, 1.0 / f, f * f, f * f * f, f * f.sqrt()]
                .iter()
                .any(|&s| {
                    // the same computation up to the rounding of the inputs and of the
                    // report's 9 digits. Residuals of exact fits are noise at the fits'
                    // grid (2⁻³⁰ of a section's length: 1 µm on 1 m, l2 ≈ 3·10⁻⁵ mm^1.5),
                    // which the ÷1000 can move: 10⁻⁴ (in millimetres) of slack
                    let xs = x * s;
                    (y - xs).abs() <= 1e-7 * y.abs().max(xs.abs()) + 1e-4 * s
                });
            if !ok {
                errors.push(format!("{path}: {x} vs {y}"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            if x.len() != y.len() {
                errors.push(format!("{path}: {} vs {} elements", x.len(), y.len()));
                return;
            }
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                compare(p, q, &format!("{path}/{i}"), f, errors);
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            for (k, p) in x {
                match y.get(k) {
                    Some(q) => compare(p, q, &format!("{path}/{k}"), f, errors),
                    None => errors.push(format!("{path}/{k}: missing")),
                }
            }
        }
        (Value::String(x), Value::String(y)) => {
            let units = |s: &str| matches!(s, "Millimetre" | "Metre" | "mm" | "m");
            // the input file's path differs (a scaled copy)
            let file = |s: &str| s.starts_with("file ");
            let design = path.ends_with("/design");
            // Compare's reasons quote lengths in job units, and its rates' units name the
            // unit; their statuses and numbers are compared
            let compare_key = path.starts_with("/processes/") || path.starts_with("/rates/");
            let quoted = compare_key
                && ["/reason", "/why_not", "/unit"]
                    .iter()
                    .any(|e| path.ends_with(e));
            if !(x == y || design || quoted || units(x) && units(y) || file(x) && file(y)) {
                errors.push(format!("{path}: {x:?} vs {y:?}"));
            }
        }
        _ => {
            if a != b {
                errors.push(format!("{path}: {a} vs {b}"));
            }
        }
    }
}

fn report(job: Job, path: &Path, out: &Path) -> Value {
    let job = resolve(path, job).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let run = run_job(&job, out, &NoProgress).unwrap();
    serde_json::from_str(&std::fs::read_to_string(run.dir.join("report.json")).unwrap()).unwrap()
}

/// Every job of `jobs/`, sorted, then those of `jobs/third-party/` when their data is
/// present (laid out in a temporary folder that lives as long as the returned guard).
fn jobs(test: &str) -> (Option<tempfile::TempDir>, Vec<PathBuf>) {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join("jobs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 20);
    let third = third_party_jobs(test).map(|(dir, more)| {
        paths.extend(more);
        dir
    });
    (third, paths)
}

/// The folder a job's relative paths are read from.
fn base_of(path: &Path) -> PathBuf {
    path.parent().map(Path::to_path_buf).unwrap_or_default()
}

/// Runs every job as written and converted by `convert(job, base, dir)`, and returns the
/// differences between the two reports, per job (`scale`: converted per original length).
fn differences(
    prepare: impl Fn(&Job) -> Job,
    convert: impl Fn(&Job, &Path, &Path) -> Job,
    scale: impl Fn(&Job) -> f64,
) -> Vec<(String, Vec<String>)> {
    let (_third, paths) = jobs("units: differences");
    let mut out = Vec::new();
    for path in &paths {
        let base = base_of(path);
        let text = std::fs::read_to_string(path).unwrap();
        let job = prepare(&parse_job(path, &text).unwrap());
        let dir = tempfile::tempdir().unwrap();
        let other = convert(&job, &base, dir.path());
        let other_path = dir.path().join(path.file_name().unwrap());
        let mut mine = report(job.clone(), path, &dir.path().join("a"));
        let mut theirs = report(other, &other_path, &dir.path().join("b"));
        // the robot cell has a size of its own (an arm does not shrink with the job):
        // `every_job_gives_the_same_results_in_millimetres_and_in_metres` checks it
        for r in [&mut mine, &mut theirs] {
            if let Some(o) = r.as_object_mut() {
                o.remove("cell");
            }
            without_prices(r);
        }
        let mut errors = Vec::new();
        // counts and verdicts exactly
        if mine.get("counts") != theirs.get("counts") {
            errors.push(format!(
                "counts: {:?} vs {:?}",
                mine.get("counts"),
                theirs.get("counts")
            ));
        }
        // `compare` takes the larger-unit report second
        let s = scale(&job);
        if s < 1.0 {
            compare(&mine, &theirs, "", s, &mut errors);
        } else {
            compare(&theirs, &mine, "", 1.0 / s, &mut errors);
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        out.push((name, errors));
    }
    out
}

/// A `Compare` report without what a smaller part really costs less for: a cost adds
/// the EPS bought (m³, which scales) to machine and operator hours (which do not: times
/// are lengths over speeds, volumes over removal rates), so costs, the margin between
/// them, the rate changes that flip the ranking, and the ranking itself, are not scaled
/// numbers. Figures, hours and m³ stay, and are compared; the mm/m test compares all.
fn without_prices(r: &mut Value) {
    if r["task"] != "Compare" {
        return;
    }
    if let Some(o) = r.as_object_mut() {
        for k in ["margin_percent", "sensitivity", "ranking", "winner"] {
            o.remove(k);
        }
    }
    for p in r["processes"].as_array_mut().into_iter().flatten() {
        if let Some(o) = p.as_object_mut() {
            o.remove("cost");
            o.remove("rank");
        }
    }
}

fn summary(diffs: &[(String, Vec<String>)]) -> String {
    diffs
        .iter()
        .filter(|(_, e)| !e.is_empty())
        .map(|(name, e)| {
            let shown: Vec<&String> = e.iter().take(6).collect();
            format!(
                "{name}: {} differences\n  {}",
                e.len(),
                shown
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("\n  ")
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// No absolute length anywhere in the code: every job scaled by 2⁻⁴ (exact in floating
/// point: the scaled inputs are the same numbers with another exponent; small enough a
/// step that the machine limits in millimetres, wire speed and travel, still hold), its
/// defaults written out, gives the same results with every length scaled.
#[test]
fn every_job_is_invariant_under_an_exact_change_of_scale() {
    let f = 1.0 / 16.0;
    let diffs = differences(
        with_defaults,
        |job, base, dir| convert(job, base, job.units, f, dir),
        |_| f,
    );
    let s = summary(&diffs);
    assert!(s.is_empty(), "{s}");
}

/// Every job in millimetres and in metres (÷1000, inputs included): the same counts,
/// pieces, blocks, verdicts and inflections, every number the same or scaled.
///
/// ÷1000 rounds every input, and the segmentations, pre-cuts and fits follow near-ties
/// (accept/reject decisions, constraint exchanges, Levenberg–Marquardt paths) that a last
/// bit can flip. They agree because each computes in a unit frame of its own (the block's
/// or the curve's, inputs rounded to a grid far below any tolerance), where the two jobs
/// are the same numbers.
#[test]
fn every_job_gives_the_same_results_in_millimetres_and_in_metres() {
    let (_third, paths) = jobs("every_job_gives_the_same_results_in_millimetres_and_in_metres");
    let mut failures = Vec::new();
    for path in &paths {
        let base = base_of(path);
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let job = parse_job(path, &std::fs::read_to_string(path).unwrap()).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let (units, f) = match job.units {
            Units::Millimetre => (Units::Metre, 1e-3),
            Units::Metre => (Units::Millimetre, 1e3),
        };
        let other = convert(&job, &base, units, f, dir.path());
        let mine = report(job.clone(), path, &dir.path().join("a"));
        let theirs = report(other, &dir.path().join(&name), &dir.path().join("b"));
        let (mm, m) = match job.units {
            Units::Millimetre => (mine, theirs),
            Units::Metre => (theirs, mine),
        };
        let mut errors = Vec::new();
        if mm.get("counts") != m.get("counts") {
            errors.push("counts differ".to_string());
        }
        compare(&mm, &m, "", 1e-3, &mut errors);
        if !errors.is_empty() {
            failures.push(format!("{name}: {}", errors.join("; ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn height_field_expressions_are_rescaled_by_token() {
    assert_eq!(
        scale_expression("exp(x)*sin(y/100)+x2", 1e-3),
        "(exp((x/0.001))*sin((y/0.001)/100)+x2)*0.001"
    );
}
