//! The robot cell of the tasks that pose the hot blade (`HotBlade`, `FacadeSegmentation`):
//! the job's `cell:` checked, resolved to millimetres (or the default cell), the whole
//! program planned by [`cell::fixture`], and its report. Shared by both tasks, which call
//! it with their blade poses.

/// The report's `cell.equilibrium` section: the blade followed through the program.
pub mod equilibrium;
/// The report's `cell` section.
pub mod report;
/// The cell in millimetres, with its defaults.
pub mod resolve;

use cell::layout::{PlacedBlock, ResolvedCell};
use cell::program::{Motion, Program};
use export::robot::Targets;

use crate::context::{Context, JobFields};
use crate::error::{HotcutError, JobError, Result};
use crate::spec::CellSpec;
use report::CellReport;
use resolve::{block_frame, end_frame};

/// What the robot files are written from.
#[derive(Debug, Clone)]
pub struct CellPlan {
    /// The cell.
    pub cell: ResolvedCell,
    /// The planned program.
    pub program: Program,
    /// Cutting speed, mm/s.
    pub cut_speed: f64,
    /// The blocks' sizes, mm, by block number, in cutting order.
    pub blocks: Vec<(usize, [f64; 3])>,
    /// The report's section.
    pub report: CellReport,
}

/// Largest distance of a frame's origin, a clearance or a centre of gravity from zero, mm
/// (a cell is a room, not a city).
const MAX_MM: f64 = 100_000.0;
/// Fastest air speed, mm/s (ABB arms top out near 7 m/s).
const MAX_AIR_MM_PER_S: f64 = 5_000.0;

/// Where a reported problem is (under `/cell`) and what it is.
type Report<'a> = &'a mut dyn FnMut(&str, String);

/// A point within [`MAX_MM`] of zero (`mm` per job unit).
fn near(p: (f64, f64, f64), mm: f64) -> bool {
    [p.0, p.1, p.2]
        .iter()
        .all(|v| v.is_finite() && (v * mm).abs() <= MAX_MM)
}

/// A frame near zero with angles within two turns.
fn frame_ok(f: &crate::spec::FrameSpec, mm: f64) -> bool {
    near(f.origin, mm)
        && [f.rotation.0, f.rotation.1, f.rotation.2]
            .iter()
            .all(|v| v.is_finite() && v.abs() <= 720.0)
}

fn frame_message() -> String {
    format!("a frame's origin must lie within {MAX_MM} mm, its angles within ±720°")
}

/// The checks every task that poses the blade for the cell makes, in one place: its motion
/// (`speed`, `approach` under the task's pointer `ptr`), the blade's kerf, the job's
/// `cell:`, and what a robot program needs of the motion: a positive approach (the blade
/// must start and end outside the block) and a cutting speed RAPID can state.
pub fn check(
    job: &JobFields<'_>,
    (ptr, speed, approach): (&str, Option<f64>, Option<f64>),
    errors: &mut Vec<JobError>,
) {
    job.check_motion(ptr, speed, approach, errors);
    job.check_kerf(errors);
    let mm = 1.0 / job.units.per_mm();
    let rapid = job
        .outputs
        .iter()
        .any(|o| matches!(o, crate::spec::OutputSpec::Rapid));
    if rapid || job.cell.is_some() {
        if approach.is_some_and(|a| !(a > 0.0)) {
            errors.push(job.error(&format!("{ptr}/approach"), "a robot program needs an approach > 0: the blade starts and ends outside the block"));
        }
        if speed.is_some_and(|v| !(v * mm >= 0.01 && v * mm <= MAX_AIR_MM_PER_S)) {
            errors.push(job.error(
                &format!("{ptr}/speed"),
                format!("a robot program's cutting speed must be 0.01–{MAX_AIR_MM_PER_S} mm/s"),
            ));
        }
    }
    let Some(c) = job.cell else { return };
    let mut err = |at: &str, m: String| errors.push(job.error(&format!("/cell{at}"), m));
    check_settings(c, mm, &mut err);
    let robots = check_robots(c, mm, &mut err);
    check_holders(c, robots, mm, &mut err);
    check_carrier(c, robots, mm, &mut err);
}

