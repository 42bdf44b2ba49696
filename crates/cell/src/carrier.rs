//! The program of a three-robot cell in which a third robot carries the block through the
//! blade, like a conveyor (the pilot cell of "Robotic Hot-Blade Cutting" §4).
//!
//! The blade works at a *station*: a frame of the cell whose origin is the blade's chord
//! midpoint, whose x-axis is the chord (first end to second) and whose z-axis is the
//! cutting plane's normal. The blade never leaves it: its two robots only change its shape
//! (chord length and end angles). Everything else is the block's motion.
//!
//! The program is the fixture's ([`crate::fixture::moves`]) seen from the block: the same
//! moves of the blade relative to the block — descend to the approach, cut, retreat, rise
//! above the block, travel to the next block, with the same clearances and the same
//! admissible blade shapes — and, for each, the block's pose that puts the blade at the
//! station. A relative pose with chord frame `F` (chord midpoint, chord, normal, in the
//! block's frame) puts the block at `S · F⁻¹`; the blade's ends are then at
//! `S · F⁻¹ · end`. So where the fixture's blade rises above the block, here the block
//! goes down under the blade; where the fixture's blade travels to the next block, here
//! the next block comes under the blade. Blocks are changed in the carrier's gripper at
//! the same points of the program as at the fixture: the first before its descent, each
//! next one while the cut block is down under the risen blade.

use nalgebra::{Isometry3, Translation3};

use crate::blade::{planar, BladePose};
use crate::error::Result;
use crate::fixture::{
    moves as relative_moves, summarize, BlockCheck, BlockCut, FixtureCell, Moves,
};
use crate::kinematics::{pose_distance, Joints};
use crate::plan::{sweep, Holder, PoseSolution, Sweep, SweepFlag, PIECE_MM, PIECE_RAD};

/// The cell and how the blade and the block move in it.
#[derive(Debug, Clone, PartialEq)]
pub struct CarrierCell {
    /// The robots holding the blade's first and second end.
    pub holders: [Holder; 2],
    /// The robot carrying the block; its tool frame is the block's frame (min corner; axes
    /// along the cut, across it, up) in its flange's frame: the grip.
    pub carrier: Holder,
    /// Where the blade cuts, in the cell's frame (mm): origin at the chord's midpoint, x
    /// along the chord, z the cutting plane's normal.
    pub station: Isometry3<f64>,
    /// The blade's length, mm.
    pub blade_length: f64,
    /// The largest curvature the blade may take between blocks, 1/mm (`None`: any).
    pub max_curvature: Option<f64>,
    /// Approach and retreat distance along the cutting plane's normal, mm (> 0).
    pub approach: f64,
    /// Distance of the whole blade from a block while the block passes under it, mm.
    pub clearance: f64,
    /// Largest step of a relative travel, mm, and of a rotation or end angle, radians.
    pub travel_step: (f64, f64),
    /// The postures the robots start from: first end's, second end's, carrier's.
    pub start: [Joints; 3],
}

/// The planned program.
#[derive(Debug, Clone, PartialEq)]
pub struct CarriedProgram {
    /// Every move of the blade relative to the block it is at (its ends in the block's
    /// frame, mm), in order.
    pub moves: Moves,
    /// The carried block's frame in the cell's frame at each move, mm.
    pub block_poses: Vec<Isometry3<f64>>,
    /// Each robot's solution at every move: first end's, second end's, carrier's.
    pub solutions: [Vec<PoseSolution>; 3],
    /// Each robot's flags, by move.
    pub flags: [Vec<SweepFlag>; 3],
    /// Per block, robots in the same order.
    pub blocks: Vec<BlockCheck>,
}

