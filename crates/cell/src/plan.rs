//! Joint solutions along one robot's sweep of tool poses: every pose solved, and the
//! straight move from each pose to the next followed in short pieces the way the
//! controller moves (the tool linearly, the orientation by spherical interpolation,
//! every joint continuous), so the solution at each pose is the one the robot arrives
//! in. The first pose takes the solution nearest a start posture. What a program must not
//! contain is flagged: a pose or a piece of a move out of reach or past a joint limit, a
//! change of the arm configuration, a joint jump (a flip through a singularity).

use nalgebra::Isometry3;

use crate::conf::{conf, Conf};
use crate::error::{CellError, Result};
use crate::kinematics::{configurations, inverse, margins, nearest, Joints};
use crate::model::RobotModel;

/// A robot in the cell and what it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Holder {
    /// The robot.
    pub model: RobotModel,
    /// Its base frame in the cell's frame (mm).
    pub base: Isometry3<f64>,
    /// The tool frame: the held point (TCP) in the flange's frame (mm).
    pub tool: Isometry3<f64>,
}

/// Largest change of one joint over one short piece of a straight move (at most
/// [`PIECE_MM`] and [`PIECE_RAD`]) that still counts as continuous, radians (10°): a
/// larger one is a flip of the wrist or the arm through a singularity.
pub const MAX_STEP_RAD: f64 = 10.0 * std::f64::consts::PI / 180.0;
/// Longest piece a straight move is followed in, mm.
pub const PIECE_MM: f64 = 25.0;
/// Largest turn of a piece, radians (2.5°).
pub const PIECE_RAD: f64 = 2.5 * std::f64::consts::PI / 180.0;

/// The solution at one pose.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct PoseSolution {
    /// How many arm configurations reach the pose within the limits (whole turns of a
    /// joint not counted apart: [`crate::kinematics::configurations`]).
    pub solutions: usize,
    /// The chosen joints, degrees (`None`: out of reach).
    pub joints: Option<[f64; 6]>,
    /// Their configuration data.
    pub conf: Option<Conf>,
    /// The least margin of a joint to its limit, degrees.
    pub margin: Option<f64>,
}

/// What is wrong with a sweep.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub enum SweepFlag {
    /// No solution within the joint limits at this pose (index).
    OutOfReach(usize),
    /// The arm configuration (`cfx`) changes between this pose and the previous one.
    ConfigurationChange(usize),
    /// A joint moves more than [`MAX_STEP_RAD`] between this pose and the previous one.
    JointJump {
        /// Pose index.
        pose: usize,
        /// Axis, 1–6.
        axis: usize,
        /// The change, degrees.
        degrees: f64,
    },
}

/// One robot's sweep.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Sweep {
    /// Per pose.
    pub poses: Vec<PoseSolution>,
    /// Everything a program must not contain; empty when the sweep can be run as is.
    pub flags: Vec<SweepFlag>,
}

impl Sweep {
    /// Every pose solved, with no configuration change and no jump.
    pub fn is_clean(&self) -> bool {
        self.flags.is_empty()
    }

    /// The least joint margin over the sweep, degrees (`None`: no pose solved).
    pub fn margin(&self) -> Option<f64> {
        self.poses.iter().filter_map(|p| p.margin).reduce(f64::min)
    }
}

/// The solution a sweep starts with: among those with the wrist centre in front of axis 1
/// and of the lower arm (`cfx` 0 or 1, the arm's working posture) if any, the nearest
/// `start`.
fn first(model: &RobotModel, solutions: &[Joints], start: &Joints) -> Option<Joints> {
    let front: Vec<Joints> = solutions
        .iter()
        .filter(|q| conf(model, q).cfx < 2)
        .copied()
        .collect();
    nearest(if front.is_empty() { solutions } else { &front }, start)
}

/// How a straight move from `a` to `b` (tool poses, cell frame) goes from joints `q`:
/// the joints it arrives with, and its largest joint change over one piece (`None`: a
/// piece is out of reach).
fn follow(
    holder: &Holder,
    a: &Isometry3<f64>,
    b: &Isometry3<f64>,
    q: &Joints,
) -> Result<Option<(Joints, usize, f64)>> {
    let (d, turn) = crate::kinematics::pose_distance(a, b);
    let n = (d / PIECE_MM)
        .max(turn / PIECE_RAD)
        .ceil()
        .clamp(1.0, 100_000.0) as usize;
    let to_base = holder.base.inverse();
    let tool_inverse = holder.tool.inverse();
    let (mut q, mut worst) = (*q, (0, 0.0));
    for k in 1..=n {
        let w = k as f64 / n as f64;
        let p = Isometry3::from_parts(
            a.translation.vector.lerp(&b.translation.vector, w).into(),
            a.rotation.slerp(&b.rotation, w),
        );
        let solutions = inverse(&holder.model, &(to_base * p * tool_inverse), Some(&q))?;
        let Some(next) = nearest(&solutions, &q) else {
            return Ok(None);
        };
        for axis in 0..6 {
            let step = (next[axis] - q[axis]).abs();
            if step > worst.1 {
                worst = (axis, step);
            }
        }
        q = next;
    }
    Ok(Some((q, worst.0, worst.1)))
}

