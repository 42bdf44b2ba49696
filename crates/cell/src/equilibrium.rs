//! The blade's shape along a program: its equilibrium followed by continuation through
//! every synchronized move ([`elastica::stability::follow`]), as the robots move its
//! ends — both tool frames interpolated as the controller does (positions linearly,
//! orientations by spherical interpolation), the blade rebuilt in the plane of the first
//! end's tool. A move snaps when the equilibrium the blade is in loses its stability on
//! the way (a fold: the margin reaches 0), when no equilibrium can be followed, or when
//! it arrives on another equilibrium than the step's planned shape
//! ([`crate::fixture::Step::shape`]). The first move starts from the blade mounted
//! straight ([`crate::fixture::Phase::Load`]): from a straight, taut blade the shape is
//! not followed but taken as planned, since its tension is undetermined; the program
//! bends it first along circular arcs, each of which holds ([`crate::fixture`]).
//!
//! Entry point: [`follow_steps`].

use elastica::stability::follow::{follow, DiscreteBlade, FollowParams, HeldEnds, Snap, SEGMENTS};
use elastica::sweep::SHAPE_STATIONS;
use nalgebra::Isometry3;

use crate::blade::{angle_between, planar, BladePose};

pub use elastica::stability::follow::SnapKind;

/// The blade through one move of the program (into step `k` from step `k − 1`).
#[derive(Debug, Clone, PartialEq)]
pub struct MoveShape {
    /// The least margin along the move (its end included).
    pub min_margin: f64,
    /// The margin at the move's end.
    pub margin: f64,
    /// How it snapped, if it did.
    pub snap: Option<SnapKind>,
    /// Where along the move it snapped (fraction).
    pub snap_at: Option<f64>,
    /// The margins along the move: `(fraction, margin)`.
    pub profile: Vec<(f64, f64)>,
}

/// The blade through a whole program.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramShapes {
    /// Per step, the move into it (`None` for the first step and for moves from a taut,
    /// straight blade, which are not followed).
    pub moves: Vec<Option<MoveShape>>,
    /// Moves followed.
    pub transitions: usize,
    /// Moves that snapped.
    pub snaps: usize,
    /// The least margin over the whole program.
    pub min_margin: f64,
}

impl ProgramShapes {
    /// The least margin over steps `range` (the moves into them).
    pub fn min_over(&self, range: std::ops::Range<usize>) -> f64 {
        self.moves[range]
            .iter()
            .flatten()
            .map(|m| m.min_margin)
            .fold(f64::INFINITY, f64::min)
    }
}

/// A pose whose chord is within this share of the blade's length is taut: straight.
const TAUT: f64 = 1e-9;

/// Two discrete equilibria this close (share of the blade's length) are the same.
const SAME: f64 = 1e-6;

/// The held ends of `p` for a blade of `length`, the angles unwrapped to lie within half a
/// turn of `near`.
fn held(p: &BladePose, near: Option<[f64; 2]>) -> Option<HeldEnds> {
    let q = planar(p).ok()?;
    let angles = match near {
        Some(n) => [
            n[0] + angle_between(n[0], q.angles[0]),
            n[1] + angle_between(n[1], q.angles[1]),
        ],
        None => q.angles,
    };
    Some(HeldEnds {
        chord: q.chord,
        angles,
    })
}

/// The planned shape's tangent angle at `u ∈ [0, 1]` (Catmull–Rom through the stations).
pub fn shape_angle(shape: &[f64; SHAPE_STATIONS], u: f64) -> f64 {
    let n = SHAPE_STATIONS - 1;
    let x = (u.clamp(0.0, 1.0) * n as f64).min(n as f64 - 1e-12);
    let i = x.floor() as usize;
    let t = x - i as f64;
    let at = |k: isize| shape[k.clamp(0, n as isize) as usize];
    let (p0, p1, p2, p3) = (
        at(i as isize - 1),
        at(i as isize),
        at(i as isize + 1),
        at(i as isize + 2),
    );
    0.5 * (2.0 * p1
        + (p2 - p0) * t
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t * t
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t * t * t)
}

