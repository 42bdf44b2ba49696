//! The `RuledBlocks` task's bad input: each gets a clear error naming its field, and
//! writes nothing; a model no ruled surface approximates within the tolerance fails with
//! its numbers, writes a report that says so, and no program.

mod common;

use common::{expect_invalid, expect_invalid_with, hotcut, stderr, write};

/// A closed cube, 400 mm, as OBJ.
const CUBE: &str = "v 0 0 0\nv 400 0 0\nv 400 400 0\nv 0 400 0\nv 0 0 400\nv 400 0 400\nv 400 400 400\nv 0 400 400\n\
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

fn job(surface: &str, block: f64, task: &str, extra: &str) -> String {
    format!(
        r#"Job(
    name: "t",
    surface: {surface},
    block: Block(size: ({block}, {block}, {block})),
    wire: Wire(tower_distance: 1400, kerf: 1.0, travel: Travel(along: (0, 4000), up: (0, 4000))),
    tolerance: Tolerance(max: 2.0),
    task: {task},
    outputs: [Report, GCode],
    {extra}
)"#
    )
}

const WAVE: &str = r#"HeightField(z: "100 + 40*sin(x/150)*cos(y/170)", x: (0, 600), y: (0, 500))"#;
const TASK: &str = "RuledBlocks(sections: 16, max_strips: 32, grid: 24, max_iterations: 4)";

/// Runs `task` on the small wave: a program per cut in the report, both strategies compared.
fn runs_with_a_program_per_cut(task: &str) {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &job(WAVE, 400.0, task, ""));
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = dir.path().join("out/t");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let cuts: usize = report["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["cuts"].as_array().unwrap().len())
        .sum();
    let programs = std::fs::read_dir(&out)
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "gcode"))
        .count();
    assert!(cuts > 0);
    assert_eq!(programs, cuts);
    assert_eq!(report["comparison"].as_array().unwrap().len(), 2);
}

#[test]
fn a_small_wave_runs_and_writes_a_program_per_cut() {
    runs_with_a_program_per_cut(TASK);
}

#[test]
fn per_block_writes_a_program_per_cut_too() {
    runs_with_a_program_per_cut(
        "RuledBlocks(strategy: PerBlock, sections: 16, max_strips: 32, grid: 24, max_iterations: 4)",
    );
}

#[test]
fn an_open_mesh_is_refused() {
    // the cube without its top
    let open: String = CUBE
        .lines()
        .filter(|l| *l != "f 5 6 7" && *l != "f 5 7 8")
        .map(|l| format!("{l}\n"))
        .collect();
    expect_invalid_with(
        &job(r#"Mesh(path: "m.obj")"#, 300.0, TASK, ""),
        &[("m.obj", &open)],
        &["/surface/Mesh/path", "open", "boundary edges"],
    );
}

#[test]
fn a_non_manifold_mesh_is_refused() {
    // three triangles on one edge
    let bad = "v 0 0 0\nv 100 0 0\nv 0 100 0\nv 0 0 100\nv 0 -100 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    expect_invalid_with(
        &job(r#"Mesh(path: "m.obj")"#, 300.0, TASK, ""),
        &[("m.obj", bad)],
        &["non-manifold"],
    );
}

#[test]
fn a_block_no_larger_than_the_tolerance_is_refused() {
    expect_invalid(&job(WAVE, 1.5, TASK, ""), &["/block/size", "tolerance"]);
}

#[test]
fn other_surfaces_and_a_block_origin_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let _ = dir;
    expect_invalid(
        &job(WAVE, 400.0, TASK, "").replace(
            "Block(size: (400, 400, 400))",
            "Block(size: (400, 400, 400), origin: (0, 0, 0))",
        ),
        &["/block/origin"],
    );
    expect_invalid(
        &job(WAVE, 400.0, "RuledBlocks(sections: 2)", ""),
        &["/task/RuledBlocks/sections"],
    );
}

#[test]
fn g_code_needs_the_wire() {
    let text = job(WAVE, 400.0, TASK, "").replace(
        "    wire: Wire(tower_distance: 1400, kerf: 1.0, travel: Travel(along: (0, 4000), up: (0, 4000))),\n",
        "",
    );
    expect_invalid(&text, &["/wire"]);
}

/// A job no ruled surface approximates, writing `outputs`: a bumpy field, 2 strips at
/// most around each section, nowhere near a 0.01 mm tolerance.
fn unapproximable(outputs: &str) -> String {
    job(
        WAVE,
        400.0,
        "RuledBlocks(sections: 8, max_strips: 2, grid: 24, max_iterations: 4)",
        "",
    )
    .replace("Tolerance(max: 2.0)", "Tolerance(max: 0.01)")
    .replace("[Report, GCode]", outputs)
}

