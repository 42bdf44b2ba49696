//! Replays the RAPID modules of every job of `jobs/` that writes them, with an independent
//! reader (`tests/rapid/reader.rs`) and an independent rebuild of the robots and the blade
//! (`tests/rapid/robot.rs`, from the report's cell), and checks what the program would do:
//! - MultiMove: every move of both tasks is synchronized, with the same `\ID`s,
//!   increasing; no move outside synchronized motion;
//! - the blade: in every move, the distance between the two held ends stays within the
//!   blade's length (both TCPs move linearly over the same time, so the distance is convex
//!   along a move: its ends bound it); along every move, sampled, the blade rebuilt from
//!   its ends never enters the block at the fixture unless it is heated, and in each heated
//!   run the blade's plane passes through the block: the heat is on exactly during cuts;
//! - the operator changes blocks only with the heat off, and the program ends cold;
//! - every robtarget is reached: forward kinematics of the joints stated with it, through
//!   the robot's base and the tool, lands on it (to the precision the file prints), the
//!   joints are within the robot's limits, and its configuration data are theirs.

#[path = "rapid/reader.rs"]
mod reader;
#[path = "rapid/robot.rs"]
mod robot;

use std::path::{Path, PathBuf};

use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::NoProgress;
use nalgebra::Isometry3;

use robot::Robot;

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

/// What a job's run wrote that the replay reads.
#[derive(Clone)]
struct Cell {
    /// The two modules, T_ROB1 first.
    modules: [String; 2],
    /// Blade length, mm.
    blade: f64,
    /// The robot of each task.
    robots: [Robot; 2],
    /// The heat's output.
    signal: String,
}

fn run(path: &Path) -> Cell {
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
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(outcome.dir.join("report.json")).unwrap())
            .unwrap_or_else(|_| panic!("{}: the check needs report.json", path.display()));
    let per_mm = match report["units"].as_str().unwrap() {
        "Millimetre" => 1.0,
        "Metre" => 1e-3,
        other => panic!("unit {other}"),
    };
    let blade = report["settings"]["blade_length"].as_f64().unwrap() / per_mm;
    let cell = &report["cell"];
    let robot = |e: usize| {
        let r = cell["holders"][e]["robot"].as_u64().unwrap() as usize;
        Robot::from_report(&cell["robots"][r])
    };
    Cell {
        modules: [module("T_ROB1"), module("T_ROB2")],
        blade,
        robots: [robot(0), robot(1)],
        signal: cell["heat_signal"].as_str().unwrap().to_string(),
    }
}

/// What the check measured.
#[derive(Debug, Default)]
struct Replay {
    moves: usize,
    heated: usize,
    cuts: usize,
    samples: usize,
    worst_fk_mm: f64,
}

/// Position and angle precision of a printed robtarget against forward kinematics: 3
/// decimals of mm per coordinate in the target, the work object and the tool, and 6
/// decimals of degrees per joint over a 3 m arm; quaternions to 7 decimals.
const FK_MM: f64 = 3.0 * 0.0005 * 1.733 + 6.0 * 3000.0 * (0.5e-6 * std::f64::consts::PI / 180.0);
const FK_RAD: f64 = 3.0 * 2.0 * 0.5e-7 * 2.0 + 6.0 * (0.5e-6 * std::f64::consts::PI / 180.0);

/// Every robtarget of task `t` reached by its stated joints.
fn check_joints(moves: &[reader::Move], robot: &Robot, r: &mut Replay) -> Result<(), String> {
    for m in moves {
        let j = m
            .joints
            .ok_or(format!("{}: no joints stated (out of reach)", m.target))?;
        for (i, (lo, hi)) in robot.limits.iter().enumerate() {
            if !(j[i] >= lo - 1e-6 && j[i] <= hi + 1e-6) {
                return Err(format!(
                    "{}: axis {} at {}° is past its limits",
                    m.target,
                    i + 1,
                    j[i]
                ));
            }
        }
        let (flange, _) = robot.flange(&j);
        let tcp = flange * m.tool;
        let d = (tcp.translation.vector - m.pose.translation.vector).norm();
        let a = tcp.rotation.angle_to(&m.pose.rotation);
        if d > FK_MM || a > FK_RAD {
            return Err(format!(
                "{}: the stated joints reach {d:.6} mm / {a:.2e} rad away",
                m.target
            ));
        }
        r.worst_fk_mm = r.worst_fk_mm.max(d);
        let conf = robot.conf(&j);
        if conf != m.conf {
            return Err(format!(
                "{}: configuration {:?}, the joints' is {conf:?}",
                m.target, m.conf
            ));
        }
    }
    Ok(())
}

/// The ends of the blade a fraction `w` along synchronized move `k`.
fn ends_at(a: &[reader::Move], b: &[reader::Move], k: usize, w: f64) -> [Isometry3<f64>; 2] {
    let at = |m: &[reader::Move]| {
        let (p, q) = (&m[k - 1].pose, &m[k].pose);
        Isometry3::from_parts(
            p.translation.vector.lerp(&q.translation.vector, w).into(),
            p.rotation.slerp(&q.rotation, w),
        )
    };
    [at(a), at(b)]
}

