//! Estimates that count what the run does: each case that once slipped past validation
//! (issue 36) is scaled up until it is just under a work limit, then run, and its wall
//! time must stay within 3× of the time its estimate implies (10⁸ steps per second),
//! plus half a second for starting the process and writing files, and the files it writes
//! must not exceed the estimate `--max-output` is checked against. Scaled once more it is
//! refused at validation, naming the field to change.
//!
//! The cases: `FitCurves` with many curves from a file; `FitCurves` with the numerical
//! spline at 48 control points; a `Design` cut through many blocks at many stations; a
//! `HotBlade` job whose custom arm may turn ±720° on every joint.

mod common;

use std::path::Path;
use std::time::Instant;

use common::{hotcut, stderr, write};

/// A case: a label, the work limit it is scaled against, and the files of a job of a
/// given scale (the job file first).
struct Case {
    label: &'static str,
    work: f64,
    files: fn(usize) -> Vec<(String, String)>,
}

fn fit_curves(n: usize) -> Vec<(String, String)> {
    let curves: Vec<String> = (0..n)
        .map(|i| {
            let pts: Vec<String> = (0..10)
                .map(|x| {
                    format!(
                        "[{}, {:.4}]",
                        x * 10,
                        30.0 * (x as f64 / 3.0 + i as f64).sin()
                    )
                })
                .collect();
            format!(r#"{{"id": "c{i}", "points": [{}]}}"#, pts.join(", "))
        })
        .collect();
    vec![
        (
            "job.ron".into(),
            r#"Job(name: "e", units: Millimetre, task: FitCurves(input: "c.json"), outputs: [Report, Svg, Html])"#.into(),
        ),
        ("c.json".into(), format!(r#"{{"curves": [{}]}}"#, curves.join(", "))),
    ]
}

fn numerical(n: usize) -> Vec<(String, String)> {
    let curves: Vec<String> = (0..n)
        .map(|i| {
            let pts: Vec<String> = (0..200)
                .map(|x| {
                    format!(
                        "[{}, {:.4}]",
                        x * 2,
                        30.0 * (x as f64 / 30.0 + i as f64).sin()
                    )
                })
                .collect();
            format!(r#"{{"id": "c{i}", "points": [{}]}}"#, pts.join(", "))
        })
        .collect();
    vec![
        (
            "job.ron".into(),
            r#"Job(name: "e", units: Millimetre, task: FitCurves(input: "c.json", method: NumericalSpline(epsilon: 1.0, control_points: 48)), outputs: [Report])"#.into(),
        ),
        ("c.json".into(), format!(r#"{{"curves": [{}]}}"#, curves.join(", "))),
    ]
}

/// One cut along x through `n` blocks side by side at `n` stations: S-shaped pieces with
/// level ends, so that neighbours join G¹, a little deeper at every station.
fn design(n: usize) -> Vec<(String, String)> {
    let (blocks, stations) = (n.clamp(1, 100), n.clamp(2, 100));
    let station = |s: usize| {
        let h = 80.0 + 40.0 * s as f64 / (stations - 1) as f64;
        let pieces: Vec<String> = (0..blocks)
            .map(|j| {
                let y = 400.0 * j as f64;
                let (a, b) = if j % 2 == 0 {
                    (150.0, 150.0 + h)
                } else {
                    (150.0 + h, 150.0)
                };
                format!(
                    "[[{y}, {a}], [{}, {a}], [{}, {b}], [{}, {b}]]",
                    y + 150.0,
                    y + 250.0,
                    y + 400.0
                )
            })
            .collect();
        format!(
            r#"{{"at": {}, "curve": {{"Bezier": [{}]}}}}"#,
            s as f64 / (stations - 1) as f64,
            pieces.join(", ")
        )
    };
    let ids: Vec<String> = (0..blocks).map(|j| format!(r#""x0y{j}""#)).collect();
    let list: Vec<String> = (0..stations).map(station).collect();
    let d = format!(
        r#"{{"blocks": {{"Grid": {{"origin": [0, 0, 0], "size": [600, 400, 400], "count": [1, {blocks}]}}}}, "cuts": [{{"id": "c", "direction": "X", "blocks": [{}], "stations": [{}]}}]}}"#,
        ids.join(", "),
        list.join(", ")
    );
    vec![
        (
            "job.ron".into(),
            r#"Job(name: "e", units: Millimetre, blade: Blade(length: 900, max_curvature: 0.011, max_inflections: 2), task: Design(design: "d.json"), outputs: [Report, Svg, Gltf, Html])"#.into(),
        ),
        ("d.json".into(), d),
    ]
}

/// A hot-blade job cut by a cell whose custom arm may turn ±720° on every joint; `n`
/// targets per block.
fn wide_arm(n: usize) -> Vec<(String, String)> {
    let job = format!(
        r#"Job(name: "e", surface: HeightField(z: "50*sin(y/100) + 10*cos(x/80)", x: (0, 300), y: (0, 900)), block: Block(size: (300, 450, 300)), blade: Blade(length: 700, max_curvature: 0.011, max_inflections: 2), cutting: Cutting(direction: (1, 0, 0), sections: 4), tolerance: Tolerance(rms: 0.5, max: 2.0), cell: Cell(robots: [Robot(model: Custom(name: "c", a1: 150, a2: -115, b: 0, c1: 445, c2: 700, c3: 795, c4: 85, offsets: [0, 0, -90, 0, 0, 0], signs: [1, 1, 1, 1, 1, 1], limits: [(-720, 720), (-720, 720), (-720, 720), (-720, 720), (-720, 720), (-720, 720)]), base: Frame(origin: (150, -1100, 0), rotation: (90, 0, 0))), Robot(model: Irb4600, base: Frame(origin: (150, 1300, 0), rotation: (-90, 0, 0)))], blade_holders: [Holder(robot: 0, tcp: Frame(origin: (0, 0, 150), rotation: (0, 0, -90)), mass: 2, cog: (0, 0, 70)), Holder(robot: 1, tcp: Frame(origin: (0, 0, 150), rotation: (180, 0, -90)), mass: 2, cog: (0, 0, 70))], fixture: Frame(origin: (0, -225, 300), rotation: (0, 0, 0)), heat: Heat(signal: "doHeat", preheat_s: 2), air_speed: 120, clearance: 80, strict: false), task: HotBlade(targets_per_block: {}, samples: 30, refine: 1), outputs: [Report, Rapid], seed: 3)"#,
        n.clamp(2, 5000)
    );
    vec![("job.ron".into(), job)]
}

/// Writes `files` into `dir`.
fn put(dir: &Path, files: &[(String, String)]) {
    for (name, text) in files {
        write(dir, name, text);
    }
}

/// The estimated work (steps) and files (MB, 0 when not estimated) `validate` prints for
/// the job in `dir` under `work`, or `None` when it refuses the job.
fn estimate(dir: &Path, work: f64) -> Option<(f64, f64)> {
    let o = hotcut(
        &["validate", "job.ron", "--max-work", &work.to_string()],
        dir,
    );
    if o.status.code() != Some(0) {
        let e = stderr(&o);
        assert!(
            e.contains("--max-work") || e.contains("--max-output") || e.contains("--max-memory"),
            "refused for another reason: {e}"
        );
        return None;
    }
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let steps = out.split("about ").nth(1)?.split(' ').next()?;
    let mb = out
        .split(" MB of files")
        .next()
        .filter(|s| s.len() < out.len())
        .and_then(|s| s.rsplit(' ').next())
        .map_or(Some(0.0), |m| m.parse().ok())?;
    Some((steps.parse().ok()?, mb))
}

/// Bytes of the files under `dir`, recursively.
fn bytes_under(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let t = e.file_type().unwrap();
            if t.is_dir() {
                bytes_under(&e.path())
            } else {
                e.metadata().unwrap().len()
            }
        })
        .sum()
}

/// The largest scale the job passes validation at under `work` (with the estimate there),
/// and the smallest it is refused at.
fn just_under(case: &Case, dir: &Path) -> (usize, (f64, f64), usize) {
    let at = |n: usize| {
        put(dir, &(case.files)(n));
        estimate(dir, case.work)
    };
    let mut lo = 1;
    let first = at(lo).unwrap_or_else(|| panic!("{}: refused at scale 1", case.label));
    let (mut good, mut hi) = (first, 2);
    // double until refused, then bisect
    while let Some(e) = at(hi) {
        (lo, good) = (hi, e);
        hi *= 2;
        assert!(hi < 1 << 20, "{}: never refused", case.label);
    }
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        match at(mid) {
            Some(e) => (lo, good) = (mid, e),
            None => hi = mid,
        }
    }
    (lo, good, hi)
}

fn check(case: &Case) {
    let dir = tempfile::tempdir().unwrap();
    let (scale, (steps, mb), refused) = just_under(case, dir.path());
    put(dir.path(), &(case.files)(scale));
    let start = Instant::now();
    let o = hotcut(
        &[
            "run",
            "job.ron",
            "--out",
            "out",
            "--max-work",
            &case.work.to_string(),
        ],
        dir.path(),
    );
    let took = start.elapsed().as_secs_f64();
    assert_eq!(o.status.code(), Some(0), "{}: {}", case.label, stderr(&o));
    let implied = steps / 1e8;
    let written = bytes_under(&dir.path().join("out")) as f64 / 1e6;
    println!(
        "{}: scale {scale} (refused at {refused}) under {:e} steps: estimate {steps:e} steps ({implied:.2} s), {mb} MB of files; ran in {took:.2} s, wrote {written:.3} MB",
        case.label, case.work
    );
    // the output estimate `--max-output` is checked against is an upper bound
    assert!(
        mb == 0.0 || written <= mb + 0.005, // `validate` prints MB to two decimals
        "{}: wrote {written} MB, more than the {mb} MB estimated",
        case.label
    );
    assert!(
        took <= 3.0 * implied + 0.5,
        "{}: ran {took:.2} s, more than 3× the {implied:.2} s its estimate implies",
        case.label
    );
}

#[test]
fn fit_curves_from_a_file_run_within_their_estimate() {
    check(&Case {
        label: "FitCurves, 10-point curves",
        work: 3e8,
        files: fit_curves,
    });
}

#[test]
fn numerical_splines_run_within_their_estimate() {
    check(&Case {
        label: "FitCurves, NumericalSpline(control_points: 48)",
        work: 1e9,
        files: numerical,
    });
}

#[test]
fn design_stations_run_within_their_estimate() {
    check(&Case {
        label: "Design, one cut: n blocks at n stations",
        work: 1e9,
        files: design,
    });
}

#[test]
fn a_wide_arm_plans_within_its_estimate() {
    check(&Case {
        label: "HotBlade, custom arm ±720° on every joint",
        work: 3e8,
        files: wide_arm,
    });
}
