//! Round two of the hostile suite (issue 36): a generated family per class, each case
//! with its own set-up (FIFOs, links to devices, what `<out>/h` is before the run) and
//! checks on top of the suite's contract:
//! - **parity**: `hotcut validate` exits as `hotcut run` does (it refuses what the run
//!   would refuse, and accepts what runs);
//! - **replay**: every G-code program read by an independent reader (`common/gcode.rs`):
//!   no rapid with the wire hot, no cutting move cold, every axis within the travel, the
//!   heat off and the program ended at its end;
//! - **xml**: drawings and pages hold no character XML 1.0 forbids;
//! - **terminal**: what the terminal gets holds no escape or other control character;
//! - **quotes**: error messages stay short, whatever the input's size;
//! - **bounds**: glTF accessors' bounds and the report's model bounds are numbers.

use std::path::Path;

use super::gcode::{replay, Rules};
use super::{run_with, Case, Outcome, COMMON, DESIGN, HEIGHT};

/// What a case sets up and checks beyond the suite's contract.
#[derive(Debug, Clone, Default)]
pub struct Extra {
    /// The family, for the tally.
    pub family: &'static str,
    /// FIFOs made in the case's folder before the run.
    pub fifos: Vec<String>,
    /// Symbolic links `(name, target)` made before the run.
    pub links: Vec<(String, String)>,
    /// Folders made before the run.
    pub dirs: Vec<String>,
    /// What `out/h` is before the run.
    pub before: Option<Before>,
    /// More job files on the command line, after `job.ron`.
    pub jobs: Vec<String>,
    /// More arguments (`--max-work 1e9`).
    pub flags: Vec<String>,
    /// `validate` must exit as `run` does.
    pub parity: bool,
    /// The run must refuse (exit 1), or must run (exit 0).
    pub expect: Option<i32>,
    /// Replay the G-code under these rules, within this travel (min, max per axis).
    pub replay: Option<(Rules, [(f64, f64); 4])>,
    /// Drawings and pages must be XML-clean.
    pub xml: bool,
    /// stdout and stderr must hold no control character but newline and tab.
    pub terminal: bool,
    /// stderr at most this long.
    pub max_stderr: Option<usize>,
    /// glTF and report bounds must be numbers.
    pub bounds: bool,
    /// This text must be in the RAPID modules.
    pub rapid_has: Option<String>,
}

/// What `out/h` is before a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Before {
    /// A regular file.
    File,
    /// A folder with a file in it.
    Dir,
    /// A link to a folder outside `out`, which must stay as it is.
    LinkToDir,
    /// A link to a file.
    LinkToFile,
    /// A link to nothing.
    Dangling,
    /// A FIFO.
    Fifo,
}

impl Extra {
    fn of(family: &'static str) -> Self {
        Self {
            family,
            parity: true,
            terminal: true,
            ..Self::default()
        }
    }

    /// The command line of the run.
    pub fn args(&self) -> Vec<String> {
        let mut a = vec!["run".to_string(), "job.ron".to_string()];
        a.extend(self.jobs.iter().cloned());
        a.extend(["--out".to_string(), "out".to_string()]);
        a.extend(self.flags.iter().cloned());
        a
    }
}

fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .is_ok_and(|s| s.success());
    assert!(ok, "mkfifo {}", path.display());
}

/// Makes the case's FIFOs, links, folders and earlier output.
pub fn set_up(dir: &Path, e: &Extra) {
    for f in &e.fifos {
        mkfifo(&dir.join(f));
    }
    for d in &e.dirs {
        std::fs::create_dir_all(dir.join(d)).expect("folder");
    }
    for (name, target) in &e.links {
        std::os::unix::fs::symlink(target, dir.join(name)).expect("link");
    }
    let Some(before) = e.before else { return };
    let out = dir.join("out");
    std::fs::create_dir_all(&out).expect("out");
    let h = out.join("h");
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).expect("elsewhere");
    std::fs::write(elsewhere.join("keep.txt"), "keep").expect("keep");
    match before {
        Before::File => std::fs::write(&h, "an earlier file").expect("file"),
        Before::Dir => {
            std::fs::create_dir_all(&h).expect("dir");
            std::fs::write(h.join("old.txt"), "old").expect("old");
        }
        Before::LinkToDir => std::os::unix::fs::symlink(&elsewhere, &h).expect("link"),
        Before::LinkToFile => {
            std::os::unix::fs::symlink(elsewhere.join("keep.txt"), &h).expect("link")
        }
        Before::Dangling => std::os::unix::fs::symlink(dir.join("nowhere"), &h).expect("link"),
        Before::Fifo => mkfifo(&h),
    }
}

/// Control characters but newline and tab, and the bidi overrides.
fn hazard(s: &str) -> Option<char> {
    s.chars().find(|&c| {
        (c.is_control() && c != '\n' && c != '\t')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
    })
}

