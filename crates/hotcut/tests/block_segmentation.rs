//! The `BlockSegmentation` task end to end: files and their format, identical
//! `blocks.json` for 1 and 2 threads, and bad jobs rejected with a pointer.

mod common;

use std::path::PathBuf;

use common::{expect_invalid, hotcut, stderr, write};
use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::NoProgress;

fn torus() -> PathBuf {
    testdata::mesh("torus.obj", "block_segmentation")
        .unwrap()
        .canonicalize()
        .unwrap()
}

fn job(task: &str, extra: &str) -> String {
    format!(
        r#"Job(
    name: "t",
    units: Metre,
    surface: Mesh(path: "{}"),
    block: Block(size: (0.8, 0.8, 0.8)),
    task: {task},
    outputs: [Report, Blocks, Svg, Obj, Gltf],
    seed: 5,
    {extra}
)"#,
        torus().display()
    )
}

const SMALL: &str = "BlockSegmentation(restarts: 3, max_iterations: 6, sample_spacing: 0.125)";

#[test]
fn runs_and_writes_every_file() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &job(SMALL, ""));
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("(BlockSegmentation):"), "{stdout}");
    let out = dir.path().join("out/t");
    for f in [
        "report.json",
        "blocks.json",
        "progress.svg",
        "blocks.obj",
        "model.gltf",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let blocks: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("blocks.json")).unwrap()).unwrap();
    let list = blocks["blocks"].as_array().unwrap();
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let seg = &report["segmentation"];
    assert_eq!(list.len() as u64, seg["final_blocks"].as_u64().unwrap());
    assert!(seg["final_blocks"].as_u64() <= seg["initial_blocks"].as_u64());
    assert_eq!(seg["seed"].as_u64(), Some(5));
    assert_eq!(seg["restarts"].as_array().unwrap().len(), 3);
    assert!(seg["history"].as_array().unwrap().len() >= 2);
    for b in list {
        let q: Vec<f64> = b["rotation"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!((norm - 1.0).abs() < 1e-6 && q[0] >= 0.0, "{q:?}");
        assert_eq!(b["center"].as_array().unwrap().len(), 3);
        for s in b["size"].as_array().unwrap() {
            assert!((s.as_f64().unwrap() - 0.8).abs() < 1e-9);
        }
    }
    let obj = std::fs::read_to_string(out.join("blocks.obj")).unwrap();
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("v ")).count(),
        8 * list.len()
    );
    let svg = std::fs::read_to_string(out.join("progress.svg")).unwrap();
    assert!(svg.contains("blocks per iteration"));
}

/// Same job and seed: identical `blocks.json` (and report) with 1 and with 2 threads.
#[test]
fn one_and_two_threads_give_identical_blocks() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "job.ron", &job(SMALL, ""));
    let job = load_job(&path).unwrap();
    let run = |threads: usize| -> (Vec<u8>, Vec<u8>) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let out = dir.path().join(format!("out{threads}"));
        let o = pool.install(|| run_job(&job, &out, &NoProgress)).unwrap();
        (
            std::fs::read(o.dir.join("blocks.json")).unwrap(),
            std::fs::read(o.dir.join("report.json")).unwrap(),
        )
    };
    let (b1, r1) = run(1);
    let (b2, r2) = run(2);
    assert!(b1 == b2, "blocks.json differs between 1 and 2 threads");
    assert!(r1 == r2, "report.json differs between 1 and 2 threads");
    assert!(b1.len() > 100);
}

#[test]
fn bad_block_segmentation_jobs_are_rejected_with_a_pointer() {
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "BlockSegmentation(p: 0.5)",
            "",
            &["/task/BlockSegmentation/p"],
        ),
        (
            "BlockSegmentation(epsilon: 0)",
            "",
            &["/task/BlockSegmentation/epsilon"],
        ),
        (
            "BlockSegmentation(epsilon: NaN)",
            "",
            &["/task/BlockSegmentation/epsilon"],
        ),
        (
            "BlockSegmentation(restarts: 0)",
            "",
            &["/task/BlockSegmentation/restarts"],
        ),
        (
            "BlockSegmentation(max_iterations: 0)",
            "",
            &["/task/BlockSegmentation/max_iterations"],
        ),
        (
            "BlockSegmentation(time_limit: Some(-1))",
            "",
            &["/task/BlockSegmentation/time_limit"],
        ),
        (
            "BlockSegmentation(sample_spacing: 0.5)",
            "",
            &["/task/BlockSegmentation/sample_spacing"],
        ),
        (
            "BlockSegmentation(operations: [])",
            "",
            &["/task/BlockSegmentation/operations"],
        ),
        (
            "BlockSegmentation(operations: [Translate, Translate])",
            "",
            &["/task/BlockSegmentation/operations/1", "twice"],
        ),
        ("BlockSegmentation(operations: [Shear])", "", &["Shear"]),
        ("BlockSegmentation(colour: 1)", "", &["colour"]),
    ];
    for (task, extra, needles) in cases {
        expect_invalid(&job(task, extra), needles);
    }
    // An open mesh (a cube without its top, `closed` not written: the mesh itself is
    // checked), a height field, no block, a placed block, a negative size.
    let t = torus().display().to_string();
    let open = tempfile::tempdir().unwrap();
    let v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
    let f = "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
    write(open.path(), "open.obj", &format!("{v}{f}"));
    let o = open.path().join("open.obj").display().to_string();
    expect_invalid(
        &format!(
            r#"Job(name: "t", surface: Mesh(path: "{o}"), block: Block(size: (1, 1, 1)), task: BlockSegmentation)"#
        ),
        &["/surface/Mesh/path", "open: 4 boundary edges in 1 loops"],
    );
    expect_invalid(
        r#"Job(name: "t", surface: HeightField(z: "x", x: (0, 1), y: (0, 1)), block: Block(size: (1, 1, 1)), task: BlockSegmentation())"#,
        &["/surface", "closed triangle mesh"],
    );
    expect_invalid(
        &format!(
            r#"Job(name: "t", surface: Mesh(path: "{t}", closed: true), task: BlockSegmentation())"#
        ),
        &["/block"],
    );
    expect_invalid(
        &format!(
            r#"Job(name: "t", surface: Mesh(path: "{t}", closed: true), block: Block(size: (1, 1, 1), origin: Some((0, 0, 0))), task: BlockSegmentation())"#
        ),
        &["/block/origin"],
    );
    expect_invalid(
        &format!(
            r#"Job(name: "t", surface: Mesh(path: "{t}", closed: true), block: Block(size: (1, -1, 1)), task: BlockSegmentation())"#
        ),
        &["/block/size/1"],
    );
    // Outputs of other tasks.
    expect_invalid(
        &format!(
            r#"Job(name: "t", surface: Mesh(path: "{t}", closed: true), block: Block(size: (1, 1, 1)), task: BlockSegmentation(), outputs: [Rapid])"#
        ),
        &["/outputs/0"],
    );
}

