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
//! Entry point: [`follow_steps`](crate::equilibrium::follow_steps).

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
    /// No moves yet.
    fn empty() -> ProgramShapes {
        ProgramShapes {
            moves: Vec::new(),
            transitions: 0,
            snaps: 0,
            min_margin: f64::INFINITY,
        }
    }

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
///
/// A program is followed in parallel (with the `parallel` feature) in stretches, from
/// each step with a planned shape to the next: the blade arrives on its planned shape
/// there or snaps, and either way the stretch after it starts from the planned shape —
/// the discrete blade settled from it, within 1e-6 of the blade's length of the one
/// followed into it. Where that shape does not settle, the stretch is followed again
/// from the blade that arrived, after the stretch before. The result is the same on any
/// number of threads.
pub fn follow_steps_with(
    length: f64,
    poses: &[BladePose],
    shapes: &[Option<[f64; SHAPE_STATIONS]>],
    how: Follow,
) -> ProgramShapes {
    let n = poses.len();
    let mut out = ProgramShapes::empty();
    let f = Follower::new(length, shapes, how);
    if how == Follow::Check || n < 3 {
        let mut state = Walk::default();
        for k in 0..n {
            if f.step(&mut state, poses, k, &mut out) && state.snapped && how == Follow::Check {
                break;
            }
        }
        return out;
    }
    // stretches: (first step, last step); each but the first starts at a planned step
    let mut bounds: Vec<usize> = vec![0];
    bounds.extend((1..n).filter(|&k| shapes.get(k).is_some_and(Option::is_some)));
    bounds.push(n.saturating_sub(1));
    bounds.dedup();
    let stretches: Vec<(usize, usize)> = bounds.windows(2).map(|w| (w[0], w[1])).collect();
    let walk = |&(a, b): &(usize, usize), mut state: Walk| {
        let mut part = ProgramShapes::empty();
        for k in a + 1..=b {
            f.step(&mut state, poses, k, &mut part);
        }
        (part, state)
    };
    let started = |a: usize| {
        let mut state = Walk::default();
        let mut first = ProgramShapes::empty();
        f.step(&mut state, poses, a, &mut first);
        (first, state)
    };
    let parts = crate::map_in_order(&stretches, |r| {
        let (first, state) = started(r.0);
        let missing = r.0 > 0 && state.blade.is_none() && !state.was_taut;
        (first, missing, walk(r, state))
    });
    let mut last: Option<Walk> = None;
    for (i, (first, missing, (mut part, mut end))) in parts.into_iter().enumerate() {
        if i == 0 {
            out.moves.extend(first.moves);
        } else if missing {
            if let Some(before) = last.take().filter(|w| w.blade.is_some()) {
                (part, end) = walk(&stretches[i], before);
            }
        }
        out.moves.extend(part.moves);
        out.transitions += part.transitions;
        out.snaps += part.snaps;
        out.min_margin = out.min_margin.min(part.min_margin);
        last = Some(end);
    }
    out
}

/// The blade's state along a program: its equilibrium after the last step (`None` when
/// taut or unknown), whether that step held it taut, whether the last move snapped.
#[derive(Debug, Clone, Default)]
struct Walk {
    blade: Option<DiscreteBlade>,
    was_taut: bool,
    snapped: bool,
}

/// One program's blade, shapes and follow parameters.
struct Follower<'a> {
    length: f64,
    shapes: &'a [Option<[f64; SHAPE_STATIONS]>],
    params: FollowParams,
}

