//! The robustness suite: several hundred hostile jobs and inputs, generated from small
//! valid jobs of every task, each run by the `hotcut` binary under a wall-clock and a
//! memory limit. The contract checked on every one:
//! - no panic (exit 101), abort (134) or signal, no timeout, no out-of-memory;
//! - exit 0 or 1;
//! - exit 1 leaves no output folder and no temporary folder;
//! - exit 0 leaves a whole folder: `report.json`, and machine files (G-code, RAPID) that
//!   are not empty and hold no non-finite number.
//!
//! The classes: every numeric literal of every job at 0, −1, 1e-300, 1e300, NaN, ±inf;
//! oblique, tilted, vertical and overflowing cutting directions for every task; deep, long
//! and ill-defined expressions; huge, degenerate, truncated and malformed meshes;
//! truncated, empty, binary, oversized and deeply nested job files.
//!
//! Round two (`hostile/round_two.rs`) adds a generated family per class of issue 36, each
//! with its own checks on top: device and FIFO inputs, large typed inputs, estimates,
//! dialect lines, RAPID names, control characters, f32 bounds, validation parity and
//! output-entry types.

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Wall-clock limit per run.
const WALL: Duration = Duration::from_secs(120);
/// Address-space limit per run, KiB (`ulimit -v`).
const MEMORY_KIB: u64 = 6_000_000;

#[path = "common/gcode.rs"]
mod gcode;
#[path = "hostile/round_two.rs"]
mod round_two;

/// One hostile case: the files of its folder, the job file to run.
struct Case {
    label: String,
    files: Vec<(String, Vec<u8>)>,
    /// Round two's set-up and checks.
    extra: round_two::Extra,
}

impl Case {
    fn job(label: impl Into<String>, text: &str) -> Self {
        Self {
            label: label.into(),
            files: vec![("job.ron".into(), text.as_bytes().to_vec())],
            extra: round_two::Extra::default(),
        }
    }
    fn with(mut self, name: &str, bytes: &[u8]) -> Self {
        self.files.push((name.into(), bytes.to_vec()));
        self
    }
}

const HEIGHT: &str =
    r#"surface: HeightField(z: "50*sin(y/100) + 10*cos(x/80)", x: (0, 300), y: (0, 900)),"#;
const COMMON: &str = r#"block: Block(size: (300, 450, 300)), blade: Blade(length: 700, max_curvature: 0.011, max_inflections: 2), cutting: Cutting(direction: (1, 0, 0), sections: 4), tolerance: Tolerance(rms: 0.5, max: 2.0),"#;

/// The design file of the `design` base: two blocks, a G¹ Bézier per block at the entry
/// and exit faces.
const DESIGN: &str = r#"{"blocks": {"Grid": {"origin": [0, 0, 0], "size": [600, 400, 400], "count": [1, 2]}}, "cuts": [{"id": "c", "direction": "X", "blocks": ["x0y0", "x0y1"], "stations": [{"at": 0, "curve": {"Bezier": [[[0, 150], [150, 300], [300, 300], [400, 250]], [[400, 250], [500, 200], [700, 150], [800, 250]]]}}, {"at": 1, "curve": {"Bezier": [[[0, 200], [150, 320], [300, 320], [400, 280]], [[400, 280], [550, 220], [700, 200], [800, 300]]]}}]}]}"#;

