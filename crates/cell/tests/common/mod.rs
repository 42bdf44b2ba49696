//! Blocks of arched blade poses shared by the cell's tests.

use cell::blade::{from_planar, PlanarPose};
use cell::fixture::BlockCut;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

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
