//! The robot files of every task that poses the blade: `targets.json` and `targets.csv`
//! (every pose in job coordinates, [`export::robot`]), and from the cell's plan
//! ([`crate::robot_cell`]) one ABB RAPID module and `.pgf` per robot task
//! ([`export::rapid`]) with `cell.csv`, every move's joints for every robot.

use cell::fixture::Phase;
use elastica::sweep::BladePose;
use export::csv::Table;
use export::rapid::{
    identifier, write_module, write_pgf, RapidMove, RapidProgram, RapidTarget, RapidTool, RapidWobj,
};
use export::robot::TARGET_DIGITS;
use export::robot::{targets_csv, EndPose, Pose, PoseBlade, Targets, TargetsBlock};
use nalgebra::Isometry3;

use super::Files;
use crate::robot_cell::report::FrameReport;
use crate::robot_cell::CellPlan;
use crate::spec::{OutputKind, Units};

/// The targets of `blocks` (poses in job units `units`) for a blade of `blade_length`.
pub fn targets(units: Units, blade_length: f64, blocks: Vec<TargetsBlock>) -> Targets {
    Targets {
        units: units.name().into(),
        per_mm: units.per_mm(),
        unit_symbol: units.symbol(),
        blade_length,
        blocks,
    }
}

/// A pose as the robot files take it, with its blade (stiffness `s`).
pub fn pose(p: &BladePose, blade: &elastica::Blade, s: &elastica::Stiffness) -> Pose {
    let end = |k: usize| EndPose {
        position: p.ends[k].position,
        tangent: p.ends[k].tangent,
        rotation: p.ends[k].rotation,
    };
    let st = &blade.stability;
    let loads = st.loads.held(s);
    Pose {
        plane_normal: p.plane_normal,
        ends: [end(0), end(1)],
        blade: PoseBlade {
            shape: p.shape,
            turning: st.turning,
            slack: blade.segment.length()
                - nalgebra::Vector3::from(p.ends[1].position)
                    .metric_distance(&nalgebra::Vector3::from(p.ends[0].position)),
            inflections: blade.inflections,
            margin: st.margin,
            stability: class_name(st.class),
            force_n: loads.force_n,
            tension_n: loads.tension_n,
            moment_nm: loads.moment_nm,
        },
    }
}

/// The name of a stability class as reports write it.
pub fn class_name(c: elastica::Class) -> &'static str {
    match c {
        elastica::Class::Stable => "Stable",
        elastica::Class::Marginal => "Marginal",
        elastica::Class::Unstable => "Unstable",
    }
}

fn target(f: &Isometry3<f64>) -> RapidTarget {
    let r = FrameReport::of(f);
    RapidTarget {
        position: r.origin_mm,
        rotation: r.rotation,
    }
}

/// Task `r`'s moves (0, 1: the blade's ends in the work object; 2: the carried block in
/// the world).
fn moves(plan: &CellPlan, r: usize) -> Vec<RapidMove> {
    let steps = &plan.program.steps;
    let poses = plan.program.block_poses.as_deref().unwrap_or(&[]);
    let names = crate::robot_cell::equilibrium::target_names(steps);
    steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let sol = &plan.program.solutions[r][k];
            let c = sol.conf;
            let next = steps.get(k + 1);
            let fine = next
                .is_none_or(|n| n.phase != s.phase || n.heat != s.heat || n.change.is_some())
                || !matches!(s.phase, Phase::Cut | Phase::Travel);
            RapidMove {
                name: names[k].clone(),
                target: target(&match (r, poses.get(k)) {
                    (2, Some(b)) => *b,
                    // the blade's first move, in the world, before the carried block leads
                    (_, Some(b)) if k == 0 => b * s.ends[r],
                    _ => s.ends[r],
                }),
                conf: c.map_or([0; 4], |c| [c.cf1, c.cf4, c.cf6, c.cfx]),
                joints: sol.joints,
                cut: matches!(s.phase, Phase::Cut | Phase::Retreat),
                fine,
                heat: s.heat,
                change: s.change,
                world: r < 2 && k == 0 && !poses.is_empty(),
            }
        })
        .collect()
}