/// What is wrong with the case's extra checks, if anything.
pub fn judge(dir: &Path, e: &Extra, o: &Outcome) -> Option<String> {
    if let Some(want) = e.expect {
        if o.code != Some(want) {
            return Some(format!("exit {:?}, expected {want}: {}", o.code, o.stderr));
        }
    }
    if e.terminal {
        for (what, text) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
            if let Some(c) = hazard(text) {
                return Some(format!("{what} holds {c:?}: {text:?}"));
            }
        }
    }
    if let Some(max) = e.max_stderr {
        if o.stderr.len() > max {
            return Some(format!(
                "{} bytes on stderr, more than {max}",
                o.stderr.len()
            ));
        }
    }
    if e.parity && matches!(o.code, Some(0 | 1)) {
        let mut args = e.args();
        args[0] = "validate".into();
        let at = args.iter().position(|a| a == "--out").expect("--out");
        args.drain(at..at + 2);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = run_with(dir, &args);
        if v.code != o.code {
            return Some(format!(
                "validate exits {:?} but run {:?}: validate {:?}, run {:?}",
                v.code, o.code, v.stderr, o.stderr
            ));
        }
    }
    if e.before.is_some() && o.code == Some(0) {
        let h = dir.join("out/h");
        let m = std::fs::symlink_metadata(&h).ok()?;
        if !m.is_dir() || !h.join("report.json").is_file() {
            return Some("out/h is not the new output folder".into());
        }
        let kept = std::fs::read_to_string(dir.join("elsewhere/keep.txt")).unwrap_or_default();
        if kept != "keep" {
            return Some("the folder an earlier link pointed to was changed".into());
        }
    }
    if o.code != Some(0) {
        return None;
    }
    let folder = dir.join("out/h");
    let entries: Vec<_> = std::fs::read_dir(&folder).ok()?.flatten().collect();
    for entry in entries {
        let name = entry.file_name().to_string_lossy().into_owned();
        let text = || std::fs::read_to_string(entry.path()).unwrap_or_default();
        if let Some((rules, travel)) = &e.replay {
            if [".gcode", ".ngc", ".nc"].iter().any(|x| name.ends_with(x)) {
                if let Some(why) = replayed(&text(), rules, travel) {
                    return Some(format!("{name}: {why}"));
                }
            }
        }
        if e.xml && (name.ends_with(".svg") || name.ends_with(".html")) {
            if let Some(c) = hazard(&text()) {
                return Some(format!("{name} holds {c:?}, which XML forbids"));
            }
        }
        if e.bounds && name.ends_with(".gltf") {
            let v: serde_json::Value = serde_json::from_str(&text()).ok()?;
            for a in v["accessors"].as_array().into_iter().flatten() {
                for k in ["min", "max"] {
                    if let Some(list) = a.get(k).and_then(|l| l.as_array()) {
                        if list.iter().any(|x| !x.is_number()) {
                            return Some(format!("{name}: an accessor's {k} is not a number"));
                        }
                    }
                }
            }
        }
        if e.bounds && name == "report.json" {
            let v: serde_json::Value = serde_json::from_str(&text()).ok()?;
            let b = &v["model_bounds"];
            let numbers = |k: &str| {
                b[k].as_array()
                    .is_some_and(|l| l.iter().all(|x| x.is_number()))
            };
            let fine = b.is_null() || (numbers("min") && numbers("max"));
            if !fine {
                return Some(format!("report.json: model_bounds {b}"));
            }
        }
        if let Some(want) = &e.rapid_has {
            if name.ends_with("T_ROB1.mod") && !text().contains(want.as_str()) {
                return Some(format!("{name} lacks {want:?}"));
            }
        }
    }
    None
}

/// Why a program replayed under `rules` does something a machine must not (`None`: it
/// does not).
fn replayed(text: &str, rules: &Rules, travel: &[(f64, f64); 4]) -> Option<String> {
    let r = match replay(text, rules) {
        Ok(r) => r,
        Err(e) => return Some(format!("the reader refuses it: {e}")),
    };
    for (i, m) in r.motions.iter().enumerate() {
        if m.cutting != m.heat {
            let what = if m.heat {
                "a rapid with the wire hot"
            } else {
                "a cut with the wire cold"
            };
            return Some(format!("motion {}: {what}", i + 1));
        }
        for (k, (lo, hi)) in travel.iter().enumerate() {
            let v = m.to[k];
            if !(v >= lo - 5e-4 && v <= hi + 5e-4) {
                return Some(format!(
                    "motion {}: axis {} at {v}, outside the travel {lo}…{hi}",
                    i + 1,
                    rules.axes[k]
                ));
            }
        }
    }
    if !(r.ended && r.cold_at_end) {
        return Some("the program does not end, or ends hot".into());
    }
    if !r.motions.iter().any(|m| m.cutting) {
        return Some("no cutting move".into());
    }
    None
}

fn case(label: String, job: &str, files: Vec<(String, Vec<u8>)>, extra: Extra) -> Case {
    let mut c = Case::job(label, job);
    c.files.extend(files);
    c.extra = extra;
    c
}

fn file(name: &str, text: impl Into<Vec<u8>>) -> (String, Vec<u8>) {
    (name.to_string(), text.into())
}

/// Every round-two case.
pub fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    devices(&mut out);
    large_inputs(&mut out);
    estimates(&mut out);
    dialects(&mut out);
    rapid_names(&mut out);
    control_characters(&mut out);
    f32_bounds(&mut out);
    parity(&mut out);
    entries(&mut out);
    out
}

