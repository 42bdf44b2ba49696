//! ABB configuration data (`confdata` of a robtarget) of a joint solution: the quarter
//! turns of axes 1, 4 and 6, and `cfx`, which of the eight arm configurations the robot is
//! in. Definitions and sources: `docs/robot-cell.md` §3.

use crate::kinematics::Joints;
use crate::model::RobotModel;

/// `[cf1, cf4, cf6, cfx]` of a robtarget.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Conf {
    /// Quarter turn of axis 1.
    pub cf1: i32,
    /// Quarter turn of axis 4.
    pub cf4: i32,
    /// Quarter turn of axis 6.
    pub cf6: i32,
    /// Arm configuration 0–7: 4 × (wrist centre behind axis 1) + 2 × (wrist centre behind
    /// the lower arm) + (axis 5 negative).
    pub cfx: i32,
}

/// ABB's quarter-turn number of an angle (radians): 0 for [0°, 90°), 1 for [90°, 180°),
/// −1 for (−90°, 0°), −2 for (−180°, −90°], … (the RAPID manual's rule: positive angles
/// truncate `a / 90°`, negative ones truncate `a / 90° − 1`). The angle is first rounded
/// to 1e-6°, the precision programs state joints with, so that an angle a hair below a
/// boundary gets the quarter its printed value has.
///
/// ```
/// use cell::conf::quadrant;
/// assert_eq!(quadrant(10f64.to_radians()), 0);
/// assert_eq!(quadrant(100f64.to_radians()), 1);
/// assert_eq!(quadrant(-10f64.to_radians()), -1);
/// assert_eq!(quadrant(-100f64.to_radians()), -2);
/// assert_eq!(quadrant(90f64.to_radians() - 1e-12), 1); // as printed: 90.000000°
/// ```
pub fn quadrant(angle: f64) -> i32 {
    let degrees = (angle.to_degrees() * 1e6).round() / 1e6;
    let angle = if degrees == 0.0 {
        0.0
    } else {
        degrees.to_radians()
    };
    let quarters = angle / std::f64::consts::FRAC_PI_2;
    if angle >= 0.0 {
        quarters.trunc() as i32
    } else {
        (quarters - 1.0).trunc() as i32
    }
}

/// The arm-plane geometry of a solution: the wrist centre's distance in front of axis 1
/// (along the arm's own forward direction), and the sine of the angle that puts it in
/// front of (> 0) or behind (< 0) the lower arm, the line from axis 2 to axis 3.
///
/// ```
/// use cell::conf::arm_geometry;
/// use cell::RobotModel;
/// let robot = RobotModel::irb1600_6_145();
/// // at zero: the wrist centre a1 + c3 in front of axis 1, the forearm square to the lower arm
/// let (front, elbow) = arm_geometry(&robot, &[0.0; 6]);
/// assert!((front - 750.0).abs() < 1e-9 && (elbow - 1.0).abs() < 1e-12);
/// // axis 1 turned half round: the arm plane turns with it, still in front
/// assert!((arm_geometry(&robot, &[3.0, 0.0, 0.0, 0.0, 0.0, 0.0]).0 - 750.0).abs() < 1e-9);
/// ```
pub fn arm_geometry(model: &RobotModel, joints: &Joints) -> (f64, f64) {
    let o = &model.opw;
    // the paper's joint angles
    let q = |i: usize| joints[i] * f64::from(o.signs[i]) - o.offsets[i];
    let (q2, q3) = (q(1), q(2));
    let psi3 = o.a2.atan2(o.c3);
    let k = o.a2.hypot(o.c3);
    let front = o.a1 + o.c2 * q2.sin() + k * (q2 + q3 + psi3).sin();
    // lower arm along (sin q2, cos q2), wrist from axis 3 along
    // (sin(q2 + q3 + ψ3), cos(q2 + q3 + ψ3)): their cross product is −sin(q3 + ψ3)
    (front, (q3 + psi3).sin())
}

/// The configuration data of a joint solution.
///
/// ```
/// use cell::{conf, Conf, RobotModel};
/// let robot = RobotModel::irb1600_6_145();
/// let home = [0.0, 0.0, 0.0, 0.0, 30f64.to_radians(), 0.0];
/// assert_eq!(conf(&robot, &home), Conf { cf1: 0, cf4: 0, cf6: 0, cfx: 0 });
/// // the wrist flipped (axis 5 negative), axis 6 past a quarter turn
/// let flipped = [0.0, 0.0, 0.0, 0.0, -0.5, 2.0];
/// assert_eq!(conf(&robot, &flipped), Conf { cf1: 0, cf4: 0, cf6: 1, cfx: 1 });
/// ```
pub fn conf(model: &RobotModel, joints: &Joints) -> Conf {
    let (front, elbow) = arm_geometry(model, joints);
    let behind_axis1 = i32::from(front < 0.0);
    let behind_arm = i32::from(elbow < 0.0);
    let wrist = i32::from(joints[4] < 0.0);
    Conf {
        cf1: quadrant(joints[0]),
        cf4: quadrant(joints[3]),
        cf6: quadrant(joints[5]),
        cfx: 4 * behind_axis1 + 2 * behind_arm + wrist,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrants_follow_the_rapid_manual() {
        for (deg, q) in [
            (10.0, 0),
            (89.9, 0),
            (100.0, 1),
            (370.0, 4),
            (-10.0, -1),
            (-100.0, -2),
            (-190.0, -3),
            (0.0, 0),
        ] {
            assert_eq!(quadrant(f64::to_radians(deg)), q, "{deg}°");
        }
    }

    #[test]
    fn the_home_pose_is_configuration_zero() {
        for m in [
            RobotModel::irb1600_6_145(),
            RobotModel::irb2600_12_165(),
            RobotModel::irb4600_60_205(),
        ] {
            let home = [0.0, 0.0, 0.0, 0.0, 30f64.to_radians(), 0.0];
            assert_eq!(
                conf(&m, &home),
                Conf {
                    cf1: 0,
                    cf4: 0,
                    cf6: 0,
                    cfx: 0
                }
            );
            // axis 5 negative
            let mut q = home;
            q[4] = -q[4];
            assert_eq!(conf(&m, &q).cfx, 1);
            // the forearm folded past the elbow's singular line (axis 3 at −90° + atan(|a2|/c3))
            let singular = -90f64.to_radians() + (-m.opw.a2).atan2(m.opw.c3);
            let mut q = home;
            q[2] = singular - 0.05;
            assert_eq!(conf(&m, &q).cfx, 2, "{}", m.name);
            q[2] = singular + 0.05;
            assert_eq!(conf(&m, &q).cfx, 0, "{}", m.name);
            // the arm leaning back over axis 1: the wrist centre behind it
            let mut q = home;
            q[1] = -60f64.to_radians();
            q[2] = -30f64.to_radians();
            let (front, _) = arm_geometry(&m, &q);
            assert!(front < 0.0, "{}: {front}", m.name);
            assert_eq!(conf(&m, &q).cfx, 4, "{}", m.name);
        }
    }
}
