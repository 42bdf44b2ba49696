//! End-to-end tests of the `hotcut` binary: exit codes, messages, atomic output, and
//! negative tests for malformed jobs and meshes. No message may ever contain `panicked`.

mod common;

use common::{expect_invalid, hotcut, stderr, write};
use std::path::Path;

const VALID: &str = r#"Job(
    name: "t",
    surface: HeightField(z: "50*sin(y/100)", x: (0, 300), y: (0, 900)),
    blade: Blade(length: 1000, max_curvature: 0.011),
    cutting: Cutting(sections: 3),
    task: Analyze(),
)
"#;

/// The names in folder `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn valid_job_validates_and_runs() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", VALID);
    let o = hotcut(&["validate", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = hotcut(&["run", "job.ron", "--out", "o"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("3 section(s)"), "{stdout}");
    assert!(dir.path().join("o/t/report.json").is_file());
    assert!(dir.path().join("o/t/sections.svg").is_file());
    // nothing else is left in the output folder (no temporary folders)
    assert_eq!(entries(&dir.path().join("o")), ["t"]);
    // a second run gives the same bytes
    let first = std::fs::read(dir.path().join("o/t/report.json")).unwrap();
    // a second run replaces the first as a whole: a file the first run wrote and the
    // second does not is gone, and no folder is left beside it
    std::fs::write(dir.path().join("o/t/stale.txt"), "from before").unwrap();
    let o = hotcut(&["run", "job.ron", "--out", "o"], dir.path());
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        first,
        std::fs::read(dir.path().join("o/t/report.json")).unwrap()
    );
    assert!(!dir.path().join("o/t/stale.txt").exists());
    assert_eq!(entries(&dir.path().join("o")), ["t"]);
}

#[test]
fn syntax_error_reports_file_line_and_column() {
    let text = VALID.replace(
        "cutting: Cutting(sections: 3),",
        "cutting: Cutting(sections: 3,,",
    );
    expect_invalid(&text, &["job.ron:5:", "syntax error"]);
    expect_invalid("Job(name: \"t\"", &["job.ron:1:"]);
    expect_invalid("", &["job.ron:1:1"]);
}

/// `task: Analyze` and `algorithm: Trace` (no parentheses) mean all defaults, for every
/// task and algorithm; errors after them still point at the column as written.
#[test]
fn unit_forms_of_tasks_and_algorithms_mean_all_defaults() {
    use hotcut::load::parse_job;
    let p = Path::new("job.ron");
    let tasks = [
        "Analyze",
        "FitCurves",
        "HotBlade",
        "FacadeSegmentation",
        "BlockSegmentation",
        "PreCut",
    ];
    for task in tasks {
        let unit = VALID.replace("task: Analyze()", &format!("task: {task}"));
        let full = VALID.replace("task: Analyze()", &format!("task: {task}()"));
        // the same job, or the same error (FacadeSegmentation has a required field)
        match (parse_job(p, &unit), parse_job(p, &full)) {
            (Ok(a), Ok(b)) => assert_eq!(a, b),
            (Err(a), Err(b)) => {
                let tail = |e: &hotcut::error::JobError| {
                    e.to_string().split_once(": ").unwrap().1.to_string()
                };
                assert_eq!(tail(&a), tail(&b));
            }
            (a, b) => panic!("{task}: {a:?} vs {b:?}"),
        }
    }
    for alg in ["Inflection", "Trace", "LongestElastica"] {
        let with = |a: &str| {
            VALID.replace(
                "task: Analyze()",
                &format!("task: FacadeSegmentation(algorithm: /* here */ {a})"),
            )
        };
        let unit = parse_job(p, &with(alg)).unwrap();
        assert_eq!(unit, parse_job(p, &with(&format!("{alg}()"))).unwrap());
    }
    // the unit form runs; a misspelt field after it on the same line is reported at its
    // column in the file as written
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "job.ron",
        &VALID.replace("task: Analyze()", "task: Analyze"),
    );
    let o = hotcut(&["run", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = VALID.replace("task: Analyze(),", "task: Analyze, sed: 1,");
    expect_invalid(&text, &["job.ron:6:20", "/sed"]);
}

#[test]
fn unknown_field_reports_its_path() {
    let text = VALID.replace("length: 1000", "lenght: 1000");
    expect_invalid(&text, &["job.ron:4:", "/blade/lenght"]);
    let text = VALID.replace("task: Analyze()", "task: Analyze(sample: 3)");
    expect_invalid(&text, &["/task/Analyze/sample"]);
    let text = VALID.replace("name: \"t\",", "name: \"t\", colour: \"red\",");
    expect_invalid(&text, &["/colour"]);
}

#[test]
fn wrong_types_and_unknown_variants_are_reported() {
    expect_invalid(
        &VALID.replace("sections: 3", "sections: \"three\""),
        &["/cutting/sections"],
    );
    expect_invalid(
        &VALID.replace("task: Analyze()", "task: Dance()"),
        &["Dance"],
    );
    expect_invalid(&VALID.replace("task: Analyze(),", ""), &["task"]);
}

#[test]
fn nan_and_negative_values_are_rejected_with_their_pointer() {
    expect_invalid(
        &VALID.replace("length: 1000", "length: NaN"),
        &["/blade/length", "finite"],
    );
    expect_invalid(
        &VALID.replace("length: 1000", "length: inf"),
        &["/blade/length", "finite"],
    );
    expect_invalid(
        &VALID.replace("length: 1000", "length: -1000"),
        &["/blade/length"],
    );
    expect_invalid(
        &VALID.replace("max_curvature: 0.011", "max_curvature: 0"),
        &["/blade/max_curvature"],
    );
    expect_invalid(
        &VALID.replace("sections: 3", "sections: 0"),
        &["/cutting/sections"],
    );
    expect_invalid(
        &VALID.replace(
            "cutting:",
            "block: Block(size: (600, -1, 600)),\n    cutting:",
        ),
        &["/block/size/1"],
    );
    expect_invalid(
        &VALID.replace("x: (0, 300)", "x: (0, NaN)"),
        &["/surface/HeightField/x/1", "finite"],
    );
    expect_invalid(
        &VALID.replace("x: (0, 300)", "x: (300, 0)"),
        &["/surface/HeightField/x", "min < max"],
    );
    expect_invalid(
        &VALID.replace("sections: 3", "sections: 3, direction: (0, 0, 0)"),
        &["/cutting/direction"],
    );
    expect_invalid(&VALID.replace("name: \"t\"", "name: \"../t\""), &["/name"]);
}

#[test]
fn bad_expressions_are_rejected_with_a_column() {
    expect_invalid(
        &VALID.replace("50*sin(y/100)", "50*sin(q/100)"),
        &["/surface/HeightField/z", "column 8", "unknown name 'q'"],
    );
    expect_invalid(
        &VALID.replace("50*sin(y/100)", "sqrt(y - 450)"),
        &["/surface/HeightField/z", "not finite"],
    );
}

#[test]
fn missing_empty_and_open_meshes_are_rejected() {
    let mesh_job = |surface: &str| {
        VALID.replace(
            "HeightField(z: \"50*sin(y/100)\", x: (0, 300), y: (0, 900))",
            surface,
        )
    };
    expect_invalid(
        &mesh_job("Mesh(path: \"models/nope.obj\")"),
        &[
            "/surface/Mesh/path",
            "mesh file not found",
            "models/nope.obj",
        ],
    );

    let dir = tempfile::tempdir().unwrap();
    let check = |obj: &str, surface: &str, needles: &[&str]| {
        write(dir.path(), "m.obj", obj);
        write(dir.path(), "job.ron", &mesh_job(surface));
        let o = hotcut(&["validate", "job.ron"], dir.path());
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        for n in needles {
            assert!(stderr(&o).contains(n), "missing {n:?}: {}", stderr(&o));
        }
    };
    check("# nothing\n", "Mesh(path: \"m.obj\")", &["empty"]);
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "Mesh(path: \"m.obj\", closed: true)",
        &["open", "boundary"],
    );
    check(
        "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "Mesh(path: \"m.obj\")",
        &["not finite"],
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
        "Mesh(path: \"m.obj\")",
        &["m.obj"],
    );
    check(
        "this is not an obj file\nf a b c\n",
        "Mesh(path: \"m.obj\")",
        &["m.obj"],
    );
    check(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
        "Mesh(path: \"m.obj\")",
        &["non-manifold"],
    );
}

#[test]
fn outputs_the_task_does_not_make_are_rejected() {
    expect_invalid(
        &VALID.replace(
            "task: Analyze(),",
            "task: Analyze(),\n    outputs: [Report, Rapid],",
        ),
        &["/outputs/1", "Rapid"],
    );
    expect_invalid(
        &VALID.replace(
            "surface: HeightField(z: \"50*sin(y/100)\", x: (0, 300), y: (0, 900)),",
            "",
        ),
        &["/surface", "needs a surface"],
    );
}

#[test]
fn usage_errors_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(hotcut(&[], dir.path()).status.code(), Some(2));
    assert_eq!(hotcut(&["run"], dir.path()).status.code(), Some(2));
    assert_eq!(hotcut(&["frobnicate"], dir.path()).status.code(), Some(2));
    assert_eq!(hotcut(&["--help"], dir.path()).status.code(), Some(0));
    let o = hotcut(&["validate", "missing.ron"], dir.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("job file not found: missing.ron"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn one_invalid_job_stops_the_whole_run() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "good.ron", VALID);
    write(
        dir.path(),
        "bad.ron",
        &VALID
            .replace("name: \"t\"", "name: \"u\"")
            .replace("sections: 3", "sections: 0"),
    );
    let o = hotcut(&["run", "good.ron", "bad.ron"], dir.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(
        !dir.path().join("out").exists(),
        "nothing may be written when a job is invalid"
    );
}

#[test]
fn checked_in_schemas_are_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let files = hotcut::schema_files();
    for hotcut::SchemaFile { file, text, .. } in &files {
        let path = root.join("schemas").join(file);
        if std::env::var_os("HOTCUT_UPDATE_SCHEMAS").is_some() {
            std::fs::write(&path, text).unwrap();
        }
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            on_disk == *text,
            "schemas/{file} is stale: run `cargo run -p hotcut -- schema --write schemas` \
             (or HOTCUT_UPDATE_SCHEMAS=1 cargo test) and commit the result"
        );
    }
    // the CLI prints the same schemas: the job's, and each task's report's by name
    let o = hotcut(&["schema"], &root);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        hotcut::job_schema_json()
    );
    for f in &files {
        let Some(task) = f.task else { continue };
        let o = hotcut(&["schema", "--report", task], &root);
        assert_eq!(String::from_utf8_lossy(&o.stdout), f.text, "{task}");
    }
    let of = |task: &str| {
        let f = files.iter().find(|f| f.task == Some(task));
        f.map(|f| f.text.clone()).unwrap_or_default()
    };
    let analyze = hotcut(&["schema", "--report"], &root);
    assert_eq!(String::from_utf8_lossy(&analyze.stdout), of("Analyze"));
    let fit = hotcut(&["schema", "--fit-report"], &root);
    assert_eq!(String::from_utf8_lossy(&fit.stdout), of("FitCurves"));
    let unknown = hotcut(&["schema", "--report", "Mill"], &root);
    assert_eq!(unknown.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("HotBlade"));
    // --write writes every one of them
    let dir = tempfile::tempdir().unwrap();
    let o = hotcut(&["schema", "--write", &dir.path().to_string_lossy()], &root);
    assert!(o.status.success());
    for f in &files {
        assert_eq!(
            std::fs::read_to_string(dir.path().join(f.file)).unwrap(),
            f.text
        );
    }
}