/// Cases per family, in order of first appearance.
pub fn family_counts(cases: &[Case]) -> Vec<(&'static str, usize)> {
    let mut out: Vec<(&'static str, usize)> = Vec::new();
    for c in cases {
        match out.iter_mut().find(|f| f.0 == c.extra.family) {
            Some(f) => f.1 += 1,
            None => out.push((c.extra.family, 1)),
        }
    }
    out
}

/// Every family is there, with cases.
pub fn totals(cases: &[Case]) {
    let counts = family_counts(cases);
    for family in [
        "devices and FIFOs",
        "large typed inputs",
        "estimates",
        "dialect lines",
        "RAPID names",
        "control characters",
        "f32 bounds",
        "validation parity",
        "output entries",
    ] {
        let n = counts.iter().find(|f| f.0 == family).map_or(0, |f| f.1);
        assert!(n >= 5, "family {family}: {n} cases");
    }
}

/// A Design job on `d.json`, with `outputs`.
fn design_job(outputs: &str) -> String {
    format!(
        r#"Job(name: "h", blade: Blade(length: 900, max_curvature: 0.011, max_inflections: 2), task: Design(design: "d.json"), outputs: [{outputs}])"#
    )
}

/// A design of blocks `ids` side by side across one cut along x, each 400 wide, with an
/// S piece per block (level ends: G¹), at the entry and exit faces.
fn design_of(ids: &[&str], cut: &str) -> String {
    let pieces: Vec<String> = (0..ids.len())
        .map(|j| {
            let y = 400.0 * j as f64;
            let (a, b) = if j % 2 == 0 { (150, 250) } else { (250, 150) };
            format!(
                "[[{y}, {a}], [{}, {a}], [{}, {b}], [{}, {b}]]",
                y + 150.0,
                y + 250.0,
                y + 400.0
            )
        })
        .collect();
    let blocks: Vec<String> = ids
        .iter()
        .enumerate()
        .map(|(j, id)| {
            format!(
                r#"{{"id": "{id}", "min": [0, {}, 0], "max": [600, {}, 400]}}"#,
                400 * j,
                400 * (j + 1)
            )
        })
        .collect();
    let names: Vec<String> = ids.iter().map(|i| format!(r#""{i}""#)).collect();
    let curve = format!(r#"{{"Bezier": [{}]}}"#, pieces.join(", "));
    format!(
        r#"{{"blocks": {{"List": [{}]}}, "cuts": [{{"id": "{cut}", "direction": "X", "blocks": [{}], "stations": [{{"at": 0, "curve": {curve}}}, {{"at": 1, "curve": {curve}}}]}}]}}"#,
        blocks.join(", "),
        names.join(", ")
    )
}

fn devices(out: &mut Vec<Case>) {
    let spline = r#"{"degree_u": 2, "degree_v": 2, "points": [[[0,0,0],[0,100,0],[0,200,0]],[[100,0,0],[100,100,10],[100,200,0]],[[200,0,0],[200,100,0],[200,200,0]]]}"#;
    // (reader, job text, the file it reads, a good file for it)
    let readers: Vec<(&str, String, &str, String)> = vec![
        ("design", design_job("Report"), "d.json", DESIGN.to_string()),
        (
            "curves",
            r#"Job(name: "h", task: FitCurves(input: "c.json"), outputs: [Report])"#.into(),
            "c.json",
            r#"{"curves": [{"id": "a", "points": [[0, 0], [10, 3], [20, 4], [30, 3], [40, 0]]}]}"#.into(),
        ),
        (
            "spline",
            r#"Job(name: "h", surface: Spline(path: "s.json"), task: Analyze(), outputs: [Report])"#.into(),
            "s.json",
            spline.into(),
        ),
        (
            "mesh",
            r#"Job(name: "h", surface: Mesh(path: "m.obj"), cutting: Cutting(sections: 3), task: Analyze(samples: 100), outputs: [Report])"#.into(),
            "m.obj",
            super::cube_obj(100.0),
        ),
    ];
    for (reader, job, name, good) in readers {
        // the good file runs
        out.push(case(
            format!("devices: {reader}: a regular file"),
            &job,
            vec![file(name, good.clone())],
            Extra {
                expect: Some(0),
                ..Extra::of("devices and FIFOs")
            },
        ));
        for (kind, extra) in [
            (
                "/dev/zero",
                Extra {
                    links: vec![(name.into(), "/dev/zero".into())],
                    ..Extra::default()
                },
            ),
            (
                "/dev/urandom",
                Extra {
                    links: vec![(name.into(), "/dev/urandom".into())],
                    ..Extra::default()
                },
            ),
            (
                "a FIFO",
                Extra {
                    fifos: vec![name.into()],
                    ..Extra::default()
                },
            ),
            (
                "a folder",
                Extra {
                    dirs: vec![name.into()],
                    ..Extra::default()
                },
            ),
        ] {
            out.push(case(
                format!("devices: {reader} is {kind}"),
                &job,
                vec![],
                Extra {
                    expect: Some(1),
                    ..Extra {
                        family: "devices and FIFOs",
                        parity: true,
                        terminal: true,
                        ..extra
                    }
                },
            ));
        }
    }
    // the job file itself
    for (kind, extra) in [
        (
            "/dev/zero",
            Extra {
                links: vec![("j.ron".into(), "/dev/zero".into())],
                ..Extra::default()
            },
        ),
        (
            "a FIFO",
            Extra {
                fifos: vec!["j.ron".into()],
                ..Extra::default()
            },
        ),
        (
            "a folder",
            Extra {
                dirs: vec!["j.ron".into()],
                ..Extra::default()
            },
        ),
    ] {
        out.push(case(
            format!("devices: a second job file is {kind}"),
            &format!(r#"Job(name: "h", {HEIGHT} task: Analyze(), outputs: [Report])"#),
            vec![],
            Extra {
                jobs: vec!["j.ron".into()],
                expect: Some(1),
                ..Extra {
                    family: "devices and FIFOs",
                    parity: true,
                    terminal: true,
                    ..extra
                }
            },
        ));
    }
}

fn large_inputs(out: &mut Vec<Case>) {
    let job = design_job("Report");
    let refused = |max: usize| Extra {
        expect: Some(1),
        max_stderr: Some(max),
        ..Extra::of("large typed inputs")
    };
    let many: Vec<String> = (0..10_001)
        .map(|i| format!(r#"{{"id": "b{i}", "min": [0, 0, 0], "max": [1, 1, 1]}}"#))
        .collect();
    let numbers = vec!["1"; 3_000_000].join(",");
    let long_id = "x".repeat(1 << 20);
    let designs = [
        (
            "10 001 blocks",
            format!(
                r#"{{"blocks": {{"List": [{}]}}, "cuts": []}}"#,
                many.join(",")
            ),
        ),
        (
            "a block list of 3 million numbers",
            format!(r#"{{"blocks": {{"List": [[{numbers}]]}}, "cuts": []}}"#),
        ),
        (
            "a 1 MB block id",
            DESIGN.replace(
                "\"Grid\"",
                &format!(r#""List": [{{"id": "{long_id}", "min": [0,0,0], "max": [1,1,1]}}], "x""#),
            ),
        ),
        (
            "a 1 MB unknown field",
            DESIGN.replacen('{', &format!(r#"{{"{long_id}": 1, "#), 1),
        ),
        (
            "a 1 MB variant name",
            DESIGN.replace("\"Bezier\"", &format!(r#""{long_id}""#)),
        ),
        (
            "a 1 MB string for a number",
            DESIGN.replacen("150", &format!(r#""{long_id}""#), 1),
        ),
        ("1001 cuts", {
            let cut = r#"{"id": "c", "direction": "X", "blocks": ["x0y0"], "stations": []}"#;
            format!(
                r#"{{"blocks": {{"Grid": {{"origin": [0,0,0], "size": [1,1,1], "count": [1,1]}}}}, "cuts": [{}]}}"#,
                vec![cut; 1001].join(",")
            )
        }),
        (
            "nested 100 000 deep",
            format!("{}{}", "[".repeat(100_000), "]".repeat(100_000)),
        ),
    ];
    for (label, d) in designs {
        out.push(case(
            format!("large: design with {label}"),
            &job,
            vec![file("d.json", d)],
            refused(4096),
        ));
    }
    let curves = [
        (
            "a 1 MB id",
            format!(
                r#"{{"curves": [{{"id": [{}], "points": [[0,0],[1,1],[2,0]]}}]}}"#,
                vec!["1"; 500_000].join(",")
            ),
        ),
        (
            "a 1 MB string id of controls",
            format!(
                r#"{{"curves": [{{"id": {{"x": "{}"}}, "points": [[0,0],[1,1],[2,0]]}}]}}"#,
                "\\u001b".repeat(200_000)
            ),
        ),
    ];
    for (label, c) in curves {
        out.push(case(
            format!("large: curves with {label}"),
            r#"Job(name: "h", task: FitCurves(input: "c.json"), outputs: [Report])"#,
            vec![file("c.json", c)],
            refused(4096),
        ));
    }
}

/// `n` curves of `points` points each, as a curves file.
fn curves(n: usize, points: usize) -> String {
    let list: Vec<String> = (0..n)
        .map(|i| {
            let p: Vec<String> = (0..points)
                .map(|x| {
                    format!(
                        "[{},{:.3}]",
                        x * 10,
                        30.0 * (x as f64 / 3.0 + i as f64).sin()
                    )
                })
                .collect();
            format!(r#"{{"id":"c{i}","points":[{}]}}"#, p.join(","))
        })
        .collect();
    format!(r#"{{"curves":[{}]}}"#, list.join(","))
}

fn estimates(out: &mut Vec<Case>) {
    let refused = || Extra {
        expect: Some(1),
        ..Extra::of("estimates")
    };
    let fit = |method: &str| {
        format!(
            r#"Job(name: "h", task: FitCurves(input: "c.json"{method}), outputs: [Report, Svg, Html])"#
        )
    };
    out.push(case(
        "estimates: FitCurves, 100 000 curves of 10 points".into(),
        &fit(""),
        vec![file("c.json", curves(100_000, 10))],
        refused(),
    ));
    out.push(case(
        "estimates: FitCurves, 10 000 curves of 10 points (the files)".into(),
        &fit(""),
        vec![file("c.json", curves(10_000, 10))],
        refused(),
    ));
    out.push(case(
        "estimates: NumericalSpline(control_points: 96) on 400 curves".into(),
        &fit(", method: NumericalSpline(epsilon: 1.0, control_points: 96)"),
        vec![file("c.json", curves(400, 100))],
        refused(),
    ));
    // one cut through 100 blocks at 100 stations, and two crossing cuts
    let ids: Vec<String> = (0..100).map(|j| format!("b{j}")).collect();
    let refs: Vec<&str> = ids.iter().map(String::as_str).collect();
    let one = design_of(&refs, "c");
    let station = one
        .split(r#""stations": ["#)
        .nth(1)
        .and_then(|s| s.split(", {\"at\": 1").next())
        .unwrap_or_default()
        .to_string();
    let stations: Vec<String> = (0..100)
        .map(|k| station.replacen("\"at\": 0", &format!("\"at\": {}", k as f64 / 99.0), 1))
        .collect();
    let hundred = format!(
        "{}\"stations\": [{}]}}]}}",
        one.split("\"stations\": [").next().unwrap_or_default(),
        stations.join(", ")
    );
    out.push(case(
        "estimates: Design, 100 blocks at 100 stations, under 10⁹ steps".into(),
        &design_job("Report"),
        vec![file("d.json", hundred)],
        Extra {
            flags: vec!["--max-work".into(), "1e9".into()],
            ..refused()
        },
    ));
    // a custom arm allowed ±720° on every joint plans in bounded time
    let (_, cell, _) = super::bases()
        .into_iter()
        .find(|b| b.0 == "cell")
        .expect("cell base");
    let wide = cell.replace(
        "limits: [(-180, 180), (-95, 155), (-180, 75), (-400, 400), (-120, 120), (-400, 400)]",
        "limits: [(-720, 720), (-720, 720), (-720, 720), (-720, 720), (-720, 720), (-720, 720)]",
    );
    assert_ne!(wide, cell);
    out.push(case(
        "estimates: a custom arm of ±720° on every joint".into(),
        &wide,
        vec![],
        Extra {
            expect: Some(0),
            ..Extra::of("estimates")
        },
    ));
    out.push(case(
        "estimates: the same arm, 400 targets per block, under 10⁸ steps".into(),
        &wide.replace("targets_per_block: 5", "targets_per_block: 400"),
        vec![],
        Extra {
            flags: vec!["--max-work".into(), "1e8".into()],
            ..refused()
        },
    ));
}

/// A PreCut job on a Custom dialect of these lines, travel 0–800 on every axis.
fn precut(header: &[&str], footer: &[&str], on: &str, off: &str, end: &str, more: &str) -> String {
    let list = |l: &[&str]| {
        l.iter()
            .map(|s| format!("{s:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        r#"Job(name: "h", units: Millimetre, surface: HeightField(z: "120 + 90*exp(-3*((x/300)^2 + (y/200)^2))", x: (-300, 300), y: (-200, 200)), block: Block(size: (600, 400, 300), origin: (-300, -200, 0)), wire: Wire(machine: Custom(axes: "XYUV", header: [{}], footer: [{}], heat_on: {on:?}, heat_off: {off:?}, end: {end:?}, percent: true, feed_mode: UnitsPerMinuteXyz, decimals: 3{more}), tower_distance: 800, kerf: 1.0, speed: 300, travel: Travel(along: (0, 800), up: (0, 800))), task: PreCut(legs: 2, directions: [X], sections: 8, samples: 8, controls: 5), outputs: [Report, GCode])"#,
        list(header),
        list(footer)
    )
}

fn rules(on: &str, off: &str) -> Rules {
    let words = |s: &str| s.split_whitespace().map(str::to_string).collect();
    Rules {
        axes: ['X', 'Y', 'U', 'V'],
        grbl: false,
        percent: true,
        dwell_ms: false,
        heat_on: words(on),
        heat_off: words(off),
    }
}

/// The quoted string after `key: ` in `text`.
fn quoted(text: &str, key: &str) -> Option<String> {
    let rest = text.split(&format!("{key}: \"")).nth(1)?;
    Some(rest.split('"').next()?.to_string())
}

/// The numbers of the first `(a, b)` after `key: (` in `text`.
fn pair(text: &str, key: &str) -> Option<(f64, f64)> {
    let rest = text.split(&format!("{key}: (")).nth(1)?;
    let (a, b) = rest.split(')').next()?.split_once(',')?;
    Some((a.trim().parse().ok()?, b.trim().parse().ok()?))
}

/// A shipped job on a Custom dialect: file name, job text, rules, travel.
type Shipped = (String, String, Rules, [(f64, f64); 4]);

/// Every job in `jobs/` on a `Custom` wire dialect, renamed `h`, with the rules its
/// dialect states (axes, `%`, dwell unit, heat lines) and its travel, as the job file says
/// them: `(file name, job, rules, travel)`.
fn shipped_dialects() -> Vec<Shipped> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("jobs/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    let mut out = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(&path).expect("job");
        if !text.contains("machine: Custom(") {
            continue;
        }
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let job_name = quoted(&text, "name").expect("a name");
        let job = text.replacen(&format!("name: \"{job_name}\""), "name: \"h\"", 1);
        let axes: Vec<char> = quoted(&text, "axes").expect("axes").chars().collect();
        let power = pair(&text, "power").map_or("1000".to_string(), |p| p.0.to_string());
        let on = quoted(&text, "heat_on")
            .unwrap_or("M3 S{power}".into())
            .replace("{power}", &power);
        let off = quoted(&text, "heat_off").unwrap_or("M5".into());
        let words = |s: &str| s.split_whitespace().map(str::to_string).collect();
        let rules = Rules {
            axes: [axes[0], axes[1], axes[2], axes[3]],
            grbl: false,
            percent: text.contains("percent: true"),
            dwell_ms: text.contains("dwell: Milliseconds"),
            heat_on: words(&on),
            heat_off: words(&off),
        };
        let along = pair(&text, "along").expect("a travel");
        let up = pair(&text, "up").expect("a travel");
        let travel = [
            along,
            up,
            pair(&text, "b_along").unwrap_or(along),
            pair(&text, "b_up").unwrap_or(up),
        ];
        out.push((name, job, rules, travel));
    }
    assert!(!out.is_empty(), "no Custom dialect in jobs/");
    out
}

fn dialects(out: &mut Vec<Case>) {
    const TRAVEL: [(f64, f64); 4] = [(0.0, 800.0); 4];
    let g = ["G17 G21 G90 G94 G61"];
    let checked = |on: &str, off: &str, expect: Option<i32>| Extra {
        replay: Some((rules(on, off), TRAVEL)),
        expect,
        ..Extra::of("dialect lines")
    };
    // every Custom dialect in jobs/, and good dialects that must run and replay
    for (name, job, rules, travel) in shipped_dialects() {
        out.push(case(
            format!("dialect: jobs/{name}"),
            &job,
            vec![],
            Extra {
                replay: Some((rules, travel)),
                expect: Some(0),
                ..Extra::of("dialect lines")
            },
        ));
    }
    type Dialect<'a> = (&'a [&'a str], &'a [&'a str], &'a str, &'a str, &'a str);
    let good: [Dialect; 7] = [
        (&g, &[], "M64 P0", "M65 P0", "M30"),
        (
            &["G17 G21 G90 G94 G61 G40 G49", "G64 P0.05", "G54"],
            &["M65 P0", "(done)"],
            "M62 P0",
            "M65 P0",
            "G90 M30",
        ),
        (&g, &["M5"], "M3 S1000", "M5", "M2"),
        (&g, &[], "M4", "M5", "M2"),
        (&g, &["M9"], "M8", "M9", "M30"),
        (&g, &[], "M7", "M9", "M2"),
        (&["G21G90"], &[], "M64 P3", "M65 P3", "M2"),
    ];
    for (h, f, on, off, end) in good {
        out.push(case(
            format!("dialect: good {h:?} {f:?} {on:?} {off:?} {end:?}"),
            &precut(h, f, on, off, end, ""),
            vec![],
            checked(on, off, Some(0)),
        ));
    }
    // every line that moves, offsets, heats, repeats or ends, in every field
    let hostile = [
        "G0 X5000 U5000",
        "G0X5000U5000",
        "g0 x5000 u5000",
        "G1 X0 Y0 U0 V0 F100",
        "G2 X10 Y0 I5 J0",
        "G92 X-3000 U-3000",
        "G92.1",
        "G10 L2 P1 X500 U500",
        "G10 L20 P1 X0",
        "G52 X100",
        "G53 G0 X0",
        "G28 X0",
        "G30",
        "G93",
        "G95",
        "G20",
        "G91",
        "M64 P0",
        "M62 P0",
        "M3 S1000",
        "M8",
        "M47",
        "M99",
        "M98 P100",
        "M0",
        "M1",
        "M60",
        "M2",
        "M30 G0 X9000",
        "T1 M6",
        "G43 H1",
        "G4 P100",
        "#1=5",
        "O100 call",
        "G0 X5000 (park)",
        "; G0 X5000",
        "M30 ; G0 X5000",
        "X100",
        "F100",
    ];
    for line in hostile {
        let fields: [(&str, String); 6] = [
            (
                "header",
                precut(&[g[0], line], &[], "M64 P0", "M65 P0", "M30", ""),
            ),
            ("footer", precut(&g, &[line], "M64 P0", "M65 P0", "M30", "")),
            ("end", precut(&g, &[], "M64 P0", "M65 P0", line, "")),
            (
                "end + M30",
                precut(&g, &[], "M64 P0", "M65 P0", &format!("{line} M30"), ""),
            ),
            ("heat_on", precut(&g, &[], line, "M65 P0", "M30", "")),
            ("heat_off", precut(&g, &[], "M64 P0", line, "M30", "")),
        ];
        for (field, job) in fields {
            let (on, off) = match field {
                "heat_on" => (line, "M65 P0"),
                "heat_off" => ("M64 P0", line),
                _ => ("M64 P0", "M65 P0"),
            };
            out.push(case(
                format!("dialect: {field} {line:?}"),
                &job,
                vec![],
                checked(on, off, None),
            ));
        }
    }
    // heat lines that do not pair up, powers that overflow, a feed mode behind the
    // profile's back
    let pairs = [
        ("M64 P0", "M9"),
        ("M3 S1000", "M65 P0"),
        ("M64 P0", "M65 P1"),
        ("M8", "M5"),
        ("M64 P0 G1 X700 Y0 U700 V0 F100", "M65 P0"),
        ("M3 S99999999", "M5"),
        ("M3 S{power}{power}", "M5"),
        ("M3 S0", "M5"),
        ("M67 E0 Q0", "M68 E0 Q0"),
        ("M5", "M3"),
    ];
    for (on, off) in pairs {
        out.push(case(
            format!("dialect: heat {on:?} / {off:?}"),
            &precut(&g, &[], on, off, "M30", ""),
            vec![],
            checked(on, off, Some(1)),
        ));
    }
    out.push(case(
        "dialect: G93 in the header with UnitsPerMinute".into(),
        &precut(&["G17 G21 G90 G93"], &[], "M64 P0", "M65 P0", "M30", "")
            .replace("UnitsPerMinuteXyz", "UnitsPerMinute"),
        vec![],
        checked("M64 P0", "M65 P0", Some(1)),
    ));
    out.push(case(
        "dialect: {power} of 1e7".into(),
        &precut(&g, &[], "M3 S{power}", "M5", "M30", "")
            .replace("speed: 300,", "speed: 300, power: 10000000,"),
        vec![],
        checked("M3 S10000000", "M5", Some(1)),
    ));
}

fn rapid_names(out: &mut Vec<Case>) {
    let (_, cell, _) = super::bases()
        .into_iter()
        .find(|b| b.0 == "cell")
        .expect("cell base");
    let with = |name: &str| cell.replace("signal: \"doHeat\"", &format!("signal: {name:?}"));
    let mut names: Vec<String> = [
        "GOTO",
        "EXIT",
        "TRAP",
        "ERROR",
        "RAISE",
        "RETRY",
        "TEST",
        "ELSEIF",
        "FUNC",
        "LOCAL",
        "goto",
        "Exit",
        "pB1_C1",
        "posBlock1",
        "num",
        "SetDO",
        "tBlade1",
        "T_ROB1",
        "h_T_ROB2",
        "v100",
        "z10",
        "ROB_1",
        "wobj0",
        "tool0",
        "fine",
        "vmax",
        "nAnswer",
        "main",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    names.extend(export::rapid_names::RESERVED.iter().map(|s| s.to_string()));
    names.extend(
        export::rapid_names::TYPES
            .iter()
            .step_by(3)
            .map(|s| s.to_string()),
    );
    names.extend(
        export::rapid_names::ROUTINES
            .iter()
            .step_by(4)
            .map(|s| s.to_lowercase()),
    );
    names.sort();
    names.dedup();
    for n in names {
        out.push(case(
            format!("RAPID: signal {n:?}"),
            &with(&n),
            vec![],
            Extra {
                expect: Some(1),
                ..Extra::of("RAPID names")
            },
        ));
    }
    for n in ["doHeat2", "Heat_On", "bladeHot", "pB", "posBlockA"] {
        out.push(case(
            format!("RAPID: signal {n:?} runs"),
            &with(n),
            vec![],
            Extra {
                expect: Some(0),
                rapid_has: Some(format!("SetDO {n}, 1;")),
                ..Extra::of("RAPID names")
            },
        ));
    }
}

fn control_characters(out: &mut Vec<Case>) {
    let ids = [
        "a\\u0001",
        "\\u001b[2J\\u001b[HX",
        "b\\u202ec",
        "\\u0085e",
        "f\\u007f",
        "g\\u0000h",
        "\\u001b]0;title\\u0007",
        "tab\\tnew\\nline",
    ];
    let runs = || Extra {
        expect: Some(0),
        xml: true,
        ..Extra::of("control characters")
    };
    for id in ids {
        out.push(case(
            format!("controls: block id {id}"),
            &design_job("Report, Svg, Gltf, Html"),
            vec![file("d.json", design_of(&["A", id], "c"))],
            runs(),
        ));
        out.push(case(
            format!("controls: cut id {id}"),
            &design_job("Report, Svg, Html"),
            vec![file("d.json", design_of(&["A", "B"], id))],
            runs(),
        ));
        // quoted in an error: a block that is not there
        out.push(case(
            format!("controls: missing block {id}"),
            &design_job("Report"),
            vec![file(
                "d.json",
                design_of(&["A"], "c")
                    .replace(r#""blocks": ["A"]"#, &format!(r#""blocks": ["{id}"]"#)),
            )],
            Extra {
                expect: Some(1),
                ..Extra::of("control characters")
            },
        ));
        out.push(case(
            format!("controls: curve id {id}"),
            r#"Job(name: "h", task: FitCurves(input: "c.json"), outputs: [Report, Svg, Html])"#,
            vec![file("c.json", format!(r#"{{"curves": [{{"id": "{id}", "points": [[0, 0], [10, 3], [20, 4], [30, 3], [40, 0]]}}]}}"#))],
            runs(),
        ));
    }
    out.push(case(
        "controls: job name with an escape".into(),
        &format!(r#"Job(name: "h\u{{1b}}[2J", {HEIGHT} task: Analyze(), outputs: [Report])"#),
        vec![],
        Extra {
            expect: Some(1),
            ..Extra::of("control characters")
        },
    ));
}

fn f32_bounds(out: &mut Vec<Case>) {
    for v in ["1e39", "-1e39", "5e38", "1e308", "-1e308", "3.5e38"] {
        let d = DESIGN.replace(
            r#""size": [600, 400, 400]"#,
            &format!(r#""size": [600, 400, {v}]"#),
        );
        out.push(case(
            format!("bounds: a design block {v} tall"),
            &design_job("Report, Gltf"),
            vec![file("d.json", d)],
            Extra {
                expect: Some(1),
                bounds: true,
                ..Extra::of("f32 bounds")
            },
        ));
        let d = DESIGN.replace(
            r#""origin": [0, 0, 0]"#,
            &format!(r#""origin": [0, 0, {v}]"#),
        );
        out.push(case(
            format!("bounds: a design at height {v}"),
            &design_job("Report, Gltf"),
            vec![file("d.json", d)],
            Extra {
                expect: Some(1),
                bounds: true,
                ..Extra::of("f32 bounds")
            },
        ));
    }
    for z in [
        "1e39 + 50*sin(y/100)",
        "1e38*sin(y/100)",
        "3e38 + x",
        "1e30*x*y",
    ] {
        let job = format!(
            r#"Job(name: "h", {} {COMMON} task: HotBlade(targets_per_block: 6, samples: 30, refine: 1), outputs: [Report, Gltf], seed: 3)"#,
            HEIGHT.replace("50*sin(y/100) + 10*cos(x/80)", z)
        );
        out.push(case(
            format!("bounds: HotBlade on z = {z}"),
            &job,
            vec![],
            Extra {
                bounds: true,
                ..Extra::of("f32 bounds")
            },
        ));
    }
}

fn parity(out: &mut Vec<Case>) {
    let refused = || Extra {
        expect: Some(1),
        ..Extra::of("validation parity")
    };
    let straight = r#"[[0, 200], [200, 200], [400, 200], [600, 200]]"#;
    let one = |curve0: &str, curve1: &str| {
        format!(
            r#"{{"blocks": {{"List": [{{"id": "W", "min": [0, 0, 0], "max": [650, 600, 400]}}]}}, "cuts": [{{"id": "c", "direction": "X", "blocks": ["W"], "stations": [{{"at": 0, "curve": {curve0}}}, {{"at": 1, "curve": {curve1}}}]}}]}}"#
        )
    };
    let bezier = |p: &str| format!(r#"{{"Bezier": [{p}]}}"#);
    let s_piece = r#"[[0, 200], [200, 250], [400, 250], [600, 200]]"#;
    let designs = [
        (
            "Bezier and Spline stations",
            one(
                &bezier(s_piece),
                r#"{"Spline": [[0, 200], [200, 250], [400, 250], [600, 200]]}"#,
            ),
        ),
        (
            "a block 1e308 long",
            one(&bezier(s_piece), &bezier(s_piece)).replace("[650, 600, 400]", "[1e308, 600, 400]"),
        ),
        (
            "a block 1e-300 wide",
            one(&bezier(s_piece), &bezier(s_piece))
                .replace("[650, 600, 400]", "[650, 1e-300, 400]"),
        ),
        ("ids a.b and a_b", design_of(&["a.b", "a_b"], "c")),
        ("ids A and a", design_of(&["A", "a"], "c")),
        ("a block named twice", design_of(&["A", "A"], "c")),
        (
            "a piece longer than the blade",
            one(
                &bezier(r#"[[0, 200], [200, 900], [400, 900], [600, 200]]"#),
                &bezier(s_piece),
            ),
        ),
        (
            "all control points at one place",
            one(
                &bezier("[[0, 200], [0, 200], [0, 200], [0, 200]]"),
                &bezier(s_piece),
            ),
        ),
    ];
    for (label, d) in designs {
        out.push(case(
            format!("parity: design with {label}"),
            &design_job("Report, Svg"),
            vec![file("d.json", d)],
            refused(),
        ));
    }
    // straight pieces are cut by a straight blade (issue 37; issue 36 refused them):
    // validate and run agree that they run
    let runs = || Extra {
        expect: Some(0),
        ..Extra::of("validation parity")
    };
    for (label, d) in [
        (
            "a straight piece",
            one(&bezier(straight), &bezier(straight)),
        ),
        (
            "a straight piece at one station",
            one(&bezier(s_piece), &bezier(straight)),
        ),
        (
            "stations bulging opposite ways (straight halfway)",
            one(
                &bezier(s_piece),
                &bezier(r#"[[0, 200], [200, 150], [400, 150], [600, 200]]"#),
            ),
        ),
    ] {
        out.push(case(
            format!("parity: design with {label}"),
            &design_job("Report, Svg"),
            vec![file("d.json", d)],
            runs(),
        ));
    }
    let g = ["G17 G21 G90 G94 G61"];
    for (label, job) in [
        (
            "heat_on M3 S99999999",
            precut(&g, &[], "M3 S99999999", "M5", "M30", ""),
        ),
        (
            "heat_on M3 S{power}{power}",
            precut(&g, &[], "M3 S{power}{power}", "M5", "M30", ""),
        ),
        (
            "footer G1 X0 F0.000001",
            precut(&g, &["G1 X0 F0.000001"], "M64 P0", "M65 P0", "M30", ""),
        ),
    ] {
        out.push(case(
            format!("parity: wire {label}"),
            &job,
            vec![],
            refused(),
        ));
    }
    // a good job and a bad one in one call: nothing is written
    let bad = design_job("Report").replace("name: \"h\"", "name: \"h2\"");
    out.push(case(
        "parity: a good job then a design longer than its blade in one call".into(),
        &format!(r#"Job(name: "h", {HEIGHT} task: Analyze(), outputs: [Report])"#),
        vec![
            file("bad.ron", bad),
            file(
                "d.json",
                one(
                    &bezier(r#"[[0, 200], [200, 900], [400, 900], [600, 200]]"#),
                    &bezier(s_piece),
                ),
            ),
        ],
        Extra {
            jobs: vec!["bad.ron".into()],
            ..refused()
        },
    ));
}

fn entries(out: &mut Vec<Case>) {
    let job = format!(r#"Job(name: "h", {HEIGHT} task: Analyze(), outputs: [Report])"#);
    for before in [
        Before::File,
        Before::Dir,
        Before::LinkToDir,
        Before::LinkToFile,
        Before::Dangling,
        Before::Fifo,
    ] {
        out.push(case(
            format!("entries: out/h is {before:?}"),
            &job,
            vec![],
            Extra {
                before: Some(before),
                expect: Some(0),
                ..Extra::of("output entries")
            },
        ));
    }
}

#[test]
fn the_replay_judge_catches_what_a_machine_must_not_do() {
    let r = rules("M64 P0", "M65 P0");
    let travel = [(0.0, 800.0); 4];
    let ok = "%\nG17 G21 G90 G94 G61\nG0 X0 Y50 U0 V50\nM64 P0\nG93\nG1 X100 Y50 U100 V50 F3\nM65 P0\nG94\nG0 X100 Y90 U100 V90\nM30\n%\n";
    assert_eq!(replayed(ok, &r, &travel), None);
    for (from, to) in [
        ("M65 P0\nG94\n", "G94\n"), // a hot rapid, and hot at the end
        ("M64 P0\n", ""),           // a cold cut
        ("X100 Y90", "X900 Y90"),   // past the travel
        ("M30\n", ""),              // never ends
        ("G0 X100 Y90 U100 V90", "G92 X0 Y0 U0 V0"), // offsets shifted
        ("M30\n", "M47\nM30\n"),    // repeats
    ] {
        let bad = ok.replace(from, to);
        assert!(replayed(&bad, &r, &travel).is_some(), "{from:?} → {to:?}");
    }
}
