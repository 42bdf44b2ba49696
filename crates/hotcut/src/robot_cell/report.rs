//! The report's `cell` section: the cell as planned (millimetres and degrees, whatever the
//! job's units, so a replay can rebuild every robot) and, per block, what the robots
//! reach.

use cell::fixture::BlockCheck;
use nalgebra::Isometry3;
use schemars::JsonSchema;
use serde::Serialize;

use cell::layout::ResolvedCell;
use cell::program::Program;

/// A frame: origin (mm) and orientation `[w, x, y, z]`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FrameReport {
    /// Origin, mm.
    pub origin_mm: [f64; 3],
    /// Orientation `[w, x, y, z]`.
    pub rotation: [f64; 4],
}

impl FrameReport {
    /// The report of an isometry.
    pub fn of(f: &Isometry3<f64>) -> Self {
        let q = f.rotation.as_ref().coords;
        let s = if q.w < 0.0 { -1.0 } else { 1.0 };
        FrameReport {
            origin_mm: f.translation.vector.into(),
            rotation: [s * q.w, s * q.x, s * q.y, s * q.z],
        }
    }
}

/// A robot as planned.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct RobotReport {
    /// Its RAPID task.
    pub task: String,
    /// Model name.
    pub model: String,
    /// OPW lengths `[a1, a2, b, c1, c2, c3, c4]`, mm.
    pub opw_mm: [f64; 7],
    /// Joint offsets from the OPW zero to the maker's, degrees.
    pub offsets_deg: [f64; 6],
    /// Joint directions, ±1.
    pub signs: [i8; 6],
    /// Joint limits, degrees.
    pub limits_deg: [(f64, f64); 6],
    /// Base frame in the cell's frame.
    pub base: FrameReport,
}

/// A blade holder as planned.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct HolderReport {
    /// Index of its robot.
    pub robot: usize,
    /// The TCP (the blade's end) in the flange's frame.
    pub tcp: FrameReport,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Centre of gravity in the flange's frame, mm.
    pub cog_mm: [f64; 3],
}

/// The block carrier as planned.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CarrierReport {
    /// Index of its robot.
    pub robot: usize,
    /// The block's frame in the flange's frame.
    pub grip: FrameReport,
    /// Mass of the gripper with a block, kg.
    pub mass_kg: f64,
    /// Where the blade cuts, in the cell's frame.
    pub station: FrameReport,
}

/// The `cell` section.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CellReport {
    /// Whether robots or holders are the default cell's (assumed, not the user's).
    pub assumed: bool,
    /// The robots, in task order.
    pub robots: Vec<RobotReport>,
    /// The holders of the blade's first and second end.
    pub holders: Vec<HolderReport>,
    /// A block's frame at the fixture, in the cell's frame (`None` with a carrier).
    pub fixture: Option<FrameReport>,
    /// The robot carrying the block, if any.
    pub carrier: Option<CarrierReport>,
    /// Height of the blade above the blocks between them, mm.
    pub clearance_mm: f64,
    /// Cutting speed, mm/s.
    pub cut_speed_mm_s: f64,
    /// Air speed, mm/s.
    pub air_speed_mm_s: f64,
    /// The heat's output.
    pub heat_signal: String,
    /// Preheat, s.
    pub preheat_s: f64,
    /// Synchronized moves of the program.
    pub moves: usize,
    /// Every move reached by every robot of the cell (the blade's two, and a carrier's)
    /// with no configuration change and no joint jump.
    pub clean: bool,
    /// Per block.
    pub blocks: Vec<BlockCheck>,
    /// The blade's equilibrium followed through every move: margins and snaps.
    pub equilibrium: super::equilibrium::EquilibriumReport,
}

impl CellReport {
    /// What a task's `report.html` shows of its cell, if it planned one: a constraint row
    /// and the per-block table, added to the page's.
    pub fn add_to_page(
        cell: Option<&Self>,
        constraints: &mut Vec<export::html::Constraint>,
        tables: &mut Vec<export::html::Table>,
    ) {
        if let Some(cell) = cell {
            constraints.push(cell.constraint());
            let e = &cell.equilibrium;
            constraints.push(export::html::Constraint {
                name: "the blade through the robot program (stability.svg)".into(),
                limit: "no snap: every move keeps the blade on the planned shape".into(),
                measured: format!(
                    "{} of {} moves snap; least margin {:.3}; {} cutting pose(s) nearly taut (slack below {} mm)",
                    e.snaps,
                    e.transitions,
                    e.min_margin,
                    e.taut_poses,
                    super::equilibrium::TAUT_SLACK_MM
                ),
                ok: e.snaps == 0,
            });
            tables.push(cell.table());
        }
    }

    /// One line for the run's summary: the robots, the moves, the verdict.
    pub fn summary(&self) -> String {
        let models: Vec<&str> = self.robots.iter().map(|r| r.model.as_str()).collect();
        let mut verdict = if self.clean {
            "every move reached, no flip".to_string()
        } else {
            format!("warning: {}", self.problems().join("; "))
        };
        let e = &self.equilibrium;
        if let Some(w) = e.taut_warning() {
            verdict.push_str(&format!("; warning: {w}"));
        }
        verdict.push_str(&if e.snaps == 0 {
            format!(
                "; the blade holds its shape through all {} moves (least margin {:.3})",
                e.transitions, e.min_margin
            )
        } else {
            format!(
                "; warning: the blade snaps on {} of {} moves: {}",
                e.snaps,
                e.transitions,
                e.problems().join("; ")
            )
        });
        let assumed = if self.assumed {
            " (default cell: placement and tool data assumed, check them on the controller)"
        } else {
            ""
        };
        format!(
            "  cell: {}{assumed}; {} synchronized moves; {verdict}",
            models.join(" + "),
            self.moves
        )
    }