#[test]
fn every_example_job_validates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut jobs: Vec<String> = std::fs::read_dir(root.join("jobs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    jobs.sort();
    assert!(jobs.len() >= 3);
    let mut args = vec!["validate"];
    args.extend(jobs.iter().map(String::as_str));
    let o = hotcut(&args, &root);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn a_placed_block_must_contain_the_surface() {
    let dir = tempfile::tempdir().unwrap();
    // surface spans x 0..300, y 0..900, z -50..50; the block is big enough but placed too high
    let text = VALID.replace(
        "cutting:",
        "block: Block(size: (400, 1000, 200), origin: (0, 0, 0)),\n    cutting:",
    );
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report = std::fs::read_to_string(dir.path().join("out/t/report.json")).unwrap();
    assert!(report.contains("surface_below_block_z"), "{report}");
    assert!(!report.contains("surface_larger_than_block"));
    let text = VALID.replace(
        "cutting:",
        "block: Block(size: (400, 1000, 200), origin: (-10, -10, -100)),\n    cutting:",
    );
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(0));
    let report = std::fs::read_to_string(dir.path().join("out/t/report.json")).unwrap();
    assert!(report.contains("\"surface_violations\": []"), "{report}");
}

#[test]
fn default_blade_is_converted_for_metre_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"Job(name: "t", units: Metre, surface: HeightField(z: "0.05*sin(y/0.1)", x: (0, 0.3), y: (0, 0.9)), cutting: Cutting(sections: 2), task: Analyze(), outputs: [Report])"#;
    write(dir.path(), "job.ron", text);
    let o = hotcut(&["run", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("/m"));
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out/t/report.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(report["constraints"]["blade_length"], serde_json::json!(1));
    assert_eq!(
        report["constraints"]["max_curvature"],
        serde_json::json!(11)
    );
    // the section is 0.9 m long: shorter than the 1 m blade; z'' reaches 0.05/0.01 = 5 /m < 11 /m
    assert_eq!(report["summary"]["sections_too_long"], serde_json::json!(0));
    assert_eq!(
        report["summary"]["sections_too_curved"],
        serde_json::json!(0)
    );
}

#[test]
fn fit_curves_jobs_are_checked() {
    let no_surface = VALID.replace(
        "surface: HeightField(z: \"50*sin(y/100)\", x: (0, 300), y: (0, 900)),",
        "",
    );
    // neither an input file nor a surface
    expect_invalid(
        &no_surface.replace("task: Analyze(),", "task: FitCurves(),"),
        &["/task/FitCurves/input", "needs `input`"],
    );
    // a missing input file
    expect_invalid(
        &no_surface.replace("task: Analyze(),", "task: FitCurves(input: \"none.json\"),"),
        &["/task/FitCurves/input", "none.json"],
    );
    // an unknown constraint, an output the task does not write, too few samples
    expect_invalid(
        &VALID.replace("task: Analyze(),", "task: FitCurves(constraint: Tight),"),
        &["Tight"],
    );
    expect_invalid(
        &VALID.replace(
            "task: Analyze(),",
            "task: FitCurves(),\n    outputs: [Report, Obj],",
        ),
        &["/outputs/1", "FitCurves"],
    );
    expect_invalid(
        &VALID.replace("task: Analyze(),", "task: FitCurves(samples: 2),"),
        &["samples"],
    );
}

#[test]
fn fit_curves_runs_on_a_curves_file() {
    let dir = tempfile::tempdir().unwrap();
    // a quarter circle and a parabola, CSV
    let mut csv = String::from("id,x,y\n");
    for i in 0..40 {
        let a = std::f64::consts::FRAC_PI_2 * i as f64 / 39.0;
        csv.push_str(&format!("arc,{},{}\n", 100.0 * a.cos(), 100.0 * a.sin()));
    }
    for i in 0..40 {
        let x = i as f64 * 10.0;
        csv.push_str(&format!("parabola,{x},{}\n", 0.001 * x * x));
    }
    write(dir.path(), "curves.csv", &csv);
    write(
        dir.path(),
        "job.ron",
        "Job(name: \"fit\", task: FitCurves(input: \"curves.csv\", constraint: EndPoints))",
    );
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out/fit/report.json")).unwrap(),
    )
    .unwrap();
    let curves = report["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 2);
    assert_eq!(curves[0]["family"], "arc");
    // exact to the fit's grid (2⁻³⁰ of the 157 mm arc: 1.5·10⁻⁷ mm)
    assert!(curves[0]["rms"].as_f64().unwrap() < 1e-6);
    assert_eq!(curves[0]["fitted"].as_array().unwrap().len(), 400);
    // end points interpolated
    let f = curves[1]["fitted"].as_array().unwrap();
    let last = &f[f.len() - 1];
    assert!((last[0].as_f64().unwrap() - 390.0).abs() < 1e-6);
    assert!((last[1].as_f64().unwrap() - 152.1).abs() < 1e-6);
    assert!(dir.path().join("out/fit/fit.svg").is_file());
}

/// A small valid HotBlade job: two blocks across the cut.
const HOT_BLADE: &str = r#"Job(
    name: "t",
    surface: HeightField(z: "100 - (x*x + y*y)/4000", x: (0, 400), y: (0, 600)),
    block: Block(size: (400, 300, 300)),
    blade: Blade(length: 500, max_curvature: 0.011),
    task: HotBlade(targets_per_block: 5, samples: 40),
    outputs: [Report, RobotTargets(per_block: 5), Rapid, Gltf, Obj, Svg, Csv],
)
"#;

