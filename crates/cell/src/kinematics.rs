//! Forward and inverse kinematics of a [`RobotModel`](crate::model::RobotModel), flange
//! poses in the robot's base frame, millimetres. Around the closed form of [`crate::opw`]
//! it gives what a cell needs: every solution within the joint limits, the other turns of
//! axes that rotate more than a full turn, each solution verified by forward kinematics,
//! the choice nearest the previous pose, and the margins to the limits.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};

use crate::error::{CellError, Result};
use crate::model::RobotModel;
use crate::opw;

/// Joint values of a 6-axis arm, radians.
pub type Joints = [f64; 6];

/// How far an inverse solution's forward kinematics may lie from the pose: position, mm.
pub const POSITION_TOLERANCE_MM: f64 = 1e-6;
/// The same for the orientation, radians.
pub const ANGLE_TOLERANCE_RAD: f64 = 1e-9;

/// The paper's angles of maker joints.
fn paper(model: &RobotModel, joints: &Joints) -> opw::Angles {
    let o = &model.opw;
    std::array::from_fn(|i| joints[i] * f64::from(o.signs[i]) - o.offsets[i])
}

/// Maker joints of the paper's angles, each in (−π, π].
fn maker(model: &RobotModel, q: &opw::Angles) -> Joints {
    let o = &model.opw;
    let tau = std::f64::consts::TAU;
    std::array::from_fn(|i| {
        let j = (q[i] + o.offsets[i]) * f64::from(o.signs[i]);
        let r = j.rem_euclid(tau);
        if r > std::f64::consts::PI {
            r - tau
        } else {
            r
        }
    })
}

/// The flange pose of `joints` in the robot's base frame (mm).
///
/// ```
/// use cell::{forward, RobotModel};
/// // at the maker's zero an IRB 1600-6/1.45 points its forearm along x: the flange at
/// // a1 + c3 + c4 in front of axis 1, c1 + c2 up
/// let robot = RobotModel::irb1600_6_145();
/// let flange = forward(&robot, &[0.0; 6])?;
/// let p = flange.translation.vector;
/// assert!((p.x - (150.0 + 600.0 + 65.0)).abs() < 1e-9);
/// assert!(p.y.abs() < 1e-9 && (p.z - (486.5 + 700.0)).abs() < 1e-9);
/// assert!(forward(&robot, &[f64::NAN; 6]).is_err());
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// [`CellError::NotFinite`] for joints that are not finite.
pub fn forward(model: &RobotModel, joints: &Joints) -> Result<Isometry3<f64>> {
    if !joints.iter().all(|q| q.is_finite()) {
        return Err(CellError::NotFinite("joints"));
    }
    let (r, p) = opw::forward(&model.opw, &paper(model, joints));
    Ok(Isometry3::from_parts(
        Translation3::from(p),
        UnitQuaternion::from_rotation_matrix(&r),
    ))
}

/// The distance of two poses: position (mm) and rotation angle (radians).
///
/// ```
/// use cell::kinematics::pose_distance;
/// use nalgebra::{Isometry3, Vector3};
/// let a = Isometry3::translation(1.0, 2.0, 3.0);
/// let b = Isometry3::new(Vector3::new(4.0, 6.0, 3.0), Vector3::z() * 0.25);
/// let (d, angle) = pose_distance(&a, &b);
/// assert!((d - 5.0).abs() < 1e-12 && (angle - 0.25).abs() < 1e-12);
/// ```
pub fn pose_distance(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    let d = (a.translation.vector - b.translation.vector).norm();
    (d, a.rotation.angle_to(&b.rotation))
}

/// Every joint solution of the flange pose `pose` (base frame, mm) within the model's
/// limits: each closed-form solution, with the whole turns of axes whose range spans them
/// — nearest `previous` and nearest the middle of the range, or the three nearest the
/// middle without `previous`: the enumeration is bounded however wide the limits —
/// sorted and deduplicated,
/// kept only when its forward kinematics lands on the pose (within
/// [`POSITION_TOLERANCE_MM`] and [`ANGLE_TOLERANCE_RAD`]). With
/// `previous`, a singularity (axis 5 at 0, the wrist centre on axis 1) is resolved at its
/// values. Empty when out of reach.
///
/// ```
/// use cell::kinematics::{forward, inverse, pose_distance};
/// use cell::RobotModel;
/// use nalgebra::Isometry3;
/// let robot = RobotModel::irb2600_12_165();
/// let pose = forward(&robot, &[0.2, 0.3, 0.1, -0.5, 0.8, 1.0])?;
/// let solutions = inverse(&robot, &pose, None)?;
/// assert!(solutions.len() >= 2);
/// for q in &solutions {
///     let (d, angle) = pose_distance(&forward(&robot, q)?, &pose);
///     assert!(d < 1e-6 && angle < 1e-9);
///     assert!(q.iter().zip(&robot.limits).all(|(v, (lo, hi))| lo <= v && v <= hi));
/// }
/// // 5 m away: out of reach
/// assert!(inverse(&robot, &Isometry3::translation(5000.0, 0.0, 0.0), None)?.is_empty());
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// [`CellError::NotFinite`] for a pose or previous joints that are not finite.
pub fn inverse(
    model: &RobotModel,
    pose: &Isometry3<f64>,
    previous: Option<&Joints>,
) -> Result<Vec<Joints>> {
    let finite = pose.translation.vector.iter().all(|v| v.is_finite())
        && pose.rotation.coords.iter().all(|v| v.is_finite());
    if !finite {
        return Err(CellError::NotFinite("pose"));
    }
    if previous.is_some_and(|p| !p.iter().all(|q| q.is_finite())) {
        return Err(CellError::NotFinite("previous joints"));
    }
    let hint = previous.map_or([0.0; 6], |p| paper(model, p));
    let raw: Vec<Joints> = opw::inverse(
        &model.opw,
        &pose.rotation.to_rotation_matrix(),
        &pose.translation.vector,
        &hint,
    )
    .iter()
    .filter(|q| q.iter().all(|v| v.is_finite()))
    .map(|q| maker(model, q))
    .collect();
    let near = previous.copied();
    let mut out: Vec<Joints> = Vec::new();
    for s in raw {
        for q in turns(model, &s, near.as_ref()) {
            let Ok(p) = forward(model, &q) else { continue };
            let (dp, da) = pose_distance(&p, pose);
            if dp <= POSITION_TOLERANCE_MM && da <= ANGLE_TOLERANCE_RAD {
                out.push(q);
            }
        }
    }
    // equal solutions (to 1e-9 rad) once, in O(n log n): sorted on their rounded joints
    let key = |q: &Joints| q.map(|v| (v * 1e9).round() as i64);
    out.sort_by_key(key);
    out.dedup_by(|a, b| key(a) == key(b));
    Ok(out)
}

