//! Replays the RAPID modules of every job of `jobs/` that writes them, with an independent
//! reader (`tests/rapid/reader.rs`) and an independent rebuild of the robots and the blade
//! (`tests/rapid/robot.rs`, from the report's cell), and checks what the program would do:
//! - MultiMove: every move of every task (two, or three with a block carrier) is
//!   synchronized, with the same `\ID`s, increasing; no move outside synchronized motion;
//! - the blade: in every move, the distance between the two held ends stays within the
//!   blade's length (both TCPs move linearly over the same time, so the distance is convex
//!   along a move: its ends bound it); along every move, sampled, the blade rebuilt from
//!   its ends never enters the block at the fixture unless it is heated, and in each heated
//!   run the blade's plane passes through the block: the heat is on exactly during cuts;
//! - the operator changes blocks only with the heat off, and the program ends cold;
//! - with a carrier: its task moves the grip (the report's) in the world; the blade's
//!   tasks move in the work object it holds, so the blade is checked in the carried
//!   block's frame, and their targets reach the world through forward kinematics of the
//!   carrier's stated joints;
//! - every robtarget is reached: forward kinematics of the joints stated with it, through
//!   the robot's base and the tool, lands on it (to the precision the file prints), the
//!   joints are within the robot's limits, and its configuration data are theirs.

#[path = "rapid/equilibrium.rs"]
mod equilibrium;
#[path = "rapid/kept.rs"]
mod kept;
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
    /// The modules, T_ROB1 first (two, or three with a block carrier).
    modules: Vec<String>,
    /// Blade length, mm.
    blade: f64,
    /// The robot of each task.
    robots: Vec<Robot>,
    /// The heat's output.
    signal: String,
    /// With a carrier: the block's frame in its flange's frame, from the report.
    grip: Option<Isometry3<f64>>,
    /// The report's deepest gouge of a blade outside its piece into what a block keeps,
    /// how many (plane, block) rows it checked, and the nearest a held end comes to a
    /// block there (issue 37), in the job's units.
    gouge: (f64, usize, f64),
    /// What the blocks keep, rebuilt from the job's surface (`HotBlade`,
    /// `FacadeSegmentation`).
    kept: Option<kept::Kept>,
    /// `targets.json`, where the job writes it: the shape planned at every cutting target
    /// (issue 52), which tells the blade the program means from the others its ends allow.
    targets: Option<serde_json::Value>,
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
            .find(|f| f.to_string_lossy().ends_with(&format!("_{task}.mod")))?;
        Some(std::fs::read_to_string(f).unwrap())
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
    let robot =
        |r: &serde_json::Value| Robot::from_report(&cell["robots"][r.as_u64().unwrap() as usize]);
    let mut modules: Vec<String> = ["T_ROB1", "T_ROB2"]
        .iter()
        .map(|t| module(t).unwrap_or_else(|| panic!("{}: no {t} module", path.display())))
        .collect();
    let mut robots = vec![
        robot(&cell["holders"][0]["robot"]),
        robot(&cell["holders"][1]["robot"]),
    ];
    let carrier = &cell["carrier"];
    let grip = (!carrier.is_null()).then(|| {
        modules.push(module("T_ROB3").expect("a carrier's module"));
        robots.push(robot(&carrier["robot"]));
        robot::frame(&carrier["grip"])
    });
    Cell {
        modules,
        blade,
        robots,
        signal: cell["heat_signal"].as_str().unwrap().to_string(),
        grip,
        gouge: gouge_figure(&report),
        kept: kept::Kept::of(&job, &report),
        targets: std::fs::read_to_string(outcome.dir.join("targets.json"))
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok()),
    }
}