impl CarriedProgram {
    /// The blade's ends in the cell's frame at move `k`.
    ///
    /// ```
    /// # use cell::blade::{from_planar, PlanarPose};
    /// # use cell::carrier::CarrierCell;
    /// # use cell::fixture::BlockCut;
    /// # use cell::plan::Holder;
    /// # use cell::RobotModel;
    /// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
    /// #
    /// # // the rotation whose x- and z-axes are `x` and `z`
    /// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
    /// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
    /// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
    /// # };
    /// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
    /// # // its end of the blade 150 mm in front of its flange
    /// # let holder = |y: f64, yaw: f64| Holder {
    /// #     model: RobotModel::irb2600_12_165(),
    /// #     base: Isometry3::from_parts(
    /// #         Translation3::new(0.0, y, 0.0),
    /// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
    /// #     ),
    /// #     tool: Isometry3::from_parts(
    /// #         Translation3::new(0.0, 0.0, 150.0),
    /// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
    /// #     ),
    /// # };
    /// # let quarter = std::f64::consts::FRAC_PI_2;
    /// # // an IRB 4600 behind the blade carrying the block from below, its flange 200 mm under the
    /// # // floor's middle and tilted 75° towards the blade; the blade's chord along y 1 m up
    /// # let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 75f64.to_radians());
    /// # let grip = Isometry3::from_parts(Translation3::new(300.0, 300.0, -200.0), tilt);
    /// # let cell = CarrierCell {
    /// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
    /// #     carrier: Holder {
    /// #         model: RobotModel::irb4600_60_205(),
    /// #         base: Isometry3::translation(-1300.0, 0.0, 0.0),
    /// #         tool: grip.inverse(),
    /// #     },
    /// #     station: Isometry3::from_parts(
    /// #         Translation3::new(0.0, 0.0, 1000.0),
    /// #         rotation(Vector3::y(), Vector3::x()),
    /// #     ),
    /// #     blade_length: 800.0,
    /// #     max_curvature: None,
    /// #     approach: 50.0,
    /// #     clearance: 100.0,
    /// #     travel_step: (100.0, 5f64.to_radians()),
    /// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 3],
    /// # };
    /// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
    /// # let turn: f64 = 0.35;
    /// # let arch = |along: f64| from_planar(&PlanarPose {
    /// #     mid: Vector3::new(along, 300.0, 350.0),
    /// #     frame: rotation(Vector3::y(), Vector3::x()),
    /// #     chord: 800.0 * turn.sin() / turn * 0.98,
    /// #     angles: [turn, -turn],
    /// # });
    /// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
    /// let program = cell::carrier::plan(&cell, &blocks)?;
    /// // move k's ends, relative to the block, put where the block is
    /// let k = 2;
    /// let world = program.blade(k);
    /// let expected = program.block_poses[k] * program.moves.steps[k].ends[0];
    /// assert!((world[0].translation.vector - expected.translation.vector).norm() < 1e-12);
    /// # Ok::<(), cell::CellError>(())
    /// ```
    pub fn blade(&self, k: usize) -> BladePose {
        let b = &self.block_poses[k];
        self.moves.steps[k].ends.map(|e| b * e)
    }
}

/// The block's frame in the cell that puts the blade of relative pose `ends` (in the
/// block's frame) at `station`.
///
/// ```
/// use cell::blade::{from_planar, planar, PlanarPose};
/// use cell::carrier::block_pose;
/// use nalgebra::{Isometry3, UnitQuaternion, Vector3};
/// // the blade 700 across a block at (300, 300, 350) in the block's frame, its plane
/// // facing along x; the station 1 m up in the cell, turned about z
/// let ends = from_planar(&PlanarPose {
///     mid: Vector3::new(300.0, 300.0, 350.0),
///     frame: UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1),
///     chord: 700.0,
///     angles: [0.3, -0.3],
/// });
/// let station = Isometry3::new(Vector3::new(0.0, 0.0, 1000.0), Vector3::z() * 0.5);
/// let block = block_pose(&station, &ends)?;
/// // with the block there the blade's chord is the station's x, centred on it
/// let q = planar(&ends.map(|e| block * e))?;
/// assert!((q.mid - station.translation.vector).norm() < 1e-9);
/// assert!(q.frame.angle_to(&station.rotation) < 1e-6);
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// [`crate::CellError::Blade`] when the ends coincide or the normal lies along the chord.
pub fn block_pose(station: &Isometry3<f64>, ends: &BladePose) -> Result<Isometry3<f64>> {
    let q = planar(ends)?;
    let chord = Isometry3::from_parts(Translation3::from(q.mid), q.frame);
    Ok(station * chord.inverse())
}