/// Whole-turn variants of `q` within the limits, a few per joint however wide the limits
/// (an arm allowed ±720° on every joint would otherwise give thousands per solution):
/// with `previous`, the one nearest it and the one nearest the range's middle (at most 64
/// in all); without, the three nearest the middle (at most 729).
fn turns(model: &RobotModel, q: &Joints, previous: Option<&Joints>) -> Vec<Joints> {
    let tau = std::f64::consts::TAU;
    let options: Vec<Vec<f64>> = q
        .iter()
        .zip(&model.limits)
        .enumerate()
        .map(|(i, (&v, &(lo, hi)))| {
            // the in-range turns nearest `target`, nearest first
            let near = |target: f64, n: usize| {
                let k = ((target - v) / tau).round();
                let mut w: Vec<f64> = (-2..=2)
                    .map(|d| v + tau * (k + f64::from(d)))
                    .filter(|w| (lo..=hi).contains(w))
                    .collect();
                w.sort_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()));
                w.truncate(n);
                w
            };
            let mid = 0.5 * (lo + hi);
            let mut o = match previous {
                Some(p) => [near(p[i], 1), near(mid, 1)].concat(),
                None => near(mid, 3),
            };
            o.sort_by(f64::total_cmp);
            o.dedup();
            o
        })
        .collect();
    let mut out = vec![[0.0; 6]];
    for (i, opts) in options.iter().enumerate() {
        let mut next = Vec::with_capacity(out.len() * opts.len());
        for partial in &out {
            for &v in opts {
                let mut p = *partial;
                p[i] = v;
                next.push(p);
            }
        }
        out = next;
    }
    out
}

/// How many distinct arm configurations `solutions` hold: solutions that differ only by
/// whole turns of a joint count once. Unlike the number of solutions, which depends on
/// the joints the robot comes from (the turns [`inverse`] enumerates are those nearest
/// them), this depends on the pose alone: at most 8 for an OPW arm.
///
/// ```
/// use cell::kinematics::configurations;
/// let q = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
/// let mut turned = q;
/// turned[5] += std::f64::consts::TAU;
/// let mut other = q;
/// other[3] += std::f64::consts::PI;
/// assert_eq!(configurations(&[q, turned, other]), 2);
/// ```
pub fn configurations(solutions: &[Joints]) -> usize {
    let tau = std::f64::consts::TAU;
    // the same configuration: every joint within 1e-6 rad of the other's, whole turns
    // aside (turns of one solution differ by rounding, ~1e-15 rad; distinct configurations
    // by far more away from a singularity)
    let same = |a: &Joints, b: &Joints| {
        a.iter().zip(b).all(|(x, y)| {
            let d = (x - y).rem_euclid(tau);
            d.min(tau - d) <= 1e-6
        })
    };
    let mut kept: Vec<Joints> = Vec::new();
    for q in solutions {
        if !kept.iter().any(|k| same(k, q)) {
            kept.push(*q);
        }
    }
    kept.len()
}

/// The solution nearest `previous`: the least largest joint change (`None` for none).
///
/// ```
/// use cell::nearest;
/// let previous = [0.0; 6];
/// let a = [0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
/// let b = [0.0, 0.0, 0.0, 0.0, 0.0, 0.5]; // less in all, more in its largest change
/// assert_eq!(nearest(&[a, b], &previous), Some(a));
/// assert_eq!(nearest(&[], &previous), None);
/// ```
pub fn nearest(solutions: &[Joints], previous: &Joints) -> Option<Joints> {
    let change = |q: &Joints| {
        q.iter()
            .zip(previous)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    solutions
        .iter()
        .min_by(|a, b| change(a).total_cmp(&change(b)))
        .copied()
}

/// The margin of each joint to its nearer limit, radians (negative: past it).
///
/// ```
/// use cell::kinematics::margins;
/// use cell::RobotModel;
/// let robot = RobotModel::irb1600_6_145(); // axis 1 within ±180°, axis 5 within ±115°
/// let m = margins(&robot, &[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]);
/// assert!((m[0] - std::f64::consts::PI).abs() < 1e-12);
/// assert!((m[4] - (115f64.to_radians() - 0.5)).abs() < 1e-12);
/// assert!(margins(&robot, &[4.0, 0.0, 0.0, 0.0, 0.0, 0.0])[0] < 0.0); // past the limit
/// ```
pub fn margins(model: &RobotModel, joints: &Joints) -> [f64; 6] {
    std::array::from_fn(|i| {
        let (lo, hi) = model.limits[i];
        (joints[i] - lo).min(hi - joints[i])
    })
}
