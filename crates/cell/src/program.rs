//! The whole program of a cell for a job's blade poses, with the default cell laid out by
//! search: every default table height, standoff, holder style and wrist side the user
//! leaves open is tried, the best program kept. At a fixture ([`crate::fixture`]) or with
//! the block carried ([`crate::carrier`]).

use nalgebra::Isometry3;

use crate::carrier::{CarriedProgram, CarrierCell};
use crate::error::{CellError, Result};
use crate::fixture::{BlockCheck, BlockCut, CellProgram, FixtureCell, Step};
use crate::layout::{
    defaults, resolve, CellSettings, HolderStyle, Layout, PlacedBlock, ResolvedCell,
};
use crate::plan::PoseSolution;

/// A planned program, at the fixture or with the block carried.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// Every move, the blade's ends in the work object's frame (the block's at the
    /// fixture, or the carried block's), in order.
    pub steps: Vec<Step>,
    /// With a carrier: the carried block's frame in the cell at each move.
    pub block_poses: Option<Vec<Isometry3<f64>>>,
    /// Each robot's solution at every move, in task order (first end's, second end's,
    /// carrier's).
    pub solutions: Vec<Vec<PoseSolution>>,
    /// Per block.
    pub blocks: Vec<BlockCheck>,
    /// The blade's equilibrium through every move ([`crate::equilibrium`]).
    pub shapes: crate::equilibrium::ProgramShapes,
}

impl From<CellProgram> for Program {
    fn from(p: CellProgram) -> Self {
        Program {
            steps: p.steps,
            block_poses: None,
            solutions: p.solutions.into(),
            blocks: p.blocks,
            shapes: p.shapes,
        }
    }
}

impl From<CarriedProgram> for Program {
    fn from(p: CarriedProgram) -> Self {
        Program {
            steps: p.moves.steps,
            block_poses: Some(p.block_poses),
            solutions: p.solutions.into(),
            blocks: p.blocks,
            shapes: p.moves.shapes,
        }
    }
}

/// The blade and its motion, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The blade's length.
    pub blade: f64,
    /// The largest curvature the blade may take, 1/mm.
    pub max_curvature: f64,
    /// How far the blade starts and ends outside a block.
    pub approach: f64,
}

/// The blocks in their own frames, with the blade's ends in them.
fn block_cuts(blocks: &[PlacedBlock]) -> Vec<BlockCut> {
    blocks
        .iter()
        .map(|b| {
            let to_block = b.frame.inverse();
            BlockCut {
                block: b.block,
                size: b.size,
                poses: b.poses.iter().map(|p| p.map(|e| to_block * e)).collect(),
                shapes: b.shapes.clone(),
            }
        })
        .collect()
}

/// The layouts to try: every default table height, standoff and holder style that the
/// settings leave to the default cell (the table with the default fixture and robots, the
/// standoff with the default robots, the style with the default holders).
pub fn layouts(settings: &CellSettings) -> Vec<Layout> {
    let robots = settings.robots.is_none();
    let fixture = settings.fixture.is_none();
    let holders = settings.holders.is_none();
    let tables: &[f64] = if robots && fixture {
        &defaults::TABLES_MM
    } else {
        &defaults::TABLES_MM[..1]
    };
    let standoffs: &[f64] = if robots {
        &defaults::STANDOFFS_MM
    } else {
        &defaults::STANDOFFS_MM[..1]
    };
    let styles: &[HolderStyle] = if holders {
        &[HolderStyle::Facing, HolderStyle::Hanging]
    } else {
        &[HolderStyle::Facing]
    };
    let mut out = Vec::new();
    for &style in styles {
        for &table in tables {
            for &standoff in standoffs {
                out.push(Layout {
                    table,
                    standoff,
                    style,
                });
            }
        }
    }
    out
}