/// The relative moves through `blocks` (in cutting order; blocks without poses are
/// skipped) and the block's pose at each.
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use cell::carrier::CarrierCell;
/// use cell::fixture::BlockCut;
/// use cell::plan::Holder;
/// use cell::RobotModel;
/// use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
///
/// // the rotation whose x- and z-axes are `x` and `z`
/// let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
///     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
///     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// };
/// // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// // its end of the blade 150 mm in front of its flange
/// let holder = |y: f64, yaw: f64| Holder {
///     model: RobotModel::irb2600_12_165(),
///     base: Isometry3::from_parts(
///         Translation3::new(0.0, y, 0.0),
///         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
///     ),
///     tool: Isometry3::from_parts(
///         Translation3::new(0.0, 0.0, 150.0),
///         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
///     ),
/// };
/// let quarter = std::f64::consts::FRAC_PI_2;
/// // an IRB 4600 behind the blade carrying the block from below, its flange 200 mm under the
/// // floor's middle and tilted 75° towards the blade; the blade's chord along y 1 m up
/// let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 75f64.to_radians());
/// let grip = Isometry3::from_parts(Translation3::new(300.0, 300.0, -200.0), tilt);
/// let cell = CarrierCell {
///     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
///     carrier: Holder {
///         model: RobotModel::irb4600_60_205(),
///         base: Isometry3::translation(-1300.0, 0.0, 0.0),
///         tool: grip.inverse(),
///     },
///     station: Isometry3::from_parts(
///         Translation3::new(0.0, 0.0, 1000.0),
///         rotation(Vector3::y(), Vector3::x()),
///     ),
///     blade_length: 800.0,
///     max_curvature: None,
///     approach: 50.0,
///     clearance: 100.0,
///     travel_step: (100.0, 5f64.to_radians()),
///     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 3],
/// };
/// // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// let turn: f64 = 0.35;
/// let arch = |along: f64| from_planar(&PlanarPose {
///     mid: Vector3::new(along, 300.0, 350.0),
///     frame: rotation(Vector3::y(), Vector3::x()),
///     chord: 800.0 * turn.sin() / turn * 0.98,
///     angles: [turn, -turn],
/// });
/// let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let (m, poses) = cell::carrier::moves(&cell, &blocks)?;
/// assert_eq!(poses.len(), m.steps.len());
/// // at every move the block is where the blade, relative to it, sits at the station
/// for (step, block) in m.steps.iter().zip(&poses) {
///     let ends = step.ends.map(|e| block * e);
///     let q = cell::blade::planar(&ends)?;
///     assert!((q.mid - cell.station.translation.vector).norm() < 1e-9);
/// }
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// Those of [`crate::fixture::moves`] and [`block_pose`].
pub fn moves(cell: &CarrierCell, blocks: &[BlockCut]) -> Result<(Moves, Vec<Isometry3<f64>>)> {
    // the fixture's planner in the block's own frame: "up" is the block's z
    let relative = FixtureCell {
        holders: cell.holders.clone(),
        fixture: Isometry3::identity(),
        blade_length: cell.blade_length,
        max_curvature: cell.max_curvature,
        approach: cell.approach,
        clearance: cell.clearance,
        travel_step: cell.travel_step,
        start: [cell.start[0], cell.start[1]],
    };
    let m = relative_moves(&relative, blocks)?;
    let poses = m
        .steps
        .iter()
        .map(|s| block_pose(&cell.station, &s.ends))
        .collect::<Result<Vec<_>>>()?;
    Ok((m, poses))
}

/// The pose a fraction `w` of the way from `a` to `b` as the controller moves a TCP: the
/// position linearly, the orientation by spherical interpolation.
fn lerp(a: &Isometry3<f64>, b: &Isometry3<f64>, w: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        a.translation.vector.lerp(&b.translation.vector, w).into(),
        a.rotation.slerp(&b.rotation, w),
    )
}

/// The world path of blade end `e`'s TCP: in coordinated motion the end moves linearly in
/// the block's frame while the block moves linearly in the world, so between two moves
/// the end follows `block(w) · end(w)`, sampled in pieces no longer than the planner's
/// ([`PIECE_MM`], [`PIECE_RAD`]) for either factor. Returns the sampled poses and, for
/// each, the move it belongs to (a move's own pose last).
fn coordinated_path(
    moves: &Moves,
    poses: &[Isometry3<f64>],
    e: usize,
) -> (Vec<Isometry3<f64>>, Vec<usize>) {
    let steps = &moves.steps;
    let (mut path, mut owner) = (Vec::new(), Vec::new());
    for k in 0..steps.len() {
        if k > 0 {
            let (a, b) = (&poses[k - 1], &poses[k]);
            let (ra, rb) = (&steps[k - 1].ends[e], &steps[k].ends[e]);
            let (d1, t1) = pose_distance(a, b);
            let (d2, t2) = pose_distance(ra, rb);
            let n = (d1.max(d2) / PIECE_MM)
                .max(t1.max(t2) / PIECE_RAD)
                .ceil()
                .clamp(1.0, 100_000.0) as usize;
            for j in 1..n {
                let w = j as f64 / n as f64;
                path.push(lerp(a, b, w) * lerp(ra, rb, w));
                owner.push(k);
            }
        }
        path.push(poses[k] * steps[k].ends[e]);
        owner.push(k);
    }
    (path, owner)
}

