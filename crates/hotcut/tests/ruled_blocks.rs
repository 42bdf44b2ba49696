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

#[test]
fn a_model_no_ruled_surface_approximates_fails_with_a_report_and_no_program() {
    // a bumpy field, 2 strips at most around each section: nowhere near 0.01 mm
    let text = job(
        WAVE,
        400.0,
        "RuledBlocks(sections: 8, max_strips: 2, grid: 24, max_iterations: 4)",
        "",
    )
    .replace("Tolerance(max: 2.0)", "Tolerance(max: 0.01)")
    .replace("[Report, GCode]", "[Report, GCode, Obj, Svg, Html]");
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
    let text = job(
        WAVE,
        400.0,
        "RuledBlocks(sections: 8, max_strips: 2, grid: 24, max_iterations: 4)",
        "",
    )
    .replace("Tolerance(max: 2.0)", "Tolerance(max: 0.01)")
    .replace("[Report, GCode]", "[GCode]");
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