/// How bad a program is: moves out of reach, then configuration changes and joint jumps,
/// then the least joint margin (larger is better).
pub fn score(p: &Program) -> (usize, usize, f64) {
    let (mut reach, mut flips, mut margin) = (0, 0, f64::INFINITY);
    for b in &p.blocks {
        for r in &b.robots {
            reach += r.out_of_reach;
            flips += r.configuration_changes + r.joint_jumps;
            margin = margin.min(r.margin_deg.unwrap_or(f64::NEG_INFINITY));
        }
    }
    (reach, flips, -margin)
}

/// What every plan starts from: the blocks in their frames, the largest block, the
/// blade's motion.
struct Setup<'a> {
    settings: &'a CellSettings,
    placed: &'a [PlacedBlock],
    cuts: Vec<BlockCut>,
    largest: [f64; 3],
    motion: Motion,
}

impl Setup<'_> {
    fn resolve(&self, layout: Layout) -> ResolvedCell {
        resolve(
            self.settings,
            self.placed,
            self.motion.blade,
            self.largest,
            layout,
        )
    }

    fn fixture_cell(&self, cell: &ResolvedCell, start: [f64; 6]) -> FixtureCell {
        FixtureCell {
            holders: [cell.holder(0), cell.holder(1)],
            fixture: cell.fixture,
            blade_length: self.motion.blade,
            max_curvature: Some(self.motion.max_curvature),
            approach: self.motion.approach,
            clearance: cell.clearance,
            travel_step: travel_step(),
            start: [start.map(f64::to_radians); 2],
        }
    }
}

fn travel_step() -> (f64, f64) {
    (
        defaults::TRAVEL_STEP_MM,
        defaults::TRAVEL_TURN_DEG.to_radians(),
    )
}

/// Plans the cell's program for the blade poses through `blocks` (mm, job coordinates):
/// at the fixture, or with the block carried when the settings give a carrier. Returns
/// the cell as laid out and its program.
///
/// At the fixture, what the settings leave to the default cell is laid out by trying the
/// default table heights, standoffs, holder styles and wrist sides in order, in chunks of
/// four, until a chunk holds a layout with every move reached, no flip and a joint margin
/// of [`defaults::GOOD_MARGIN_DEG`]; the first best is kept (fewest moves out of reach,
/// then fewest flips, then the largest joint margin). The result does not depend on the
/// thread count. With a carrier, the wrist sides of the blade robots and of the carrier
/// are tried (four plans).
///
/// # Errors
/// A move the planner cannot make ([`CellError`]), or no plan at all.
///
/// ```
/// use cell::layout::{CellSettings, PlacedBlock};
/// use cell::program::{plan, score, Motion};
/// use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
///
/// // a 600 × 600 × 400 mm block on the default fixture, a blade 820 mm long held with
/// // its ends 800 mm apart across it (y), 300 mm up, travelling along x; each tool frame
/// // has x along the blade (+y) and z along the cutting plane's normal (+x)
/// let turn = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let end = |x: f64, y: f64| Isometry3::from_parts(Translation3::new(x, y, 300.0), turn);
/// let block = PlacedBlock {
///     block: 0,
///     frame: Isometry3::identity(),
///     size: [600.0, 600.0, 400.0],
///     poses: (0..=4).map(|i| [end(150.0 * i as f64, -100.0), end(150.0 * i as f64, 700.0)]).collect(),
///     shapes: Vec::new(),
/// };
/// let motion = Motion { blade: 820.0, max_curvature: 1e-2, approach: 50.0 };
/// let (cell, program) = plan(&CellSettings::default(), &[block], &motion)?;
/// assert!(cell.assumed); // the default cell, laid out for these poses
/// let (out_of_reach, flips, _) = score(&program);
/// assert_eq!((out_of_reach, flips), (0, 0));
/// assert_eq!(program.solutions.len(), 2); // one joint track per blade robot
/// assert_eq!(program.solutions[0].len(), program.steps.len());
/// # Ok::<(), cell::CellError>(())
/// ```
pub fn plan(
    settings: &CellSettings,
    blocks: &[PlacedBlock],
    motion: &Motion,
) -> Result<(ResolvedCell, Program)> {
    let setup = Setup {
        settings,
        placed: blocks,
        cuts: block_cuts(blocks),
        largest: blocks.iter().fold([0.0f64; 3], |m, b| {
            [
                m[0].max(b.size[0]),
                m[1].max(b.size[1]),
                m[2].max(b.size[2]),
            ]
        }),
        motion: *motion,
    };
    if settings.carrier.is_some() {
        plan_carried(&setup)
    } else {
        plan_fixture(&setup)
    }
}