/// A sweep along a sampled path, reduced to the moves: each move's solution at its own
/// pose, each flag on the move its sample belongs to (once per kind and axis).
fn per_move(sw: Sweep, owner: &[usize]) -> Sweep {
    let mut poses = Vec::new();
    for (i, p) in sw.poses.into_iter().enumerate() {
        if owner.get(i + 1) != owner.get(i) {
            poses.push(p);
        }
    }
    let mut flags: Vec<SweepFlag> = Vec::new();
    for f in sw.flags {
        let f = match f {
            SweepFlag::OutOfReach(i) => SweepFlag::OutOfReach(owner[i]),
            SweepFlag::ConfigurationChange(i) => SweepFlag::ConfigurationChange(owner[i]),
            SweepFlag::JointJump {
                pose,
                axis,
                degrees,
            } => SweepFlag::JointJump {
                pose: owner[pose],
                axis,
                degrees,
            },
        };
        let same = |g: &SweepFlag| match (g, &f) {
            (
                SweepFlag::JointJump {
                    pose: a, axis: x, ..
                },
                SweepFlag::JointJump {
                    pose: b, axis: y, ..
                },
            ) => a == b && x == y,
            (g, f) => g == f,
        };
        if !flags.iter().any(same) {
            flags.push(f);
        }
    }
    Sweep { poses, flags }
}

/// All three robots' joints along `moves` with the block at `poses`, and the summary. The
/// carrier's TCP (the block's frame) moves linearly in the world; each blade end moves
/// linearly in the block's frame (coordinated motion), and its robot is followed along
/// that composed path. The first move is the exception: it starts from wherever the robots
/// stand, and the blade's robots make it in the world.
///
/// ```
/// # use cell::blade::{from_planar, PlanarPose};
/// # use cell::carrier::CarrierCell;
/// # use cell::fixture::BlockCut;
/// # use cell::plan::Holder;
/// # use cell::RobotModel;
/// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
/// #
/// # // the rotation whose x- and z-axes are `x` and `z`
/// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
/// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
/// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// # };
/// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// # // its end of the blade 150 mm in front of its flange
/// # let holder = |y: f64, yaw: f64| Holder {
/// #     model: RobotModel::irb2600_12_165(),
/// #     base: Isometry3::from_parts(
/// #         Translation3::new(0.0, y, 0.0),
/// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
/// #     ),
/// #     tool: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 150.0),
/// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// # };
/// # let quarter = std::f64::consts::FRAC_PI_2;
/// # // an IRB 4600 behind the blade carrying the block from below, its flange 200 mm under the
/// # // floor's middle and tilted 75° towards the blade; the blade's chord along y 1 m up
/// # let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 75f64.to_radians());
/// # let grip = Isometry3::from_parts(Translation3::new(300.0, 300.0, -200.0), tilt);
/// # let cell = CarrierCell {
/// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
/// #     carrier: Holder {
/// #         model: RobotModel::irb4600_60_205(),
/// #         base: Isometry3::translation(-1300.0, 0.0, 0.0),
/// #         tool: grip.inverse(),
/// #     },
/// #     station: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 1000.0),
/// #         rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// #     blade_length: 800.0,
/// #     max_curvature: None,
/// #     approach: 50.0,
/// #     clearance: 100.0,
/// #     travel_step: (100.0, 5f64.to_radians()),
/// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 3],
/// # };
/// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// # let turn: f64 = 0.35;
/// # let arch = |along: f64| from_planar(&PlanarPose {
/// #     mid: Vector3::new(along, 300.0, 350.0),
/// #     frame: rotation(Vector3::y(), Vector3::x()),
/// #     chord: 800.0 * turn.sin() / turn * 0.98,
/// #     angles: [turn, -turn],
/// # });
/// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let (m, poses) = cell::carrier::moves(&cell, &blocks)?;
/// let program = cell::carrier::solve(&cell, &m, &poses)?;
/// assert_eq!(program.solutions.len(), 3); // both blade robots and the carrier
/// assert!(program.solutions.iter().all(|s| s.len() == m.steps.len()));
/// // the blade stays at the station at every move
/// for k in 0..m.steps.len() {
///     let q = cell::blade::planar(&program.blade(k))?;
///     assert!((q.mid - cell.station.translation.vector).norm() < 1e-9);
/// }
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// The errors of [`sweep`].
pub fn solve(
    cell: &CarrierCell,
    moves: &Moves,
    poses: &[Isometry3<f64>],
) -> Result<CarriedProgram> {
    let mut solutions: [Vec<PoseSolution>; 3] = Default::default();
    let mut flags: [Vec<SweepFlag>; 3] = Default::default();
    for r in 0..3 {
        let sw = if r == 2 {
            sweep(&cell.carrier, poses, &cell.start[2])?
        } else {
            let (path, owner) = coordinated_path(moves, poses, r);
            per_move(sweep(&cell.holders[r], &path, &cell.start[r])?, &owner)
        };
        solutions[r] = sw.poses;
        flags[r] = sw.flags;
    }
    let blocks = summarize(moves, &solutions, &flags);
    Ok(CarriedProgram {
        moves: moves.clone(),
        block_poses: poses.to_vec(),
        solutions,
        flags,
        blocks,
    })
}

