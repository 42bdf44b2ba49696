//! End-to-end tests of the `PreCut` task: files and their format, and bad jobs.

mod common;

use common::{expect_invalid, hotcut, stderr, write};

fn job(task: &str, extra: &str) -> String {
    format!(
        r#"Job(
    name: "t",
    units: Millimetre,
    surface: HeightField(z: "200 + 250*exp(-3*((x/500)^2 + (y/500)^2))", x: (-500, 500), y: (-500, 500)),
    block: Block(size: (1000, 1000, 600), origin: (-500, -500, 0)),
    task: {task},
    outputs: [Report, PreCut, Svg],
    {extra}
)"#
    )
}

/// A JSON array of numbers.
fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

const SMALL: &str =
    "PreCut(legs: 3, directions: [X, Degrees(90)], sections: 10, samples: 10, controls: 5)";

#[test]
fn runs_and_writes_every_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = job(SMALL, "").replace(
        "outputs: [Report, PreCut, Svg]",
        "outputs: [Report, PreCut, Svg, Obj, Gltf]",
    );
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("(PreCut):"), "{stdout}");
    let out = dir.path().join("out/t");
    for f in [
        "report.json",
        "precut.json",
        "sections.svg",
        "precut.obj",
        "model.gltf",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let obj = std::fs::read_to_string(out.join("precut.obj")).unwrap();
    for o in ["o design", "o cut_d1", "o cut_d2", "o block"] {
        assert!(obj.contains(o), "{o} missing from precut.obj");
    }
    let pc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("precut.json")).unwrap()).unwrap();
    let dirs = pc["directions"].as_array().unwrap();
    assert_eq!(dirs.len(), 2);
    for d in dirs {
        let v: Vec<f64> = floats(&d["direction"]);
        assert!(
            (v[0].hypot(v[1]) - 1.0).abs() < 1e-9 && v[2] == 0.0,
            "{v:?}"
        );
        let sections = d["sections"].as_array().unwrap();
        assert_eq!(sections.len(), 11);
        for s in sections {
            let poly = s["polygon"].as_array().unwrap();
            assert!(poly.len() >= 2);
            // Every vertex lies in the section plane: direction · (x, y) = offset.
            let u = s["offset"].as_f64().unwrap();
            for p in poly {
                let p: Vec<f64> = floats(p);
                assert!(
                    (v[0] * p[0] + v[1] * p[1] - u).abs() < 1e-6,
                    "{p:?} off plane {u}"
                );
            }
            // Convex cap: slopes never increase from one edge to the next.
            let slopes: Vec<f64> = poly
                .windows(2)
                .map(|w| {
                    let a: Vec<f64> = floats(&w[0]);
                    let b: Vec<f64> = floats(&w[1]);
                    (b[2] - a[2]) / ((b[0] - a[0]).hypot(b[1] - a[1])).max(1e-12)
                })
                .collect();
            for w in slopes.windows(2) {
                assert!(w[1] <= w[0] + 1e-6, "not convex: {slopes:?}");
            }
        }
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let v = &report["volumes"];
    assert!(v["ruled"].as_f64().unwrap() < v["convex_hull"].as_f64().unwrap());
    assert!(v["more_than_hull_percent"].as_f64().unwrap() > 0.0);
    for d in report["directions"].as_array().unwrap() {
        assert!(d["clearance"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn bad_jobs_are_refused_with_their_field() {
    expect_invalid(&job("PreCut(legs: 0)", ""), &["/task/PreCut/legs"]);
    expect_invalid(
        &job("PreCut(degree: 3, controls: 3)", ""),
        &["/task/PreCut/controls"],
    );
    expect_invalid(
        &job("PreCut(directions: [])", ""),
        &["/task/PreCut/directions"],
    );
    expect_invalid(
        &job("PreCut(directions: [Vector(0, 0)])", ""),
        &["/task/PreCut/directions/0"],
    );
    expect_invalid(
        &job("PreCut(directions: [X, Degrees(0)])", ""),
        &["/task/PreCut/directions/1", "repeats"],
    );
    expect_invalid(&job("PreCut(sections: 1)", ""), &["/task/PreCut/sections"]);
    expect_invalid(&job("PreCut(wires: 3)", ""), &["wires"]);
    expect_invalid(
        &job("PreCut()", "").replace(
            "    block: Block(size: (1000, 1000, 600), origin: (-500, -500, 0)),\n",
            "",
        ),
        &["/block"],
    );
    expect_invalid(
        &job("PreCut()", "").replace(
            "outputs: [Report, PreCut, Svg]",
            "outputs: [Report, Blocks]",
        ),
        &["Blocks"],
    );
}

#[test]
fn wire_outputs_need_a_fitting_machine() {
    expect_invalid(
        &job("PreCut()", "").replace("outputs: [Report, PreCut, Svg]", "outputs: [Report, GCode]"),
        &["/outputs/1", "wire"],
    );
    expect_invalid(
        &job("PreCut()", "wire: Wire(tower_distance: -5, kerf: 1),"),
        &["/wire/tower_distance"],
    );
    // the kerf given once: missing, twice, or a table out of order
    for (wire, field) in [
        ("wire: Wire(tower_distance: 1500),", "/wire/kerf"),
        (
            "wire: Wire(tower_distance: 1500, kerf: 1, kerf_table: [(100, 1)]),",
            "/wire/kerf",
        ),
        (
            "wire: Wire(tower_distance: 1500, kerf_table: [(300, 1), (100, 2)]),",
            "/wire/kerf_table",
        ),
        (
            "wire: Wire(tower_distance: 1500, kerf: 1, preheat_s: 900),",
            "/wire/preheat_s",
        ),
        (
            "wire: Wire(tower_distance: 1500, kerf: 1, speed: 3000, max_speed: 2000),",
            "/wire/speed",
        ),
        (
            "wire: Wire(machine: FluidNc, tower_distance: 1500, kerf: 1),",
            "/wire/machine",
        ),
    ] {
        expect_invalid(&job("PreCut()", wire), &[field]);
    }
    // Towers closer than the block is wide: refused when the cut is known.
    let dir = tempfile::tempdir().unwrap();
    let text = job(
        "PreCut(sections: 6, samples: 6, controls: 4)",
        "wire: Wire(tower_distance: 900, kerf: 1),",
    )
    .replace("outputs: [Report, PreCut, Svg]", "outputs: [Report, GCode]");
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_ne!(o.status.code(), Some(0));
    assert!(stderr(&o).contains("tower_distance"), "{}", stderr(&o));
    assert!(!dir.path().join("out/t").exists());
}

#[test]
fn surface_outside_the_block_fails_at_run_time() {
    let dir = tempfile::tempdir().unwrap();
    let text = job("PreCut(sections: 6, samples: 6, controls: 4)", "")
        .replace("(1000, 1000, 600)", "(1000, 1000, 300)");
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_ne!(o.status.code(), Some(0));
    assert!(stderr(&o).contains("outside the block"), "{}", stderr(&o));
    assert!(!dir.path().join("out/t").exists());
}