/// The program at the fixture (see [`plan`]).
fn plan_fixture(s: &Setup<'_>) -> Result<(ResolvedCell, Program)> {
    let layouts = layouts(s.settings);
    let first = s.resolve(layouts[0]);
    // the fixture only moves up between layouts: the moves stay
    let moves = crate::fixture::moves(&s.fixture_cell(&first, defaults::STARTS_DEG[0]), &s.cuts)?;
    let tries: Vec<(Layout, [f64; 6])> = layouts
        .iter()
        .flat_map(|l| defaults::STARTS_DEG.iter().map(move |s| (*l, *s)))
        .collect();
    // in chunks of a fixed size, in order, until one is good enough: the same result
    // whatever the thread count
    let mut best: Option<(ResolvedCell, Program)> = None;
    for chunk in tries.chunks(4) {
        let solved = crate::map_in_order(chunk, |(layout, start)| {
            let cell = s.resolve(*layout);
            let program = crate::fixture::solve(&s.fixture_cell(&cell, *start), &moves)?;
            Ok((cell, Program::from(program)))
        })
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
        keep_best(&mut best, solved);
        if good_enough(best.as_ref()) {
            break;
        }
    }
    best.ok_or_else(|| CellError::Blade("no layout".into()))
}

/// Keeps the best of `best` and `solved` (the first of equals).
fn keep_best(best: &mut Option<(ResolvedCell, Program)>, solved: Vec<(ResolvedCell, Program)>) {
    for (cell, program) in solved {
        if best
            .as_ref()
            .is_none_or(|(_, b)| score(&program) < score(b))
        {
            *best = Some((cell, program));
        }
    }
}

/// Every move reached with no flip and a good joint margin.
fn good_enough(best: Option<&(ResolvedCell, Program)>) -> bool {
    best.is_some_and(|(_, b)| {
        let (reach, flips, margin) = score(b);
        reach + flips == 0 && -margin >= defaults::GOOD_MARGIN_DEG
    })
}

/// The program with the block carried through the blade at the station (see [`plan`]).
fn plan_carried(s: &Setup<'_>) -> Result<(ResolvedCell, Program)> {
    let layout = layouts(s.settings)[0];
    let cell = s.resolve(layout);
    let Some(carry) = cell.carrier.clone() else {
        return Err(CellError::Blade("no block carrier".into()));
    };
    let carrier_cell = |blade: [f64; 6], carrier: [f64; 6]| CarrierCell {
        holders: [cell.holder(0), cell.holder(1)],
        carrier: cell.arm(carry.robot, carry.grip),
        station: carry.station,
        blade_length: s.motion.blade,
        max_curvature: Some(s.motion.max_curvature),
        approach: s.motion.approach,
        clearance: cell.clearance,
        travel_step: travel_step(),
        start: [
            blade.map(f64::to_radians),
            blade.map(f64::to_radians),
            carrier.map(f64::to_radians),
        ],
    };
    let starts = defaults::STARTS_DEG;
    let (moves, poses) = crate::carrier::moves(&carrier_cell(starts[0], starts[0]), &s.cuts)?;
    let tries: Vec<([f64; 6], [f64; 6])> = starts
        .iter()
        .flat_map(|a| starts.iter().map(move |b| (*a, *b)))
        .collect();
    let solved = crate::map_in_order(&tries, |(a, b)| {
        let program = crate::carrier::solve(&carrier_cell(*a, *b), &moves, &poses)?;
        Ok((cell.clone(), Program::from(program)))
    })
    .into_iter()
    .collect::<Result<Vec<_>>>()?;
    let mut best = None;
    keep_best(&mut best, solved);
    best.ok_or_else(|| CellError::Blade("no plan".into()))
}