    /// What is wrong, one line per block and robot.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        for b in &self.blocks {
            for (r, c) in b.robots.iter().enumerate() {
                if c.out_of_reach + c.configuration_changes + c.joint_jumps > 0 {
                    out.push(format!(
                        "block {}, robot {}: {} move(s) out of reach, {} configuration change(s), {} joint jump(s)",
                        b.block,
                        r + 1,
                        c.out_of_reach,
                        c.configuration_changes,
                        c.joint_jumps
                    ));
                }
            }
        }
        out
    }

    /// The cell's row of a `report.html` constraint table: every move reached.
    pub fn constraint(&self) -> export::html::Constraint {
        let models: Vec<&str> = self.robots.iter().map(|r| r.model.as_str()).collect();
        let bad = self.problems().len();
        let assumed = if self.assumed {
            " — default cell: placement and tool data assumed, check them on the controller"
        } else {
            ""
        };
        export::html::Constraint {
            name: format!("robot cell ({})", models.join(" + ")),
            limit: "every move reached, no configuration change, no joint jump".into(),
            measured: if bad == 0 {
                format!("{} synchronized moves, all clean{assumed}", self.moves)
            } else {
                format!("{bad} block/robot pair(s) with problems{assumed}")
            },
            ok: self.clean,
        }
    }

    /// The per-block table of the cell for `report.html` (what each robot reaches), rows
    /// with a problem flagged.
    pub fn table(&self) -> export::html::Table {
        let mut columns = vec![
            "block".to_string(),
            "moves".into(),
            "air clearance (mm)".into(),
        ];
        for r in 0..self.robots.len() {
            columns.push(format!(
                "robot {} out of reach / config. changes / jumps",
                r + 1
            ));
            columns.push(format!("robot {} joint margin", r + 1));
        }
        let rows = self
            .blocks
            .iter()
            .map(|b| {
                let mut cells = vec![
                    b.block.to_string(),
                    b.moves.to_string(),
                    format!("{:.1}", b.air_clearance),
                ];
                let mut why = Vec::new();
                for c in &b.robots {
                    cells.push(format!(
                        "{} / {} / {}",
                        c.out_of_reach, c.configuration_changes, c.joint_jumps
                    ));
                    cells.push(c.margin_deg.map_or("—".into(), |m| format!("{m:.1}°")));
                    if c.out_of_reach > 0 {
                        why.push("out of reach");
                    }
                    if c.configuration_changes > 0 {
                        why.push("configuration change");
                    }
                    if c.joint_jumps > 0 {
                        why.push("joint jump");
                    }
                }
                why.dedup();
                export::html::Row::new(cells, why)
            })
            .collect();
        export::html::Table {
            title: "Robot cell: what the robots reach, per placement of a block in the cell".into(),
            columns,
            rows,
        }
    }
}

/// The report of a planned cell.
pub fn report(
    cell: &ResolvedCell,
    program: &Program,
    cut_speed: f64,
    marginal: f64,
    slacks: &[f64],
) -> CellReport {
    // the holder of end e is task T_ROB<e+1>, the carrier T_ROB3
    let task = |i: usize| {
        let n = match cell.holders.iter().position(|h| h.robot == i) {
            Some(e) => e + 1,
            None => 3,
        };
        format!("T_ROB{n}")
    };
    let robots = cell
        .robots
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let o = &r.model.opw;
            RobotReport {
                task: task(i),
                model: r.model.name.clone(),
                opw_mm: [o.a1, o.a2, o.b, o.c1, o.c2, o.c3, o.c4],
                offsets_deg: o.offsets.map(f64::to_degrees),
                signs: o.signs,
                limits_deg: r
                    .model
                    .limits
                    .map(|(a, b)| (a.to_degrees(), b.to_degrees())),
                base: FrameReport::of(&r.base),
            }
        })
        .collect();
    let holders = cell
        .holders
        .iter()
        .map(|h| HolderReport {
            robot: h.robot,
            tcp: FrameReport::of(&h.tcp),
            mass_kg: h.mass,
            cog_mm: h.cog,
        })
        .collect();
    let clean = program.blocks.iter().all(BlockCheck::is_clean);
    CellReport {
        assumed: cell.assumed,
        robots,
        holders,
        fixture: cell
            .carrier
            .is_none()
            .then(|| FrameReport::of(&cell.fixture)),
        carrier: cell.carrier.as_ref().map(|k| CarrierReport {
            robot: k.robot,
            grip: FrameReport::of(&k.grip),
            mass_kg: k.mass,
            station: FrameReport::of(&k.station),
        }),
        clearance_mm: cell.clearance,
        cut_speed_mm_s: cut_speed,
        air_speed_mm_s: cell.air_speed,
        heat_signal: cell.heat.0.clone(),
        preheat_s: cell.heat.1,
        moves: program.steps.len(),
        clean,
        blocks: program.blocks.clone(),
        equilibrium: super::equilibrium::report(&program.steps, &program.shapes, marginal, slacks),
    }
}