#[test]
fn hot_blade_job_runs_and_writes_its_files() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", HOT_BLADE);
    let o = hotcut(&["run", "job.ron", "--out", "o"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("2 block(s)"), "{stdout}");
    for f in [
        "report.json",
        "targets.json",
        "targets.csv",
        "t_T_ROB1.mod",
        "t_T_ROB1.pgf",
        "t_T_ROB2.mod",
        "t_T_ROB2.pgf",
        "model.gltf",
        "surface_block_001.obj",
        "block_002.svg",
        "sections.csv",
    ] {
        assert!(dir.path().join("o/t").join(f).is_file(), "missing {f}");
    }
    let targets: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("o/t/targets.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(targets["blade_length"].as_f64(), Some(500.0));
    assert_eq!(targets["blocks"][1]["poses"].as_array().unwrap().len(), 5);
}

#[test]
fn hot_blade_jobs_are_checked() {
    let task = "task: HotBlade(targets_per_block: 5, samples: 40),";
    let with_task = |t: &str| HOT_BLADE.replace(task, t);
    // what the task needs from the job
    expect_invalid(
        &HOT_BLADE.replace(
            "surface: HeightField(z: \"100 - (x*x + y*y)/4000\", x: (0, 400), y: (0, 600)),",
            "",
        ),
        &["/surface", "task HotBlade needs a surface"],
    );
    expect_invalid(
        &HOT_BLADE.replace("block: Block(size: (400, 300, 300)),", ""),
        &["/block", "needs `block`"],
    );
    // a free fit would let neighbouring blocks drift apart
    expect_invalid(
        &with_task("task: HotBlade(targets_per_block: 5, samples: 40, constraint: Free),"),
        &["/task/HotBlade/constraint", "EndPoints"],
    );
    // the robot targets must be the task's poses
    expect_invalid(
        &HOT_BLADE.replace("RobotTargets(per_block: 5)", "RobotTargets(per_block: 51)"),
        &["/outputs/1/RobotTargets/per_block", "targets_per_block (5)"],
    );
    // out of range numbers, each with its pointer
    for (field, needle) in [
        ("speed: 0", "/task/HotBlade/speed"),
        ("speed: -7", "/task/HotBlade/speed"),
        ("approach: -1", "/task/HotBlade/approach"),
        ("max_plane_angle: 2", "/task/HotBlade/max_plane_angle"),
        ("max_plane_angle: -0.1", "/task/HotBlade/max_plane_angle"),
        ("targets_per_block: 1", "targets_per_block"),
        ("samples: 3", "samples"),
        ("split_depth: 9", "split_depth"),
        ("continuity: C2", "C2"),
    ] {
        let t = format!("task: HotBlade(targets_per_block: 5, samples: 40, {field}),")
            .replace(
                "targets_per_block: 5, samples: 40, targets_per_block: 1",
                "targets_per_block: 1, samples: 40",
            )
            .replace("samples: 40, samples: 3", "samples: 3");
        expect_invalid(&with_task(&t), &[needle]);
    }
    // a speed given as NaN is not a number the robot can run
    expect_invalid(
        &with_task("task: HotBlade(targets_per_block: 5, samples: 40, speed: NaN),"),
        &["speed"],
    );
    // cutting-direction curves
    let curve = |c: &str| {
        HOT_BLADE.replace(
            "task: HotBlade",
            &format!("cutting: Cutting(curve: {c}),\n    task: HotBlade"),
        )
    };
    expect_invalid(
        &curve("[(0, 300)]"),
        &["/cutting/curve", "at least 2 points"],
    );
    expect_invalid(
        &curve("[(0, 300), (0, 300)]"),
        &["/cutting/curve", "coincide"],
    );
    expect_invalid(
        &curve("[(0, 300), (300, 300), (200, 250), (400, 300)]"),
        &["/cutting/curve", "point 2 does not advance"],
    );
    expect_invalid(&curve("[(0, 300), (inf, 300)]"), &["/cutting/curve"]);
    // a curve is for HotBlade only: others say so
    expect_invalid(
        &VALID.replace(
            "cutting: Cutting(sections: 3),",
            "cutting: Cutting(curve: [(0, 0), (300, 0)]),",
        ),
        &["/cutting/curve", "not used by task Analyze"],
    );
}

#[test]
fn bad_block_carriers_are_rejected_with_their_pointer() {
    let job = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/hot-blade-carried.ron"),
    )
    .unwrap();
    // the carrier must be a third robot that does not hold the blade
    expect_invalid(
        &job.replace("robot: 2,\n            grip", "robot: 1,\n            grip"),
        &["/cell/block_carrier/robot", "not hold the blade"],
    );
    expect_invalid(
        &job.replace("robot: 2,\n            grip", "robot: 7,\n            grip"),
        &["/cell/block_carrier/robot"],
    );
    // three robots with no carrier; a carrier with two robots
    let third = "            Robot(model: Irb4600, base: Frame(origin: (-1300, 0, 0))),\n";
    assert!(job.contains(third));
    let start = job.find("        block_carrier:").unwrap();
    let end = start + job[start..].find("        ),\n").unwrap() + 11;
    expect_invalid(
        &format!("{}{}", &job[..start], &job[end..]),
        &["/cell/robots", "third robot"],
    );
    expect_invalid(
        &job.replace(third, ""),
        &["/cell/block_carrier", "3 robots"],
    );
    // no fixture with a carrier; a real mass; frames within the room
    expect_invalid(
        &job.replace("heat:", "fixture: Frame(origin: (0, 0, 0)),\n        heat:"),
        &["/cell/fixture", "carried"],
    );
    expect_invalid(
        &job.replace("mass: 40", "mass: 0"),
        &["/cell/block_carrier/mass"],
    );
    expect_invalid(
        &job.replace(
            "origin: (0, 0, 1000), rotation: (90, 0, 90)",
            "origin: (0, 0, 1e9), rotation: (90, 0, 90)",
        ),
        &["/cell/block_carrier/station"],
    );
    expect_invalid(
        &job.replace("rotation: (0, -75, 0)", "rotation: (0, NaN, 0)"),
        &["/cell/block_carrier/grip"],
    );
}

