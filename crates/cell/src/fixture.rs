//! The whole program of a two-robot cell that cuts blocks one at a time at a fixture: every
//! synchronized move of the blade, with the heat and the operator's block changes, and
//! both robots' joint solutions along it.
//!
//! For each block, in order:
//! 1. *descend* in the first cutting plane, shifted back until it is the approach distance
//!    clear of the block, from the clearance height to the approach point (air, cold);
//! 2. heat on, then *cut*: into the block and through every pose, and *retreat* by the
//!    approach distance along the cutting plane's normal;
//! 3. heat off, *rise* in the cutting plane until the whole blade is `clearance` above the
//!    block;
//! 4. the operator removes the block and places the next one; the blade *travels* at the
//!    clearance height to above the next block's approach point.
//!
//! The blade keeps its shape while it descends, approaches, retreats and rises (both ends
//! move by the same vector). While it travels it changes from one block's last pose to
//! the next block's first through poses interpolated in the blade's plane
//! ([`crate::blade::interpolate`]); each one is checked to hold an elastica of the blade's
//! length within its curvature limit, and the height is raised until every one clears the
//! blocks. Every move is synchronized, so both ends move on straight lines in step and the
//! distance between them never exceeds the longer of the move's two poses.

use nalgebra::{Isometry3, Vector3};

use elastica::sweep::SHAPE_STATIONS;

use crate::blade::{self, BladePose};
use crate::equilibrium::{follow_steps, follow_steps_with, Follow, ProgramShapes};
use crate::error::{CellError, Result};
use crate::kinematics::Joints;
use crate::plan::{sweep, Holder, PoseSolution, SweepFlag};

/// The cell and how the blade moves in it.
#[derive(Debug, Clone, PartialEq)]
pub struct FixtureCell {
    /// The robots holding the blade's first and second end.
    pub holders: [Holder; 2],
    /// Where a block's frame (its min corner, its axes) is while it is cut, in the cell's
    /// frame (z up), mm.
    pub fixture: Isometry3<f64>,
    /// The blade's length, mm.
    pub blade_length: f64,
    /// The largest curvature the blade may take while it travels, 1/mm (`None`: any).
    pub max_curvature: Option<f64>,
    /// Approach and retreat distance along the cutting plane's normal, mm (> 0).
    pub approach: f64,
    /// Height of the whole blade above the blocks while it travels, mm (> 0).
    pub clearance: f64,
    /// Largest step of a traveling end, mm, and of a rotation or end angle, radians.
    pub travel_step: (f64, f64),
    /// The postures the robots start from (the first pose's solution is the one nearest).
    pub start: [Joints; 2],
}

/// One block to cut.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockCut {
    /// Its number.
    pub block: usize,
    /// Its size along its own axes, mm.
    pub size: [f64; 3],
    /// The blade poses through it in cutting order, in the block's frame, mm.
    pub poses: Vec<BladePose>,
    /// The shape the blade is planned to take at each pose
    /// ([`elastica::sweep::BladePose::shape`]): its tangent angle against the chord at
    /// [`SHAPE_STATIONS`] stations. Empty when unknown: the program's moves are then
    /// followed for folds only.
    pub shapes: Vec<[f64; SHAPE_STATIONS]>,
}

/// What a move of the program does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub enum Phase {
    /// The blade mounted straight, its ends one blade length apart: the program's first
    /// target, where the operator mounts it.
    Load,
    /// Bending the mounted blade into a gentle arch (circular arcs of growing turn), to
    /// the side the first cut bends it.
    Bend,
    /// To above the fixture, before anything else (no block stands there yet).
    Start,
    /// Down in the approach plane to the approach point.
    Descend,
    /// Through the block (heated): into it, then pose by pose.
    Cut,
    /// Out of the block along the cutting plane's normal (heated).
    Retreat,
    /// Up in the cutting plane to the clearance height.
    Rise,
    /// At the clearance height towards the next block.
    Travel,
}

/// One synchronized move of both ends.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// What it does.
    pub phase: Phase,
    /// The block it belongs to (the block it travels to).
    pub block: usize,
    /// Where it goes: both tool frames in the fixture's frame (a block's frame), mm.
    pub ends: BladePose,
    /// Whether the blade is heated during the move.
    pub heat: bool,
    /// Before the move, the operator changes blocks: (block to remove, block to place).
    pub change: Option<(Option<usize>, usize)>,
    /// The shape the blade is planned to take there (as [`BlockCut::shapes`]), where the
    /// program means one: at cuts, and wherever the blade keeps a cut's or an arc's shape.
    pub shape: Option<[f64; SHAPE_STATIONS]>,
}

/// A move of the program being built: its phase, both tool frames, and the planned shape.
type PlannedMove = (Phase, BladePose, Option<[f64; SHAPE_STATIONS]>);