/// The blade along every move against the block at the fixture and the heat.
fn check_blade(
    a: &reader::Task,
    b: &reader::Task,
    blade: f64,
    r: &mut Replay,
) -> Result<(), String> {
    let (ma, mb) = (&a.moves, &b.moves);
    // a heated run: whether it cut into the block
    let mut run_cut: Option<bool> = None;
    for k in 0..ma.len() {
        let heat = ma[k].heat.unwrap_or(false);
        if heat != (ma[k].speed == "vCut") {
            return Err(format!(
                "{}: heated {heat} at speed {}",
                ma[k].target, ma[k].speed
            ));
        }
        // before the first block is placed nothing stands at the fixture
        let Some(block) = ma[k].block else {
            if heat {
                return Err(format!(
                    "{}: heated with no block at the fixture",
                    ma[k].target
                ));
            }
            continue;
        };
        let size = a
            .blocks
            .get(&block)
            .ok_or(format!("no size of block {block}"))?;
        // the first move starts wherever the operator left the robots: only its target
        let fractions: &[f64] = if k == 0 {
            &[1.0]
        } else {
            &[0.25, 0.5, 0.75, 1.0]
        };
        let mut inside = false;
        for &w in fractions {
            let ends = if k == 0 {
                [ma[0].pose, mb[0].pose]
            } else {
                ends_at(ma, mb, k, w)
            };
            let points = robot::blade([&ends[0], &ends[1]], blade)
                .map_err(|e| format!("{} (\\ID {:?}): no blade: {e}", ma[k].target, ma[k].id))?;
            r.samples += 1;
            let deepest = points
                .iter()
                .map(|p| robot::depth(&ma[k].wobj, size, p))
                .fold(f64::NEG_INFINITY, f64::max);
            // a heated run cuts when its blade's plane passes through the block (the
            // rebuilt shape of a nearly taut blade may take the other of two equilibria,
            // so the plane, which does not depend on it, decides)
            if robot::crosses(&ma[k].wobj, size, &ends[0]) {
                inside = true;
            }
            if deepest > 0.1 && !heat {
                return Err(format!(
                    "{} (\\ID {:?}): the cold blade is {deepest:.1} mm inside block {block}",
                    ma[k].target, ma[k].id
                ));
            }
        }
        match (heat, run_cut) {
            (true, _) => {
                r.heated += 1;
                run_cut = Some(run_cut.unwrap_or(false) || inside);
            }
            (false, Some(cut)) => {
                if !cut {
                    return Err(format!(
                        "{}: the heat was on, but the blade cut nothing",
                        ma[k].target
                    ));
                }
                r.cuts += 1;
                run_cut = None;
            }
            (false, None) => {}
        }
    }
    if run_cut.is_some() || a.heat_at_end != Some(false) {
        return Err("the program ends with the blade heated".into());
    }
    if a.heat_at_changes.iter().any(|h| *h) {
        return Err("the operator is asked to change blocks with the blade heated".into());
    }
    Ok(())
}

/// What is wrong with a cell's program.
fn check(cell: &Cell) -> Result<Replay, String> {
    let (a, b) = (
        reader::read(&cell.modules[0])?,
        reader::read(&cell.modules[1])?,
    );
    if a.segments != b.segments {
        return Err("the tasks' synchronized segments differ".into());
    }
    for s in &a.segments {
        if !s.windows(2).all(|w| w[0] < w[1]) {
            return Err(format!("\\IDs not increasing: {s:?}"));
        }
    }
    if let Some(m) = a.moves.iter().chain(&b.moves).find(|m| !m.synced) {
        return Err(format!("{}: a move outside synchronized motion", m.target));
    }
    if a.moves.len() != b.moves.len() || a.moves.is_empty() {
        return Err("different numbers of synchronized moves".into());
    }
    // positions are written to 0.001 mm: both ends' rounding
    let slack = 2e-3;
    for (ma, mb) in a.moves.iter().zip(&b.moves) {
        let d = (ma.pose.translation.vector - mb.pose.translation.vector).norm();
        if d > cell.blade + slack {
            return Err(format!(
                "{} / {} (\\ID {:?}): the ends are {d:.3} mm apart, the blade is {} mm",
                ma.target, mb.target, ma.id, cell.blade
            ));
        }
    }
    // one task switches the heat, the report's output, and asks the operator to change
    if !b.signals.is_empty() || a.signals.iter().any(|s| *s != cell.signal) || a.signals.is_empty()
    {
        return Err(format!(
            "heat outputs {:?} / {:?}, the cell's is {}",
            a.signals, b.signals, cell.signal
        ));
    }
    if !a.heat_at_changes.is_empty() && !a.asks_operator {
        return Err("block changes without the operator's confirmation".into());
    }
    let mut r = Replay {
        moves: a.moves.len(),
        ..Replay::default()
    };
    check_blade(&a, &b, cell.blade, &mut r)?;
    check_joints(&a.moves, &cell.robots[0], &mut r)?;
    check_joints(&b.moves, &cell.robots[1], &mut r)?;
    Ok(r)
}