/// A block far too small for the model: a clear error at validation (the sample cap and
/// the memory estimate, each naming its field), no output folder.
#[test]
fn too_small_blocks_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let text = job(SMALL, "").replace("(0.8, 0.8, 0.8)", "(0.002, 0.002, 0.002)");
    write(dir.path(), "job.ron", &text);
    for cmd in ["validate", "run"] {
        let o = hotcut(&[cmd, "job.ron"], dir.path());
        assert_eq!(o.status.code(), Some(1));
        let e = stderr(&o);
        assert!(
            e.contains("/task/BlockSegmentation/sample_spacing")
                && e.contains("samples would be needed"),
            "{e}"
        );
        assert!(
            e.contains("/block/size") && e.contains("--max-memory"),
            "{e}"
        );
        assert!(!dir.path().join("out/t").exists());
    }
}

/// Bounding box of object `name`'s vertices in an OBJ text.
fn obj_box(text: &str, name: &str) -> ([f64; 3], [f64; 3]) {
    let mut inside = false;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for line in text.lines() {
        if let Some(o) = line.strip_prefix("o ") {
            inside = o == name;
        } else if let (true, Some(v)) = (inside, line.strip_prefix("v ")) {
            let p: Vec<f64> = v.split_whitespace().map(|x| x.parse().unwrap()).collect();
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    (lo, hi)
}

#[test]
fn obj_y_up_lands_where_the_gltf_does() {
    // `Obj(axes: YUp)` writes what glTF readers show: the glTF's block_0, in metres and
    // turned by its root node, is the OBJ's block_0; plain `Obj` stays z up
    let dir = tempfile::tempdir().unwrap();
    let text = job(SMALL, "").replace(
        "outputs: [Report, Blocks, Svg, Obj, Gltf]",
        "outputs: [Report, Obj(axes: YUp), Gltf]",
    );
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = dir.path().join("out/t");
    let obj = std::fs::read_to_string(out.join("blocks.obj")).unwrap();
    assert!(obj.contains("# units: Metre (1 unit = 1 m)"), "{obj}");
    assert!(obj.contains("+y up"), "{obj}");
    let g: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("model.gltf")).unwrap()).unwrap();
    assert_eq!(g["asset"]["extras"]["source_units"], "Metre");
    let mesh = g["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "block_0")
        .unwrap();
    let acc = &g["accessors"][mesh["primitives"][0]["attributes"]["POSITION"]
        .as_u64()
        .unwrap() as usize];
    let v = |k: &str| -> Vec<f64> {
        acc[k]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (a, b) = (v("min"), v("max"));
    // the root node `z-up`: (x, y, z) → (x, z, −y)
    let (want_lo, want_hi) = ([a[0], a[2], -b[1]], [b[0], b[2], -a[1]]);
    let (lo, hi) = obj_box(&obj, "block_0");
    for k in 0..3 {
        assert!((lo[k] - want_lo[k]).abs() < 1e-6, "{lo:?} vs {want_lo:?}");
        assert!((hi[k] - want_hi[k]).abs() < 1e-6, "{hi:?} vs {want_hi:?}");
    }
    let root = g["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["name"] == "z-up")
        .unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let q: Vec<f64> = root["rotation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((q[0] + h).abs() < 1e-12 && q[1] == 0.0 && q[2] == 0.0 && (q[3] - h).abs() < 1e-12);
    // and the default form, in the same list syntax, stays z up
    let text = job(SMALL, "").replace(
        "outputs: [Report, Blocks, Svg, Obj, Gltf]",
        "outputs: [Report, Obj]",
    );
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out2"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let obj = std::fs::read_to_string(dir.path().join("out2/t/blocks.obj")).unwrap();
    assert!(obj.contains("+z up"), "{obj}");
}