/// The block carrier, if any, in a cell of `robots` robots.
fn check_carrier(c: &CellSpec, robots: usize, mm: f64, err: Report<'_>) {
    let Some(k) = &c.block_carrier else {
        if robots == 3 {
            err(
                "/robots",
                "a third robot only carries the block: give block_carrier, or list 2 robots".into(),
            );
        }
        return;
    };
    if c.robots.is_none() {
        err(
            "/robots",
            "a cell with a block carrier lists its three robots".into(),
        );
    } else if robots != 3 {
        err(
            "/block_carrier",
            format!("a block carrier is the cell's third robot: list 3 robots, got {robots}"),
        );
    }
    if c.fixture.is_some() {
        err(
            "/fixture",
            "a carried block has no fixture: leave fixture out (the carrier's station says where the blade cuts)".into(),
        );
    }
    let holders: Vec<usize> = match &c.blade_holders {
        Some(h) => h.iter().map(|h| h.robot).collect(),
        None => vec![0, 1],
    };
    if k.robot >= robots.max(2) || holders.contains(&k.robot) {
        err(
            "/block_carrier/robot",
            format!(
                "robot {} cannot carry the block: it must exist and not hold the blade",
                k.robot
            ),
        );
    }
    if !frame_ok(&k.grip, mm) {
        err("/block_carrier/grip", frame_message());
    }
    if !frame_ok(&k.station, mm) {
        err("/block_carrier/station", frame_message());
    }
    if !(k.mass > 0.0 && k.mass <= 2000.0) {
        err(
            "/block_carrier/mass",
            "the mass must be positive, at most 2000 kg".into(),
        );
    }
}

/// Speeds, clearance, heat, fixture, carrier.
fn check_settings(c: &CellSpec, mm: f64, err: Report<'_>) {
    let within = |v: Option<f64>, max: f64| v.is_none_or(|v| v > 0.0 && v * mm <= max);
    if !within(c.air_speed, MAX_AIR_MM_PER_S) || c.air_speed.is_some_and(|v| v * mm < 0.01) {
        err(
            "/air_speed",
            format!("the air speed must be 0.01–{MAX_AIR_MM_PER_S} mm/s"),
        );
    }
    if !within(c.clearance, MAX_MM) {
        err(
            "/clearance",
            format!("the clearance must be positive, at most {MAX_MM} mm"),
        );
    }
    if let Some(why) = export::rapid_names::name_problem(&c.heat.signal) {
        err(
            "/heat/signal",
            format!(
                "{:?} {why}: name the heat's digital output otherwise",
                c.heat.signal
            ),
        );
    }
    if !(0.0..=600.0).contains(&c.heat.preheat_s) {
        err(
            "/heat/preheat_s",
            format!("the preheat must be 0–600 s, got {}", c.heat.preheat_s),
        );
    }
    if c.fixture.as_ref().is_some_and(|f| !frame_ok(f, mm)) {
        err("/fixture", frame_message());
    }
}

/// The robots; returns how many the cell has.
fn check_robots(c: &CellSpec, mm: f64, err: Report<'_>) -> usize {
    let Some(rs) = &c.robots else { return 2 };
    if rs.len() < 2 || rs.len() > 3 {
        err(
            "/robots",
            format!(
                "the cell needs 2 robots (3 with a block carrier), got {}",
                rs.len()
            ),
        );
    }
    for (i, r) in rs.iter().enumerate() {
        if !frame_ok(&r.base, mm) {
            err(&format!("/robots/{i}/base"), frame_message());
        }
        if let crate::spec::ModelSpec::Custom(c) = &r.model {
            let printable = |s: &str| {
                !s.is_empty()
                    && s.len() <= 40
                    && s.chars().all(|c| c.is_ascii_graphic() || c == ' ')
            };
            if !printable(&c.name) {
                err(&format!("/robots/{i}/model/Custom/name"), "the name must be 1–40 printable ASCII characters (it is written into the programs' comments)".into());
            }
            let six = |n: Option<usize>| n.is_none_or(|n| n == 6);
            if !six(Some(c.limits.len()))
                || !six(c.offsets.as_ref().map(Vec::len))
                || !six(c.signs.as_ref().map(Vec::len))
            {
                err(
                    &format!("/robots/{i}/model/Custom"),
                    "limits, offsets and signs have one entry per axis: 6".into(),
                );
                continue;
            }
        }
        if let Err(e) = resolve::model(&r.model, mm).check() {
            err(&format!("/robots/{i}/model"), e.to_string());
        }
    }
    rs.len()
}