#[test]
fn bad_designs_are_rejected_naming_the_station_and_face() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let g1 = std::fs::read_to_string(root.join("jobs/designs/bezier-g1.json")).unwrap();
    let spline = std::fs::read_to_string(root.join("jobs/designs/spline-c2.json")).unwrap();
    let job = |resolution: &str, outputs: &str| {
        format!(
            "Job(name: \"t\", blade: Blade(length: 900, max_curvature: 0.011, max_inflections: 2), task: Design(design: \"d.json\", resolution: {resolution}), outputs: [{outputs}])"
        )
    };
    let ok = job("Production", "Report, Svg");
    let bad = |design: &str, needles: &[&str]| {
        common::expect_invalid_with(&ok, &[("d.json", design)], needles);
    };
    // the last leg of piece 0 and the first of piece 1 no longer on one line
    bad(
        &g1.replacen("[750, 350]", "[750, 390]", 1),
        &[
            "/task/Design/design",
            "/cuts/0/stations/1/curve",
            "face 1",
            "one line",
        ],
    );
    // a piece's end off its face
    bad(
        &g1.replacen("[1800, 350]", "[1790, 350]", 1),
        &["/cuts/0/stations/0/curve", "face 3"],
    );
    // a spline's knot image off its face; too few control points
    bad(
        &spline.replacen("[600, 400]", "[650, 400]", 1),
        &["/cuts/0/stations/0/curve", "knot image"],
    );
    bad(
        &spline
            .replacen("[1800, 320]]", "]", 1)
            .replacen("[1600, 220], ]", "[1600, 220]]", 1),
        &["control points"],
    );
    // blocks: unknown, not side by side, unknown key, a huge grid
    bad(
        &g1.replacen("\"x0y2\"]", "\"x0y9\"]", 1),
        &["/cuts/0/blocks/2", "no block"],
    );
    bad(
        &g1.replacen("\"x0y1\", \"x0y2\"", "\"x0y2\", \"x0y1\"", 1),
        &["side by side"],
    );
    bad(
        &g1.replacen("\"id\": \"wave\"", "\"id\": \"wave\", \"colour\": 1", 1),
        &["colour"],
    );
    bad(
        &g1.replacen("\"count\": [1, 3]", "\"count\": [1, 3000000]", 1),
        &["design.schema.json"],
    );
    // stations: the ends required, in order
    bad(
        &g1.replacen("{\"at\": 1,", "{\"at\": 0.9,", 1),
        &["/stations", "exit face"],
    );
    // a piece longer than the blade
    common::expect_invalid_with(
        &ok.replace("length: 900", "length: 500"),
        &[("d.json", &g1)],
        &["longer than the blade", "blade.length"],
    );
    // robot files need Production; no surface
    common::expect_invalid_with(
        &job("Design", "Report, Rapid"),
        &[("d.json", &g1)],
        &["/outputs/1", "Production"],
    );
    common::expect_invalid_with(
        &ok.replace(
            "task:",
            "surface: HeightField(z: \"0\", x: (0, 1), y: (0, 1)), task:",
        ),
        &[("d.json", &g1)],
        &["/surface", "design file"],
    );
    // a missing design file
    common::expect_invalid(&ok, &["/task/Design/design", "design file not found"]);
}

