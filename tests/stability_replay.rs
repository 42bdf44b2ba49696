//! The blade through every robot program, replayed independently (issue 52): this test
//! reads only what a run wrote for the cell — `targets.json` (each pose's planned shape
//! and stability margin) and the RAPID modules (read by `tests/rapid/reader.rs`) — and
//! follows the blade through every synchronized move with a solver of its own:
//! - the blade as `N` equal segments, its equilibrium found by Newton's method on the
//!   dense KKT system (nalgebra's LU), its stability by the eigenvalues of the Hessian
//!   projected on the constraints' null space (nalgebra's symmetric eigen-decomposition);
//! - each move as the controller executes it: both TCPs linearly, their orientations by
//!   spherical interpolation, in fixed sub-steps (halved where Newton's method fails);
//! - from the program's first target, the blade mounted straight (its ends a blade length
//!   apart), the blade taken on the first arc it is bent to, and followed from there.
//!
//! It checks, for every shipped job that writes RAPID:
//! - the first target is the straight, mounted blade;
//! - no move snaps: the followed equilibrium stays stable, and at every cutting target it
//!   is the planned shape (the discrete equilibrium settled from `targets.json`'s shape);
//!   the report (`report.json`, `cell.equilibrium.snaps`) says the same;
//! - at every cutting target, the margin of the replay's blade (Richardson-extrapolated
//!   from 64 and 128 segments) is `targets.json`'s within the replay's stated error.
//!
//! A program with one cutting target turned so that the blade must turn over its bulge
//! is caught.

#[path = "rapid/equilibrium.rs"]
mod equilibrium;
#[path = "rapid/reader.rs"]
mod reader;

use std::path::{Path, PathBuf};

use equilibrium::{ends_of, follow, settle_like, Ends, N};
use hotcut::limits::Limits;
use hotcut::load::load_job_text;
use hotcut::run::run_job;
use hotcut::NoProgress;
use nalgebra::{UnitQuaternion, Vector3};

/// What a run wrote for the cell.
struct Written {
    /// Blade length, mm.
    blade: f64,
    /// targets.json.
    targets: serde_json::Value,
    /// report.json.
    report: serde_json::Value,
    /// The two blade tasks' modules.
    modules: [String; 2],
}

fn run(path: &Path) -> Written {
    // the replay reads targets.json: asked for where the job writes only RAPID
    let mut text = std::fs::read_to_string(path).unwrap();
    if !text.contains("RobotTargets") {
        text = text.replacen("Rapid", "RobotTargets(), Rapid", 1);
    }
    let job = load_job_text(path, text, &Limits::default())
        .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_job(&job, dir.path(), &NoProgress).unwrap();
    let read = |name: &str| std::fs::read_to_string(outcome.dir.join(name)).unwrap();
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
    let targets: serde_json::Value = serde_json::from_str(&read("targets.json"))
        .unwrap_or_else(|_| panic!("{}: the replay reads targets.json", path.display()));
    let report: serde_json::Value = serde_json::from_str(&read("report.json")).unwrap();
    let per_mm = match targets["units"].as_str().unwrap() {
        "Millimetre" => 1.0,
        "Metre" => 1e-3,
        u => panic!("unit {u}"),
    };
    Written {
        blade: targets["blade_length"].as_f64().unwrap() / per_mm,
        targets,
        report,
        modules: [module("T_ROB1"), module("T_ROB2")],
    }
}

/// What the replay measured.
#[derive(Debug, Default)]
struct Replayed {
    moves: usize,
    cut_targets: usize,
    worst_margin_gap: f64,
    least_margin: f64,
}

/// The planned pose `k` (1-based) of block `b` in targets.json: (shape, margin).
fn planned(t: &serde_json::Value, b: usize, k: usize) -> Option<(Vec<f64>, f64)> {
    let block = t["blocks"]
        .as_array()?
        .iter()
        .find(|x| x["block"].as_u64() == Some(b as u64))?;
    let pose = &block["poses"].as_array()?.get(k - 1)?["blade"];
    let shape = pose["shape"]
        .as_array()?
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    Some((shape, pose["margin"].as_f64()?))
}

