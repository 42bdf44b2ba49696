//! Blocks of arched blade poses shared by the cell's tests.

use cell::blade::{from_planar, PlanarPose};
use cell::conf::conf;
use cell::fixture::BlockCut;
use cell::kinematics::{forward, pose_distance};
use cell::model::RobotModel;
use cell::plan::{Holder, PoseSolution, SweepFlag};
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

/// The blade's length, mm.
pub const BLADE: f64 = 800.0;

/// The rotation whose x- and z-axes are `x` and `z`.
pub fn rotation(x: Vector3<f64>, z: Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(Matrix3::from_columns(
        &[x, z.cross(&x), z],
    )))
}

/// Poses through a 600 mm block along x: arches of the blade with ends turned by `turn`
/// against the chord, the chord tilted by `tilt` about x, its midpoint at `height`.
pub fn block(number: usize, turn: f64, tilt: f64, height: f64, n: usize) -> BlockCut {
    let chord = BLADE * turn.sin() / turn * 0.98;
    let x = Vector3::new(0.0, tilt.cos(), tilt.sin());
    let poses = (0..n)
        .map(|k| {
            let along = 600.0 * k as f64 / (n - 1) as f64;
            from_planar(&PlanarPose {
                mid: Vector3::new(along, 300.0, height),
                frame: rotation(x, Vector3::x()),
                chord,
                angles: [turn, -turn],
            })
        })
        .collect();
    BlockCut {
        block: number,
        size: [600.0, 600.0, 600.0],
        poses,
        shapes: Vec::new(),
    }
}

/// Three blocks of arches: ends turned by about `turn`, chords tilted by about `tilt`.
pub fn blocks(turn: f64, tilt: f64) -> Vec<BlockCut> {
    vec![
        block(1, turn, tilt, 350.0, 9),
        block(2, 0.6 * turn, -tilt, 300.0, 9),
        block(3, turn, 0.5 * tilt, 380.0, 9),
    ]
}

/// Checks robot `r`'s solution at move `k`: reached, its joints land on `target` through
/// forward kinematics (1e-6 mm, 1e-9 rad) with the stated configuration data and a
/// margin ≥ 0; or flagged out of reach. Returns whether it was reached.
pub fn reaches(
    h: &Holder,
    sol: &PoseSolution,
    flags: &[SweepFlag],
    target: &Isometry3<f64>,
    (k, r): (usize, usize),
) -> bool {
    let Some(joints) = sol.joints else {
        assert!(
            flags.contains(&SweepFlag::OutOfReach(k)),
            "move {k} robot {r}: not flagged"
        );
        return false;
    };
    let joints = joints.map(f64::to_radians);
    let tcp = h.base * forward(&h.model, &joints).unwrap() * h.tool;
    let (dp, da) = pose_distance(&tcp, target);
    assert!(
        dp < 1e-6 && da < 1e-9,
        "move {k} robot {r}: {dp} mm, {da} rad"
    );
    assert_eq!(sol.conf, Some(conf(&h.model, &joints)));
    assert!(sol.margin.unwrap() >= 0.0);
    true
}

/// Two plans of one robot agree: the same flags (kind, move, axis) and the same joints to
/// 1e-6°.
pub fn same_robot(
    (a, fa): (&[PoseSolution], &[SweepFlag]),
    (b, fb): (&[PoseSolution], &[SweepFlag]),
) -> Result<(), TestCaseError> {
    let key = |f: &SweepFlag| match f {
        SweepFlag::OutOfReach(i) => (0, *i, 0),
        SweepFlag::ConfigurationChange(i) => (1, *i, 0),
        SweepFlag::JointJump { pose, axis, .. } => (2, *pose, *axis),
    };
    let keys = |v: &[SweepFlag]| v.iter().map(key).collect::<Vec<_>>();
    prop_assert_eq!(keys(fa), keys(fb));
    prop_assert_eq!(a.len(), b.len());
    for (a, b) in a.iter().zip(b) {
        match (a.joints, b.joints) {
            (Some(a), Some(b)) => prop_assert!(
                a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-6),
                "{:?} {:?}",
                a,
                b
            ),
            (a, b) => prop_assert_eq!(a, b),
        }
    }
    Ok(())
}

/// A robot's base on the floor at (`x`, `y`), turned by `yaw` about z.
pub fn base(x: f64, y: f64, yaw: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(x, y, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
    )
}

/// Two IRB 2600 facing each other across the cut, 1200 mm either side of x's axis, each
/// holding its blade end 150 mm in front of its flange: at the mean pose the flange's z
/// along the cut (x), its x down, the blade's tangent along y at both ends.
pub fn blade_holders() -> [Holder; 2] {
    let holder = |base| Holder {
        model: RobotModel::irb2600_12_165(),
        base,
        tool: Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 150.0),
            rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
        ),
    };
    [
        holder(base(0.0, -1200.0, std::f64::consts::FRAC_PI_2)),
        holder(base(0.0, 1200.0, -std::f64::consts::FRAC_PI_2)),
    ]
}
