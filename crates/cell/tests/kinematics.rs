//! Inverse kinematics against forward kinematics, and forward kinematics against an
//! independent rebuild of the OPW chain: for random joints within each built-in robot's
//! limits (away from its singularities), the pose's inverse solutions hold the joints
//! again, and every solution lands on the pose to 1e-6 mm and 1e-9 rad.

use cell::conf::{arm_geometry, conf};
use cell::kinematics::{configurations, forward, inverse, margins, nearest, pose_distance, Joints};
use cell::model::RobotModel;
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

fn models() -> [RobotModel; 4] {
    // and an arm with a lateral offset, axes turning the other way and another zero
    let mut custom = RobotModel::irb2600_12_165();
    custom.name = "custom".into();
    custom.opw.b = 40.0;
    custom.opw.signs = [-1, 1, 1, -1, 1, -1];
    custom.opw.offsets[1] = 0.2;
    [
        RobotModel::irb1600_6_145(),
        RobotModel::irb2600_12_165(),
        RobotModel::irb4600_60_205(),
        custom,
    ]
}

/// The OPW chain rebuilt from the paper's description, independent of the solver: the arm
/// plane turned by axis 1, the wrist centre from axes 2 and 3, the wrist as Z-Y-Z turns of
/// axes 4, 5, 6 in the forearm's frame, the flange `c4` along the wrist's last axis.
fn chain(m: &RobotModel, joints: &Joints) -> Isometry3<f64> {
    let o = &m.opw;
    let q: Vec<f64> = (0..6)
        .map(|i| joints[i] * f64::from(o.signs[i]) - o.offsets[i])
        .collect();
    let (psi3, k) = (o.a2.atan2(o.c3), o.a2.hypot(o.c3));
    // wrist centre in the arm plane (x forward, y lateral, z up), then turned by axis 1
    let x = o.a1 + o.c2 * q[1].sin() + k * (q[1] + q[2] + psi3).sin();
    let z = o.c1 + o.c2 * q[1].cos() + k * (q[1] + q[2] + psi3).cos();
    let (s1, c1) = q[0].sin_cos();
    let wrist = Vector3::new(x * c1 - o.b * s1, x * s1 + o.b * c1, z);
    // the forearm's frame: axis 1 about z, then axes 2 + 3 about y
    let r0c = Rotation3::from_axis_angle(&Vector3::z_axis(), q[0])
        * Rotation3::from_axis_angle(&Vector3::y_axis(), q[1] + q[2]);
    let rce = Rotation3::from_axis_angle(&Vector3::z_axis(), q[3])
        * Rotation3::from_axis_angle(&Vector3::y_axis(), q[4])
        * Rotation3::from_axis_angle(&Vector3::z_axis(), q[5]);
    let r = r0c * rce;
    let flange = wrist + r * Vector3::new(0.0, 0.0, o.c4);
    Isometry3::from_parts(
        Translation3::from(flange),
        UnitQuaternion::from_rotation_matrix(&r),
    )
}

/// Joints within the limits, away from the wrist (axis 5 ≈ 0), elbow and shoulder
/// singularities, where solutions are not isolated.
fn regular(m: &RobotModel, q: &Joints) -> bool {
    let (front, elbow) = arm_geometry(m, q);
    q[4].abs() > 0.05 && elbow.abs() > 0.05 && front.abs() > 50.0
}

fn unit() -> impl Strategy<Value = [f64; 6]> {
    proptest::array::uniform6(0.0f64..1.0)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn inverse_solutions_land_on_the_pose_and_hold_the_joints(u in unit(), which in 0usize..4) {
        let m = &models()[which];
        let q: Joints = std::array::from_fn(|i| {
            let (lo, hi) = m.limits[i];
            lo + (hi - lo) * u[i]
        });
        prop_assume!(regular(m, &q));
        let pose = forward(m, &q).unwrap();
        // forward kinematics is the OPW chain
        let (dp, da) = pose_distance(&pose, &chain(m, &q));
        prop_assert!(dp < 1e-9 && da < 1e-12, "FK vs chain: {dp} mm, {da} rad");
        let solutions = inverse(m, &pose, None).unwrap();
        prop_assert!(!solutions.is_empty());
        for s in &solutions {
            let (dp, da) = pose_distance(&forward(m, s).unwrap(), &pose);
            prop_assert!(dp <= 1e-6 && da <= 1e-9, "{}: {dp} mm, {da} rad", m.name);
            prop_assert!(margins(m, s).iter().all(|&v| v >= 0.0));
        }
        let back = nearest(&solutions, &q).unwrap();
        prop_assert!(back.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9), "{back:?} vs {q:?}");
        prop_assert_eq!(conf(m, &back), conf(m, &q));
        // with the previous joints as a hint, the same
        let hinted = inverse(m, &pose, Some(&q)).unwrap();
        let back = nearest(&hinted, &q).unwrap();
        prop_assert!(back.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
        // the configurations are the pose's, whatever joints the robot comes from
        let n = configurations(&solutions);
        prop_assert!((1..=8).contains(&n), "{n}");
        prop_assert_eq!(configurations(&hinted), n);
        let other = solutions[solutions.len() / 2];
        prop_assert_eq!(configurations(&inverse(m, &pose, Some(&other)).unwrap()), n);
    }
}

