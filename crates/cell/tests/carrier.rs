//! The carried-block cell's program: the blade never leaves the station (its chord's
//! midpoint at the station's origin, its chord along the station's x, its plane the
//! station's), the blade clears the block between blocks and never passes under its floor
//! (where the gripper holds it), every
//! reached move's joints land on the target through forward kinematics (1e-6 mm, 1e-9
//! rad) — the carrier's on the block's frame, the holders' on the blade's ends — with
//! the stated configuration data, and moving the whole cell rigidly (any rotation: the
//! carried cell has no "up" of its own) changes no joint.

mod common;

use cell::blade::{planar, shape};
use cell::carrier::{plan, CarriedProgram, CarrierCell};
use cell::fixture::{BlockCut, Phase};
use cell::model::RobotModel;
use cell::plan::Holder;
use common::{base, blade_holders, blocks, reaches, rotation, same_robot, BLADE};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

/// The pilot cell: two IRB 2600 holding the blade across a station 1 m up (chord along
/// y, plane facing +x), an IRB 4600 behind it carrying the block from below, its flange
/// 200 mm under the floor's middle and tilted 75° towards the blade.
fn cell() -> CarrierCell {
    let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 75f64.to_radians());
    let flange = Isometry3::from_parts(Translation3::new(300.0, 300.0, -200.0), tilt);
    CarrierCell {
        holders: blade_holders(),
        carrier: Holder {
            model: RobotModel::irb4600_60_205(),
            base: base(-1300.0, 0.0, 0.0),
            tool: flange.inverse(),
        },
        station: Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 1000.0),
            rotation(Vector3::y(), Vector3::x()),
        ),
        blade_length: BLADE,
        max_curvature: None,
        approach: 50.0,
        clearance: 100.0,
        travel_step: (100.0, 5f64.to_radians()),
        start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 3],
    }
}

/// Every check of the module's doc on one program.
fn check(cell: &CarrierCell, blocks: &[BlockCut], p: &CarriedProgram) {
    // the blade against the block, in the block's frame: above it by the clearance
    // between blocks, and never under its floor within its footprint (where the gripper
    // holds it)
    for (k, st) in p.moves.steps.iter().enumerate() {
        let size = blocks.iter().find(|b| b.block == st.block).unwrap().size;
        let blade = shape(&st.ends, BLADE).unwrap();
        if matches!(st.phase, Phase::Rise | Phase::Travel | Phase::Start) {
            assert!(
                blade.lowest() >= size[2] + cell.clearance - 1e-6,
                "move {k}"
            );
        }
        let under = blade.points.iter().any(|q| {
            q[2] < 0.0 && (0.0..=size[0]).contains(&q[0]) && (0.0..=size[1]).contains(&q[1])
        });
        assert!(!under, "move {k}: the blade passes under the block's floor");
    }
    let s = &cell.station;
    for k in 0..p.moves.steps.len() {
        let world = p.blade(k);
        let q = planar(&world).unwrap();
        assert!((q.mid - s.translation.vector).norm() < 1e-9, "move {k}");
        let along = |v: Vector3<f64>| (q.frame * v - s.rotation * v).norm();
        assert!(
            along(Vector3::x()) < 1e-9 && along(Vector3::z()) < 1e-9,
            "move {k}"
        );
        let targets = [world[0], world[1], p.block_poses[k]];
        let arms = [&cell.holders[0], &cell.holders[1], &cell.carrier];
        for (r, (h, target)) in arms.iter().zip(&targets).enumerate() {
            reaches(h, &p.solutions[r][k], &p.flags[r], target, (k, r));
        }
    }
}

#[test]
fn the_blade_stays_at_the_station_and_every_joint_reaches_its_target() {
    let (cell, blocks) = (cell(), blocks(0.35, 0.2));
    let p = plan(&cell, &blocks).unwrap();
    check(&cell, &blocks, &p);
    // this cell reaches every move of these blocks without a flip
    assert!(p.flags.iter().all(Vec::is_empty), "{:?}", p.flags);
    assert!(p.blocks.iter().all(|b| b.is_clean() && b.robots.len() == 3));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn moving_the_whole_carried_cell_changes_nothing(
        turn in 0.15f64..0.45, tilt in -0.25f64..0.25,
        shift in proptest::array::uniform3(-2000.0f64..2000.0),
        axis in proptest::array::uniform3(-1.0f64..1.0), angle in -3.1f64..3.1,
    ) {
        let (cell, blocks) = (cell(), blocks(turn, tilt));
        let p = plan(&cell, &blocks).unwrap();
        check(&cell, &blocks, &p);
        let axis = Vector3::from(axis);
        prop_assume!(axis.norm() > 0.1);
        let g = Isometry3::from_parts(
            Translation3::new(shift[0], shift[1], shift[2]),
            UnitQuaternion::from_scaled_axis(axis.normalize() * angle),
        );
        let mut moved = cell.clone();
        moved.station = g * cell.station;
        for h in moved.holders.iter_mut().chain([&mut moved.carrier]) {
            h.base = g * h.base;
        }
        let q = plan(&moved, &blocks).unwrap();
        prop_assert_eq!(&p.moves, &q.moves);
        for r in 0..3 {
            same_robot(
                (&p.solutions[r], &p.flags[r]),
                (&q.solutions[r], &q.flags[r]),
            )?;
        }
    }
}
