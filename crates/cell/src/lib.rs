//! # cell — the robot cell of the hot blade
//!
//! The robots that hold the blade's ends (and, in a three-robot cell, the one that carries
//! the block) are 6-axis arms with an ortho-parallel base and a spherical wrist. This crate
//! gives their kinematics in the closed form of Brandstötter, Angerer and Hofbaur (2014),
//! "OPW". A posture of the arm to its flange pose and back, with its ABB configuration
//! data:
//!
//! ```
//! use cell::{conf, forward, inverse, nearest, RobotModel};
//!
//! let robot = RobotModel::irb1600_6_145();
//! let joints = [0.3, 0.2, -0.4, 0.5, 0.6, -0.7];
//! let flange = forward(&robot, &joints)?;
//! let solutions = inverse(&robot, &flange, None)?;
//! let back = nearest(&solutions, &joints).ok_or("out of reach")?;
//! assert!(solutions.len() > 1); // the other arm configurations reach the flange too
//! assert!(back.iter().zip(&joints).all(|(a, b)| (a - b).abs() < 1e-9));
//! assert_eq!(conf(&robot, &back).cfx, 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The modules:
//!
//! - [`model`]: OPW parameters and joint limits; built-in ABB IRB 1600-6/1.45,
//!   IRB 2600-12/1.65 and IRB 4600-60/2.05.
//! - [`opw`]: the closed form, in the paper's angles (our own; see the module for why).
//! - [`kinematics`]: forward kinematics; every inverse solution within the limits, verified
//!   by forward kinematics; the solution nearest a previous one; margins to the limits.
//! - [`conf`](mod@conf): ABB configuration data (`cf1`, `cf4`, `cf6`, `cfx`) of a solution.
//! - [`blade`]: the blade between its two held ends, in its plane, interpolated, rebuilt.
//! - [`equilibrium`]: the blade's equilibrium followed through every move of a program,
//!   with its stability margin, and every snap to another shape.
//! - [`fixture`]: the synchronized program of a cell that cuts blocks one at a time at a
//!   fixture — descend, cut, retreat, rise, travel — with both robots' joints.
//! - [`carrier`]: the same program in a three-robot cell where a robot carries the block
//!   through a blade that stays at a station.
//! - [`layout`]: a cell in millimetres, with the default cell (robots facing each other
//!   across the blade's mean chord, holders, fixture) placed for a job's blade poses.
//! - [`program`]: the whole program for a job's blade poses, the default layout searched
//!   over table heights, standoffs, holder styles and wrist sides.
//! - [`plan`]: a robot's sweep of tool poses solved in order, continuous from a start
//!   posture, with every pose out of reach, configuration change and joint jump flagged.
//!
//! Like the other algorithm crates it does no I/O. Lengths are millimetres, angles radians.

/// The hot blade between its held ends: poses, interpolation, shape.
pub mod blade;
/// The program of a three-robot cell whose third robot carries the block.
pub mod carrier;
/// ABB configuration data of a joint solution.
pub mod conf;
/// The blade's equilibrium followed through a program's moves: margins and snaps.
pub mod equilibrium;
/// Errors of the robot cell.
pub mod error;
/// The whole program of a two-robot cell cutting blocks one at a time at a fixture.
pub mod fixture;
/// Forward and inverse kinematics, joint choice, limit margins.
pub mod kinematics;
/// A cell in millimetres with the default cell where parts are left out.
pub mod layout;
/// Robot models: OPW parameters, joint limits, built-in ABB arms.
pub mod model;
/// The closed-form OPW kinematics in the paper's angles.
pub mod opw;
/// Joint solutions along a robot's sweep of tool poses, with flags.
pub mod plan;
/// The whole program of a cell for a job's blade poses, with the default layout searched.
pub mod program;

pub use conf::{conf, Conf};
pub use error::{CellError, Result};
pub use kinematics::{forward, inverse, nearest, Joints};
pub use model::RobotModel;

/// Runs `f` over `items` in order: in parallel with the `parallel` feature. The results
/// come back in the items' order either way.
pub(crate) fn map_in_order<T: Sync, R: Send>(
    items: &[T],
    f: impl Fn(&T) -> R + Sync + Send,
) -> Vec<R> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items.par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        items.iter().map(f).collect()
    }
}
