//! The `Compare` task's bad input: every bad rate, tool or process gets an error naming
//! its field, at validation and before any run; a process that cannot apply to the
//! design is reported "not applicable" with the reason; a comparison where no process
//! makes the design fails with a report that says why, and no machine file.

mod common;

use common::{expect_invalid, hotcut, stderr, write};

/// A small mould: a bump in a 400 mm block.
fn job(processes: &str, rates: &str, extra: &str) -> String {
    format!(
        r#"Job(
    name: "t",
    surface: HeightField(z: "100 + 80*exp(-((x/150)^2 + (y/150)^2))", x: (-200, 200), y: (-200, 200)),
    block: Block(size: (400, 400, 300), origin: (-200, -200, 0)),
    wire: Wire(tower_distance: 1000, kerf: 1.0, travel: Travel(along: (0, 2000), up: (0, 2000))),
    tolerance: Tolerance(max: 2.0),
    task: Compare(processes: [{processes}], rates: Rates({rates})),
    outputs: [Report, Svg, GCode, Html],
    {extra}
)"#
    )
}

const MILL: &str = "Milling(tool: Tool(diameter: 10, stepover: 2))";
const PRECUT: &str = "PreCutThenMilling(pre_cut: PreCut(legs: 3, directions: [X], sections: 10, samples: 10, controls: 5))";

#[test]
fn a_negative_price_is_refused_naming_the_rate() {
    expect_invalid(
        &job(MILL, "eps_per_m3: -5", ""),
        &["/task/Compare/rates/eps_per_m3", "from 0"],
    );
}

#[test]
fn a_speed_of_zero_is_refused_naming_the_rate() {
    expect_invalid(
        &job(MILL, "wire_speed: 0", ""),
        &["/task/Compare/rates/wire_speed", "above 0"],
    );
    expect_invalid(
        &job(MILL, "blade_speed: 0.0", ""),
        &["/task/Compare/rates/blade_speed"],
    );
}

#[test]
fn a_nan_or_infinite_rate_is_refused_naming_the_rate() {
    for v in ["NaN", "inf", "-inf"] {
        expect_invalid(
            &job(MILL, &format!("removal_rate: {v}"), ""),
            &["/task/Compare/rates/removal_rate"],
        );
    }
}

#[test]
fn an_unknown_process_or_rate_is_refused() {
    expect_invalid(&job("Lasering(power: 5)", "", ""), &["Lasering"]);
    expect_invalid(&job(MILL, "eps_per_litre: 5", ""), &["eps_per_litre"]);
}

#[test]
fn a_bad_tool_is_refused_naming_its_field() {
    expect_invalid(
        &job("Milling(tool: Tool(diameter: 10, stepover: 12))", "", ""),
        &["/task/Compare/processes/0/Milling/tool/stepover"],
    );
    expect_invalid(
        &job("Milling(tool: Tool(diameter: -1))", "", ""),
        &["/task/Compare/processes/0/Milling/tool/diameter"],
    );
}

#[test]
fn an_empty_list_is_refused() {
    expect_invalid(&job("", "", ""), &["/task/Compare/processes"]);
}

#[test]
fn a_process_task_error_names_the_field_inside_the_process() {
    // PreCut's own check: legs must be at least 1
    expect_invalid(
        &job(
            "PreCutThenMilling(pre_cut: PreCut(legs: 0, directions: [X]))",
            "",
            "",
        ),
        &["/task/Compare/processes/0/PreCutThenMilling/pre_cut"],
    );
}

#[test]
fn a_hot_wire_process_without_a_wire_is_refused() {
    let text = job(PRECUT, "", "").replace(
        "    wire: Wire(tower_distance: 1000, kerf: 1.0, travel: Travel(along: (0, 2000), up: (0, 2000))),\n",
        "",
    );
    expect_invalid(&text, &["/wire", "PreCutThenMilling"]);
}

/// The report of `text` run in a fresh folder, and the run's exit code.
fn run(text: &str) -> (Option<i32>, serde_json::Value, tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    let report = std::fs::read_to_string(dir.path().join("out/t/report.json"))
        .map(|t| serde_json::from_str(&t).unwrap())
        .unwrap_or(serde_json::Value::Null);
    (o.status.code(), report, dir, stderr(&o))
}

