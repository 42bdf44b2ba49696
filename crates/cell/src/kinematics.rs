//! Forward and inverse kinematics of a [`RobotModel`](crate::model::RobotModel), flange poses in the robot's base
//! frame, millimetres. The closed-form OPW solution comes from `rs-opw-kinematics` (default
//! features off); this module adds what a cell needs around it: every solution within the
//! joint limits, the other turns of axes that rotate more than a full turn, each solution
//! verified by forward kinematics, the choice nearest the previous pose, and the margins
//! to the limits.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use rs_opw_kinematics::glam::{DQuat, DVec3};
use rs_opw_kinematics::kinematic_traits::{Kinematics, Pose};
use rs_opw_kinematics::kinematics_impl::OPWKinematics;
use rs_opw_kinematics::parameters::opw_kinematics::Parameters;

use crate::error::{CellError, Result};
use crate::model::RobotModel;

/// Joint values of a 6-axis arm, radians.
pub type Joints = [f64; 6];

/// How far an inverse solution's forward kinematics may lie from the pose: position, mm.
pub const POSITION_TOLERANCE_MM: f64 = 1e-6;
/// The same for the orientation, radians.
pub const ANGLE_TOLERANCE_RAD: f64 = 1e-9;

fn solver(model: &RobotModel) -> OPWKinematics {
    let o = &model.opw;
    OPWKinematics::new(Parameters {
        a1: o.a1,
        a2: o.a2,
        b: o.b,
        c1: o.c1,
        c2: o.c2,
        c3: o.c3,
        c4: o.c4,
        offsets: o.offsets,
        sign_corrections: o.signs,
        dof: 6,
    })
}

fn to_pose(p: &Isometry3<f64>) -> Option<Pose> {
    let t = p.translation.vector;
    let q = p.rotation.quaternion();
    Pose::try_from_parts(
        DVec3::new(t.x, t.y, t.z),
        DQuat::from_xyzw(q.i, q.j, q.k, q.w),
    )
    .ok()
}

fn from_pose(p: &Pose) -> Isometry3<f64> {
    let (t, q) = (p.translation, p.rotation);
    Isometry3::from_parts(
        Translation3::new(t.x, t.y, t.z),
        UnitQuaternion::from_quaternion(Quaternion::new(q.w, q.x, q.y, q.z)),
    )
}

/// The flange pose of `joints` in the robot's base frame (mm).
///
/// # Errors
/// [`CellError::NotFinite`] for joints that are not finite.
pub fn forward(model: &RobotModel, joints: &Joints) -> Result<Isometry3<f64>> {
    if !joints.iter().all(|q| q.is_finite()) {
        return Err(CellError::NotFinite("joints"));
    }
    solver(model)
        .try_forward(joints)
        .map(|p| from_pose(&p))
        .map_err(|_| CellError::NotFinite("pose"))
}

/// The distance of two poses: position (mm) and rotation angle (radians).
pub fn pose_distance(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    let d = (a.translation.vector - b.translation.vector).norm();
    (d, a.rotation.angle_to(&b.rotation))
}

/// Every joint solution of the flange pose `pose` (base frame, mm) within the model's
/// limits: each closed-form solution, with the other turns of axes whose range spans them,
/// kept only when its forward kinematics lands on the pose (within
/// [`POSITION_TOLERANCE_MM`] and [`ANGLE_TOLERANCE_RAD`]). With
/// `previous`, a wrist singularity is resolved near it. Empty when out of reach.
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
    let target = to_pose(pose)
        .filter(|_| finite)
        .ok_or(CellError::NotFinite("pose"))?;
    if previous.is_some_and(|p| !p.iter().all(|q| q.is_finite())) {
        return Err(CellError::NotFinite("previous joints"));
    }
    let kin = solver(model);
    let raw = match previous {
        Some(p) => kin.inverse_continuing(&target, p),
        None => kin.inverse(&target),
    };
    let mut out: Vec<Joints> = Vec::new();
    for s in raw {
        for q in turns(model, &s) {
            let Ok(p) = forward(model, &q) else { continue };
            let (dp, da) = pose_distance(&p, pose);
            let exact = dp <= POSITION_TOLERANCE_MM && da <= ANGLE_TOLERANCE_RAD;
            if exact && !out.iter().any(|o| same(o, &q)) {
                out.push(q);
            }
        }
    }
    Ok(out)
}

/// Two joint vectors equal to 1e-9 rad.
fn same(a: &Joints, b: &Joints) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
}

/// `q` with every joint moved by whole turns in every way that stays within the limits.
fn turns(model: &RobotModel, q: &Joints) -> Vec<Joints> {
    let tau = std::f64::consts::TAU;
    let options: Vec<Vec<f64>> = q
        .iter()
        .zip(&model.limits)
        .map(|(&v, &(lo, hi))| {
            (-2..=2)
                .map(|k| v + tau * k as f64)
                .filter(|w| (lo..=hi).contains(w))
                .collect()
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

/// The solution nearest `previous`: the least largest joint change (`None` for none).
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
pub fn margins(model: &RobotModel, joints: &Joints) -> [f64; 6] {
    std::array::from_fn(|i| {
        let (lo, hi) = model.limits[i];
        (joints[i] - lo).min(hi - joints[i])
    })
}