#[test]
fn the_zero_pose_is_the_datasheets() {
    // at all joints 0 the upper arm stands up, the forearm points along +x, and the flange
    // faces +x: tool z = base x, tool x = base −z
    for (m, flange) in [
        (RobotModel::irb1600_6_145(), [815.0, 0.0, 1186.5]),
        (RobotModel::irb2600_12_165(), [1030.0, 0.0, 1260.0]),
        (RobotModel::irb4600_60_205(), [1270.0, 0.0, 1570.0]),
    ] {
        let p = forward(&m, &[0.0; 6]).unwrap();
        let t = p.translation.vector;
        assert!((t - Vector3::from(flange)).norm() < 1e-9, "{}: {t}", m.name);
        let r: Matrix3<f64> = p.rotation.to_rotation_matrix().into_inner();
        assert!((r.column(2) - Vector3::x()).norm() < 1e-12, "{}", m.name);
        assert!((r.column(0) + Vector3::z()).norm() < 1e-12, "{}", m.name);
    }
}

#[test]
fn poses_out_of_reach_have_no_solution() {
    for m in models().into_iter().take(3) {
        let far = Isometry3::translation(m.reach() + 200.0, 0.0, 800.0);
        assert!(inverse(&m, &far, None).unwrap().is_empty(), "{}", m.name);
    }
    let m = RobotModel::irb1600_6_145();
    let bad = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(inverse(&m, &bad, None).is_err());
    assert!(forward(&m, &[f64::INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0]).is_err());
}

#[test]
fn turns_of_axes_four_and_six_are_solutions_too() {
    // axes 4 and 6 of an IRB 2600 turn ±400°: a pose with axis 6 at 10° is also reached
    // at 370° and −350°
    let m = RobotModel::irb2600_12_165();
    let q = [0.2, 0.3, -0.2, 0.4, 0.7, 10f64.to_radians()];
    let solutions = inverse(&m, &forward(&m, &q).unwrap(), None).unwrap();
    for a6 in [10.0, 370.0, -350.0] {
        let want = [q[0], q[1], q[2], q[3], q[4], f64::to_radians(a6)];
        assert!(
            solutions
                .iter()
                .any(|s| s.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-9)),
            "axis 6 at {a6}°"
        );
    }
}

#[test]
fn wide_limits_keep_the_enumeration_bounded() {
    // every joint allowed ±720°: four turns each, 4⁶ variants per closed-form solution if
    // all were kept; the previous joints pick one turn (and the middle's) per joint
    let mut m = RobotModel::irb2600_12_165();
    let wide = 4.0 * std::f64::consts::PI;
    m.limits = [(-wide, wide); 6];
    let q = [0.2, 0.3, -0.2, 0.4, 0.7, 0.1];
    let pose = forward(&m, &q).unwrap();
    let all = inverse(&m, &pose, None).unwrap();
    assert!(!all.is_empty() && all.len() <= 8 * 729, "{}", all.len());
    let hinted = inverse(&m, &pose, Some(&q)).unwrap();
    assert!(hinted.len() <= 8 * 64, "{}", hinted.len());
    assert_eq!(configurations(&hinted), configurations(&all));
    assert!(configurations(&all) <= 8);
    let back = nearest(&hinted, &q).unwrap();
    assert!(back.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
    // a turn away from the middle, found near the previous joints
    let far = [q[0] + wide / 2.0, q[1], q[2], q[3], q[4], q[5] - wide / 2.0];
    let back = nearest(&inverse(&m, &pose, Some(&far)).unwrap(), &far).unwrap();
    assert!(
        back.iter().zip(&far).all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
}