/// A base job: label, job text, extra files.
type Base = (&'static str, String, Vec<(String, Vec<u8>)>);

/// Small valid jobs of every task.
fn bases() -> Vec<Base> {
    let job = |task: &str, outputs: &str| {
        format!(r#"Job(name: "h", {HEIGHT} {COMMON} task: {task}, outputs: [{outputs}], seed: 3)"#)
    };
    let cube = cube_obj(100.0);
    vec![
        ("analyze", job("Analyze(samples: 200)", "Report, Svg"), vec![]),
        (
            "fit",
            job("FitCurves(samples: 40)", "Report"),
            vec![],
        ),
        (
            "blade",
            job(
                "HotBlade(targets_per_block: 6, samples: 30, refine: 1)",
                "Report, RobotTargets(per_block: 6), Rapid",
            ),
            vec![],
        ),
        (
            "trace",
            job("FacadeSegmentation(algorithm: Trace(), samples: 24)", "Report, Rapid"),
            vec![],
        ),
        (
            "inflection",
            job(
                "FacadeSegmentation(algorithm: Inflection(symmetric: true), samples: 24)",
                "Report, Rapid",
            ),
            vec![],
        ),
        (
            "longest",
            job(
                "FacadeSegmentation(algorithm: LongestElastica(precision: 5), samples: 24)",
                "Report, Rapid",
            ),
            vec![],
        ),
        (
            "cell",
            job(
                "HotBlade(targets_per_block: 5, samples: 30, refine: 1)",
                "Report, Rapid",
            )
            .replace(
                "task:",
                r#"cell: Cell(robots: [Robot(model: Custom(name: "c", a1: 150, a2: -115, b: 0, c1: 445, c2: 700, c3: 795, c4: 85, offsets: [0, 0, -90, 0, 0, 0], signs: [1, 1, 1, 1, 1, 1], limits: [(-180, 180), (-95, 155), (-180, 75), (-400, 400), (-120, 120), (-400, 400)]), base: Frame(origin: (150, -1100, 0), rotation: (90, 0, 0))), Robot(model: Irb4600, base: Frame(origin: (150, 1300, 0), rotation: (-90, 0, 0)))], blade_holders: [Holder(robot: 0, tcp: Frame(origin: (0, 0, 150), rotation: (0, 0, -90)), mass: 2, cog: (0, 0, 70)), Holder(robot: 1, tcp: Frame(origin: (0, 0, 150), rotation: (180, 0, -90)), mass: 2, cog: (0, 0, 70))], fixture: Frame(origin: (0, -225, 300), rotation: (0, 0, 0)), heat: Heat(signal: "doHeat", preheat_s: 2), air_speed: 120, clearance: 80, strict: false), task:"#,
            ),
            vec![],
        ),
        (
            "carried",
            job(
                "HotBlade(targets_per_block: 5, samples: 30, refine: 1)",
                "Report, Rapid",
            )
            .replace(
                "task:",
                r#"cell: Cell(robots: [Robot(model: Irb2600, base: Frame(origin: (0, -1100, 0), rotation: (90, 0, 0))), Robot(model: Irb2600, base: Frame(origin: (0, 1100, 0), rotation: (-90, 0, 0))), Robot(model: Irb4600, base: Frame(origin: (-1200, 0, 0)))], block_carrier: Carrier(robot: 2, grip: Frame(origin: (-150, -225, -200), rotation: (0, -75, 0)), mass: 30, station: Frame(origin: (0, 0, 1000), rotation: (90, 0, 90)))), task:"#,
            ),
            vec![],
        ),
        (
            "precut",
            r#"Job(name: "h", surface: HeightField(z: "100 + 80*exp(-((x/200)^2 + (y/200)^2))", x: (-300, 300), y: (-300, 300)), block: Block(size: (600, 600, 300), origin: (-300, -300, 0)), wire: Wire(tower_distance: 900, kerf: 1.5, speed: 300, lead: 20, clearance: 50), task: PreCut(legs: 2, directions: [X], sections: 8, samples: 8, controls: 5), outputs: [Report, GCode, Csv])"#.to_string(),
            vec![],
        ),
        (
            "design",
            r#"Job(name: "h", blade: Blade(length: 900, max_curvature: 0.011, max_inflections: 2), task: Design(design: "d.json", speed: 7, approach: 50), outputs: [Report, Svg, Gltf, RobotTargets(), Rapid])"#.to_string(),
            vec![("d.json".to_string(), DESIGN.as_bytes().to_vec())],
        ),
        (
            "blocks",
            r#"Job(name: "h", surface: Mesh(path: "cube.obj", closed: true), block: Block(size: (60, 60, 60)), task: BlockSegmentation(restarts: 1, max_iterations: 5), outputs: [Report, Blocks], seed: 7)"#.to_string(),
            vec![("cube.obj".to_string(), cube.into_bytes())],
        ),
    ]
}

/// A closed cube of edge `a` as OBJ text.
fn cube_obj(a: f64) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let (x, y, z) = (i & 1, (i >> 1) & 1, (i >> 2) & 1);
        s += &format!("v {} {} {}\n", x as f64 * a, y as f64 * a, z as f64 * a);
    }
    for f in [
        [1, 3, 4],
        [1, 4, 2],
        [5, 6, 8],
        [5, 8, 7],
        [1, 2, 6],
        [1, 6, 5],
        [3, 7, 8],
        [3, 8, 4],
        [1, 5, 7],
        [1, 7, 3],
        [2, 4, 8],
        [2, 8, 6],
    ] {
        s += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    s
}

/// Byte ranges of the numeric literals of `text` outside string literals.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let (mut i, mut quoted) = (0, false);
    while i < b.len() {
        let c = b[i];
        if c == b'"' {
            quoted = !quoted;
            i += 1;
            continue;
        }
        let starts = c.is_ascii_digit()
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if !quoted && starts {
            let s = if i > 0 && b[i - 1] == b'-' { i - 1 } else { i };
            let mut e = i;
            while e < b.len()
                && (b[e].is_ascii_digit()
                    || b[e] == b'.'
                    || b[e] == b'e'
                    || b[e] == b'E'
                    || ((b[e] == b'-' || b[e] == b'+') && (b[e - 1] == b'e' || b[e - 1] == b'E')))
            {
                e += 1;
            }
            out.push((s, e));
            i = e;
            continue;
        }
        i += 1;
    }
    out
}