/// One robot's summary for one block.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct RobotCheck {
    /// Moves of the block with no joint solution within the limits.
    pub out_of_reach: usize,
    /// Moves that change the arm configuration (`cfx`).
    pub configuration_changes: usize,
    /// Moves in which a joint turns by more than 30°.
    pub joint_jumps: usize,
    /// Fewest arm configurations that reach a reached pose within the limits (whole turns
    /// of a joint not counted apart: [`crate::kinematics::configurations`]; at most 8).
    pub fewest_solutions: usize,
    /// Least margin of a joint to its limit, degrees.
    pub margin_deg: Option<f64>,
}

/// One block's summary.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct BlockCheck {
    /// The block.
    pub block: usize,
    /// Moves from the travel to it through its rise.
    pub moves: usize,
    /// Its robots in task order: the first end's, the second end's (and the carrier's).
    pub robots: Vec<RobotCheck>,
    /// Least height of the blade above the block while it travels to or from it, mm.
    pub air_clearance: f64,
}

impl BlockCheck {
    /// Every move reached, with no configuration change and no joint jump.
    pub fn is_clean(&self) -> bool {
        self.robots
            .iter()
            .all(|r| r.out_of_reach + r.configuration_changes + r.joint_jumps == 0)
    }
}

/// The planned program.
#[derive(Debug, Clone, PartialEq)]
pub struct CellProgram {
    /// Every move, in order.
    pub steps: Vec<Step>,
    /// Each robot's solution at every step.
    pub solutions: [Vec<PoseSolution>; 2],
    /// Each robot's flags, by step.
    pub flags: [Vec<SweepFlag>; 2],
    /// Per block.
    pub blocks: Vec<BlockCheck>,
    /// The blade's equilibrium through every move.
    pub shapes: ProgramShapes,
}

fn check(cell: &FixtureCell, blocks: &[BlockCut]) -> Result<()> {
    let positive = |v: f64| v > 0.0 && v.is_finite();
    let bad = |what: &str| Err(CellError::Blade(what.to_string()));
    if !positive(cell.blade_length) {
        return bad("the blade's length must be positive");
    }
    if !positive(cell.approach) || !positive(cell.clearance) {
        return bad("the approach distance and the clearance must be positive");
    }
    if !positive(cell.travel_step.0) || !positive(cell.travel_step.1) {
        return bad("the travel steps must be positive");
    }
    if blocks.iter().all(|b| b.poses.is_empty()) {
        return bad("no block has a blade pose");
    }
    Ok(())
}