/// `pB<b>_C<k>` → (b, k).
fn cut_target(name: &str) -> Option<(usize, usize)> {
    let rest = name.strip_prefix("pB")?;
    let (b, k) = rest.split_once("_C")?;
    Some((b.parse().ok()?, k.parse().ok()?))
}

/// The replay's margin of planned shape `shape` at `ends` on 128 segments, and its stated
/// error: the discrete margin converges as 1/n² (crates/elastica/tests/stability.rs), so
/// its error at 128 segments is about a third of its change from 64, and three times that
/// change is the bound; plus what the RAPID file's rounding moves it (positions to 0.001
/// mm, orientations to 1e-7: the chord by up to 0.002 mm, the angles by 2e-7 rad), which
/// matters for a nearly taut blade, whose slack may be a few micrometres.
fn replay_margin(length: f64, ends: Ends, shape: &[f64]) -> Option<(f64, f64)> {
    let a = settle_like(length, ends, shape, 64)?;
    let b = settle_like(length, ends, shape, 128)?;
    let (ma, mb) = (a.margin(), b.margin());
    let mut rounding = 0.0f64;
    for (dc, da) in [(2e-3, 0.0), (-2e-3, 0.0), (0.0, 2e-7), (0.0, -2e-7)] {
        let e = Ends {
            chord: ends.chord + dc,
            angles: [ends.angles[0] + da, ends.angles[1] - da],
        };
        if let Some(c) = settle_like(length, e, shape, 64) {
            rounding = rounding.max((c.margin() - ma).abs());
        }
    }
    Some((mb, (mb - ma).abs() + rounding + 1e-6 * (1.0 + mb.abs())))
}

/// Replays the blade through the program; `Err` names the first snap or disagreement.
fn replay(w: &Written) -> Result<Replayed, String> {
    let tasks: Vec<reader::Task> = w
        .modules
        .iter()
        .map(|m| reader::read(m))
        .collect::<Result<_, _>>()?;
    let (a, b) = (&tasks[0].moves, &tasks[1].moves);
    if a.len() != b.len() || a.len() < 3 {
        return Err("the tasks' moves differ in number".into());
    }
    let pose = |k: usize| [a[k].pose, b[k].pose];
    let length = w.blade;
    // the blade mounted straight at the first target
    let first = ends_of(&a[0].pose, &b[0].pose);
    if !((first.chord - length).abs() < 2e-3 && first.angles.iter().all(|x| x.abs() < 1e-5)) {
        return Err(format!(
            "{}: the first target is not the blade mounted straight (chord {:.4} of {length}, angles {:?})",
            a[0].target, first.chord, first.angles
        ));
    }
    // bent along an arc at the second: the arc is taken
    let arc = ends_of(&a[1].pose, &b[1].pose);
    let turn = arc.angles[0];
    let arc_shape: Vec<f64> = (0..=16)
        .map(|k| turn - 2.0 * turn * k as f64 / 16.0)
        .collect();
    let mut blade = settle_like(length, arc, &arc_shape, N)
        .ok_or(format!("{}: no arc of the blade there", a[1].target))?;
    if (arc.angles[0] + arc.angles[1]).abs() > 1e-5 {
        return Err(format!(
            "{}: the blade is not bent into an arc",
            a[1].target
        ));
    }
    let mut r = Replayed {
        least_margin: f64::INFINITY,
        ..Replayed::default()
    };
    #[allow(clippy::needless_range_loop)] // k also names the move and its previous pose
    for k in 2..a.len() {
        r.moves += 1;
        blade = follow(&blade, &pose(k - 1), &pose(k))
            .map_err(|e| format!("{} (move {}): {e}", a[k].target, k + 1))?;
        let Some((bk, pk)) = cut_target(&a[k].target) else {
            continue;
        };
        let (shape, margin) = planned(&w.targets, bk, pk).ok_or(format!(
            "{}: no pose {pk} of block {bk} in targets.json",
            a[k].target
        ))?;
        let plan = settle_like(length, blade.ends, &shape, N).ok_or(format!(
            "{}: the planned shape settles nowhere",
            a[k].target
        ))?;
        let apart = plan.distance(&blade);
        if apart > 1e-6 * length {
            return Err(format!(
                "{} (move {}): the blade arrives {apart:.3} mm from the planned shape (a snap to another)",
                a[k].target,
                k + 1
            ));
        }
        let (m, error) = replay_margin(length, blade.ends, &shape)
            .ok_or(format!("{}: no margin", a[k].target))?;
        let gap = (m - margin).abs();
        if gap > error {
            return Err(format!(
                "{}: margin {margin} in targets.json, {m} replayed (± {error})",
                a[k].target
            ));
        }
        r.cut_targets += 1;
        r.worst_margin_gap = r.worst_margin_gap.max(gap);
        r.least_margin = r.least_margin.min(m);
    }
    Ok(r)
}