/// Every hostile case.
fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let values = ["0", "-1", "1e-300", "1e300", "NaN", "inf", "-inf"];
    for (label, text, files) in bases() {
        let add = |out: &mut Vec<Case>, l: String, t: String| {
            let mut c = Case::job(l, &t);
            for (n, b) in &files {
                c = c.with(n, b);
            }
            out.push(c);
        };
        // the base itself must run
        add(&mut out, format!("{label}: as written"), text.clone());
        // every numeric literal at every hostile value
        for (k, (s, e)) in numbers(&text).into_iter().enumerate() {
            for v in values {
                let t = format!("{}{v}{}", &text[..s], &text[e..]);
                add(
                    &mut out,
                    format!("{label}: number {k} ({}) = {v}", &text[s..e]),
                    t,
                );
            }
        }
        // every numeric literal of a design file at a hostile value (JSON has no NaN or
        // infinity: those make it unreadable, once is enough)
        for (name, bytes) in files.iter().filter(|(n, _)| n.ends_with(".json")) {
            let design = String::from_utf8_lossy(bytes).into_owned();
            for (k, (s, e)) in numbers(&design).into_iter().enumerate() {
                for v in ["0", "-1", "1e-300", "1e300", "-1e300"] {
                    let mut c = Case::job(
                        format!("{label}: {name} number {k} ({}) = {v}", &design[s..e]),
                        &text,
                    );
                    for (n, b) in &files {
                        let b = if n == name {
                            format!("{}{v}{}", &design[..s], &design[e..]).into_bytes()
                        } else {
                            b.clone()
                        };
                        c = c.with(n, &b);
                    }
                    out.push(c);
                }
            }
            let mut c = Case::job(format!("{label}: {name} with NaN"), &text);
            for (n, b) in &files {
                let b = if n == name {
                    design.replacen("150", "NaN", 1).into_bytes()
                } else {
                    b.clone()
                };
                c = c.with(n, &b);
            }
            out.push(c);
        }
        // cutting directions: oblique, tilted, vertical, overflowing, underflowing
        if text.contains("direction: (1, 0, 0)") {
            for d in [
                "(1, 1, 0)",
                "(1, 0.2, 0)",
                "(-1, 0.3, 0)",
                "(0, 1, 0)",
                "(0, -1, 0)",
                "(1, 1, 1)",
                "(1, 0, 0.3)",
                "(0, 0, 1)",
                "(1e308, 1e308, 0)",
                "(1e-300, 0, 0)",
            ] {
                add(
                    &mut out,
                    format!("{label}: direction {d}"),
                    text.replace("direction: (1, 0, 0)", &format!("direction: {d}")),
                );
            }
        }
        // truncated job files
        for cut in [1, 5, 17, text.len() / 3, text.len() / 2, text.len() - 2] {
            add(
                &mut out,
                format!("{label}: truncated at {cut}"),
                text[..cut].to_string(),
            );
        }
        // a byte-order mark, CRLF line ends
        add(&mut out, format!("{label}: BOM"), format!("\u{feff}{text}"));
    }
    // expressions, on the Analyze and HotBlade jobs
    let long_sum = vec!["x"; 3000].join("+");
    let too_long = vec!["x"; 20_000].join("+");
    let exprs = [
        format!("{}x{}", "(".repeat(12_000), ")".repeat(12_000)),
        format!("{}x", "-".repeat(30_000)),
        format!("{}*x", vec!["1"; 1000].join("^")),
        long_sum,
        too_long,
        "x/0".into(),
        "ln(-1) + x".into(),
        "sqrt(x - 1000)".into(),
        "1e308*1e308 + x".into(),
        "exp(1000) + y".into(),
        "0*x".into(),
        "1/(x - 150)".into(),
        "tan(x/95.49)".into(),
        "abs(y - 450)".into(),
        "x^y".into(),
        "".into(),
        "sin(".into(),
    ];
    for (label, text, _) in bases()
        .into_iter()
        .filter(|b| b.0 == "analyze" || b.0 == "blade" || b.0 == "trace")
    {
        for (k, e) in exprs.iter().enumerate() {
            let t = text.replace("50*sin(y/100) + 10*cos(x/80)", e);
            out.push(Case::job(
                format!("{label}: expression {k} ({} bytes)", e.len()),
                &t,
            ));
        }
    }
    // meshes, for Analyze (open) and BlockSegmentation (closed)
    let cube = cube_obj(100.0);
    let meshes: Vec<(&str, Vec<u8>)> = vec![
        ("huge coordinates", cube_obj(1e29).into_bytes()),
        ("coordinates 1e300", cube_obj(1e300).into_bytes()),
        ("tiny coordinates", cube_obj(1e-200).into_bytes()),
        (
            "NaN vertex",
            cube.replacen("v 0 0 0", "v NaN 0 0", 1).into_bytes(),
        ),
        (
            "repeated face vertex",
            format!("{cube}f 1 1 2\n").into_bytes(),
        ),
        (
            "non-manifold",
            format!("{cube}v 50 50 300\nf 1 2 9\n").into_bytes(),
        ),
        (
            "index out of range",
            format!("{cube}f 1 2 99\n").into_bytes(),
        ),
        ("empty", Vec::new()),
        ("truncated", cube.as_bytes()[..cube.len() / 2 - 3].to_vec()),
        (
            "binary",
            (0..4096u32)
                .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
                .collect(),
        ),
        (
            "one triangle",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
        ),
        (
            "all degenerate",
            b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 3 2 1\n".to_vec(),
        ),
        (
            "BOM and CRLF",
            format!("\u{feff}{}", cube.replace('\n', "\r\n")).into_bytes(),
        ),
        ("moved by 3.1e6", {
            let mut s = String::new();
            for line in cube.lines() {
                if let Some(rest) = line.strip_prefix("v ") {
                    let v: Vec<f64> = rest.split(' ').map(|t| t.parse().unwrap()).collect();
                    s += &format!("v {} {} {}\n", v[0] + 3.1e6, v[1] + 3.1e6, v[2] + 1e6);
                } else {
                    s += line;
                    s.push('\n');
                }
            }
            s.into_bytes()
        }),
    ];
    for (label, bytes) in &meshes {
        let analyze = r#"Job(name: "h", surface: Mesh(path: "m.obj"), cutting: Cutting(sections: 3), task: Analyze(samples: 100), outputs: [Report])"#;
        out.push(Case::job(format!("mesh {label}: Analyze"), analyze).with("m.obj", bytes));
        let blocks = r#"Job(name: "h", surface: Mesh(path: "m.obj", closed: true), block: Block(size: (60, 60, 60)), task: BlockSegmentation(restarts: 1, max_iterations: 5), outputs: [Report])"#;
        out.push(
            Case::job(format!("mesh {label}: BlockSegmentation"), blocks).with("m.obj", bytes),
        );
    }
    // job files that are not jobs
    out.push(Case::job("empty job file", ""));
    out.push(Case {
        label: "binary job file".into(),
        files: vec![(
            "job.ron".into(),
            (0..2048u32).map(|i| (i * 37 % 251) as u8).collect(),
        )],
        extra: round_two::Extra::default(),
    });
    out.push(Case::job(
        "oversized job file",
        &format!("// {}\n", "x".repeat(3 << 20)),
    ));
    out.push(Case::job(
        "deeply nested job",
        &format!(
            "Job(name: \"h\", task: Analyze(), surface: {}",
            "(".repeat(200_000)
        ),
    ));
    out.push(Case::job(
        "two outputs of a kind",
        &format!(r#"Job(name: "h", {HEIGHT} task: Analyze(), outputs: [Report, Report])"#),
    ));
    out
}

