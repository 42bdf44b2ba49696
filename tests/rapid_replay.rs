//! Replays the RAPID modules of every job of `jobs/` that writes them, with an independent
//! reader (`tests/rapid/reader.rs`), and checks the MultiMove rules and the blade:
//! - both tasks run the same synchronized segments with the same `\ID`s, increasing;
//!   every move in synchronized motion has an `\ID` and no other move has one;
//! - in every synchronized move, the distance between the two held ends stays within the
//!   blade's length. Both TCPs move linearly over the same time, so the distance is a
//!   convex function of time along a move: checking its ends bounds every point between.
//!
//! Issue 21 adds the checks of the transitions between blocks, the blocks present in the
//! cell, the configuration data and the heat (see `docs/robot-cell.md`).

#[path = "rapid/reader.rs"]
mod reader;

use std::path::{Path, PathBuf};

use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::NoProgress;

/// The jobs of `jobs/` with a `Rapid` output whose name starts with `prefix`.
fn jobs(prefix: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            name.starts_with(prefix)
                && name.ends_with(".ron")
                && std::fs::read_to_string(p).unwrap().contains("Rapid")
        })
        .collect();
    out.sort();
    out
}

/// The two modules and the blade length (mm) of a job's run.
fn run(path: &Path) -> (String, String, f64) {
    let job = load_job(path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_job(&job, dir.path(), &NoProgress).unwrap();
    let files: Vec<PathBuf> = std::fs::read_dir(&outcome.dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    let module = |task: &str| {
        let f = files
            .iter()
            .find(|f| f.to_string_lossy().ends_with(&format!("_{task}.mod")))
            .unwrap_or_else(|| panic!("{}: no {task} module", path.display()));
        std::fs::read_to_string(f).unwrap()
    };
    let targets: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(outcome.dir.join("targets.json")).unwrap())
            .unwrap_or_else(|_| panic!("{}: the check needs targets.json", path.display()));
    let per_mm = match targets["units"].as_str().unwrap() {
        "Millimetre" => 1.0,
        "Metre" => 1e-3,
        other => panic!("unit {other}"),
    };
    let blade = targets["blade_length"].as_f64().unwrap() / per_mm;
    (module("T_ROB1"), module("T_ROB2"), blade)
}

/// What is wrong with a pair of modules holding a blade of `blade` mm.
fn check(rob1: &str, rob2: &str, blade: f64) -> Result<usize, String> {
    let (a, b) = (reader::read(rob1)?, reader::read(rob2)?);
    if a.segments != b.segments {
        return Err("the tasks' synchronized segments differ".into());
    }
    for s in &a.segments {
        if !s.windows(2).all(|w| w[0] < w[1]) {
            return Err(format!("\\IDs not increasing: {s:?}"));
        }
    }
    let (sa, sb): (Vec<_>, Vec<_>) = (
        a.moves.iter().filter(|m| m.synced).collect(),
        b.moves.iter().filter(|m| m.synced).collect(),
    );
    if sa.len() != sb.len() {
        return Err("different numbers of synchronized moves".into());
    }
    // positions are written to 0.001 mm: both ends' rounding
    let slack = 2e-3;
    for (ma, mb) in sa.iter().zip(&sb) {
        let d = (ma.pose.translation.vector - mb.pose.translation.vector).norm();
        if d > blade + slack {
            return Err(format!(
                "{} / {} (\\ID {:?}): the ends are {d:.3} mm apart, the blade is {blade} mm",
                ma.target, mb.target, ma.id
            ));
        }
    }
    Ok(sa.len())
}

fn replay_all(prefix: &str) {
    let paths = jobs(prefix);
    assert!(!paths.is_empty());
    for path in paths {
        let (rob1, rob2, blade) = run(&path);
        let moves =
            check(&rob1, &rob2, blade).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(moves > 0, "{}: no synchronized move", path.display());
    }
}

#[test]
fn hot_blade_programs_keep_the_multimove_rules_and_the_blade() {
    replay_all("hot-blade-");
}

#[test]
fn facade_programs_keep_the_multimove_rules_and_the_blade() {
    replay_all("seg-");
}

#[test]
fn the_check_fails_on_programs_made_unsafe_on_purpose() {
    let (rob1, rob2, blade) =
        run(&Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron"));
    assert!(check(&rob1, &rob2, blade).is_ok());
    // robot 2's third cutting target of block 1 moved 100 mm away from robot 1 along the
    // blade: the blade would be stretched
    let line = rob2
        .lines()
        .find(|l| l.contains("robtarget pB1_3 "))
        .unwrap()
        .to_string();
    let start = line.find(":= [[").unwrap() + 5;
    let end = start + line[start..].find(']').unwrap();
    let xyz: Vec<f64> = line[start..end]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let moved = format!("{},{},{}", xyz[0], xyz[1] + 100.0, xyz[2]);
    let stretched = format!("{}{moved}{}", &line[..start], &line[end..]);
    assert_ne!(stretched, line);
    let bad = rob2.replace(&line, &stretched);
    let e = check(&rob1, &bad, blade).unwrap_err();
    assert!(e.contains("pB1_3") && e.contains("apart"), "{e}");
    // an \ID missing in synchronized motion, or one task's segment shorter
    let no_id = rob2.replacen(" \\ID:=30,", ",", 1);
    assert!(check(&rob1, &no_id, blade).unwrap_err().contains("\\ID"));
    let fewer = rob2.replacen(" \\ID:=30,", " \\ID:=31,", 1);
    assert!(check(&rob1, &fewer, blade).is_err());
}