#[test]
fn processes_that_cannot_apply_are_reported_with_their_reason() {
    // a closed cube: the hot blade and pre-cuts do not apply
    let cube = "v 0 0 0\nv 300 0 0\nv 300 300 0\nv 0 300 0\nv 0 0 300\nv 300 0 300\nv 300 300 300\nv 0 300 300\n\
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
    let text = job(
        &format!("{MILL}, {PRECUT}, HotBlade(targets_per_block: 11)"),
        "",
        "",
    )
    .replace(
        r#"HeightField(z: "100 + 80*exp(-((x/150)^2 + (y/150)^2))", x: (-200, 200), y: (-200, 200))"#,
        r#"Mesh(path: "cube.obj", closed: true)"#,
    )
    .replace(", origin: (-200, -200, 0)", "");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cube.obj", cube);
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out/t/report.json")).unwrap(),
    )
    .unwrap();
    let p = r["processes"].as_array().unwrap();
    assert_eq!(p.len(), 3, "no process is left out");
    assert_eq!(p[0]["status"], "Feasible");
    for (i, word) in [(1, "pre-cuts"), (2, "hot blade")] {
        assert_eq!(p[i]["status"], "NotApplicable");
        assert!(p[i]["reason"].as_str().unwrap().contains(word), "{}", p[i]);
        assert!(p[i]["cost"].is_null());
    }
    assert_eq!(r["winner"], "milling");
    // what did not run has no folder
    assert!(p[2]["folder"].is_null());
}

#[test]
fn when_no_process_is_feasible_the_run_fails_with_its_report_and_no_program() {
    // a 5 mm ball at a 4.9 mm stepover leaves a 2.0 mm scallop: over a tolerance of
    // 0.1 mm, for the plain milling and for the pre-cut's
    let text = job(
        "Milling(tool: Tool(diameter: 5, stepover: 4.9)), PreCutThenMilling(pre_cut: PreCut(legs: 3, directions: [X], sections: 10, samples: 10, controls: 5), tool: Tool(diameter: 5, stepover: 4.9))",
        "",
        "",
    )
    .replace("Tolerance(max: 2.0)", "Tolerance(max: 0.1)");
    let (code, report, dir, err) = run(&text);
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("no process makes the design"), "{err}");
    assert!(report["winner"].is_null());
    for p in report["processes"].as_array().unwrap() {
        assert_eq!(p["status"], "Infeasible");
        assert!(p["reason"].as_str().unwrap().contains("scallop"), "{p}");
    }
    let out = dir.path().join("out/t");
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["report.html", "report.json"], "no machine file");
}

#[test]
fn a_mould_runs_and_each_process_writes_its_own_files() {
    let (code, r, dir, err) = run(&job(&format!("{MILL}, {PRECUT}"), "", ""));
    assert_eq!(code, Some(0), "{err}");
    let out = dir.path().join("out/t");
    assert!(out.join("precut_milling/report.json").is_file());
    assert!(out.join("precut_milling/wire_d1_c1.gcode").is_file());
    assert!(out.join("comparison.svg").is_file());
    assert_eq!(r["processes"][1]["folder"], "precut_milling");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    // the page opens on the comparison: its table comes before the drawings
    let table = html.find("Processes side by side").unwrap();
    let drawing = html.find("comparison.svg").unwrap();
    assert!(table < drawing);
    assert!(html.contains("★ cheapest"));
}

#[test]
fn a_rate_or_tool_far_out_of_range_is_refused_naming_its_field() {
    for (rates, field) in [
        ("removal_rate: 1e-300", "removal_rate"),
        ("eps_per_m3: 1e300", "eps_per_m3"),
        ("wire_speed: 1e-320", "wire_speed"),
    ] {
        expect_invalid(
            &job(MILL, rates, ""),
            &[&format!("/task/Compare/rates/{field}")],
        );
    }
    expect_invalid(
        &job(
            "Milling(tool: Tool(diameter: 1e300, stepover: 1e299))",
            "",
            "",
        ),
        &["/task/Compare/processes/0/Milling/tool/diameter"],
    );
}

