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

/// A meandering wavy facade whose bands are wider than their parts: some pieces' blades,
/// 800 mm long in 600 mm blocks, keep a held end inside the block (issue 37).
const MEANDER: &str = r#"Job(
    name: "m",
    surface: HeightField(z: "40*sin((y + 120*sin(x/300))/90) + 20*cos(x/300)", x: (0, 1200), y: (0, 2400)),
    block: Block(size: (600, 600, 400)),
    blade: Blade(length: 800, max_curvature: 0.011),
    cutting: Cutting(sections: 8),
    task: FacadeSegmentation(algorithm: Trace(), samples: 32),
    outputs: [Report, RobotTargets()],
)
"#;

/// The signed distance from `(u, v)` to the rectangle `[0, w] × [0, h]` (negative inside).
fn to_rect(u: f64, v: f64, w: f64, h: f64) -> f64 {
    let (du, dv) = ((-u).max(u - w), (-v).max(v - h));
    if du <= 0.0 && dv <= 0.0 {
        du.max(dv)
    } else {
        du.max(0.0).hypot(dv.max(0.0))
    }
}

#[test]
fn holders_on_a_block_are_reported_as_the_targets_place_them_and_strict_refuses() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "m.ron", MEANDER);
    let o = hotcut(&["run", "m.ron", "--out", "o"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("hold the blade within 1 %"), "{stdout}");
    let read = |f: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/m").join(f)).unwrap())
            .unwrap()
    };
    let (report, targets) = (read("report.json"), read("targets.json"));
    let counts = &report["counts"];
    assert!(counts["collisions"].as_u64().unwrap() > 0, "{counts}");
    assert_eq!(counts["all_ok"], false);
    let blade = report["settings"]["blade_length"].as_f64().unwrap();
    let v3 =
        |v: &serde_json::Value| -> [f64; 3] { std::array::from_fn(|i| v[i].as_f64().unwrap()) };
    let (mut checked, mut colliding) = (0, 0);
    for (p, b) in report["pieces"]
        .as_array()
        .unwrap()
        .iter()
        .zip(targets["blocks"].as_array().unwrap())
    {
        assert_eq!(p["id"], b["block"]);
        // the block's frame from targets.json: the ends and the part in block coordinates
        let (o, size) = (v3(&b["origin"]), v3(&p["block"]["size"]));
        let r: [f64; 4] = std::array::from_fn(|i| b["rotation"][i].as_f64().unwrap());
        let (w, q) = (r[0], [r[1], r[2], r[3]]);
        let local = |x: [f64; 3]| -> [f64; 3] {
            // the inverse rotation of (x − o) by the unit quaternion (w, q)
            let d = [x[0] - o[0], x[1] - o[1], x[2] - o[2]];
            let (qx, qy, qz) = (-q[0], -q[1], -q[2]);
            let t = [
                2.0 * (qy * d[2] - qz * d[1]),
                2.0 * (qz * d[0] - qx * d[2]),
                2.0 * (qx * d[1] - qy * d[0]),
            ];
            [
                d[0] + w * t[0] + (qy * t[2] - qz * t[1]),
                d[1] + w * t[1] + (qz * t[0] - qx * t[2]),
                d[2] + w * t[2] + (qx * t[1] - qy * t[0]),
            ]
        };
        let posed: Vec<&serde_json::Value> = p["sections"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|s| s["blade_fit"].is_object())
            .collect();
        let poses = b["poses"].as_array().unwrap();
        assert_eq!(posed.len(), poses.len());
        for (s, pose) in posed.iter().zip(poses) {
            // the block holds its piece's part
            for x in [v3(&s["start"]), v3(&s["end"])] {
                let l = local(x);
                for k in 0..3 {
                    let tol = 1e-6 * blade;
                    assert!(
                        l[k] > -tol && l[k] < size[k] + tol,
                        "piece {}: {l:?}",
                        p["id"]
                    );
                }
            }
            let measured = pose["ends"]
                .as_array()
                .unwrap()
                .iter()
                .map(|e| {
                    let l = local(v3(&e["position"]));
                    to_rect(l[1], l[2], size[1], size[2])
                })
                .fold(f64::INFINITY, f64::min);
            let f = &s["blade_fit"];
            let reported = f["holder_clearance"].as_f64().unwrap();
            assert!(
                (measured - reported).abs() < 1e-6 * blade,
                "piece {}: {measured} vs {reported}",
                p["id"]
            );
            // (printed to a few decimals: judged away from the margin itself)
            if (measured - 0.01 * blade).abs() > 1e-6 * blade {
                assert_eq!(f["holders_clear"].as_bool(), Some(measured > 0.01 * blade));
            }
            checked += 1;
            colliding += usize::from(measured <= 0.01 * blade);
        }
    }
    assert!(checked > 20 && colliding > 0, "{checked} {colliding}");
    // strict: no robot program, and the run fails naming the block
    let strict = MEANDER
        .replace(
            "outputs: [Report, RobotTargets()]",
            "outputs: [Report, Rapid]",
        )
        .replace("    task:", "    cell: Cell(strict: true),\n    task:");
    write(dir.path(), "s.ron", &strict);
    let o = hotcut(&["run", "s.ron", "--out", "s"], dir.path());
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("strict: no robot program") && e.contains("holder clearance"),
        "{e}"
    );
    let wrote_mod = std::fs::read_dir(dir.path().join("s"))
        .into_iter()
        .flatten()
        .flatten()
        .any(|f| f.path().to_string_lossy().contains(".mod"));
    assert!(!wrote_mod);
}