/// Machine files (G-code, RAPID, wire CSV) checked.
static MACHINE_FILES: AtomicUsize = AtomicUsize::new(0);

/// What a run did.
struct Outcome {
    code: Option<i32>,
    took: Duration,
    stdout: String,
    stderr: String,
}

/// Runs `hotcut <args>` in `dir` under the limits.
fn run_with(dir: &Path, args: &[&str]) -> Outcome {
    let start = Instant::now();
    let quoted: Vec<String> = args.iter().map(|a| format!("'{a}'")).collect();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {MEMORY_KIB} && exec \"$0\" {}",
            quoted.join(" ")
        ))
        .arg(env!("CARGO_BIN_EXE_hotcut"))
        // the address-space limit must not depend on the machine's core count: a few
        // worker threads and malloc arenas, whatever the machine
        .env("RAYON_NUM_THREADS", "2")
        .env("MALLOC_ARENA_MAX", "2")
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    let drain = |mut r: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut b = Vec::new();
            let _ = r.read_to_end(&mut b);
            String::from_utf8_lossy(&b).into_owned()
        })
    };
    let err = drain(Box::new(child.stderr.take().expect("piped")));
    let out = drain(Box::new(child.stdout.take().expect("piped")));
    let code = loop {
        if let Some(status) = child.try_wait().expect("waits") {
            break status.code();
        }
        if start.elapsed() > WALL {
            let _ = child.kill();
            let _ = child.wait();
            break Some(-1);
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Outcome {
        code,
        took: start.elapsed(),
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
    }
}

/// What is wrong with a finished run, if anything.
fn judge(dir: &Path, o: &Outcome) -> Option<String> {
    if o.code == Some(-1) {
        return Some(format!("timed out after {:?}", o.took));
    }
    if o.stderr.contains("panicked") || o.stderr.contains("memory allocation") {
        return Some(format!("panicked: {}", o.stderr));
    }
    let out = dir.join("out");
    let temporaries: Vec<String> = std::fs::read_dir(&out)
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.contains(".tmp-"))
                .collect()
        })
        .unwrap_or_default();
    if !temporaries.is_empty() {
        return Some(format!("temporary folders left: {temporaries:?}"));
    }
    match o.code {
        Some(1) => out
            .join("h")
            .exists()
            .then(|| format!("exit 1 but an output folder was written: {}", o.stderr)),
        Some(0) => {
            let folder = out.join("h");
            if !folder.join("report.json").is_file() {
                return Some("exit 0 without report.json".into());
            }
            for e in std::fs::read_dir(&folder).ok()?.flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                if ![".gcode", ".ngc", ".nc", ".mod", ".csv"]
                    .iter()
                    .any(|x| name.ends_with(x))
                {
                    continue;
                }
                MACHINE_FILES.fetch_add(1, Ordering::Relaxed);
                let text = std::fs::read_to_string(e.path()).unwrap_or_default();
                if text.trim().is_empty() {
                    return Some(format!("{name} is empty"));
                }
                // `inf`, `NaN`, or a G-code word of one (`Xinf`, `F-inf`)
                let lower = text.to_ascii_lowercase();
                let non_finite = lower.split(|c: char| !c.is_ascii_alphanumeric()).any(|t| {
                    let t = t
                        .strip_prefix(|c: char| c.is_ascii_alphabetic() && t.len() == 4)
                        .unwrap_or(t);
                    t == "inf" || t == "nan" || t == "infinity"
                });
                if non_finite {
                    return Some(format!("{name} holds a non-finite number"));
                }
            }
            None
        }
        other => Some(format!("exit {other:?}: {}", o.stderr)),
    }
}

