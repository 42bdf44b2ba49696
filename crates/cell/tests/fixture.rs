//! The fixture cell's program on blocks of arched blade poses: every move's chosen joints
//! reach its target through forward kinematics (1e-6 mm, 1e-9 rad) with the stated
//! configuration data, the blade never stretches, the heat is on exactly from the entry
//! into a block to the retreat, the blade clears the blocks between them, and the program
//! does not change when the whole cell is moved rigidly.

mod common;

use cell::blade::{planar, shape, BladePose};
use cell::fixture::{plan, BlockCut, CellProgram, FixtureCell, Phase};
use common::{blade_holders, blocks, reaches, same_robot, BLADE};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

/// Two IRB 2600 facing each other across a fixture 200 mm up, holders facing along the
/// cut with the blade 150 mm in front of the flange.
fn cell() -> FixtureCell {
    FixtureCell {
        holders: blade_holders(),
        fixture: Isometry3::translation(-300.0, -300.0, 200.0),
        blade_length: BLADE,
        max_curvature: None,
        approach: 50.0,
        clearance: 100.0,
        travel_step: (100.0, 5f64.to_radians()),
        start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 2],
    }
}

/// Every check of the module's doc on one program. A move out of reach must be flagged;
/// every cutting move must be reached (this cell reaches the blocks).
fn check(cell: &FixtureCell, blocks: &[BlockCut], p: &CellProgram) {
    for (k, s) in p.steps.iter().enumerate() {
        let world: BladePose = [cell.fixture * s.ends[0], cell.fixture * s.ends[1]];
        // the chord never exceeds the blade (the blade is mounted straight, a blade
        // length apart, only at the first move), and the blade between is an elastica
        let q = planar(&world).unwrap();
        if s.phase == Phase::Load {
            assert!(
                k == 0 && (q.chord - BLADE).abs() < 1e-9,
                "move {k}: load at {}",
                q.chord
            );
        } else {
            assert!(q.chord < BLADE, "move {k}: chord {}", q.chord);
        }
        let blade = shape(&world, BLADE).unwrap();
        // heat exactly on the moves that cut: into the block, through it, out of it
        assert_eq!(
            s.heat,
            matches!(s.phase, Phase::Cut | Phase::Retreat),
            "move {k}"
        );
        if matches!(
            s.phase,
            Phase::Load | Phase::Bend | Phase::Rise | Phase::Travel | Phase::Start
        ) {
            let top = 200.0 + 600.0;
            assert!(
                blade.lowest() >= top + cell.clearance - 1e-6,
                "move {k}: {}",
                blade.lowest()
            );
        }
        for (r, (h, end)) in cell.holders.iter().zip(&world).enumerate() {
            let reached = reaches(h, &p.solutions[r][k], &p.flags[r], end, (k, r));
            assert!(
                reached || s.phase != Phase::Cut,
                "move {k} robot {r}: a cut out of reach"
            );
        }
    }
    // blocks in order, each placed once, each cut through every pose
    let changes: Vec<_> = p.steps.iter().filter_map(|s| s.change).collect();
    let numbers: Vec<usize> = blocks.iter().map(|b| b.block).collect();
    assert_eq!(changes.iter().map(|c| c.1).collect::<Vec<_>>(), numbers);
    let cuts = p.steps.iter().filter(|s| s.phase == Phase::Cut).count();
    assert_eq!(cuts, blocks.iter().map(|b| b.poses.len()).sum::<usize>());
}

#[test]
fn every_chosen_joint_reaches_its_target_and_the_blade_stays_safe() {
    let (cell, blocks) = (cell(), blocks(0.35, 0.2));
    let p = plan(&cell, &blocks).unwrap();
    check(&cell, &blocks, &p);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn moving_the_whole_cell_changes_nothing(
        turn in 0.15f64..0.45, tilt in -0.25f64..0.25,
        shift in proptest::array::uniform3(-2000.0f64..2000.0), yaw in -3.1f64..3.1,
    ) {
        let (cell, blocks) = (cell(), blocks(turn, tilt));
        let p = plan(&cell, &blocks).unwrap();
        check(&cell, &blocks, &p);
        // a rigid motion that keeps "up": bases and fixture moved together
        let g = Isometry3::from_parts(
            Translation3::new(shift[0], shift[1], shift[2]),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        );
        let mut moved = cell.clone();
        moved.fixture = g * cell.fixture;
        for h in &mut moved.holders {
            h.base = g * h.base;
        }
        let q = plan(&moved, &blocks).unwrap();
        prop_assert_eq!(p.steps.len(), q.steps.len());
        for r in 0..2 {
            same_robot(
                (&p.solutions[r], &p.flags[r]),
                (&q.solutions[r], &q.flags[r]),
            )?;
        }
    }
}