/// Plans the program of `blocks` (in cutting order): [`moves`], then [`solve`].
///
/// ```
/// # use cell::blade::{from_planar, PlanarPose};
/// # use cell::carrier::CarrierCell;
/// # use cell::fixture::BlockCut;
/// # use cell::plan::Holder;
/// # use cell::RobotModel;
/// # use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
/// #
/// # // the rotation whose x- and z-axes are `x` and `z`
/// # let rotation = |x: Vector3<f64>, z: Vector3<f64>| {
/// #     let m = Matrix3::from_columns(&[x, z.cross(&x), z]);
/// #     UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
/// # };
/// # // two IRB 2600 facing each other across the cut (x), 1200 mm either side, each holding
/// # // its end of the blade 150 mm in front of its flange
/// # let holder = |y: f64, yaw: f64| Holder {
/// #     model: RobotModel::irb2600_12_165(),
/// #     base: Isometry3::from_parts(
/// #         Translation3::new(0.0, y, 0.0),
/// #         UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
/// #     ),
/// #     tool: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 150.0),
/// #         rotation(-Vector3::z(), Vector3::x()).inverse() * rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// # };
/// # let quarter = std::f64::consts::FRAC_PI_2;
/// # // an IRB 4600 behind the blade carrying the block from below, its flange 200 mm under the
/// # // floor's middle and tilted 75° towards the blade; the blade's chord along y 1 m up
/// # let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 75f64.to_radians());
/// # let grip = Isometry3::from_parts(Translation3::new(300.0, 300.0, -200.0), tilt);
/// # let cell = CarrierCell {
/// #     holders: [holder(-1200.0, quarter), holder(1200.0, -quarter)],
/// #     carrier: Holder {
/// #         model: RobotModel::irb4600_60_205(),
/// #         base: Isometry3::translation(-1300.0, 0.0, 0.0),
/// #         tool: grip.inverse(),
/// #     },
/// #     station: Isometry3::from_parts(
/// #         Translation3::new(0.0, 0.0, 1000.0),
/// #         rotation(Vector3::y(), Vector3::x()),
/// #     ),
/// #     blade_length: 800.0,
/// #     max_curvature: None,
/// #     approach: 50.0,
/// #     clearance: 100.0,
/// #     travel_step: (100.0, 5f64.to_radians()),
/// #     start: [[0.0, 0.0, 0.0, 0.0, 0.5, 0.0]; 3],
/// # };
/// # // a 600 mm block cut along x by arches of the blade, its ends turned 0.35 rad
/// # let turn: f64 = 0.35;
/// # let arch = |along: f64| from_planar(&PlanarPose {
/// #     mid: Vector3::new(along, 300.0, 350.0),
/// #     frame: rotation(Vector3::y(), Vector3::x()),
/// #     chord: 800.0 * turn.sin() / turn * 0.98,
/// #     angles: [turn, -turn],
/// # });
/// # let blocks = [BlockCut { block: 1, size: [600.0; 3], poses: (0..3).map(|k| arch(300.0 * k as f64)).collect(), shapes: Vec::new() }];
/// let program = cell::carrier::plan(&cell, &blocks)?;
/// let (m, poses) = cell::carrier::moves(&cell, &blocks)?;
/// assert_eq!(program, cell::carrier::solve(&cell, &m, &poses)?);
/// // every cutting move reached by all three robots
/// for (k, step) in m.steps.iter().enumerate() {
///     if step.heat {
///         assert!(program.solutions.iter().all(|s| s[k].joints.is_some()), "move {k}");
///     }
/// }
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// As [`moves`] and [`solve`].
pub fn plan(cell: &CarrierCell, blocks: &[BlockCut]) -> Result<CarriedProgram> {
    let (m, poses) = moves(cell, blocks)?;
    solve(cell, &m, &poses)
}