impl Follower<'_> {
    fn new(length: f64, shapes: &[Option<[f64; SHAPE_STATIONS]>], how: Follow) -> Follower<'_> {
        let check = how == Follow::Check;
        Follower {
            length,
            shapes,
            params: FollowParams {
                margins: !check,
                min_step: if check { 1e-3 } else { 1e-5 },
                ..FollowParams::default()
            },
        }
    }

    fn taut(&self, h: &HeldEnds) -> bool {
        h.chord >= self.length * (1.0 - TAUT)
    }

    /// The planned shape of step `k` settled at `ends`.
    fn planned(&self, k: usize, ends: HeldEnds) -> Option<DiscreteBlade> {
        self.shapes
            .get(k)
            .copied()
            .flatten()
            .and_then(|s| planned_blade(self.length, ends, &s))
    }

    /// Step `k`: the move into it from `state` pushed on `out` (or `None` where not
    /// followed), `state` updated. Whether a move was followed.
    fn step(
        &self,
        state: &mut Walk,
        poses: &[BladePose],
        k: usize,
        out: &mut ProgramShapes,
    ) -> bool {
        let length = self.length;
        state.snapped = false;
        let Some(ends) = held(&poses[k], state.blade.as_ref().map(|s| s.ends.angles)) else {
            out.moves.push(None);
            state.blade = None;
            return false;
        };
        // out of a taut, straight blade (after the mount) the blade may go either way: a
        // snap unless it stays straight
        if k > 1 && state.blade.is_none() && state.was_taut && !self.taut(&ends) {
            out.moves.push(Some(MoveShape {
                min_margin: f64::NAN,
                margin: f64::NAN,
                snap: Some(SnapKind::Lost),
                snap_at: Some(0.0),
                profile: Vec::new(),
            }));
            out.transitions += 1;
            out.snaps += 1;
            *state = Walk {
                blade: self.planned(k, ends),
                was_taut: false,
                snapped: true,
            };
            return true;
        }
        state.was_taut = self.taut(&ends);
        let Some(from) = state.blade.take().filter(|_| k > 0) else {
            // the first step, or after a taut or unknown state: the blade takes the
            // planned shape (or, straight, none)
            out.moves.push(None);
            state.blade = if self.taut(&ends) {
                None
            } else {
                self.planned(k, ends)
            };
            return false;
        };
        let (a, b) = (poses[k - 1], poses[k]);
        let start_angles = from.ends.angles;
        let path = |w: f64| -> HeldEnds {
            held(&ends_between(&a, &b, w), Some(start_angles)).unwrap_or(HeldEnds {
                chord: length,
                angles: start_angles,
            })
        };
        let f = follow(&from, &path, &self.params);
        let snap_at = f.snap.map(|s| match s {
            Snap::Fold { at, .. } | Snap::Lost { at, .. } => at,
        });
        let (snap, next) = match f.snap {
            // after a snap the blade is wherever it landed, which is not followed: the
            // program is followed again from the next step with a planned shape
            Some(s) => (Some(SnapKind::from(s)), self.planned(k, ends)),
            None => self.arrival(k, f.blade.clone()),
        };
        let margin = f.margins.last().map_or(f64::NAN, |m| m.1);
        let min_margin = f.min_margin();
        out.transitions += 1;
        out.snaps += usize::from(snap.is_some());
        out.min_margin = out.min_margin.min(min_margin);
        state.snapped = snap.is_some();
        out.moves.push(Some(MoveShape {
            min_margin,
            margin,
            snap,
            snap_at,
            profile: f.margins,
        }));
        state.blade = next;
        true
    }

    /// The blade `arrived` at step `k` against its planned shape, if it has one: a snap
    /// to another shape, and the blade the program goes on from.
    fn arrival(
        &self,
        k: usize,
        arrived: DiscreteBlade,
    ) -> (Option<SnapKind>, Option<DiscreteBlade>) {
        let length = self.length;
        let Some(shape) = self.shapes.get(k).copied().flatten() else {
            return (None, Some(arrived));
        };
        match planned_blade(length, arrived.ends, &shape) {
            Some(p) if p.distance(&arrived) <= SAME * length => (None, Some(arrived)),
            Some(p) => (Some(SnapKind::OtherShape), Some(p)),
            // the planned shape is not an equilibrium the discrete blade finds: compared
            // by its points
            None => {
                let pts = arrived.points();
                let h = length / SEGMENTS as f64;
                let mut q = [-0.5 * arrived.ends.chord, 0.0];
                let mut far = 0.0f64;
                for (i, p) in pts.iter().enumerate().skip(1) {
                    let t = shape_angle(&shape, (i as f64 - 0.5) / SEGMENTS as f64);
                    q = [q[0] + h * t.cos(), q[1] + h * t.sin()];
                    far = far.max((p[0] - q[0]).hypot(p[1] - q[1]));
                }
                (
                    (far > 1e-3 * length).then_some(SnapKind::OtherShape),
                    Some(arrived),
                )
            }
        }
    }
}