/// The jobs of `jobs/` that write RAPID.
fn rapid_jobs() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "ron")
                && std::fs::read_to_string(p).unwrap().contains("Rapid")
                && !p
                    .file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with("compare")
        })
        .collect();
    out.sort();
    out
}

#[test]
fn every_program_keeps_the_blade_on_its_planned_shapes() {
    let jobs = rapid_jobs();
    assert!(jobs.len() >= 10, "{jobs:?}");
    for path in jobs {
        let w = run(&path);
        let r = replay(&w).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let snaps = w.report["cell"]["equilibrium"]["snaps"].as_u64();
        assert_eq!(snaps, Some(0), "{}: the report's snaps", path.display());
        assert!(r.cut_targets > 0, "{}: {r:?}", path.display());
        println!(
            "{}: {} moves followed, {} cutting targets on their planned shapes, margins within {:.2e} of targets.json, least {:.3}",
            path.file_name().unwrap().to_string_lossy(),
            r.moves,
            r.cut_targets,
            r.worst_margin_gap,
            r.least_margin
        );
    }
}

/// The robtarget `name` of `module` turned about its tool's z (the plane's normal) by
/// `angle`.
fn turned(module: &str, name: &str, angle: f64) -> String {
    reader::edit_robtarget(module, name, 1, |q| {
        let r = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
        let r = r * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle);
        let c = r.as_ref().coords;
        format!("{:.7},{:.7},{:.7},{:.7}", c.w, c.x, c.y, c.z)
    })
}

#[test]
fn a_program_that_must_snap_is_caught() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron");
    let w = run(&path);
    let good = replay(&w).unwrap();
    assert!(good.cut_targets > 400, "{good:?}");
    // one cutting target of block 1 with both end tangents turned over (each end's angle
    // against the chord the other way): the blade must turn its bulge over, and snaps
    let tasks: Vec<reader::Task> = w.modules.iter().map(|m| reader::read(m).unwrap()).collect();
    let k = tasks[0]
        .moves
        .iter()
        .position(|m| m.target == "pB1_C26")
        .unwrap();
    let e = ends_of(&tasks[0].moves[k].pose, &tasks[1].moves[k].pose);
    let bad = Written {
        modules: [
            turned(&w.modules[0], "pB1_C26", -2.0 * e.angles[0]),
            turned(&w.modules[1], "pB1_C26", -2.0 * e.angles[1]),
        ],
        ..w
    };
    let err = replay(&bad).unwrap_err();
    assert!(
        err.contains("pB1_C2")
            && (err.contains("fold") || err.contains("planned") || err.contains("no equilibrium")),
        "{err}"
    );
}

/// What [`measure`] finds along one program.
#[derive(Debug, Default)]
struct Measured {
    poses: usize,
    unstable: usize,
    marginal: usize,
    least_margin: f64,
    moves: usize,
    snaps: usize,
}