#[test]
fn bad_numerical_spline_settings_are_rejected_naming_the_field() {
    let curves = r#"{"curves": [{"id": "c", "points": [[0,0],[1,1],[2,1],[3,0],[4,-1],[5,0]]}]}"#;
    let job = |method: &str| {
        format!(
            "Job(name: \"t\", units: Metre, task: FitCurves(input: \"c.json\", method: {method}), outputs: [Report])"
        )
    };
    for (method, needles) in [
        (
            "NumericalSpline(epsilon: 0.002, control_points: 500, fix_tangents: true, fix_length: true)",
            &["/task/FitCurves/method/NumericalSpline/control_points", "at most 96"][..],
        ),
        (
            "NumericalSpline(epsilon: 0.002, control_points: 8, fix_tangents: true, fix_length: true)",
            &["/task/FitCurves/method/NumericalSpline/control_points", "has 6 points"][..],
        ),
        (
            "NumericalSpline(epsilon: -1, control_points: 6, fix_tangents: true, fix_length: true)",
            &["/task/FitCurves/method/NumericalSpline/epsilon"][..],
        ),
    ] {
        common::expect_invalid_with(&job(method), &[("c.json", curves)], needles);
    }
}

/// Issue 35 item 5: a bad blade kerf is refused before anything runs, naming the field.
#[test]
fn bad_blade_kerfs_are_rejected_naming_the_field() {
    let job = |blade: &str| {
        format!(
            "Job(name: \"t\", surface: HeightField(z: \"20*sin(y/300)\", x: (0, 600), y: (0, 1200)), block: Block(size: (600, 600, 400)), blade: Blade(length: 1000, max_curvature: 0.011, {blade}), task: HotBlade(targets_per_block: 5), outputs: [Report])"
        )
    };
    for (blade, needles) in [
        ("kerf: -1", &["/blade/kerf", "≥ 0"][..]),
        (
            "kerf: 200",
            &["/blade/kerf", "wider than the blade's tightest bend"][..],
        ),
        (
            "kerf: 2, kerf_table: [(5, 2)]",
            &["/blade/kerf", "not both"][..],
        ),
        ("kerf_table: []", &["/blade/kerf_table", "1–64 rows"][..]),
        (
            "kerf_table: [(8, 2), (6, 1)]",
            &["/blade/kerf_table/1/0", "increase strictly"][..],
        ),
        (
            "kerf_table: [(0, 2)]",
            &["/blade/kerf_table/0/0", "positive"][..],
        ),
    ] {
        common::expect_invalid(&job(blade), needles);
    }
}