/// The rows of a run of `processes` on the small mould (`edit` applied to the job text).
fn rows(processes: &str, edit: impl Fn(String) -> String) -> Vec<serde_json::Value> {
    let (code, r, _dir, err) = run(&edit(job(processes, "", "")));
    assert_eq!(code, Some(0), "{err}");
    r["processes"].as_array().unwrap().clone()
}

#[test]
fn a_pre_cut_that_makes_one_block_of_a_wider_design_is_infeasible() {
    // the design runs 200 mm past the block in x: milling tiles it, the pre-cut cannot
    let p = rows(&format!("{MILL}, {PRECUT}"), |t| {
        t.replace("x: (-200, 200)", "x: (-200, 400)")
    });
    assert_eq!(p[0]["status"], "Feasible", "{}", p[0]);
    assert_eq!(p[0]["figures"]["blocks"], 2);
    assert_eq!(p[1]["status"], "Infeasible", "{}", p[1]);
    assert!(p[1]["reason"].as_str().unwrap().contains("one block"));
}

#[test]
fn milling_a_placed_block_the_design_is_not_in_is_infeasible() {
    let text = job(MILL, "", "")
        .replace("origin: (-200, -200, 0)", "origin: (-200, -200, 150)")
        .replace("GCode, ", "");
    let (code, r, _dir, err) = run(&text);
    // the only process cannot make it: the run fails with its report
    assert_eq!(code, Some(1), "{err}");
    let p = &r["processes"][0];
    assert_eq!(p["status"], "Infeasible", "{p}");
    assert!(p["reason"]
        .as_str()
        .unwrap()
        .contains("below the blocks' origin"));
}

#[test]
fn block_segmentation_on_a_height_field_is_not_applicable_and_the_ruled_wire_runs_on_a_placed_block(
) {
    let p = rows(
        &format!("{MILL}, Milling(stock: BlockSegmentation(restarts: 1)), HotWireRuled(sections: 10, max_strips: 16, grid: 16, max_iterations: 3)"),
        |t| t,
    );
    assert_eq!(p[1]["status"], "NotApplicable", "{}", p[1]);
    assert!(p[1]["folder"].is_null(), "nothing written, no folder");
    // RuledBlocks places its blocks itself: the job's origin is left out for it
    assert_ne!(p[2]["status"], "NotApplicable", "{}", p[2]);
    assert!(p[2]["figures"]["blocks"].as_u64().unwrap() >= 1);
}

#[test]
fn a_wire_process_is_timed_at_its_own_programs_speed() {
    // hours cutting, the preheat dwells left out
    let hours = |speed: &str| {
        let p = rows(PRECUT, |t| {
            t.replace("kerf: 1.0,", &format!("kerf: 1.0, speed: {speed},"))
        });
        p[0]["hours"]["wire"].as_f64().unwrap()
            - p[0]["figures"]["dwell_s"].as_f64().unwrap() / 3600.0
    };
    let (fast, slow) = (hours("300"), hours("150"));
    assert!(
        (slow / fast - 2.0).abs() < 1e-6,
        "{fast} h at 300 mm/min, {slow} h at 150"
    );
}

#[test]
fn an_output_no_process_writes_is_refused() {
    // milling alone writes no G-code
    expect_invalid(&job(MILL, "", ""), &["/outputs/2", "GCode"]);
}

#[test]
fn a_scallop_over_the_rms_tolerance_is_infeasible() {
    // 10 mm ball, 6 mm stepover: scallop 1.0 mm high (within max 2), RMS ≈ 0.29 mm
    let text = job(
        &format!("Milling(tool: Tool(diameter: 10, stepover: 6)), {MILL}"),
        "",
        "",
    )
    .replace("Tolerance(max: 2.0)", "Tolerance(rms: 0.1, max: 2.0)")
    .replace("GCode, ", "");
    let (code, r, _dir, err) = run(&text);
    assert_eq!(code, Some(0), "{err}");
    let p = r["processes"].as_array().unwrap();
    assert_eq!(p[0]["status"], "Infeasible", "{}", p[0]);
    assert!(p[0]["reason"].as_str().unwrap().contains("tolerance.rms"));
    assert_eq!(p[1]["status"], "Feasible", "{}", p[1]);
}
