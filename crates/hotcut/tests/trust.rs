//! What an unattended run may rely on (issue 18): a kill at any instant leaves the old or
//! the new output whole; Ctrl-C and TERM leave no temporary folder; concurrent runs of one
//! job both end with a whole folder; a closed or full stdout does not stop the runs; jobs
//! of one name are rejected together; a run with nothing to cut writes nothing.

mod common;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{hotcut, stderr, write};

/// A small HotBlade job (about half a second) writing eight files; `sections` varies the
/// content so two versions of the output can be told apart.
fn blade_job(name: &str, targets: u32) -> String {
    format!(
        r#"Job(name: "{name}", surface: HeightField(z: "(x*x - y*y)/3000", x: (-300, 300), y: (-600, 600)),
        block: Block(size: (600, 600, 400)), blade: Blade(length: 1000, max_curvature: 0.011, max_inflections: 2),
        tolerance: Tolerance(rms: 0.5, max: 2.0),
        task: HotBlade(targets_per_block: {targets}, constraint: EndPoints),
        outputs: [Report, RobotTargets(per_block: {targets}), Rapid, Obj, Svg])"#
    )
}

/// Every file of `dir` (relative name → bytes), empty when `dir` does not exist.
fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    if let Ok(entries) = std::fs::read_dir(dir) {
        for e in entries.flatten() {
            out.insert(
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            );
        }
    }
    out
}

/// Names in `out` that are temporary folders of job `name`.
fn temporaries(out: &Path, name: &str) -> Vec<String> {
    std::fs::read_dir(out)
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|f| f.starts_with(&format!(".{name}.tmp-")))
                .collect()
        })
        .unwrap_or_default()
}

/// SplitMix64: the kill instants, reproducible.
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

fn spawn(args: &[&str], cwd: &Path) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_hotcut"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Two versions of one job's output, as whole runs write them, and a run's duration.
fn references(dir: &Path) -> ([BTreeMap<String, Vec<u8>>; 2], Duration) {
    write(dir, "a.ron", &blade_job("k", 21));
    write(dir, "b.ron", &blade_job("k", 31));
    let start = Instant::now();
    assert!(hotcut(&["run", "a.ron", "--out", "ref-a"], dir)
        .status
        .success());
    let took = start.elapsed();
    assert!(hotcut(&["run", "b.ron", "--out", "ref-b"], dir)
        .status
        .success());
    let refs = [
        contents(&dir.join("ref-a/k")),
        contents(&dir.join("ref-b/k")),
    ];
    assert_ne!(refs[0], refs[1]);
    assert!(refs[0].len() >= 8, "{:?}", refs[0].keys());
    (refs, took)
}

/// A folder with both references and version A's output in place at `out/k`.
fn with_old_output() -> (tempfile::TempDir, [BTreeMap<String, Vec<u8>>; 2], Duration) {
    let dir = tempfile::tempdir().unwrap();
    let (refs, took) = references(dir.path());
    assert!(hotcut(&["run", "a.ron"], dir.path()).status.success());
    (dir, refs, took)
}

/// 36 runs killed (SIGKILL) at random instants over their whole span, writing included:
/// after each, `out/k` is one whole earlier or new output, never a mix or nothing; the
/// temporary folders the kills leave are deleted by the next run.
#[test]
fn a_killed_run_leaves_the_old_or_the_new_output_whole() {
    let (dir, refs, took) = with_old_output();
    let d = dir.path();
    let mut state = 18u64;
    let (mut old, mut new) = (0, 0);
    let mut current = 0usize;
    for k in 0..36 {
        let next = 1 - current;
        let job = if next == 0 { "a.ron" } else { "b.ron" };
        let mut child = spawn(&["run", job], d);
        // instants over the run, denser near its end where the files are written
        let r = splitmix(&mut state);
        std::thread::sleep(took.mul_f64(0.2 + 1.1 * r.sqrt()));
        let _ = child.kill();
        let status = child.wait().unwrap();
        let now = contents(&d.join("out/k"));
        if now == refs[next] {
            new += 1;
            current = next;
        } else {
            assert_eq!(
                now, refs[current],
                "kill {k} ({status}): out/k is neither the old nor the new output"
            );
            old += 1;
        }
    }
    // (how the kills split depends on the machine's load; each outcome was checked whole)
    println!("36 kills: {old} left the old output, {new} the new one");
    assert!(hotcut(&["run", "a.ron"], d).status.success());
    assert_eq!(temporaries(&d.join("out"), "k"), Vec::<String>::new());
    assert_eq!(contents(&d.join("out/k")), refs[0]);
}