/// What a batch of cases did.
struct Tally {
    failures: Vec<String>,
    ok: usize,
    refused: usize,
    slowest: (Duration, String),
    /// The ten slowest cases.
    top: Vec<(Duration, String)>,
    /// Time by the label's first word (the base or family), most first.
    by_prefix: Vec<(Duration, String)>,
}

/// Runs every case on two workers, each under the limits, and judges it.
fn run_all(cases: &[Case]) -> Tally {
    let next = AtomicUsize::new(0);
    let failures: Mutex<Vec<String>> = Mutex::new(Vec::new());
    let counts: Mutex<[usize; 2]> = Mutex::new([0, 0]);
    let slowest: Mutex<(Duration, String)> = Mutex::new((Duration::ZERO, String::new()));
    let all: Mutex<Vec<(Duration, String)>> = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(case) = cases.get(i) else { break };
                let dir = tempfile::tempdir().expect("temp dir");
                for (name, bytes) in &case.files {
                    std::fs::write(dir.path().join(name), bytes).expect("writes");
                }
                round_two::set_up(dir.path(), &case.extra);
                let args = case.extra.args();
                let args: Vec<&str> = args.iter().map(String::as_str).collect();
                let o = run_with(dir.path(), &args);
                let why =
                    judge(dir.path(), &o).or_else(|| round_two::judge(dir.path(), &case.extra, &o));
                if let Some(why) = why {
                    failures
                        .lock()
                        .unwrap()
                        .push(format!("{}: {why}", case.label));
                }
                if let Some(c @ (0 | 1)) = o.code {
                    counts.lock().unwrap()[c as usize] += 1;
                }
                if case.label.ends_with(": as written") && o.code != Some(0) {
                    failures
                        .lock()
                        .unwrap()
                        .push(format!("{}: a base job must run: {}", case.label, o.stderr));
                }
                all.lock().unwrap().push((o.took, case.label.clone()));
                let mut slow = slowest.lock().unwrap();
                if o.took > slow.0 {
                    *slow = (o.took, case.label.clone());
                }
            });
        }
    });
    let [ok, refused] = *counts.lock().unwrap();
    let mut top = all.into_inner().unwrap();
    let mut by_prefix: Vec<(Duration, String)> = Vec::new();
    for (d, label) in &top {
        let p = label.split(':').next().unwrap_or_default().to_string();
        match by_prefix.iter_mut().find(|e| e.1 == p) {
            Some(e) => e.0 += *d,
            None => by_prefix.push((*d, p)),
        }
    }
    by_prefix.sort_by_key(|e| std::cmp::Reverse(e.0));
    top.sort_by_key(|e| std::cmp::Reverse(e.0));
    top.truncate(10);
    Tally {
        top,
        by_prefix,
        failures: failures.into_inner().unwrap(),
        ok,
        refused,
        slowest: slowest.into_inner().unwrap(),
    }
}