/// Follows the program of the modules `[rob1, rob2]` (blade `length`, mm) with the replay's
/// solver, whatever it was planned to do: from its first target where the blade is bent
/// (settled from the shape turning evenly between its end angles), through every move; a
/// move that snaps (a fold, or no equilibrium to follow) is counted and the blade settled
/// afresh at its target. At each cutting target the margin of the blade the robots hold
/// (settled again on 128 segments).
/// For programs planned before issue 52 (no shapes in targets.json), this is what their
/// blade does when the robots run them.
fn measure(modules: &[String; 2], length: f64) -> Result<Measured, String> {
    let tasks: Vec<reader::Task> = modules
        .iter()
        .map(|m| reader::read(m))
        .collect::<Result<_, _>>()?;
    let (a, b) = (&tasks[0].moves, &tasks[1].moves);
    if a.len() != b.len() {
        return Err("the tasks' moves differ in number".into());
    }
    let pose = |k: usize| [a[k].pose, b[k].pose];
    let even = |k: usize| {
        let e = ends_of(&a[k].pose, &b[k].pose);
        let shape: Vec<f64> = (0..=16)
            .map(|i| e.angles[0] + (e.angles[1] - e.angles[0]) * i as f64 / 16.0)
            .collect();
        (e.chord < length - 1e-6)
            .then(|| settle_like(length, e, &shape, N))
            .flatten()
    };
    let mut m = Measured {
        least_margin: f64::INFINITY,
        ..Measured::default()
    };
    let mut blade: Option<equilibrium::Blade> = None;
    #[allow(clippy::needless_range_loop)] // k indexes both tasks' moves
    for k in 0..a.len() {
        blade = match blade {
            Some(from) if k > 0 => {
                m.moves += 1;
                match follow(&from, &pose(k - 1), &pose(k)) {
                    Ok(b) => Some(b),
                    Err(_) => {
                        m.snaps += 1;
                        even(k)
                    }
                }
            }
            _ => even(k),
        };
        if let (Some(bl), Some(_)) = (&blade, cut_target(&a[k].target)) {
            // on 128 segments, as the replay judges margins (a nearly taut blade's
            // boundary layers need them)
            let shape: Vec<f64> = bl.theta.iter().copied().collect();
            let margin =
                settle_like(length, bl.ends, &shape, 2 * N).map_or(bl.margin(), |f| f.margin());
            m.poses += 1;
            m.unstable += usize::from(margin < 0.0);
            m.marginal += usize::from((0.0..0.05).contains(&margin));
            m.least_margin = m.least_margin.min(margin);
        }
    }
    Ok(m)
}

/// The measurement of a freshly written program finds what the planner promised: every
/// cutting pose stable beyond the marginal margin, no move that folds or loses its
/// equilibrium. With `HOTCUT_MEASURE_DIR` set (a directory of run outputs, one directory
/// per job, e.g. written by an older hotcut) it also prints the measurement of every
/// program there, as in BENCHMARKS.md's "Blade stability":
/// `HOTCUT_MEASURE_DIR=/tmp/out cargo test --test stability_replay measure -- --nocapture`.
#[test]
fn measure_finds_what_the_planner_promised() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-saddle.ron");
    let w = run(&path);
    let m = measure(&w.modules, w.blade).unwrap();
    let poses: usize = w.targets["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["poses"].as_array().unwrap().len())
        .sum();
    assert_eq!(m.poses, poses, "{m:?}");
    assert_eq!((m.unstable, m.marginal, m.snaps), (0, 0, 0), "{m:?}");
    assert!(m.moves > m.poses && m.least_margin >= 0.05, "{m:?}");
    if let Ok(dir) = std::env::var("HOTCUT_MEASURE_DIR") {
        measure_directory(Path::new(&dir));
    }
}

/// Prints [`measure`] of every program in `dir` as a BENCHMARKS.md row.
fn measure_directory(dir: &Path) {
    let mut jobs: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    jobs.sort();
    for job in jobs {
        let Ok(t) = std::fs::read_to_string(job.join("targets.json")) else {
            continue;
        };
        let t: serde_json::Value = serde_json::from_str(&t).unwrap();
        let per_mm = if t["units"] == "Metre" { 1e-3 } else { 1.0 };
        let length = t["blade_length"].as_f64().unwrap() / per_mm;
        let files: Vec<PathBuf> = std::fs::read_dir(&job)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .collect();
        let module = |task: &str| {
            files
                .iter()
                .find(|f| f.to_string_lossy().ends_with(&format!("_{task}.mod")))
                .and_then(|f| std::fs::read_to_string(f).ok())
        };
        let (Some(r1), Some(r2)) = (module("T_ROB1"), module("T_ROB2")) else {
            continue;
        };
        let name = job.file_name().unwrap().to_string_lossy().to_string();
        match measure(&[r1, r2], length) {
            Ok(m) => println!(
                "| `{name}` | {} | {} / {} | {:.3} | {} | {} |",
                m.poses, m.unstable, m.marginal, m.least_margin, m.moves, m.snaps
            ),
            Err(e) => println!("| `{name}` | {e} |"),
        }
    }
}
