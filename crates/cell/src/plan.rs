//! Joint solutions along one robot's sweep of tool poses: every pose solved, the solution
//! at each pose the nearest to the previous one (the first: the nearest to a start
//! posture), and what a program must not contain flagged — a pose out of reach or past a
//! joint limit, a change of arm or wrist configuration, a joint jump.

use nalgebra::Isometry3;
use schemars::JsonSchema;
use serde::Serialize;

use crate::conf::{conf, Conf};
use crate::error::{CellError, Result};
use crate::kinematics::{inverse, margins, nearest, Joints};
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

/// Largest change of one joint between two poses of a sweep that still counts as
/// continuous, radians (30°): the targets of a sweep are close, so a larger step is a flip
/// of the wrist or the arm.
pub const MAX_STEP_RAD: f64 = std::f64::consts::FRAC_PI_6;

/// The solution at one pose.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PoseSolution {
    /// How many joint solutions reach the pose within the limits.
    pub solutions: usize,
    /// The chosen joints, degrees (`None`: out of reach).
    pub joints: Option<[f64; 6]>,
    /// Their configuration data.
    pub conf: Option<Conf>,
    /// The least margin of a joint to its limit, degrees.
    pub margin: Option<f64>,
}

/// What is wrong with a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
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
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
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

/// Solves the tool poses `tcp` (cell frame, mm) of one robot in order, starting from the
/// solution nearest `start`. A pose out of reach is flagged and the next pose starts again
/// from `start`.
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
        let hint = previous.unwrap_or(*start);
        let solutions = inverse(&holder.model, &flange, previous.as_ref())?;
        let Some(q) = nearest(&solutions, &hint) else {
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
            for axis in 0..6 {
                let step = (q[axis] - p[axis]).abs();
                if step > MAX_STEP_RAD {
                    flags.push(SweepFlag::JointJump {
                        pose: i,
                        axis: axis + 1,
                        degrees: step.to_degrees(),
                    });
                }
            }
        }
        let margin = margins(&holder.model, &q)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        poses.push(PoseSolution {
            solutions: solutions.len(),
            joints: Some(q.map(f64::to_degrees)),
            conf: Some(c),
            margin: Some(margin.to_degrees()),
        });
        previous = Some(q);
    }
    Ok(Sweep { poses, flags })
}