/// The discrete equilibrium of planned shape `shape` held at `ends` (Newton's method from
/// the shape), with the angles of the shape moved by whole turns to the ends'.
fn planned_blade(
    length: f64,
    ends: HeldEnds,
    shape: &[f64; SHAPE_STATIONS],
) -> Option<DiscreteBlade> {
    let turns =
        ((ends.angles[0] - shape[0]) / std::f64::consts::TAU).round() * std::f64::consts::TAU;
    DiscreteBlade::settle_like(
        length,
        ends,
        |u| shape_angle(shape, u) + turns,
        SEGMENTS,
        None,
    )
    .ok()
}

/// The ends a fraction `w` along the synchronized move from `a` to `b`: each tool frame
/// as the controller moves it.
pub fn ends_between(a: &BladePose, b: &BladePose, w: f64) -> BladePose {
    let at = |e: usize| {
        Isometry3::from_parts(
            a[e].translation
                .vector
                .lerp(&b[e].translation.vector, w)
                .into(),
            a[e].rotation.slerp(&b[e].rotation, w),
        )
    };
    [at(0), at(1)]
}

/// Follows the blade of `length` through `poses` (the program's steps' ends, in order)
/// with the planned shapes `shapes` (per step, where there is one). See the module docs.
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use cell::equilibrium::follow_steps;
/// use nalgebra::{UnitQuaternion, Vector3};
/// // an arch whose ends close in and turn further, then (a new plan) turned over at
/// // the same chord: the arch cannot follow the second move
/// let pose = |chord: f64, a: f64| from_planar(&PlanarPose {
///     mid: Vector3::zeros(), frame: UnitQuaternion::identity(), chord, angles: [a, -a],
/// });
/// let arc = |a: f64| -> [f64; 17] { std::array::from_fn(|k| a - 2.0 * a * k as f64 / 16.0) };
/// let poses = [pose(950.0, 0.4), pose(940.0, 0.45), pose(940.0, -0.45)];
/// let planned = [Some(arc(0.4)), None, Some(arc(-0.45))];
/// let s = follow_steps(1000.0, &poses, &planned);
/// assert_eq!((s.transitions, s.snaps), (2, 1));
/// assert!(s.moves[1].as_ref().unwrap().snap.is_none());
/// assert!(s.moves[2].as_ref().unwrap().snap.is_some());
/// ```
pub fn follow_steps(
    length: f64,
    poses: &[BladePose],
    shapes: &[Option<[f64; SHAPE_STATIONS]>],
) -> ProgramShapes {
    follow_steps_with(length, poses, shapes, Follow::Report)
}

/// How [`follow_steps_with`] follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Follow {
    /// Every move, with the margins at the moves' ends (a program's report).
    Report,
    /// Until the first snap, stability only checked (every margin recorded is 1 where
    /// stable), a fold located to 1e-3 of the move: whether a route holds, several times
    /// faster.
    Check,
}

