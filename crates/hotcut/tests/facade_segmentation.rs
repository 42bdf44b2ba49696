//! End-to-end tests of the `FacadeSegmentation` task through the `hotcut` binary: a small
//! run writes every file and its robot targets are the pieces' poses; bad jobs are
//! rejected with their JSON pointers.

mod common;

use common::{expect_invalid, hotcut, stderr, write};

/// A small valid FacadeSegmentation job: a wave across a 1.2 m facade, two rows of blocks.
const SEG: &str = r#"Job(
    name: "t",
    surface: HeightField(z: "40*sin(y/90)", x: (0, 600), y: (0, 1200)),
    block: Block(size: (300, 600, 400)),
    blade: Blade(length: 800, max_curvature: 0.011),
    cutting: Cutting(sections: 6),
    task: FacadeSegmentation(algorithm: Inflection(symmetric: false), samples: 32),
    outputs: [Report, Svg, Gltf, Obj, Csv, RobotTargets(), Rapid],
)
"#;

#[test]
fn facade_segmentation_runs_and_writes_its_files() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", SEG);
    let o = hotcut(&["run", "job.ron", "--out", "o"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("FacadeSegmentation, Inflection"),
        "{stdout}"
    );
    for f in [
        "report.json",
        "segmentation.svg",
        "model.gltf",
        "segmentation.obj",
        "sections.csv",
        "targets.json",
        "targets.csv",
        "t_T_ROB1.mod",
        "t_T_ROB1.pgf",
        "t_T_ROB2.mod",
        "t_T_ROB2.pgf",
    ] {
        assert!(dir.path().join("o/t").join(f).is_file(), "missing {f}");
    }
    let read = |f: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/t").join(f)).unwrap())
            .unwrap()
    };
    let report = read("report.json");
    let targets = read("targets.json");
    let pieces = report["pieces"].as_array().unwrap();
    assert_eq!(
        report["counts"]["pieces"].as_u64(),
        Some(pieces.len() as u64)
    );
    assert_eq!(
        report["counts"]["blocks"].as_u64(),
        Some(pieces.len() as u64)
    );
    // the issue's shape: per piece its id, block, per-section 3D ends, verdicts
    for p in pieces {
        assert!(p["id"].is_u64() && p["block"].is_object() && p["verdicts"].is_object());
        for s in p["sections"].as_array().unwrap() {
            assert!(s["offset"].is_number());
            assert_eq!(s["start"].as_array().unwrap().len(), 3);
            assert_eq!(s["end"].as_array().unwrap().len(), 3);
        }
    }
    // one pose per section part of every piece, the targets blocks are the pieces
    let blocks = targets["blocks"].as_array().unwrap();
    assert_eq!(blocks.len(), pieces.len());
    for (b, p) in blocks.iter().zip(pieces) {
        assert_eq!(b["block"], p["id"]);
        assert_eq!(
            b["poses"].as_array().unwrap().len(),
            p["sections"].as_array().unwrap().len()
        );
    }
}

#[test]
fn facade_segmentation_jobs_are_checked() {
    let task = "task: FacadeSegmentation(algorithm: Inflection(symmetric: false), samples: 32),";
    let with_task = |t: &str| SEG.replace(task, t);
    expect_invalid(
        &SEG.replace("block: Block(size: (300, 600, 400)),", ""),
        &["/block", "needs `block`"],
    );
    expect_invalid(
        &SEG.replace(
            "surface: HeightField(z: \"40*sin(y/90)\", x: (0, 600), y: (0, 1200)),",
            "",
        ),
        &["/surface", "needs a surface"],
    );
    expect_invalid(
        &SEG.replace(
            "max_curvature: 0.011)",
            "max_curvature: 0.011, max_inflections: 0)",
        ),
        &["/blade/max_inflections", "max_inflections ≥ 1"],
    );
    for (t, needle) in [
        (
            "FacadeSegmentation(algorithm: LongestElastica(precision: 0))",
            "/task/FacadeSegmentation/algorithm/LongestElastica/precision",
        ),
        (
            "FacadeSegmentation(algorithm: LongestElastica(precision: NaN))",
            "precision",
        ),
        (
            "FacadeSegmentation(algorithm: LongestElastica(max_step: -3))",
            "/task/FacadeSegmentation/algorithm/LongestElastica/max_step",
        ),
        (
            "FacadeSegmentation(algorithm: Trace(link_distance: -1))",
            "/task/FacadeSegmentation/algorithm/Trace/link_distance",
        ),
        (
            "FacadeSegmentation(algorithm: Trace(min_sections: 0))",
            "min_sections",
        ),
        (
            "FacadeSegmentation(algorithm: Trace(), samples: 4)",
            "samples",
        ),
        (
            "FacadeSegmentation(algorithm: Trace(), constraint: Free)",
            "/task/FacadeSegmentation/constraint",
        ),
        (
            "FacadeSegmentation(algorithm: Trace(), speed: -7)",
            "/task/FacadeSegmentation/speed",
        ),
        ("FacadeSegmentation(algorithm: Zigzag())", "Zigzag"),
        ("FacadeSegmentation()", "algorithm"),
        (
            "FacadeSegmentation(algorithm: Inflection(symmetric: false, wobble: 1))",
            "wobble",
        ),
    ] {
        expect_invalid(&with_task(&format!("task: {t},")), &[needle]);
    }
    // robot files need the pieces posed, and FacadeSegmentation has no per_block
    expect_invalid(
        &with_task("task: FacadeSegmentation(algorithm: Trace(), rationalize: false),"),
        &["/outputs/5", "rationalize: true"],
    );
    expect_invalid(
        &SEG.replace("RobotTargets()", "RobotTargets(per_block: 5)"),
        &["/outputs/5/RobotTargets/per_block", "leave per_block out"],
    );
}