#[test]
fn hostile_jobs_keep_the_contract() {
    let cases = cases();
    assert!(cases.len() >= 300, "{} cases", cases.len());
    let t = run_all(&cases);
    println!(
        "{} hostile cases: {} ran (exit 0), {} refused (exit 1); slowest {:?} ({})",
        cases.len(),
        t.ok,
        t.refused,
        t.slowest.0,
        t.slowest.1
    );
    for (d, label) in &t.top {
        println!("  {d:>10.2?}  {label}");
    }
    for (d, prefix) in &t.by_prefix {
        println!("  {d:>10.2?}  in all for {prefix}");
    }
    assert!(
        t.failures.is_empty(),
        "{} broken:\n{}",
        t.failures.len(),
        t.failures.join("\n")
    );
    // every base job runs as written, and machine files were read
    assert!(t.ok >= bases().len());
    let machine = MACHINE_FILES.load(Ordering::Relaxed);
    println!("{machine} machine files read back");
    assert!(machine > 100, "{machine} machine files");
}

#[test]
fn round_two_families_keep_the_contract() {
    let cases = round_two::cases();
    let t = run_all(&cases);
    println!(
        "{} round-two cases: {} ran (exit 0), {} refused (exit 1); slowest {:?} ({})",
        cases.len(),
        t.ok,
        t.refused,
        t.slowest.0,
        t.slowest.1
    );
    for (family, n) in round_two::family_counts(&cases) {
        println!("  {family}: {n} cases");
    }
    assert!(
        t.failures.is_empty(),
        "{} broken:\n{}",
        t.failures.len(),
        t.failures.join("\n")
    );
    round_two::totals(&cases);
}