/// Solves the tool poses `tcp` (cell frame, mm) of one robot in order, starting from the
/// working-posture solution nearest `start` and following each straight move to the next pose. A pose
/// out of reach is flagged and the next pose starts again from `start`; so is a move
/// with a piece out of reach.
///
/// ```
/// use cell::plan::{sweep, Holder};
/// use cell::{forward, RobotModel};
/// use nalgebra::Isometry3;
///
/// // an IRB 1600 at the origin holding nothing (TCP at the flange), swept through the
/// // flange poses of a slow turn of axis 1
/// let holder = Holder {
///     model: RobotModel::irb1600_6_145(),
///     base: Isometry3::identity(),
///     tool: Isometry3::identity(),
/// };
/// let posture = |a: f64| [a, 0.2, -0.3, 0.4, 0.6, 0.5];
/// let tcp = (0..5).map(|i| forward(&holder.model, &posture(0.1 * i as f64))).collect::<Result<Vec<_>, _>>()?;
/// let s = sweep(&holder, &tcp, &posture(0.0))?;
/// assert!(s.is_clean());
/// // the robot follows the turn: axis 1 at 0°, 5.7°, 11.5°, … the others kept
/// for (i, p) in s.poses.iter().enumerate() {
///     let joints = p.joints.ok_or("out of reach")?;
///     assert!((joints[0] - (0.1 * i as f64).to_degrees()).abs() < 1e-6);
///     assert!((joints[4] - 0.6f64.to_degrees()).abs() < 1e-6);
/// }
/// assert!(s.margin().ok_or("no margin")? > 0.0);
/// // a pose 5 m away is flagged out of reach
/// let far = [tcp[0], Isometry3::translation(5000.0, 0.0, 0.0)];
/// assert!(!sweep(&holder, &far, &posture(0.0))?.is_clean());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`CellError::InvalidModel`] for a bad robot model, [`CellError::NotFinite`] for a pose
/// that is not finite.
pub fn sweep(holder: &Holder, tcp: &[Isometry3<f64>], start: &Joints) -> Result<Sweep> {
    holder.model.check()?;
    if !start.iter().all(|q| q.is_finite()) {
        return Err(CellError::NotFinite("start joints"));
    }
    let to_flange = holder.base.inverse();
    let tool_inverse = holder.tool.inverse();
    let mut poses = Vec::with_capacity(tcp.len());
    let mut flags = Vec::new();
    let mut previous: Option<Joints> = None;
    for (i, t) in tcp.iter().enumerate() {
        let flange = to_flange * t * tool_inverse;
        let solutions = inverse(&holder.model, &flange, previous.as_ref())?;
        let followed = match previous {
            Some(p) if !solutions.is_empty() => follow(holder, &tcp[i - 1], t, &p)?,
            _ => None,
        };
        let chosen = match (previous, followed) {
            (Some(_), Some((q, axis, step))) => {
                if step > MAX_STEP_RAD {
                    flags.push(SweepFlag::JointJump {
                        pose: i,
                        axis: axis + 1,
                        degrees: step.to_degrees(),
                    });
                }
                // the end of the followed move is one of the pose's solutions
                nearest(&solutions, &q)
            }
            (Some(_), None) if !solutions.is_empty() => {
                flags.push(SweepFlag::OutOfReach(i));
                first(&holder.model, &solutions, start)
            }
            _ => first(&holder.model, &solutions, start),
        };
        let Some(q) = chosen else {
            flags.push(SweepFlag::OutOfReach(i));
            poses.push(PoseSolution {
                solutions: 0,
                joints: None,
                conf: None,
                margin: None,
            });
            previous = None;
            continue;
        };
        let c = conf(&holder.model, &q);
        if let Some(p) = previous {
            if conf(&holder.model, &p).cfx != c.cfx {
                flags.push(SweepFlag::ConfigurationChange(i));
            }
        }
        let margin = margins(&holder.model, &q)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        poses.push(PoseSolution {
            solutions: configurations(&solutions),
            joints: Some(q.map(f64::to_degrees)),
            conf: Some(c),
            margin: Some(margin.to_degrees()),
        });
        previous = Some(q);
    }
    Ok(Sweep { poses, flags })
}