#[test]
fn a_model_no_ruled_surface_approximates_fails_with_a_report_and_no_program() {
    let text = unapproximable("[Report, GCode, Obj, Svg, Html]");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &text);
    // an earlier good run's programs must not survive next to the failed run's report
    let old = dir.path().join("out/t");
    std::fs::create_dir_all(&old).unwrap();
    std::fs::write(old.join("block_01_cut_01.gcode"), "G0 X0\n").unwrap();
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("no piecewise ruled surface"), "{e}");
    assert!(
        e.contains("deviation max") && e.contains("> tolerance.max 0.01"),
        "{e}"
    );
    assert!(
        e.contains("only report.json and report.html written"),
        "{e}"
    );
    let mut files: Vec<String> = std::fs::read_dir(&old)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["report.html", "report.json"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(old.join("report.json")).unwrap()).unwrap();
    let why = report["nothing_to_cut"]
        .as_str()
        .expect("the report says why");
    assert!(why.contains("no piecewise ruled surface"), "{why}");
    // and lists no program it did not write
    for b in report["blocks"].as_array().unwrap() {
        for c in b["cuts"].as_array().unwrap() {
            assert!(c["program"].is_null(), "{c}");
        }
    }
    let d = &report["deviation"];
    assert_eq!(d["within_tolerance"], false);
    assert!(d["max"].as_f64().unwrap() > 0.01, "{d}");
    let page = std::fs::read_to_string(old.join("report.html")).unwrap();
    assert!(
        page.contains("No piecewise ruled surface"),
        "the page says so"
    );
}

#[test]
fn without_a_report_output_a_model_no_ruled_surface_approximates_writes_nothing() {
    let text = unapproximable("[GCode]");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("no file written"), "{}", stderr(&o));
    assert!(
        !dir.path().join("out/t").exists(),
        "a failed run wrote files"
    );
}

/// A degree-1 B-spline surface of `rows` (each a list of `(x, y, z)` control points) as
/// the control-grid JSON a job's `Spline(path: ..)` reads.
fn grid_json(rows: &[Vec<(f64, f64, f64)>]) -> String {
    let rows: Vec<String> = rows
        .iter()
        .map(|r| {
            let pts: Vec<String> = r
                .iter()
                .map(|(x, y, z)| format!("[{x}, {y}, {z}]"))
                .collect();
            format!("[{}]", pts.join(", "))
        })
        .collect();
    format!(
        r#"{{"degree_u": 1, "degree_v": 1, "points": [{}]}}"#,
        rows.join(", ")
    )
}

#[test]
fn an_open_b_spline_surface_is_closed_into_a_slab_and_cut() {
    // a twisted panel over 800 × 600 mm: one height per (x, y)
    let rows: Vec<Vec<(f64, f64, f64)>> = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| {
                    let (x, y) = (400.0 * i as f64, 300.0 * j as f64);
                    (x, y, 100.0 + 0.0002 * (x - 400.0) * (y - 300.0))
                })
                .collect()
        })
        .collect();
    let text = job(r#"Spline(path: "panel.json")"#, 400.0, TASK, "")
        .replace("[Report, GCode]", "[Report, Obj, GCode]");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "panel.json", &grid_json(&rows));
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = dir.path().join("out/t");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    // the slab: the panel over its 800 × 600 mm shadow, down to 50 mm under its lowest
    // point (76 mm); the panel's mean height is 100 mm, and the job's 24 × 24 cells, each
    // split along its rising diagonal, add a·h²k²/12 each for the twist a·x·y
    let v = report["model"]["volume"].as_f64().unwrap();
    let (h, k) = (800.0 / 24.0, 600.0 / 24.0);
    let expected = 800.0 * 600.0 * (100.0 - (76.0 - 50.0)) + 576.0 * 0.0002 * h * h * k * k / 12.0;
    assert!((v - expected).abs() < 1e-6 * expected, "{v} vs {expected}");
    assert!(std::fs::read_to_string(out.join("rationalized.obj"))
        .unwrap()
        .contains("o model"));
    assert!(report["deviation"]["within_tolerance"].as_bool().unwrap());
}

#[test]
fn a_b_spline_surface_that_folds_over_is_refused_at_validation() {
    // the middle row of control points pulled back past the first: the surface folds
    let rows: Vec<Vec<(f64, f64, f64)>> = [0.0, -300.0, 400.0]
        .iter()
        .map(|&x| (0..3).map(|j| (x, 300.0 * j as f64, 100.0)).collect())
        .collect();
    expect_invalid_with(
        &job(r#"Spline(path: "panel.json")"#, 400.0, TASK, ""),
        &[("panel.json", &grid_json(&rows))],
        &["/surface/Spline/path", "not a graph over the xy-plane"],
    );
}