/// The report's gouge figure: the deepest depth and the number of (plane, block) rows, over
/// `cuts[].planes.clearance` (Design), `blocks[].clearance` (HotBlade) or
/// `pieces[].sections[].blade_fit` (FacadeSegmentation).
fn gouge_figure(report: &serde_json::Value) -> (f64, usize, f64) {
    let rows: Vec<&serde_json::Value> = report["cuts"]
        .as_array()
        .into_iter()
        .flatten()
        .flat_map(|c| c["planes"]["clearance"].as_array().into_iter().flatten())
        .chain(
            report["blocks"]
                .as_array()
                .into_iter()
                .flatten()
                .flat_map(|b| b["clearance"].as_array().into_iter().flatten()),
        )
        .chain(
            report["pieces"]
                .as_array()
                .into_iter()
                .flatten()
                .flat_map(|p| p["sections"].as_array().into_iter().flatten())
                .map(|s| &s["blade_fit"])
                .filter(|f| f.is_object()),
        )
        .collect();
    let deepest = rows
        .iter()
        .map(|r| r["gouge_depth"].as_f64().unwrap())
        .fold(0.0, f64::max);
    let nearest = rows
        .iter()
        .map(|r| r["holder_clearance"].as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    (deepest, rows.len(), nearest)
}

/// What the check measured.
#[derive(Debug, Default)]
struct Replay {
    moves: usize,
    heated: usize,
    cuts: usize,
    samples: usize,
    worst_fk_mm: f64,
    /// Heated targets whose blade was checked against what the block keeps.
    heated_targets: usize,
    /// The deepest a heated blade went below the design surface inside the block, mm.
    deepest_below: f64,
    /// The farthest a heated blade inside the block stayed from the surface, mm (among
    /// those that touch it).
    farthest_touch: f64,
    /// Heated targets whose blade, rebuilt from its ends, misses the design altogether:
    /// it took the other equilibrium of a nearly taut blade (not checked).
    other_equilibrium: usize,
    /// Of those, the targets where every blade found runs below the design.
    ambiguous_gouging: usize,
    /// The nearest a held end (a TCP) comes to the block at the fixture at a heated
    /// target, mm (negative: inside it).
    nearest_holder: f64,
}

/// Position and angle precision of a printed robtarget against forward kinematics: 3
/// decimals of mm per coordinate in the target, the work object and the tool, and 6
/// decimals of degrees per joint over a 3 m arm; quaternions to 7 decimals.
const FK_MM: f64 = 3.0 * 0.0005 * 1.733 + 6.0 * 3000.0 * (0.5e-6 * std::f64::consts::PI / 180.0);
const FK_RAD: f64 = 3.0 * 2.0 * 0.5e-7 * 2.0 + 6.0 * (0.5e-6 * std::f64::consts::PI / 180.0);

/// Every robtarget of a task reached by its stated joints; `parents[k]` is the frame
/// move `k`'s pose is in (the world, or the carrier's flange).
fn check_joints(
    moves: &[reader::Move],
    parents: &[Isometry3<f64>],
    robot: &Robot,
    r: &mut Replay,
) -> Result<(), String> {
    for (m, parent) in moves.iter().zip(parents) {
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
        let pose = parent * m.pose;
        let d = (tcp.translation.vector - pose.translation.vector).norm();
        let a = tcp.rotation.angle_to(&pose.rotation);
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
        // the first move starts wherever the operator left the robots: only its target;
        // a block placed before a move is checked from the move's start
        let fractions: &[f64] = if k == 0 {
            &[1.0]
        } else if ma[k - 1].block != ma[k].block {
            &[0.0, 0.25, 0.5, 0.75, 1.0]
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

/// The heated targets of the two blade tasks: both moves, the block at the fixture and
/// its size.
#[allow(clippy::type_complexity)]
fn heated<'a>(
    a: &'a reader::Task,
    b: &'a reader::Task,
) -> Result<Vec<(&'a reader::Move, &'a reader::Move, usize, &'a [f64; 3])>, String> {
    let mut out = Vec::new();
    for (ma, mb) in a.moves.iter().zip(&b.moves) {
        let (Some(true), Some(block)) = (ma.heat, ma.block) else {
            continue;
        };
        let size = a
            .blocks
            .get(&block)
            .ok_or(format!("no size of block {block}"))?;
        out.push((ma, mb, block, size));
    }
    Ok(out)
}

/// At every heated target, the blade rebuilt from its ends against what the block keeps
/// (issue 37): where the rebuilt blade touches the design (the cut: which shows the
/// surface, the block's placement and the blade were rebuilt right), no point of it inside
/// the block lies deeper below the design than the tolerance.
fn check_heated(
    a: &reader::Task,
    b: &reader::Task,
    blade: f64,
    kept: &kept::Kept,
    targets: Option<&serde_json::Value>,
    r: &mut Replay,
) -> Result<(), String> {
    for (ma, mb, block, size) in heated(a, b)? {
        let to_block = ma.wobj.inverse();
        let normal = to_block.rotation * (ma.pose.rotation * nalgebra::Vector3::z());
        // the blade the program means: the shape targets.json plans at a cutting target,
        // else, of the blades the ends allow (a turning off by whole turns too), the one
        // through the cut
        let planned = targets
            .and_then(|t| planned_shape(t, &ma.target))
            .and_then(|s| equilibrium::planned_points([&ma.pose, &mb.pose], blade, &s, 128));
        let mut found: Vec<(f64, f64)> = Vec::new();
        let blades = planned.into_iter().map(Ok).chain(
            [0.0, -1.0, 1.0]
                .into_iter()
                .map(|turns| robot::blade_turned([&ma.pose, &mb.pose], blade, 128, turns)),
        );
        for points in blades {
            let Ok(points) = points else {
                continue;
            };
            let local: Vec<nalgebra::Vector3<f64>> = points
                .iter()
                .map(|p| (to_block * nalgebra::Point3::from(*p)).coords)
                .collect();
            if let Some(c) = kept.below(block, size, &normal, &local)? {
                found.push(c);
                if c.1 <= kept.consistency {
                    break;
                }
            }
        }
        let Some(&(deepest, nearest)) = found.iter().min_by(|x, y| x.1.total_cmp(&y.1)) else {
            continue;
        };
        let shallowest = found.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
        if deepest > kept.tolerance && (nearest <= kept.consistency || !kept.is_facade()) {
            return Err(format!(
                "{} (\\ID {:?}): the heated blade runs {deepest:.1} mm below the design inside block {block} (a gouge)",
                ma.target, ma.id
            ));
        }
        if nearest > kept.consistency {
            if !kept.is_facade() {
                return Err(format!(
                    "{} (\\ID {:?}): the heated blade in block {block} misses the design by {nearest:.2} mm",
                    ma.target, ma.id
                ));
            }
            // a facade's blade, longer than its part and waving beyond it, may have other
            // equilibria with the same held ends: one that misses the part is not the one
            // the program means. Where every one found runs below the design, the blade
            // would gouge if it took one of them: counted apart (a nearly taut blade's
            // other equilibrium; a program lowered on purpose lands here too)
            if shallowest > kept.tolerance {
                r.ambiguous_gouging += 1;
            }
            r.other_equilibrium += 1;
            continue;
        }
        r.heated_targets += 1;
        r.deepest_below = r.deepest_below.max(deepest);
        r.farthest_touch = r.farthest_touch.max(nearest);
    }
    Ok(())
}

/// The shape targets.json plans at cutting target `pB<block>_C<k>` (pose k of the block).
fn planned_shape(t: &serde_json::Value, target: &str) -> Option<Vec<f64>> {
    let (b, k) = target.strip_prefix("pB")?.split_once("_C")?;
    let (b, k): (u64, usize) = (b.parse().ok()?, k.parse().ok()?);
    let block = t["blocks"]
        .as_array()?
        .iter()
        .find(|x| x["block"].as_u64() == Some(b))?;
    block["poses"].as_array()?.get(k.checked_sub(1)?)?["blade"]["shape"]
        .as_array()?
        .iter()
        .map(|v| v.as_f64())
        .collect()
}

/// The signed distance (mm; negative inside) of `p` from the box `[0, size]`.
fn to_box(p: &nalgebra::Vector3<f64>, size: &[f64; 3]) -> f64 {
    let d: Vec<f64> = (0..3).map(|i| (-p[i]).max(p[i] - size[i])).collect();
    if d.iter().all(|v| *v <= 0.0) {
        d.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    } else {
        d.iter().map(|v| v.max(0.0).powi(2)).sum::<f64>().sqrt()
    }
}

/// The nearest either held end comes to the block at the fixture over the heated targets
/// (where the holders must stay off the block while the blade cuts), mm.
fn nearest_holder(a: &reader::Task, b: &reader::Task) -> Result<f64, String> {
    let mut nearest = f64::INFINITY;
    for (ma, mb, _, size) in heated(a, b)? {
        let to_block = ma.wobj.inverse();
        for m in [ma, mb] {
            let l = to_block * nalgebra::Point3::from(m.pose.translation.vector);
            nearest = nearest.min(to_box(&l.coords, size));
        }
    }
    Ok(nearest)
}

/// The tasks' MultiMove rules: the same synchronized segments, increasing `\ID`s, every
/// move synchronized, as many moves in each.
fn check_sync(tasks: &[reader::Task]) -> Result<(), String> {
    let a = &tasks[0];
    for t in &tasks[1..] {
        if t.segments != a.segments {
            return Err("the tasks' synchronized segments differ".into());
        }
        if t.moves.len() != a.moves.len() {
            return Err("different numbers of synchronized moves".into());
        }
    }
    for s in &a.segments {
        if !s.windows(2).all(|w| w[0] < w[1]) {
            return Err(format!("\\IDs not increasing: {s:?}"));
        }
    }
    if let Some(m) = tasks.iter().flat_map(|t| &t.moves).find(|m| !m.synced) {
        return Err(format!("{}: a move outside synchronized motion", m.target));
    }
    if a.moves.is_empty() {
        return Err("no move".into());
    }
    Ok(())
}

/// With a carrier (task 3): its moves are in the world with the block's frame as its
/// tool (the report's grip), and the blade's tasks move in a work object it holds.
/// Returns, per move, the frame the blade tasks' poses are in: the carrier's flange by
/// forward kinematics of its stated joints (the identity without a carrier); and puts
/// the block's frame (the grip, in that flange frame) in the blade tasks' moves.
fn carried(cell: &Cell, tasks: &mut [reader::Task]) -> Result<Vec<Isometry3<f64>>, String> {
    let n = tasks[0].moves.len();
    let Some(grip) = cell.grip else {
        if let Some(m) = tasks
            .iter()
            .flat_map(|t| &t.moves)
            .find(|m| m.held_by.is_some())
        {
            return Err(format!(
                "{}: a moving work object without a carrier",
                m.target
            ));
        }
        return Ok(vec![Isometry3::identity(); n]);
    };
    let (blade, carrier) = tasks.split_at_mut(2);
    let carrier = &carrier[0];
    let mut parents = Vec::with_capacity(n);
    for m in &carrier.moves {
        if m.held_by.is_some() || m.wobj != Isometry3::identity() {
            return Err(format!("{}: the carrier moves in a work object", m.target));
        }
        if m.tool
            .translation
            .vector
            .metric_distance(&grip.translation.vector)
            > 1e-3
            || m.tool.rotation.angle_to(&grip.rotation) > 1e-6
        {
            return Err(format!("{}: the carrier's tool is not the grip", m.target));
        }
        let j = m.joints.ok_or(format!("{}: no joints stated", m.target))?;
        parents.push(cell.robots[2].flange(&j).0);
    }
    for t in blade {
        for (k, m) in t.moves.iter_mut().enumerate() {
            match m.held_by.as_deref() {
                Some("ROB_3") => {}
                // the first move comes from wherever the robots stand: in the world
                None if k == 0 && m.wobj == Isometry3::identity() => {
                    m.pose = parents[k].inverse() * m.pose;
                }
                _ => {
                    return Err(format!(
                        "{}: the blade does not move with the carried block",
                        m.target
                    ))
                }
            }
            m.wobj = grip;
        }
    }
    Ok(parents)
}

/// What is wrong with a cell's program.
fn check(cell: &Cell) -> Result<Replay, String> {
    check_with(cell, true)
}

/// [`check`], the robots' joints left out with `joints` false (a target moved on purpose
/// no longer matches its stated joints: the blade's checks are then seen alone).
fn check_with(cell: &Cell, joints: bool) -> Result<Replay, String> {
    let mut tasks = cell
        .modules
        .iter()
        .map(|m| reader::read(m))
        .collect::<Result<Vec<_>, _>>()?;
    check_sync(&tasks)?;
    let parents = carried(cell, &mut tasks)?;
    let (a, b) = (&tasks[0], &tasks[1]);
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
    let others: Vec<&String> = tasks[1..].iter().flat_map(|t| &t.signals).collect();
    if !others.is_empty() || a.signals.iter().any(|s| *s != cell.signal) || a.signals.is_empty() {
        return Err(format!(
            "heat outputs {:?} / {others:?}, the cell's is {}",
            a.signals, cell.signal
        ));
    }
    if !a.heat_at_changes.is_empty() && !a.asks_operator {
        return Err("block changes without the operator's confirmation".into());
    }
    let mut r = Replay {
        moves: a.moves.len(),
        ..Replay::default()
    };
    check_blade(a, b, cell.blade, &mut r)?;
    if let Some(kept) = &cell.kept {
        check_heated(a, b, cell.blade, kept, cell.targets.as_ref(), &mut r)?;
    }
    r.nearest_holder = nearest_holder(a, b)?;
    let world = vec![Isometry3::identity(); parents.len()];
    for (k, t) in tasks.iter().enumerate().filter(|_| joints) {
        let frames = if k < 2 { &parents } else { &world };
        check_joints(&t.moves, frames, &cell.robots[k], &mut r)?;
    }
    Ok(r)
}

fn replay_all(prefix: &str) {
    let paths = jobs(prefix);
    assert!(!paths.is_empty());
    for path in paths {
        let cell = run(&path);
        let r = check(&cell).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(r.moves > 0 && r.cuts > 0, "{}: {r:?}", path.display());
        // every shipped job that writes robot programs is clean: its report says 0
        let (deepest, rows, holder) = cell.gouge;
        assert_eq!(deepest, 0.0, "{}: a gouge in the report", path.display());
        // and the replay measured that on the blades the programs hold
        if cell.kept.is_some() {
            assert!(
                r.heated_targets > 0,
                "{}: no heated target judged",
                path.display()
            );
        }
        // the held ends: clear of the block at every heated target exactly when the report
        // says so (1 % of the blade; in 3D a plane's own faces along the cut count too, so
        // the replay's figure is the report's or nearer)
        let margin = 0.01 * cell.blade;
        assert_eq!(
            holder > margin,
            r.nearest_holder > margin,
            "{}: holders: report {holder}, replay {}",
            path.display(),
            r.nearest_holder
        );
        let replayed = if cell.kept.is_some() {
            format!(
                "; replayed: {} heated targets ({} more rebuilt on another equilibrium, {} of them all below the design), deepest below the design {:.2} mm, farthest from it {:.2} mm",
                r.heated_targets, r.other_equilibrium, r.ambiguous_gouging, r.deepest_below, r.farthest_touch
            )
        } else {
            String::new()
        };
        println!(
            "{}: gouge 0 on {rows} (plane, block) rows{replayed}; nearest holder: report {holder:.3}, replay {:.3} mm",
            path.file_name().unwrap().to_string_lossy(),
            r.nearest_holder
        );
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

#[test]
fn design_programs_keep_the_multimove_rules_the_blade_and_the_robots() {
    replay_all("design-");
}

/// The line declaring robtarget `name` with its position shifted by `d`.
fn shifted(module: &str, name: &str, d: [f64; 3]) -> String {
    reader::edit_robtarget(module, name, 0, |p| {
        format!("{},{},{}", p[0] + d[0], p[1] + d[1], p[2] + d[2])
    })
}

#[test]
fn the_check_fails_on_programs_made_unsafe_on_purpose() {
    let cell = run(&Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron"));
    let good = check(&cell).unwrap();
    assert!(good.cuts == 8 && good.heated > 8 * 51, "{good:?}");
    let with = |r1: String, r2: String| Cell {
        modules: vec![r1, r2],
        ..cell.clone()
    };
    let (r1, r2) = (cell.modules[0].clone(), cell.modules[1].clone());
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
    // a cutting target lowered by 10 mm in both tasks: the heated blade below the design
    let (l1, l2) = (
        shifted(&r1, "pB1_C5", [0.0, 0.0, -10.0]),
        shifted(&r2, "pB1_C5", [0.0, 0.0, -10.0]),
    );
    let e = check(&with(l1, l2)).unwrap_err();
    assert!(
        e.contains("pB1_C5") && e.contains("below the design"),
        "{e}"
    );
    // or raised by 1 mm: it misses the design (a hot blade's always meets it)
    let (l1, l2) = (
        shifted(&r1, "pB1_C5", [0.0, 0.0, 1.0]),
        shifted(&r2, "pB1_C5", [0.0, 0.0, 1.0]),
    );
    let e = check(&with(l1, l2)).unwrap_err();
    assert!(
        e.contains("pB1_C5") && e.contains("misses the design"),
        "{e}"
    );
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

#[test]
fn a_facade_program_lowered_on_purpose_is_caught() {
    let cell = run(&Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/seg-mesh-trace.ron"));
    let good = check(&cell).unwrap();
    assert_eq!(
        (good.other_equilibrium, good.ambiguous_gouging),
        (0, 0),
        "{good:?}"
    );
    let (r1, r2) = (cell.modules[0].clone(), cell.modules[1].clone());
    // a cutting target of block 1 lowered by 10 mm in both tasks: no blade these ends
    // allow meets its part, and every one runs below the design
    let lowered = Cell {
        modules: vec![
            shifted(&r1, "pB1_C3", [0.0, 0.0, -10.0]),
            shifted(&r2, "pB1_C3", [0.0, 0.0, -10.0]),
        ],
        ..cell.clone()
    };
    match check_with(&lowered, false) {
        Ok(r) => assert_eq!(r.ambiguous_gouging, 1, "{r:?}"),
        Err(e) => assert!(
            e.contains("pB1_C3") && e.contains("below the design"),
            "{e}"
        ),
    }
}

#[test]
fn the_check_fails_on_carried_programs_made_unsafe_on_purpose() {
    let cell = run(&Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-carried.ron"));
    assert_eq!(cell.modules.len(), 3);
    let good = check(&cell).unwrap();
    assert!(good.cuts == 2 && good.worst_fk_mm < FK_MM, "{good:?}");
    let with = |k: usize, m: String| {
        let mut c = cell.clone();
        c.modules[k] = m;
        c
    };
    let [r1, r2, r3] = [0, 1, 2].map(|k| cell.modules[k].clone());
    // a travel to block 2 lowered by 500 mm in the block's frame by both blade tasks:
    // through the carried block, cold
    let mut low = cell.clone();
    low.modules[0] = shifted(&r1, "pB2_T3", [0.0, 0.0, -500.0]);
    low.modules[1] = shifted(&r2, "pB2_T3", [0.0, 0.0, -500.0]);
    let e = check(&low).unwrap_err();
    assert!(e.contains("inside block"), "{e}");
    // the carrier's target moved: its stated joints no longer reach it
    let e = check(&with(2, shifted(&r3, "pB1_C4", [0.0, 0.0, 5.0]))).unwrap_err();
    assert!(e.contains("stated joints"), "{e}");
    // the blade's ends in a fixed work object instead of the carried one
    let fixed = r1.replace("[FALSE,FALSE,\"ROB_3\",", "[FALSE,TRUE,\"\",");
    assert_ne!(fixed, r1);
    let e = check(&with(0, fixed)).unwrap_err();
    assert!(e.contains("carried block"), "{e}");
    // the carrier's tool is not the block's frame
    let line = r3.lines().find(|l| l.contains("tooldata tGrip")).unwrap();
    let at = line.find("[TRUE,[[").unwrap() + 8;
    let end = at + line[at..].find(',').unwrap();
    let x: f64 = line[at..end].parse().unwrap();
    let moved = format!("{}{}{}", &line[..at], x + 10.0, &line[end..]);
    let e = check(&with(2, r3.replace(line, &moved))).unwrap_err();
    assert!(e.contains("grip"), "{e}");
    // the carrier leaves the synchronized motion for one move
    let off = r3.replacen(" \\ID:=40,", ",", 1);
    assert!(check(&with(2, off)).unwrap_err().contains("\\ID"));
}