/// Top of block `b` at the fixture (highest corner), mm.
fn top(cell: &FixtureCell, b: &BlockCut) -> f64 {
    corners(cell, b)
        .iter()
        .map(|c| c.z)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// A pose in the cell's frame.
fn world(cell: &FixtureCell, p: &BladePose) -> BladePose {
    [cell.fixture * p[0], cell.fixture * p[1]]
}

/// A pose in the fixture's frame.
fn local(cell: &FixtureCell, p: &BladePose) -> BladePose {
    let inv = cell.fixture.inverse();
    [inv * p[0], inv * p[1]]
}

/// The lowest point of the blade at world pose `p`.
fn lowest(cell: &FixtureCell, p: &BladePose) -> Result<f64> {
    Ok(blade::shape(p, cell.blade_length)?.lowest())
}

/// The unit direction that rises in the cutting plane of world pose `p`.
fn rise_direction(p: &BladePose, block: usize) -> Result<Vector3<f64>> {
    let n = blade::normal(p);
    let up = Vector3::z() - n * n.z;
    if up.norm() < 0.2 {
        return Err(CellError::Blade(format!(
            "block {block}: the cutting plane is within 12° of horizontal, so the blade cannot rise in it to leave the block"
        )));
    }
    Ok(up.normalize())
}

/// World pose `p` moved up in its plane (along `u`) until its lowest point is at `z`
/// (not moved when it already is above).
fn lifted(cell: &FixtureCell, p: &BladePose, u: &Vector3<f64>, z: f64) -> Result<BladePose> {
    let low = lowest(cell, p)?;
    let h = ((z - low) / u.z).max(0.0);
    Ok(blade::translated(p, &(u * h)))
}

/// The travel from world pose `a` to world pose `b`: the interpolated poses after `a`,
/// `b` last.
fn travel(cell: &FixtureCell, a: &BladePose, b: &BladePose) -> Result<Vec<BladePose>> {
    let (pa, pb) = (blade::planar(a)?, blade::planar(b)?);
    let far = (pa.mid - pb.mid).norm() + 0.5 * (pa.chord - pb.chord).abs();
    let turn = pa
        .frame
        .angle_to(&pb.frame)
        .max(blade::angle_between(pa.angles[0], pb.angles[0]).abs())
        .max(blade::angle_between(pa.angles[1], pb.angles[1]).abs());
    let n = (far / cell.travel_step.0)
        .max(turn / cell.travel_step.1)
        .ceil()
        .clamp(1.0, 1000.0) as usize;
    Ok((1..=n)
        .map(|k| blade::from_planar(&blade::interpolate(&pa, &pb, k as f64 / n as f64)))
        .collect())
}

/// A block's moves in and out, in the cell's frame.
struct Ends {
    /// The first pose moved back by the approach distance.
    approach: BladePose,
    /// The last pose moved on by the approach distance.
    retreat: BladePose,
    /// Rise directions in the first and the last cutting plane.
    rise: [Vector3<f64>; 2],
    /// Top of the block at the fixture.
    top: f64,
    /// The planned shapes of the first and the last pose.
    shapes: [Option<[f64; SHAPE_STATIONS]>; 2],
}

/// How far the block reaches beyond the plane of world pose `p` along `dir` (the largest
/// signed distance of a corner, 0 when none is beyond).
fn overhang(cell: &FixtureCell, b: &BlockCut, p: &BladePose, dir: &Vector3<f64>) -> f64 {
    let at = p[0].translation.vector;
    corners(cell, b)
        .iter()
        .map(|c| (c - at).dot(dir))
        .fold(0.0, f64::max)
}

/// The block's corners at the fixture.
fn corners(cell: &FixtureCell, b: &BlockCut) -> Vec<Vector3<f64>> {
    (0..8)
        .map(|corner| {
            let c = Vector3::from_fn(|i, _| {
                if corner & (1 << i) != 0 {
                    b.size[i]
                } else {
                    0.0
                }
            });
            (cell.fixture * nalgebra::Point3::from(c)).coords
        })
        .collect()
}

/// The approach and retreat lie `approach` beyond the block: outside the first and last
/// cutting plane by that much, more where the block reaches past them (a plane turned
/// against the block, a curved cut), so the blade never enters the block cold.
fn ends_of(cell: &FixtureCell, b: &BlockCut) -> Result<Ends> {
    let first = world(cell, &b.poses[0]);
    let last = world(cell, &b.poses[b.poses.len() - 1]);
    let (n0, n1) = (blade::normal(&first), blade::normal(&last));
    let back = cell.approach + overhang(cell, b, &first, &-n0);
    let on = cell.approach + overhang(cell, b, &last, &n1);
    Ok(Ends {
        approach: blade::translated(&first, &(n0 * -back)),
        retreat: blade::translated(&last, &(n1 * on)),
        rise: [
            rise_direction(&first, b.block)?,
            rise_direction(&last, b.block)?,
        ],
        top: top(cell, b),
        shapes: [b.shapes.first().copied(), b.shapes.last().copied()],
    })
}

/// The lowest point of the blade on a travel (the risen pose, then `path`), and whether
/// every pose on the path holds a blade bent no more than its limit, or than the travel's
/// two end poses (cutting shapes, checked by the fit; the discrete blade measures them a
/// little above their closed form). `Err(curvature)` names the worst bend over the limit.
fn travel_low(
    cell: &FixtureCell,
    first: &blade::BladeShape,
    path: &[BladePose],
) -> Result<std::result::Result<f64, f64>> {
    let shapes = path
        .iter()
        .map(|p| blade::shape(p, cell.blade_length))
        .collect::<Result<Vec<_>>>()?;
    let last = shapes.last().unwrap_or(first);
    let limit = cell.max_curvature.map_or(f64::INFINITY, |k| {
        k.max(first.max_curvature).max(last.max_curvature) * (1.0 + 1e-6)
    });
    let (mut low, mut worst) = (first.lowest(), 0.0f64);
    for s in &shapes {
        worst = worst.max(s.max_curvature);
        low = low.min(s.lowest());
    }
    Ok(if worst > limit { Err(worst) } else { Ok(low) })
}

/// Turn of each end of a relaxed blade against its chord, radians: a gentle arch.
const RELAXED_RAD: f64 = 0.2;

/// Pose `p` relaxed to a gentle circular arch of the blade's length in the same plane,
/// about the same midpoint, bulging to `side` (±1).
fn relaxed(cell: &FixtureCell, p: &BladePose, side: f64) -> Result<BladePose> {
    let mut q = blade::planar(p)?;
    q.chord = cell.blade_length * RELAXED_RAD.sin() / RELAXED_RAD;
    q.angles = [side * RELAXED_RAD, -side * RELAXED_RAD];
    Ok(blade::from_planar(&q))
}

/// Whether the blade followed from `a` (planned shape `shapes[0]`) through `path` to its
/// last pose (planned shape `shapes[1]`) snaps: 1 if it does ([`Follow::Check`]: it
/// stops at the first snap), else 0.
fn snaps(
    cell: &FixtureCell,
    a: &BladePose,
    path: &[BladePose],
    shapes: [Option<[f64; SHAPE_STATIONS]>; 2],
) -> usize {
    let poses: Vec<BladePose> = std::iter::once(*a).chain(path.iter().copied()).collect();
    let mut planned = vec![None; poses.len()];
    planned[0] = shapes[0];
    if let Some(last) = planned.last_mut() {
        *last = shapes[1];
    }
    follow_steps_with(cell.blade_length, &poses, &planned, Follow::Check).snaps
}

/// A waypoint from `a` to `b` that turns one end at a time: the chord, midpoint and plane
/// halfway, end `end` already at `b`'s angle, the other still at `a`'s. Moving a nearly
/// taut blade's bulge from one side to the other this way rolls it through an S, where
/// turning both ends at once would pass its buckling point and snap.
fn one_end(a: &BladePose, b: &BladePose, end: usize) -> Result<BladePose> {
    let (pa, pb) = (blade::planar(a)?, blade::planar(b)?);
    let mut q = blade::interpolate(&pa, &pb, 0.5);
    let turned = |e: usize| pa.angles[e] + blade::angle_between(pa.angles[e], pb.angles[e]);
    q.angles = if end == 0 {
        [turned(0), pa.angles[1]]
    } else {
        [pa.angles[0], turned(1)]
    };
    Ok(blade::from_planar(&q))
}

/// The routes the blade may take from `a` to `b` (bulging to `sides`), in order of
/// preference: straight (interpolated in the blade's plane), through both poses relaxed,
/// turning one end at a time (either first), and through both relaxed turning one end at
/// a time between them. Each is the poses after `a`, `b` last.
fn routes(
    cell: &FixtureCell,
    a: &BladePose,
    b: &BladePose,
    sides: [f64; 2],
) -> Result<Vec<Vec<BladePose>>> {
    let mut out = vec![travel(cell, a, b)?];
    let (ra, rb) = (relaxed(cell, a, sides[0])?, relaxed(cell, b, sides[1])?);
    let mut path = travel(cell, a, &ra)?;
    path.extend(travel(cell, &ra, &rb)?);
    path.extend(travel(cell, &rb, b)?);
    out.push(path);
    for end in [0, 1] {
        let w = one_end(a, b, end)?;
        let mut path = travel(cell, a, &w)?;
        path.extend(travel(cell, &w, b)?);
        out.push(path);
    }
    // relaxed, with room to roll the bulge over one end at a time
    for end in [0, 1] {
        let w = one_end(&ra, &rb, end)?;
        let mut path = travel(cell, a, &ra)?;
        path.extend(travel(cell, &ra, &w)?);
        path.extend(travel(cell, &w, &rb)?);
        path.extend(travel(cell, &rb, b)?);
        out.push(path);
    }
    Ok(out)
}

/// The travel from `a` to `b`: the first of [`routes`] on which no pose bends the blade
/// too much and the blade follows without snapping, else the one within the curvature
/// limit that snaps least (its snaps are the program's report): the poses after `a`, the
/// lowest blade point, and which route it is. With `route`, that route is taken unchecked
/// for snaps (a route chosen before, the poses since moved).
fn travel_path(
    cell: &FixtureCell,
    a: &BladePose,
    b: &BladePose,
    shapes: [Option<[f64; SHAPE_STATIONS]>; 2],
    route: Option<usize>,
) -> Result<(Vec<BladePose>, f64, usize)> {
    let mut best: Option<(usize, Vec<BladePose>, f64, usize)> = None;
    let mut worst = 0.0f64;
    let sides = [bulge(a, shapes[0])?, bulge(b, shapes[1])?];
    let first = blade::shape(a, cell.blade_length)?;
    for (i, path) in routes(cell, a, b, sides)?.into_iter().enumerate() {
        if route.is_some_and(|r| r != i) {
            continue;
        }
        let low = match travel_low(cell, &first, &path)? {
            Ok(low) => low,
            Err(k) => {
                worst = worst.max(k);
                continue;
            }
        };
        let n = if route.is_some() {
            0
        } else {
            snaps(cell, a, &path, shapes)
        };
        if n == 0 {
            return Ok((path, low, i));
        }
        if best.as_ref().is_none_or(|(m, _, _, _)| n < *m) {
            best = Some((n, path, low, i));
        }
    }
    best.map(|(_, path, low, i)| (path, low, i)).ok_or_else(|| {
        CellError::Blade(format!(
            "every travel between two blocks bends the blade too much: to curvature {worst:.6}/mm at least"
        ))
    })
}

/// Arcs the mounted blade is bent through before it goes to its first pose.
pub const BENDS: usize = 4;

/// The planned shape of a circular arc turning `a` at its first end and `−a` at its
/// second against the chord.
fn arc_shape(a: f64) -> [f64; SHAPE_STATIONS] {
    std::array::from_fn(|k| a - 2.0 * a * k as f64 / (SHAPE_STATIONS - 1) as f64)
}

/// From the blade mounted straight to the pose `above` (planned shape `shape`): the Load
/// pose (straight, chord = the blade's length, in the plane of `above`, about its
/// midpoint), [`BENDS`] circular arcs of growing turn up to [`RELAXED_RAD`] bulging to
/// `side` (±1), then `above` — raised along `up` where an arc would dip below `above`'s
/// lowest point.
fn loading(
    cell: &FixtureCell,
    above: &BladePose,
    up: &Vector3<f64>,
    side: f64,
) -> Result<Vec<PlannedMove>> {
    let q = blade::planar(above)?;
    let length = cell.blade_length;
    let mut poses = vec![(
        Phase::Load,
        blade::from_planar(&blade::PlanarPose {
            chord: length,
            angles: [0.0, 0.0],
            ..q
        }),
        None,
    )];
    for k in 1..=BENDS {
        let a = RELAXED_RAD * k as f64 / BENDS as f64;
        let pose = blade::from_planar(&blade::PlanarPose {
            chord: length * a.sin() / a,
            angles: [side * a, -side * a],
            ..q
        });
        poses.push((Phase::Bend, pose, Some(arc_shape(side * a))));
    }
    let low = lowest(cell, above)?;
    let mut deficit = 0.0f64;
    for (_, p, _) in &poses {
        deficit = deficit.max(low - lowest(cell, p)?);
    }
    if deficit > 0.0 {
        let lift = up * (deficit / up.z.max(1e-9));
        for (_, p, _) in poses.iter_mut() {
            *p = blade::translated(p, &lift);
        }
    }
    Ok(poses)
}

/// The side (±1) a planned shape bulges to: the side of its middle point against the
/// chord (without a shape, the side of an arch with the pose's end angles).
fn bulge(p: &BladePose, shape: Option<[f64; SHAPE_STATIONS]>) -> Result<f64> {
    let d = match shape {
        // the middle's offset from the chord: ∫ sin θ over the first half (trapezoid)
        Some(s) => (0..(SHAPE_STATIONS - 1) / 2)
            .map(|k| s[k].sin() + s[k + 1].sin())
            .sum::<f64>(),
        None => {
            let q = blade::planar(p)?;
            q.angles[0] - q.angles[1]
        }
    };
    Ok(if d < 0.0 { -1.0 } else { 1.0 })
}

/// The program's first moves: the blade loaded and bent to the side its first pose bulges
/// to, then to `above` (planned shape `shape`); through poses interpolated in the blade's
/// plane from the relaxed arc where the direct move snaps, or bent to the other side
/// where that holds better.
fn start(
    cell: &FixtureCell,
    above: &BladePose,
    up: &Vector3<f64>,
    shape: Option<[f64; SHAPE_STATIONS]>,
) -> Result<Vec<PlannedMove>> {
    let side = bulge(above, shape)?;
    type Moves = Vec<PlannedMove>;
    let mut best: Option<(usize, Moves)> = None;
    for s in [side, -side] {
        let load = loading(cell, above, up, s)?;
        let Some(&(_, bent, bent_shape)) = load.last() else {
            continue;
        };
        for path in routes(cell, &bent, above, [s, side])? {
            let n = snaps(cell, &bent, &path, [bent_shape, shape]);
            if best.as_ref().is_none_or(|(b, _)| n < *b) {
                let mut moves = load.clone();
                let last = path.len() - 1;
                moves.extend(
                    path.iter()
                        .enumerate()
                        .map(|(k, p)| (Phase::Start, *p, if k == last { shape } else { None })),
                );
                best = Some((n, moves));
            }
            if best.as_ref().is_some_and(|(b, _)| *b == 0) {
                return Ok(best.map(|b| b.1).unwrap_or_default());
            }
        }
    }
    Ok(best.map(|b| b.1).unwrap_or_default())
}

/// From block `a`'s retreat up to the height where the whole blade is at `z` or above,
/// across to above block `b`'s approach: the risen pose, the travel after it (ending
/// above `b`'s approach), and the lowest blade point on the way.
fn transition(
    cell: &FixtureCell,
    a: &Ends,
    b: &Ends,
    z: f64,
) -> Result<(BladePose, Vec<BladePose>, f64)> {
    let mut target = z;
    // the route is chosen once: lifting changes where the blade travels, not its shapes
    let mut route = None;
    // lifting both ends by dz lifts every pose between by dz: one correction is enough
    // unless a pose was already above the height; a few more settle that case
    for _ in 0..8 {
        let risen = lifted(cell, &a.retreat, &a.rise[1], target)?;
        let above = lifted(cell, &b.approach, &b.rise[0], target)?;
        let (path, low, chosen) =
            travel_path(cell, &risen, &above, [a.shapes[1], b.shapes[0]], route)?;
        route = Some(chosen);
        if low >= z - 1e-6 {
            return Ok((risen, path, low));
        }
        target += z - low;
    }
    Err(CellError::Blade(format!(
        "no travel keeps the blade {:.3} mm above the blocks",
        cell.clearance
    )))
}

/// The moves of a program before any robot is solved: they depend on the fixture only
/// through which way is up (a fixture moved without turning keeps them).
#[derive(Debug, Clone, PartialEq)]
pub struct Moves {
    /// Every move, in order.
    pub steps: Vec<Step>,
    /// Per block (in cutting order): its number and the least height of the blade above
    /// it while it travels to or from it, mm.
    pub clearances: Vec<(usize, f64)>,
    /// The blade's equilibrium followed through every move ([`crate::equilibrium`]).
    pub shapes: ProgramShapes,
}

/// Plans the program of `blocks` (in cutting order; blocks without poses are skipped):
/// [`moves`], then [`solve`].
///
/// ```
/// # use cell::blade::{from_planar, PlanarPose};
/// # use cell::fixture::{BlockCut, FixtureCell, Phase};
/// # use cell::plan::Holder;
/// # use cell::RobotModel;
/// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
/// #
/// # // the rotation whose x- and z-axes are `x` and `z`
/// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
/// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
/// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// # };
/// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// # // its end of the blade 150 mm in front of its flange
/// # let holder = |y: f64, yaw: f64| Holder {
/// #     model: RobotModel::irb2600_12_165(),
/// #     base: Isometry3::from_parts(
/// #         Translation3::new(0.0, y, 0.0),
/// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
/// #     ),
/// #     tool: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 150.0),
/// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// # };
/// # let quarter = std::f64::consts::FRAC_PI_2;
/// # let cell = FixtureCell {
/// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
/// #     fixture: Isometry3::translation(-300.0, -300.0, 200.0),
/// #     blade_length: 800.0,
/// #     max_curvature: None,
/// #     approach: 50.0,
/// #     clearance: 100.0,
/// #     travel_step: (100.0, 5f64.to_radians()),
/// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 2],
/// # };
/// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// # let turn: f64 = 0.35;
/// # let arch = |along: f64| from_planar(&PlanarPose {
/// #     mid: Vector3::new(along, 300.0, 350.0),
/// #     frame: rotation(Vector3::y(), Vector3::x()),
/// #     chord: 800.0 * turn.sin() / turn * 0.98,
/// #     angles: [turn, -turn],
/// # });
/// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let program = cell::fixture::plan(&cell, &blocks)?;
/// let by_hand = cell::fixture::solve(&cell, &cell::fixture::moves(&cell, &blocks)?)?;
/// assert_eq!(program, by_hand);
/// assert_eq!(program.blocks.len(), 1);
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// As [`moves`] and [`solve`].
pub fn plan(cell: &FixtureCell, blocks: &[BlockCut]) -> Result<CellProgram> {
    solve(cell, &moves(cell, blocks)?)
}

/// The moves through `blocks` (in cutting order; blocks without poses are skipped).
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use cell::fixture::{BlockCut, FixtureCell, Phase};
/// use cell::plan::Holder;
/// use cell::RobotModel;
/// use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
///
/// // the rotation whose x- and z-axes are `x` and `z`
/// let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
///     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
///     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// };
/// // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// // its end of the blade 150 mm in front of its flange
/// let holder = |y: f64, yaw: f64| Holder {
///     model: RobotModel::irb2600_12_165(),
///     base: Isometry3::from_parts(
///         Translation3::new(0.0, y, 0.0),
///         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
///     ),
///     tool: Isometry3::from_parts(
///         Translation3::new(0.0, 0.0, 150.0),
///         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
///     ),
/// };
/// let quarter = std::f64::consts::FRAC_PI_2;
/// let cell = FixtureCell {
///     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
///     fixture: Isometry3::translation(-300.0, -300.0, 200.0),
///     blade_length: 800.0,
///     max_curvature: None,
///     approach: 50.0,
///     clearance: 100.0,
///     travel_step: (100.0, 5f64.to_radians()),
///     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 2],
/// };
/// // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// let turn: f64 = 0.35;
/// let arch = |along: f64| from_planar(&PlanarPose {
///     mid: Vector3::new(along, 300.0, 350.0),
///     frame: rotation(Vector3::y(), Vector3::x()),
///     chord: 800.0 * turn.sin() / turn * 0.98,
///     angles: [turn, -turn],
/// });
/// let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let m = cell::fixture::moves(&cell, &blocks)?;
/// let phases: Vec<Phase> = m.steps.iter().map(|s| s.phase).collect();
/// use Phase::*;
/// // the blade is mounted straight and bent into a gentle arch first, then turned in its
/// // plane to the first pose above the block (in steps of at most 5°)
/// assert_eq!(phases, [Load, Bend, Bend, Bend, Bend, Start, Start, Descend, Cut, Cut, Cut, Retreat, Rise]);
/// assert_eq!(m.steps[7].change, Some((None, 1))); // the block is placed before the descent
/// // followed through every move after the mount, the blade never snaps
/// assert_eq!((m.shapes.transitions, m.shapes.snaps), (11, 0));
/// assert!(m.steps.iter().all(|s| s.heat == matches!(s.phase, Cut | Retreat)));
/// // the blade waits above the block by at least the clearance
/// assert_eq!(m.clearances[0].0, 1);
/// assert!(m.clearances[0].1 >= cell.clearance - 1e-6);
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// [`CellError::Blade`] for bad settings, a cutting plane too flat to rise in, or a
/// travel pose that holds no admissible blade.
pub fn moves(cell: &FixtureCell, blocks: &[BlockCut]) -> Result<Moves> {
    check(cell, blocks)?;
    let blocks: Vec<&BlockCut> = blocks.iter().filter(|b| !b.poses.is_empty()).collect();
    let ends = blocks
        .iter()
        .map(|b| ends_of(cell, b))
        .collect::<Result<Vec<_>>>()?;
    let mut steps: Vec<Step> = Vec::new();
    let mut clearances = vec![f64::INFINITY; blocks.len()];
    let step = |phase, block: usize, ends: &BladePose, heat, shape| Step {
        phase,
        block,
        ends: local(cell, ends),
        heat,
        change: None,
        shape,
    };
    for (i, (b, e)) in blocks.iter().zip(&ends).enumerate() {
        if i == 0 {
            let above = lifted(cell, &e.approach, &e.rise[0], e.top + cell.clearance)?;
            let first = start(cell, &above, &e.rise[0], e.shapes[0])?;
            let low = first
                .iter()
                .map(|(_, p, _)| lowest(cell, p))
                .collect::<Result<Vec<f64>>>()?
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            clearances[0] = low - e.top;
            for (phase, p, shape) in first {
                steps.push(step(phase, b.block, &p, false, shape));
            }
        } else {
            let (a, before) = (blocks[i - 1], &ends[i - 1]);
            let tops = before.top.max(e.top);
            let (risen, path, low) = transition(cell, before, e, tops + cell.clearance)?;
            for k in [i - 1, i] {
                clearances[k] = clearances[k].min(low - tops);
            }
            steps.push(step(Phase::Rise, a.block, &risen, false, before.shapes[1]));
            let last = path.len().saturating_sub(1);
            for (k, p) in path.iter().enumerate() {
                let shape = if k == last { e.shapes[0] } else { None };
                steps.push(Step {
                    change: (k == 0).then_some((Some(a.block), b.block)),
                    ..step(Phase::Travel, b.block, p, false, shape)
                });
            }
        }
        // the first block is placed once the blade waits above the fixture
        steps.push(Step {
            change: (i == 0).then_some((None, b.block)),
            ..step(Phase::Descend, b.block, &e.approach, false, e.shapes[0])
        });
        for (k, p) in b.poses.iter().enumerate() {
            steps.push(Step {
                phase: Phase::Cut,
                block: b.block,
                ends: *p,
                heat: true,
                change: None,
                shape: b.shapes.get(k).copied(),
            });
        }
        steps.push(step(Phase::Retreat, b.block, &e.retreat, true, e.shapes[1]));
    }
    let (b, e) = (blocks[blocks.len() - 1], &ends[ends.len() - 1]);
    let risen = lifted(cell, &e.retreat, &e.rise[1], e.top + cell.clearance)?;
    let k = blocks.len() - 1;
    clearances[k] = clearances[k].min(lowest(cell, &risen)? - e.top);
    steps.push(step(Phase::Rise, b.block, &risen, false, e.shapes[1]));
    let poses: Vec<BladePose> = steps.iter().map(|s| s.ends).collect();
    let planned: Vec<Option<[f64; SHAPE_STATIONS]>> = steps.iter().map(|s| s.shape).collect();
    let shapes = follow_steps(cell.blade_length, &poses, &planned);
    Ok(Moves {
        steps,
        clearances: blocks.iter().map(|b| b.block).zip(clearances).collect(),
        shapes,
    })
}

/// Both robots' joints along the moves, and the per-block summary.
///
/// ```
/// # use cell::blade::{from_planar, PlanarPose};
/// # use cell::fixture::{BlockCut, FixtureCell, Phase};
/// # use cell::plan::Holder;
/// # use cell::RobotModel;
/// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
/// #
/// # // the rotation whose x- and z-axes are `x` and `z`
/// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
/// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
/// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// # };
/// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// # // its end of the blade 150 mm in front of its flange
/// # let holder = |y: f64, yaw: f64| Holder {
/// #     model: RobotModel::irb2600_12_165(),
/// #     base: Isometry3::from_parts(
/// #         Translation3::new(0.0, y, 0.0),
/// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
/// #     ),
/// #     tool: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 150.0),
/// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// # };
/// # let quarter = std::f64::consts::FRAC_PI_2;
/// # let cell = FixtureCell {
/// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
/// #     fixture: Isometry3::translation(-300.0, -300.0, 200.0),
/// #     blade_length: 800.0,
/// #     max_curvature: None,
/// #     approach: 50.0,
/// #     clearance: 100.0,
/// #     travel_step: (100.0, 5f64.to_radians()),
/// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 2],
/// # };
/// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// # let turn: f64 = 0.35;
/// # let arch = |along: f64| from_planar(&PlanarPose {
/// #     mid: Vector3::new(along, 300.0, 350.0),
/// #     frame: rotation(Vector3::y(), Vector3::x()),
/// #     chord: 800.0 * turn.sin() / turn * 0.98,
/// #     angles: [turn, -turn],
/// # });
/// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let m = cell::fixture::moves(&cell, &blocks)?;
/// let program = cell::fixture::solve(&cell, &m)?;
/// // one solution per move and robot; both robots reach every cutting move
/// assert!(program.solutions.iter().all(|s| s.len() == m.steps.len()));
/// for (k, step) in m.steps.iter().enumerate() {
///     if step.phase == Phase::Cut {
///         assert!(program.solutions.iter().all(|s| s[k].joints.is_some()), "move {k}");
///     }
/// }
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// The errors of [`sweep`].
pub fn solve(cell: &FixtureCell, moves: &Moves) -> Result<CellProgram> {
    let steps = &moves.steps;
    let mut solutions: [Vec<PoseSolution>; 2] = [Vec::new(), Vec::new()];
    let mut flags: [Vec<SweepFlag>; 2] = [Vec::new(), Vec::new()];
    for r in 0..2 {
        let tcp: Vec<Isometry3<f64>> = steps.iter().map(|s| cell.fixture * s.ends[r]).collect();
        let sw = sweep(&cell.holders[r], &tcp, &cell.start[r])?;
        solutions[r] = sw.poses;
        flags[r] = sw.flags;
    }
    let blocks = summarize(moves, &solutions, &flags);
    Ok(CellProgram {
        steps: steps.clone(),
        solutions,
        flags,
        blocks,
        shapes: moves.shapes.clone(),
    })
}

/// The per-block summary of robots' `solutions` and `flags` (one list per robot, by step)
/// along `moves`.
///
/// ```
/// # use cell::blade::{from_planar, PlanarPose};
/// # use cell::fixture::{BlockCut, FixtureCell, Phase};
/// # use cell::plan::Holder;
/// # use cell::RobotModel;
/// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
/// #
/// # // the rotation whose x- and z-axes are `x` and `z`
/// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
/// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
/// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// # };
/// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// # // its end of the blade 150 mm in front of its flange
/// # let holder = |y: f64, yaw: f64| Holder {
/// #     model: RobotModel::irb2600_12_165(),
/// #     base: Isometry3::from_parts(
/// #         Translation3::new(0.0, y, 0.0),
/// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
/// #     ),
/// #     tool: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 150.0),
/// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// # };
/// # let quarter = std::f64::consts::FRAC_PI_2;
/// # let cell = FixtureCell {
/// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
/// #     fixture: Isometry3::translation(-300.0, -300.0, 200.0),
/// #     blade_length: 800.0,
/// #     max_curvature: None,
/// #     approach: 50.0,
/// #     clearance: 100.0,
/// #     travel_step: (100.0, 5f64.to_radians()),
/// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 2],
/// # };
/// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// # let turn: f64 = 0.35;
/// # let arch = |along: f64| from_planar(&PlanarPose {
/// #     mid: Vector3::new(along, 300.0, 350.0),
/// #     frame: rotation(Vector3::y(), Vector3::x()),
/// #     chord: 800.0 * turn.sin() / turn * 0.98,
/// #     angles: [turn, -turn],
/// # });
/// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let program = cell::fixture::plan(&cell, &blocks)?;
/// let m = cell::fixture::moves(&cell, &blocks)?;
/// // the summary of the robots' solutions along the moves is the program's
/// assert_eq!(cell::fixture::summarize(&m, &program.solutions, &program.flags), program.blocks);
/// assert_eq!(program.blocks[0].moves, m.steps.len());
/// # Ok::<(), cell::CellError>(())
/// ```
pub fn summarize(
    moves: &Moves,
    solutions: &[Vec<PoseSolution>],
    flags: &[Vec<SweepFlag>],
) -> Vec<BlockCheck> {
    let steps = &moves.steps;
    moves
        .clearances
        .iter()
        .map(|&(block, air)| {
            let idx: Vec<usize> = (0..steps.len())
                .filter(|&i| steps[i].block == block)
                .collect();
            let robot = |r: usize| {
                let mine = |i: usize| steps.get(i).is_some_and(|s| s.block == block);
                let count = |f: &dyn Fn(&SweepFlag) -> Option<usize>| {
                    flags[r].iter().filter_map(f).filter(|i| mine(*i)).count()
                };
                let reached = idx.iter().filter_map(|&i| {
                    solutions[r][i]
                        .margin
                        .map(|m| (solutions[r][i].solutions, m))
                });
                let (fewest, margin) = reached.fold((usize::MAX, None::<f64>), |(n, m), (s, g)| {
                    (n.min(s), Some(m.map_or(g, |m| m.min(g))))
                });
                RobotCheck {
                    out_of_reach: count(&|f| match f {
                        SweepFlag::OutOfReach(i) => Some(*i),
                        _ => None,
                    }),
                    configuration_changes: count(&|f| match f {
                        SweepFlag::ConfigurationChange(i) => Some(*i),
                        _ => None,
                    }),
                    joint_jumps: count(&|f| match f {
                        SweepFlag::JointJump { pose, .. } => Some(*pose),
                        _ => None,
                    }),
                    fewest_solutions: if fewest == usize::MAX { 0 } else { fewest },
                    margin_deg: margin,
                }
            };
            BlockCheck {
                block,
                moves: idx.len(),
                robots: (0..solutions.len()).map(robot).collect(),
                air_clearance: air,
            }
        })
        .collect()
}