/// The blade holders of a cell of `robots` robots.
fn check_holders(c: &CellSpec, robots: usize, mm: f64, err: Report<'_>) {
    let Some(hs) = &c.blade_holders else {
        if robots < 2 {
            err(
                "/blade_holders",
                "give the holders of the blade's two ends".into(),
            );
        }
        return;
    };
    if hs.len() != 2 {
        err(
            "/blade_holders",
            format!("the blade has two ends: give 2 holders, got {}", hs.len()),
        );
    }
    for (i, h) in hs.iter().enumerate() {
        if h.robot >= robots {
            err(
                &format!("/blade_holders/{i}/robot"),
                format!("robot {} does not exist (the cell has {robots})", h.robot),
            );
        }
        if h.tcp.as_ref().is_some_and(|f| !frame_ok(f, mm)) {
            err(&format!("/blade_holders/{i}/tcp"), frame_message());
        }
        if !h.mass.is_none_or(|m| m > 0.0 && m <= 1000.0) {
            err(
                &format!("/blade_holders/{i}/mass"),
                "the mass must be positive, at most 1000 kg".into(),
            );
        }
        if !h.cog.is_none_or(|p| near(p, mm)) {
            err(
                &format!("/blade_holders/{i}/cog"),
                format!("the centre of gravity must lie within {MAX_MM} mm"),
            );
        }
    }
    if hs.len() == 2 && hs[0].robot == hs[1].robot {
        err(
            "/blade_holders/1/robot",
            "one robot cannot hold both ends of the blade".into(),
        );
    }
}

/// The robot program of a task that poses the blade, the one place the three such tasks
/// (`HotBlade`, `FacadeSegmentation`, `Design`) meet the cell: with `strict` and RAPID
/// asked, a blade that gouges or whose holders hit a block (`refusal()` says how, after
/// "a blade that") fails the run; else, when RAPID or a `cell:` is asked and the run
/// posed a blade (`posed`), the poses `targets()` make are planned ([`plan`]) at the
/// task's `(speed, approach)` (job units).
///
/// # Errors
/// The strict refusal, the targets' error, or [`plan`]'s.
pub fn program(
    job: &Context,
    (speed, approach): (f64, f64),
    posed: bool,
    refusal: impl FnOnce() -> Option<String>,
    targets: impl FnOnce() -> Result<(Targets, Vec<[f64; 3]>)>,
) -> Result<Option<CellPlan>> {
    let strict = job.rapid && job.cell.as_ref().is_some_and(|c| c.strict);
    if strict {
        if let Some(m) = refusal() {
            return Err(job.fail(format!("strict: no robot program for a blade that {m}")));
        }
    }
    if !(posed && (job.rapid || job.cell.is_some())) {
        return Ok(None);
    }
    let (t, sizes) = targets()?;
    if strict {
        if let Some(m) = not_holding(&t) {
            return Err(job.fail(format!("strict: no robot program for a blade that {m}")));
        }
    }
    plan(job, &t, &sizes, speed, approach).map(Some)
}

/// Why the blade would not hold the shape a pose of `t` plans (the first such pose, named
/// by its block and number), if one would not: unstable or marginal.
pub fn not_holding(t: &Targets) -> Option<String> {
    let bad: Vec<(usize, usize, &export::robot::PoseBlade)> = t
        .blocks
        .iter()
        .flat_map(|b| {
            b.poses
                .iter()
                .enumerate()
                .map(move |(k, p)| (b.block, k + 1, &p.blade))
        })
        .filter(|(_, _, b)| b.stability != "Stable")
        .collect();
    let (block, pose, b) = bad.first()?;
    Some(format!(
        "does not hold its shape: block {block}, pose {pose} is {} (margin {:.3}, {} inflections); {} such pose(s) in all",
        b.stability.to_lowercase(),
        b.margin,
        b.inflections,
        bad.len()
    ))
}

/// The blocks of `t` (sizes `sizes`, job units) with the blade's ends, in mm.
fn placed_blocks(t: &Targets, sizes: &[[f64; 3]]) -> Vec<PlacedBlock> {
    let mm = 1.0 / t.per_mm;
    t.blocks
        .iter()
        .zip(sizes)
        .map(|(b, size)| PlacedBlock {
            block: b.block,
            frame: block_frame(b, mm),
            size: size.map(|v| v * mm),
            poses: b
                .poses
                .iter()
                .map(|p| p.ends.map(|e| end_frame(&e, mm)))
                .collect(),
            shapes: b.poses.iter().map(|p| p.blade.shape).collect(),
        })
        .collect()
}