/// The CLI's verdict line is report.html's verdict: the same words, the same answer.
#[test]
fn the_printed_verdict_is_the_pages() {
    // one blade cuts it (ok), and a blade too stiff for its curvature (not ok)
    let page = VALID.replace(
        "task: Analyze(),",
        "task: Analyze(),\n    outputs: [Report, Html],",
    );
    let stiff = page.replace("max_curvature: 0.011", "max_curvature: 0.0001");
    for (job, ok) in [(page.as_str(), true), (stiff.as_str(), false)] {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "job.ron", job);
        let o = hotcut(&["run", "job.ron", "--out", "o"], dir.path());
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let stdout = String::from_utf8_lossy(&o.stdout);
        let word = if ok { "  verdict: " } else { "  warning: " };
        let line = stdout
            .lines()
            .rfind(|l| l.starts_with(word))
            .unwrap_or_else(|| panic!("no {word:?} line in {stdout}"));
        let text = &line[word.len()..];
        let html = std::fs::read_to_string(dir.path().join("o/t/report.html")).unwrap();
        let class = if ok { "ok" } else { "bad" };
        let escaped = text
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        assert!(
            html.contains(&format!("<section id=\"verdict\" class=\"{class}\">"))
                && html.contains(&escaped),
            "{text}"
        );
    }
}