/// [`follow_steps`] as `how` says.
pub fn follow_steps_with(
    length: f64,
    poses: &[BladePose],
    shapes: &[Option<[f64; SHAPE_STATIONS]>],
    how: Follow,
) -> ProgramShapes {
    let check = how == Follow::Check;
    let params = FollowParams {
        margins: !check,
        min_step: if check { 1e-3 } else { 1e-5 },
        ..FollowParams::default()
    };
    let mut out = ProgramShapes {
        moves: Vec::with_capacity(poses.len()),
        transitions: 0,
        snaps: 0,
        min_margin: f64::INFINITY,
    };
    let taut = |h: &HeldEnds| h.chord >= length * (1.0 - TAUT);
    // the blade's state after each step: its equilibrium, or None when taut or unknown
    let mut state: Option<DiscreteBlade> = None;
    let mut was_taut = false;
    let straight_or_planned = |k: usize, ends: HeldEnds| -> Option<DiscreteBlade> {
        shapes
            .get(k)
            .copied()
            .flatten()
            .and_then(|s| planned_blade(length, ends, &s))
    };
    for k in 0..poses.len() {
        let ends = held(&poses[k], state.as_ref().map(|s| s.ends.angles));
        let Some(ends) = ends else {
            out.moves.push(None);
            state = None;
            continue;
        };
        // out of a taut, straight blade (after the mount) the blade may go either way: a
        // snap unless it stays straight
        if k > 1 && state.is_none() && was_taut && !taut(&ends) {
            out.moves.push(Some(MoveShape {
                min_margin: f64::NAN,
                margin: f64::NAN,
                snap: Some(SnapKind::Lost),
                snap_at: Some(0.0),
                profile: Vec::new(),
            }));
            out.transitions += 1;
            out.snaps += 1;
            was_taut = false;
            state = straight_or_planned(k, ends);
            if check {
                break;
            }
            continue;
        }
        was_taut = taut(&ends);
        let Some(from) = state.take().filter(|_| k > 0) else {
            // the first step, or after a taut or unknown state: the blade takes the
            // planned shape (or, straight, none)
            out.moves.push(None);
            state = if taut(&ends) {
                None
            } else {
                straight_or_planned(k, ends)
            };
            continue;
        };
        let (a, b) = (poses[k - 1], poses[k]);
        let start_angles = from.ends.angles;
        let path = |w: f64| -> HeldEnds {
            held(&ends_between(&a, &b, w), Some(start_angles)).unwrap_or(HeldEnds {
                chord: length,
                angles: start_angles,
            })
        };
        let f = follow(&from, &path, &params);
        let mut snap = f.snap.map(SnapKind::from);
        let snap_at = f.snap.map(|s| match s {
            Snap::Fold { at, .. } | Snap::Lost { at, .. } => at,
        });
        let mut next = Some(f.blade.clone());
        if snap.is_none() {
            if let Some(shape) = shapes.get(k).copied().flatten() {
                match planned_blade(length, f.blade.ends, &shape) {
                    Some(p) if p.distance(&f.blade) <= SAME * length => {}
                    Some(p) => {
                        snap = Some(SnapKind::OtherShape);
                        next = Some(p);
                    }
                    // the planned shape is not an equilibrium the discrete blade finds:
                    // compared by its points
                    None => {
                        let pts = f.blade.points();
                        let h = length / SEGMENTS as f64;
                        let mut q = [-0.5 * f.blade.ends.chord, 0.0];
                        let mut far = 0.0f64;
                        for (i, p) in pts.iter().enumerate().skip(1) {
                            let t = shape_angle(&shape, (i as f64 - 0.5) / SEGMENTS as f64);
                            q = [q[0] + h * t.cos(), q[1] + h * t.sin()];
                            far = far.max((p[0] - q[0]).hypot(p[1] - q[1]));
                        }
                        if far > 1e-3 * length {
                            snap = Some(SnapKind::OtherShape);
                        }
                    }
                }
            }
        } else {
            // after a snap the blade is wherever it landed, which is not followed: the
            // program is followed again from the next step with a planned shape
            next = shapes
                .get(k)
                .copied()
                .flatten()
                .and_then(|s| planned_blade(length, ends, &s));
        }
        let margin = f.margins.last().map_or(f64::NAN, |m| m.1);
        let min_margin = f.min_margin();
        out.transitions += 1;
        out.snaps += usize::from(snap.is_some());
        out.min_margin = out.min_margin.min(min_margin);
        let snapped = snap.is_some();
        out.moves.push(Some(MoveShape {
            min_margin,
            margin,
            snap,
            snap_at,
            profile: f.margins,
        }));
        state = next;
        if snapped && check {
            break;
        }
    }
    out
}