fn replay_all(prefix: &str) {
    let paths = jobs(prefix);
    assert!(!paths.is_empty());
    for path in paths {
        let cell = run(&path);
        let r = check(&cell).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(r.moves > 0 && r.cuts > 0, "{}: {r:?}", path.display());
    }
}

#[test]
fn hot_blade_programs_keep_the_multimove_rules_the_blade_and_the_robots() {
    replay_all("hot-blade-");
}

#[test]
fn facade_programs_keep_the_multimove_rules_the_blade_and_the_robots() {
    replay_all("seg-");
}

/// The line declaring robtarget `name` with its position shifted by `d`.
fn shifted(module: &str, name: &str, d: [f64; 3]) -> String {
    let line = module
        .lines()
        .find(|l| l.contains(&format!("robtarget {name} ")))
        .unwrap_or_else(|| panic!("no robtarget {name}"))
        .to_string();
    let start = line.find(":= [[").unwrap() + 5;
    let end = start + line[start..].find(']').unwrap();
    let xyz: Vec<f64> = line[start..end]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let moved = format!("{},{},{}", xyz[0] + d[0], xyz[1] + d[1], xyz[2] + d[2]);
    module.replace(&line, &format!("{}{moved}{}", &line[..start], &line[end..]))
}

#[test]
fn the_check_fails_on_programs_made_unsafe_on_purpose() {
    let cell = run(&Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron"));
    let good = check(&cell).unwrap();
    assert!(good.cuts == 8 && good.heated > 8 * 51, "{good:?}");
    let with = |r1: String, r2: String| Cell {
        modules: [r1, r2],
        ..cell.clone()
    };
    let [r1, r2] = cell.modules.clone();
    // robot 2's third cutting target of block 1 moved 100 mm away along the blade: stretched
    let e = check(&with(r1.clone(), shifted(&r2, "pB1_C3", [0.0, 100.0, 0.0]))).unwrap_err();
    assert!(e.contains("pB1_C3") && e.contains("apart"), "{e}");
    // a travel to block 2 lowered by 500 mm in both tasks: through the block, cold
    let (l1, l2) = (
        shifted(&r1, "pB2_T3", [0.0, 0.0, -500.0]),
        shifted(&r2, "pB2_T3", [0.0, 0.0, -500.0]),
    );
    let e = check(&with(l1, l2)).unwrap_err();
    assert!(e.contains("inside block"), "{e}");
    // the travel's joints no longer those of its target, or the configuration changed
    let moved = shifted(&r1, "pB2_T3", [0.0, 0.0, 1.0]);
    assert!(check(&with(moved, r2.clone()))
        .unwrap_err()
        .contains("stated joints"));
    let line = r1
        .lines()
        .find(|l| l.contains("robtarget pB1_C5 "))
        .unwrap();
    // [trans, rot, robconf, extax]: cf1 is the first number after the quaternion
    let conf = line.find("],[9E+09").unwrap();
    let open = line[..conf].rfind('[').unwrap();
    let cf: Vec<i32> = line[open + 1..conf]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let new_conf = format!("{},{},{},{}", cf[0] + 1, cf[1], cf[2], cf[3]);
    let flipped = format!("{}{new_conf}{}", &line[..open + 1], &line[conf..]);
    assert_ne!(flipped, line);
    let e = check(&with(r1.replace(line, &flipped), r2.clone())).unwrap_err();
    assert!(e.contains("configuration"), "{e}");
    // the heat left on after block 1's retreat, over the block change
    let late = r1.replacen(
        "        SetDO doBladeHeat, 0;\n        MoveL pB1_U1",
        "        MoveL pB1_U1",
        1,
    );
    assert_ne!(late, r1);
    let e = check(&with(late, r2.clone())).unwrap_err();
    assert!(e.contains("heated"), "{e}");
    // an \ID missing, or one task's moves out of step
    let no_id = r2.replacen(" \\ID:=30,", ",", 1);
    assert!(check(&with(r1.clone(), no_id))
        .unwrap_err()
        .contains("\\ID"));
    let other = r2.replacen(" \\ID:=30,", " \\ID:=31,", 1);
    let e = check(&with(r1.clone(), other)).unwrap_err();
    assert!(e.contains("segments differ"), "{e}");
    // the heat switched in a corner zone, or by the other task, or without the operator
    let zone = r1.replacen(
        "fine, tBlade1 \\WObj:=wFixture;\n        SetDO",
        "z1, tBlade1 \\WObj:=wFixture;\n        SetDO",
        1,
    );
    assert_ne!(zone, r1);
    assert!(check(&with(zone, r2.clone())).unwrap_err().contains("zone"));
    let silent = r1.replace("        TPReadFK ", "        ! TPReadFK ");
    assert!(check(&with(silent, r2.clone()))
        .unwrap_err()
        .contains("operator"));
    let hot = r2.replacen(
        "        SyncMoveOn",
        "        SetDO doBladeHeat, 0;\n        SyncMoveOn",
        1,
    );
    assert!(check(&with(r1, hot)).unwrap_err().contains("heat outputs"));
}