/// Plans the cell's program for the poses `t` (blocks of `sizes`, job units, in the
/// order of `t.blocks`), cutting at `speed` with `approach` (job units), with
/// [`cell::program::plan`]: at the fixture or with the block carried.
///
/// # Errors
/// A plan that cannot be made (named), or with `strict: true`, any flag.
pub fn plan(
    job: &Context,
    t: &Targets,
    sizes: &[[f64; 3]],
    speed: f64,
    approach: f64,
) -> Result<CellPlan> {
    let mm = 1.0 / t.per_mm;
    let placed = placed_blocks(t, sizes);
    let motion = Motion {
        blade: t.blade_length * mm,
        max_curvature: job.blade.max_curvature / mm,
        approach: approach * mm,
    };
    let settings = resolve::settings(job.cell.as_ref(), mm);
    let (cell, program) = cell::program::plan(&settings, &placed, &motion)
        .map_err(|e| job.fail(format!("robot cell: {e}")))?;
    let slacks: Vec<f64> = t
        .blocks
        .iter()
        .flat_map(|b| &b.poses)
        .map(|p| p.blade.slack * mm)
        .collect();
    let report = report::report(&cell, &program, speed * mm, job.blade.min_margin, &slacks);
    if cell.strict && !(report.clean && report.equilibrium.snaps == 0) {
        let mut problems = report.problems();
        problems.extend(report.equilibrium.problems());
        return Err(HotcutError::Task {
            path: job.path.clone(),
            message: format!("robot cell (strict): {}", problems.join("; ")),
        });
    }
    Ok(CellPlan {
        cut_speed: speed * mm,
        blocks: placed
            .iter()
            .filter(|b| !b.poses.is_empty())
            .map(|b| (b.block, b.size))
            .collect(),
        cell,
        program,
        report,
    })
}

/// The blade's heated path in a planned program, mm, and how many times the heat goes
/// on: per heated move, the farther of the two ends' travels through the block (the
/// synchronized move lasts as long as the end that goes farther takes at the cutting
/// speed), each move measured in its block's frame from the move before it in the same
/// block.
pub fn heated_path_mm(plan: &CellPlan) -> (f64, usize) {
    let steps = &plan.program.steps;
    let path = steps
        .windows(2)
        .filter(|w| w[1].heat && w[0].block == w[1].block)
        .map(|w| {
            let d = |k: usize| {
                (w[1].ends[k].translation.vector - w[0].ends[k].translation.vector).norm()
            };
            d(0).max(d(1))
        })
        .sum();
    let first = usize::from(steps.first().is_some_and(|s| s.heat));
    let ons = first + steps.windows(2).filter(|w| w[1].heat && !w[0].heat).count();
    (path, ons)
}

/// A blade process's figures ([`crate::process::ProcessFigures`]) from its planned
/// program: the heated path and its speed, the preheat dwells, one set-up per block; why
/// not when the task's own `why_not` says so, or when no program was planned or it is not
/// clean. `blocks`, `stock` and `part` are the task's, in job units.
pub fn blade_figures(
    cell: Option<&CellPlan>,
    why_not: Option<String>,
    (blocks, stock, part): (usize, f64, f64),
    deviation: Option<crate::process::Deviation>,
    per_mm: f64,
) -> crate::process::ProcessFigures {
    let why_not = why_not.or_else(|| match cell {
        None => Some("no robot program was planned".into()),
        Some(c) if !c.report.clean => Some(
            "the robot program is not clean (a pose out of reach, a configuration change or a joint jump): see its report".into(),
        ),
        Some(_) => None,
    });
    let (path, heat_ons) = cell.map_or((0.0, 0), heated_path_mm);
    crate::process::ProcessFigures {
        why_not,
        blocks,
        stock_volume: stock,
        part_volume: part,
        milling_volume: 0.0,
        milled_area: 0.0,
        cutter: crate::process::Cutter::Blade,
        cut_length: path * per_mm,
        cut_speed: cell.map_or(0.0, |c| c.cut_speed * per_mm),
        dwell_s: heat_ons as f64 * cell.map_or(0.0, |c| c.report.preheat_s),
        setups: blocks,
        programs: usize::from(cell.is_some()),
        deviation,
    }
}