/// SIGINT and SIGTERM in the middle of a run: exit 130, no temporary folder, the earlier
/// output untouched.
#[test]
fn interrupted_runs_remove_their_temporary_folder() {
    let (dir, refs, took) = with_old_output();
    let d = dir.path();
    for (signal, at) in [("INT", 0.3), ("TERM", 0.6), ("INT", 0.9)] {
        let mut child = spawn(&["run", "b.ron"], d);
        std::thread::sleep(took.mul_f64(at));
        let sent = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let status = child.wait().unwrap();
        let now = contents(&d.join("out/k"));
        if status.success() {
            // the run finished before the signal
            assert_eq!(now, refs[1]);
            assert!(hotcut(&["run", "a.ron"], d).status.success());
        } else {
            assert_eq!(status.code(), Some(130), "{signal}: {status}");
            assert_eq!(now, refs[0], "{signal}");
        }
        assert_eq!(temporaries(&d.join("out"), "k"), Vec::<String>::new());
    }
}

/// Two runs of one job into one folder at once, five times: both succeed and the folder
/// holds one whole output.
#[test]
fn concurrent_runs_of_one_job_both_end_with_a_whole_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (refs, _) = references(d);
    for round in 0..5 {
        let jobs = if round % 2 == 0 {
            ["a.ron", "b.ron"]
        } else {
            ["b.ron", "b.ron"]
        };
        let mut children: Vec<_> = jobs.iter().map(|j| spawn(&["run", j], d)).collect();
        for c in &mut children {
            let status = c.wait().unwrap();
            assert!(status.success(), "round {round}: {status}");
        }
        let now = contents(&d.join("out/k"));
        assert!(
            now == refs[0] || now == refs[1],
            "round {round}: a mixed folder"
        );
        assert_eq!(temporaries(&d.join("out"), "k"), Vec::<String>::new());
    }
}

/// `hotcut run a b c | head -1`: the reader goes away after the first line; every job
/// still runs and writes its files, and nothing panics.
#[test]
fn a_closed_stdout_does_not_stop_the_runs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let small = |name: &str| {
        format!(
            r#"Job(name: "{name}", surface: HeightField(z: "50*sin(y/100)", x: (0, 300), y: (0, 900)), cutting: Cutting(sections: 3), task: Analyze(samples: 100), outputs: [Report, Svg])"#
        )
    };
    for n in ["p1", "p2", "p3"] {
        write(d, &format!("{n}.ron"), &small(n));
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_hotcut"))
        .args(["run", "p1.ron", "p2.ron", "p3.ron"])
        .current_dir(d)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"));
    for n in ["p1", "p2", "p3"] {
        assert!(d.join("out").join(n).join("report.json").is_file(), "{n}");
    }
    // a full stdout: the schema cannot be printed, exit 1 and a message, no panic
    if Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_hotcut"))
            .arg("schema")
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
    }
}

/// Two job files of one name in one call are rejected before anything runs.
#[test]
fn jobs_of_one_name_are_rejected_together() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.ron", &blade_job("same", 21));
    write(d, "b.ron", &blade_job("same", 31));
    for cmd in ["validate", "run"] {
        let o = hotcut(&[cmd, "a.ron", "b.ron"], d);
        assert_eq!(o.status.code(), Some(1), "{cmd}");
        assert!(
            stderr(&o).contains("/name") && stderr(&o).contains("a.ron"),
            "{}",
            stderr(&o)
        );
        assert!(!d.join("out").exists());
    }
}

/// A run that produces nothing to cut fails, says why, and writes no file: the blade is
/// far longer than any section it would have to span.
#[test]
fn a_run_with_nothing_to_cut_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = blade_job("empty", 21).replace("length: 1000", "length: 25000");
    write(d, "e.ron", &job);
    let o = hotcut(&["run", "e.ron"], d);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nothing to cut"), "{}", stderr(&o));
    assert!(!d.join("out/empty").exists());
    assert_eq!(temporaries(&d.join("out"), "empty"), Vec::<String>::new());
}
