//! Sweeps of tool poses made from known joint paths: the plan finds the joints again,
//! whatever the robot's base and tool, and flags what a program must not contain.

use cell::kinematics::{forward, Joints};
use cell::model::RobotModel;
use cell::plan::{sweep, Holder, SweepFlag};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

fn holder(model: RobotModel) -> Holder {
    Holder {
        model,
        // standing 1.2 m along −y of the cell, turned to face +y
        base: Isometry3::from_parts(
            Translation3::new(300.0, -1200.0, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
        ),
        // a blade holder: 180 mm out of the flange, tilted 20°
        tool: Isometry3::from_parts(
            Translation3::new(0.0, 40.0, 180.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 20f64.to_radians()),
        ),
    }
}

/// The TCP poses (cell frame) of a joint path.
fn tcp(h: &Holder, path: &[Joints]) -> Vec<Isometry3<f64>> {
    path.iter()
        .map(|q| h.base * forward(&h.model, q).unwrap() * h.tool)
        .collect()
}

fn path(from: Joints, to: Joints, n: usize) -> Vec<Joints> {
    (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            std::array::from_fn(|k| from[k] + (to[k] - from[k]) * t)
        })
        .collect()
}

fn deg(q: [f64; 6]) -> Joints {
    q.map(f64::to_radians)
}

#[test]
fn a_smooth_path_is_found_again_under_any_placement() {
    for model in [
        RobotModel::irb1600_6_145(),
        RobotModel::irb2600_12_165(),
        RobotModel::irb4600_60_205(),
    ] {
        let h = holder(model);
        let p = path(
            deg([-20.0, 10.0, -10.0, 30.0, 40.0, -50.0]),
            deg([25.0, 30.0, 15.0, -20.0, 60.0, 80.0]),
            40,
        );
        let poses = tcp(&h, &p);
        let s = sweep(&h, &poses, &p[0]).unwrap();
        assert!(s.is_clean(), "{}: {:?}", h.model.name, s.flags);
        for (got, want) in s.poses.iter().zip(&p) {
            let got = got.joints.unwrap();
            for k in 0..6 {
                assert!(
                    (got[k] - want[k].to_degrees()).abs() < 1e-7,
                    "{}",
                    h.model.name
                );
            }
        }
        assert!(s.margin().unwrap() > 0.0);
        // the whole cell moved and turned: the same joints
        let motion = Isometry3::from_parts(
            Translation3::new(5000.0, -2000.0, 300.0),
            UnitQuaternion::from_euler_angles(0.1, -0.2, 1.3),
        );
        let moved = Holder {
            base: motion * h.base,
            ..h.clone()
        };
        let poses: Vec<_> = poses.iter().map(|t| motion * t).collect();
        let again = sweep(&moved, &poses, &p[0]).unwrap();
        for (a, b) in again.poses.iter().zip(&s.poses) {
            let (a, b) = (a.joints.unwrap(), b.joints.unwrap());
            assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-7));
        }
    }
}

#[test]
fn poses_out_of_reach_are_flagged_and_the_rest_solved() {
    let h = holder(RobotModel::irb1600_6_145());
    let p = path(
        deg([0.0, 10.0, 0.0, 0.0, 45.0, 0.0]),
        deg([10.0, 20.0, 5.0, 10.0, 50.0, 10.0]),
        5,
    );
    let mut poses = tcp(&h, &p);
    poses[2] = Isometry3::translation(0.0, 5000.0, 0.0) * poses[2];
    let s = sweep(&h, &poses, &p[0]).unwrap();
    assert_eq!(s.flags, vec![SweepFlag::OutOfReach(2)]);
    assert!(s.poses[2].joints.is_none() && s.poses[2].solutions == 0);
    assert!([0, 1, 3, 4].iter().all(|&i| s.poses[i].joints.is_some()));
}

#[test]
fn a_wrist_passing_axis_five_zero_changes_configuration() {
    // axis 5 from +20° to −20°: the nearest solutions follow it through zero, which
    // changes cfx (axis 5's sign)
    let h = holder(RobotModel::irb2600_12_165());
    let p = path(
        deg([0.0, 20.0, 0.0, 30.0, 20.0, 10.0]),
        deg([0.0, 20.0, 0.0, 30.0, -20.0, 10.0]),
        8,
    );
    let s = sweep(&h, &tcp(&h, &p), &p[0]).unwrap();
    assert!(
        s.flags
            .iter()
            .any(|f| matches!(f, SweepFlag::ConfigurationChange(_))),
        "{:?}",
        s.flags
    );
}

#[test]
fn a_long_turn_of_the_tool_is_followed_not_a_jump() {
    // axis 6 turning 90° between two poses: the move is followed in pieces, continuously
    let h = holder(RobotModel::irb4600_60_205());
    let a = deg([0.0, 20.0, 0.0, 0.0, 50.0, 0.0]);
    let b = deg([0.0, 20.0, 0.0, 0.0, 50.0, 90.0]);
    let s = sweep(&h, &tcp(&h, &[a, b]), &a).unwrap();
    assert!(s.is_clean(), "{:?}", s.flags);
    let j = s.poses[1].joints.unwrap();
    assert!((j[5] - 90.0).abs() < 1e-6, "{j:?}");
}

#[test]
fn a_wrist_flip_near_its_singularity_is_a_joint_jump() {
    // axis 5 at 2°: two flange poses a few degrees apart need axes 4 and 6 to swing 120°
    // the other way round; the straight move between them flips the wrist
    let h = holder(RobotModel::irb4600_60_205());
    let a = deg([0.0, 20.0, 0.0, 60.0, 2.0, -60.0]);
    let b = deg([0.0, 20.0, 0.0, -60.0, 2.0, 60.0]);
    let s = sweep(&h, &tcp(&h, &[a, b]), &a).unwrap();
    assert!(
        s.flags.iter().any(|f| matches!(
            f,
            SweepFlag::JointJump {
                pose: 1,
                axis: 4 | 6,
                ..
            }
        )),
        "{:?}",
        s.flags
    );
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let h = holder(RobotModel::irb1600_6_145());
    let nan = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(sweep(&h, &[nan], &[0.0; 6]).is_err());
    assert!(sweep(&h, &[], &[f64::NAN; 6]).is_err());
    let mut bad = h.clone();
    bad.model.opw.c3 = -1.0;
    assert!(sweep(&bad, &[], &[0.0; 6]).is_err());
    assert!(sweep(&h, &[], &[0.0; 6]).unwrap().is_clean());
}