/// The header comment of task `r`'s module.
fn comment(plan: &CellPlan, job: &str, r: usize) -> Vec<String> {
    let cell = &plan.cell;
    let (index, role) = match (r, &cell.carrier) {
        (2, Some(k)) => (k.robot, "carries the block (tool tGrip: the block's frame)"),
        (0, _) => (cell.holders[0].robot, "holds the blade's first end"),
        _ => (cell.holders[1].robot, "holds the blade's second end"),
    };
    let robot = &cell.robots[index];
    let base = FrameReport::of(&robot.base);
    let f = |v: &[f64]| {
        v.iter()
            .map(|x| export::fmt_float(*x, 3))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut c = vec![
        format!(
            "hotcut job \"{job}\": hot-blade cut. Task T_ROB{} ({}) {role}.",
            r + 1,
            robot.model.name
        ),
        format!(
            "Its base frame in the world (set it in the controller): [{}] mm, q [{}].",
            f(&base.origin_mm),
            f(&base.rotation)
        ),
    ];
    if cell.carrier.is_some() {
        c.extend([
            "T_ROB3 carries each block through the blade, which stays at the station; after their first move".into(),
            "(in wobj0) the blade's ends move in wCarried, the block's frame held by ROB_3 (coordinated motion;".into(),
            "its object frame is the grip in ROB_3's flange frame: confirm that your system attaches the user".into(),
            "frame of a work object moved by ROB_3 to its flange, tool0). The cut runs at vCut relative to the".into(),
            "block, slower where the carrier's own move is longer (the slowest task sets the pace).".into(),
            format!("Between blocks the carrier lowers the block {} mm clear under the blade, and waits for the block change.", export::fmt_float(cell.clearance, 1)),
        ]);
    } else {
        c.extend([
            "wFixture: where each block stands while it is cut (min corner; axes along the cut, across, up).".into(),
            format!("Between blocks the blade retreats, rises {} mm clear of the block and waits, cold, for the block change.", export::fmt_float(cell.clearance, 1)),
        ]);
    }
    c.extend([
        "The whole program is one synchronized motion: all ends move in step, the blade never stretches.".into(),
        format!("Heat: {} on before each approach (preheat {} s), off after each retreat.", cell.heat.0, export::fmt_float(cell.heat.1, 3)),
        "The first target pB*_L1 is the blade mounted straight (its ends a blade length apart): mount it there,".into(),
        "then the program bends it into a gentle arch (pB*_B*) before its first approach; from there every move".into(),
        "keeps the blade on the planned shape (report: cell.equilibrium; the margin along the program in stability.svg).".into(),
    ]);
    if cell.assumed {
        c.push("WARNING: the robots' placement and tool data are hotcut's default cell, not yours: check the base".into());
        c.push("frames, tooldata and confdata on the controller before running (README, \"The robot cell\").".into());
    }
    c
}

/// Task `r`'s tool and work object.
fn tool_and_wobj(plan: &CellPlan, r: usize) -> (RapidTool, Option<RapidWobj>) {
    let cell = &plan.cell;
    if let (2, Some(k)) = (r, &cell.carrier) {
        // the load's centre at the middle of the largest block
        let largest = plan.blocks.iter().fold([0.0f64; 3], |m, (_, s)| {
            [m[0].max(s[0]), m[1].max(s[1]), m[2].max(s[2])]
        });
        let middle = nalgebra::Point3::from(nalgebra::Vector3::from(largest) * 0.5);
        let tool = RapidTool {
            name: "tGrip".into(),
            frame: target(&k.grip),
            mass: k.mass,
            cog: (k.grip * middle).coords.into(),
        };
        return (tool, None);
    }
    let h = &cell.holders[r];
    let tool = RapidTool {
        name: format!("tBlade{}", r + 1),
        frame: target(&h.tcp),
        mass: h.mass,
        cog: h.cog,
    };
    let wobj = match &cell.carrier {
        Some(k) => RapidWobj {
            name: "wCarried".into(),
            frame: target(&k.grip),
            held_by: Some("ROB_3".into()),
        },
        None => RapidWobj {
            name: "wFixture".into(),
            frame: target(&cell.fixture),
            held_by: None,
        },
    };
    (tool, Some(wobj))
}

/// Writes the robot files of output `kind`: `targets.json` and `targets.csv`
/// (`RobotTargets`), or one RAPID module and `.pgf` per blade robot, named after the job,
/// and `cell.csv` (`Rapid`); nothing for other kinds.
///
/// # Errors
/// Serialisation, formatting or file-system failures; `Rapid` without a plan.
pub fn write(
    files: &mut Files,
    t: &Targets,
    plan: Option<&CellPlan>,
    job: &str,
    kind: OutputKind,
) -> export::Result<()> {
    match kind {
        OutputKind::RobotTargets => {
            files.json("targets.json", t, TARGET_DIGITS)?;
            files.text("targets.csv", targets_csv(t))
        }
        OutputKind::Rapid => {
            let plan =
                plan.ok_or_else(|| export::ExportError::Data("no robot cell was planned".into()))?;
            let unreached: Vec<String> = plan
                .report
                .blocks
                .iter()
                .filter(|b| b.robots.iter().any(|r| r.out_of_reach > 0))
                .map(|b| b.block.to_string())
                .collect();
            if !unreached.is_empty() {
                return Err(export::ExportError::Data(format!(
                    "the robots cannot reach every move of block(s) {} (report: cell): no program is written; move the robots, the fixture or the station (cell:), or leave Rapid out",
                    unreached.join(", ")
                )));
            }
            let n = plan.program.solutions.len();
            let tasks: Vec<String> = (1..=n).map(|r| format!("T_ROB{r}")).collect();
            let stem = identifier(job, 25);
            for r in 0..n {
                let module = format!("{stem}_T_ROB{}", r + 1);
                let (tool, wobj) = tool_and_wobj(plan, r);
                let moves = moves(plan, r);
                let comment = comment(plan, job, r);
                let program = RapidProgram {
                    name: &module,
                    comment: &comment,
                    tasks: &tasks,
                    master: r == 0,
                    tool: &tool,
                    wobj: wobj.as_ref(),
                    blocks: &plan.blocks,
                    cut_speed: plan.cut_speed,
                    air_speed: plan.cell.air_speed,
                    heat_signal: &plan.cell.heat.0,
                    preheat_s: plan.cell.heat.1,
                    moves: &moves,
                };
                let mod_file = format!("{module}.mod");
                files.add(&mod_file, |buf| write_module(&program, buf))?;
                files.add(format!("{module}.pgf"), |buf| write_pgf(&mod_file, buf))?;
            }
            files.text("cell.csv", cell_csv(plan))?;
            files.add("stability.svg", |buf| stability_svg(plan, job).write(buf))
        }
        _ => Ok(()),
    }
}

/// `stability.svg`: the blade's stability margin along the program — the least along each
/// synchronized move — with the moves that snap marked, the blocks' moves apart, and the
/// marginal line.
fn stability_svg(plan: &CellPlan, job: &str) -> export::svg::SvgDoc {
    let e = &plan.report.equilibrium;
    let (w, h) = (900.0, 400.0);
    let frame = (70.0, 90.0, w - 100.0, h - 150.0);
    let (x0, y0, pw, ph) = frame;
    let mut doc = export::svg::SvgDoc::new(w, h);
    let n = e.margins.len().max(1);
    let known: Vec<f64> = e.margins.iter().flatten().copied().collect();
    let top = known
        .iter()
        .copied()
        .fold(e.marginal * 2.0, f64::max)
        .min(10.0);
    let bottom = known.iter().copied().fold(0.0, f64::min).max(-top);
    let x = |k: usize| x0 + pw * (k as f64 + 0.5) / n as f64;
    let y = |m: f64| y0 + ph - ph * (m.clamp(bottom, top) - bottom) / (top - bottom);
    let mut title: String = job.chars().take(40).collect();
    title.push_str(": the blade's stability margin along the program");
    doc.text((10.0, 20.0), 13.0, "black", &title);
    doc.text(
        (10.0, 38.0),
        11.0,
        "#333333",
        &format!(
            "{} moves followed, {} snap(s), least margin {}",
            e.transitions,
            e.snaps,
            crate::output::page::num(e.min_margin)
        ),
    );
    use export::svg::{Legend, Mark};
    doc.legend(
        (10.0, 48.0),
        w - 20.0,
        &[
            Legend::new(Mark::Line, "#1f5fa8", "least margin along each move"),
            Legend::new(Mark::Dashed, "#cc8800", "the least margin a pose keeps"),
            Legend::new(Mark::Dot, "#cc0000", "a move that snaps"),
            Legend::new(Mark::Line, "#dddddd", "a block's moves begin"),
        ],
    );
    doc.chart_axes(
        frame,
        (1.0, n as f64),
        (bottom, top),
        "move",
        "margin (1 = a straight, unloaded blade)",
    );
    // where the blocks' moves begin
    let steps = &plan.program.steps;
    for k in 1..steps.len() {
        if steps[k].block != steps[k - 1].block {
            let px = x(k) - 0.5 * pw / n as f64;
            doc.polyline(
                &[(px, y0), (px, y0 + ph)],
                "#dddddd",
                1.0,
                Some(&format!("block {}", steps[k].block)),
            );
        }
    }
    let marginal = y(e.marginal);
    doc.dashed_polyline(
        &[(x0, marginal), (x0 + pw, marginal)],
        "#cc8800",
        1.0,
        4.0,
        Some("the least margin a pose keeps (blade.min_margin)"),
    );
    if bottom < 0.0 {
        let zero = y(0.0);
        doc.polyline(
            &[(x0, zero), (x0 + pw, zero)],
            "#cc0000",
            1.0,
            Some("0: unstable below"),
        );
    }
    // the margin, in runs of followed moves
    let mut run: Vec<(f64, f64)> = Vec::new();
    for (k, m) in e.margins.iter().enumerate() {
        match m {
            Some(m) if m.is_finite() => run.push((x(k), y(*m))),
            _ => {
                if run.len() > 1 {
                    doc.polyline(&run, "#1f5fa8", 1.2, Some("margin"));
                }
                run.clear();
            }
        }
    }
    if run.len() > 1 {
        doc.polyline(&run, "#1f5fa8", 1.2, Some("margin"));
    }
    for s in &e.snap_moves {
        let k = s.r#move - 1;
        let m = e.margins.get(k).copied().flatten().unwrap_or(0.0);
        doc.circle(
            (x(k), y(m)),
            4.0,
            "#cc0000",
            Some(&format!("{}: {:?}", s.target, s.kind)),
        );
    }
    doc
}

/// `cell.csv`: one row per move and robot.
fn cell_csv(plan: &CellPlan) -> String {
    let mut t = Table::new(
        "move,block,phase,heat,robot,solutions,j1,j2,j3,j4,j5,j6,cf1,cf4,cf6,cfx,margin_deg",
    );
    let f = Table::num;
    for (k, s) in plan.program.steps.iter().enumerate() {
        for (r, solutions) in plan.program.solutions.iter().enumerate() {
            let sol = &solutions[k];
            let mut row = vec![
                (k + 1).to_string(),
                s.block.to_string(),
                format!("{:?}", s.phase),
                u8::from(s.heat).to_string(),
                (r + 1).to_string(),
                sol.solutions.to_string(),
            ];
            match sol.joints {
                Some(j) => row.extend(j.iter().map(|v| f(*v))),
                None => row.extend((0..6).map(|_| String::new())),
            }
            match sol.conf {
                Some(c) => row.extend([c.cf1, c.cf4, c.cf6, c.cfx].map(|v| v.to_string())),
                None => row.extend((0..4).map(|_| String::new())),
            }
            row.push(sol.margin.map(f).unwrap_or_default());
            t.row(&row);
        }
    }
    t.finish()
}
