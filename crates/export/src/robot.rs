//! The robot files of a two-robot hot-blade cell from blade poses: `targets.json` (the
//! [`Targets`](crate::robot::Targets) serialized), `targets.csv` (one row per pose and held
//! end) and, per blade robot, an ABB RAPID module (MultiMove, a work object per block,
//! targets in mm in the block's frame; see [`crate::rapid`]).

use std::io::Write;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::Serialize;

use crate::csv::Table;
use crate::fmt_float;
use crate::rapid::{write_module, RapidBlock, RapidModule, RapidTarget};
use crate::Result;

/// Significant digits of `targets.json` (finer than a report: robot data).
pub const TARGET_DIGITS: usize = 12;

/// One held end of the blade.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EndPose {
    /// Position.
    pub position: [f64; 3],
    /// Unit tangent of the blade there, from its first end to its second.
    pub tangent: [f64; 3],
    /// Tool orientation `[w, x, y, z]`: x-axis = `tangent`, z-axis = the plane normal.
    pub rotation: [f64; 4],
}

/// A blade pose: the cutting plane's normal and both held ends, the blade's start first.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Pose {
    /// Unit normal of the cutting plane.
    pub plane_normal: [f64; 3],
    /// The two ends.
    pub ends: [EndPose; 2],
}

/// The poses of a run, `targets.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Targets {
    /// Length unit of every position, as the job names it (`Millimetre`, `Metre`).
    pub units: String,
    /// How many of those units one millimetre is.
    #[serde(skip)]
    pub per_mm: f64,
    /// The unit's symbol (`mm`, `m`).
    #[serde(skip)]
    pub unit_symbol: &'static str,
    /// Physical blade length.
    pub blade_length: f64,
    /// Blocks in cutting order.
    pub blocks: Vec<TargetsBlock>,
}

/// One block (or piece) of `targets.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetsBlock {
    /// Block number.
    pub block: usize,
    /// The block's min corner, the work object's origin (job coordinates).
    pub origin: [f64; 3],
    /// Orientation `[w, x, y, z]` of the block axes (work object frame).
    pub rotation: [f64; 4],
    /// Poses in cutting order, positions in job coordinates.
    pub poses: Vec<Pose>,
}

/// Blade motion settings of a RAPID program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Cutting speed, job units per second.
    pub speed: f64,
    /// Approach and retreat distance along the cut.
    pub approach: f64,
}

/// `targets.csv`: one row per pose and held end.
pub fn targets_csv(targets: &Targets) -> String {
    let mut t = Table::new(
        "block,pose,end,x,y,z,tangent_x,tangent_y,tangent_z,q_w,q_x,q_y,q_z,normal_x,normal_y,normal_z",
    );
    let f = Table::num;
    for b in &targets.blocks {
        for (k, pose) in b.poses.iter().enumerate() {
            for (e, end) in pose.ends.iter().enumerate() {
                let mut row = vec![
                    b.block.to_string(),
                    (k + 1).to_string(),
                    (e + 1).to_string(),
                ];
                row.extend(end.position.iter().map(|v| f(*v)));
                row.extend(end.tangent.iter().map(|v| f(*v)));
                row.extend(end.rotation.iter().map(|v| f(*v)));
                row.extend(pose.plane_normal.iter().map(|v| f(*v)));
                t.row(&row);
            }
        }
    }
    t.finish()
}

fn uq(q: &[f64; 4]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
}

fn wxyz(q: &UnitQuaternion<f64>) -> [f64; 4] {
    let c = q.as_ref().coords;
    let s = if c.w < 0.0 { -1.0 } else { 1.0 };
    [s * c.w, s * c.x, s * c.y, s * c.z]
}

/// Writes the RAPID module `module` of blade robot `robot` (0: the blade's start, task
/// `T_ROB1`; 1: its end, `T_ROB2`) for job `job`.
///
/// # Errors
/// [`ExportError::Data`](crate::ExportError::Data) for a robot other than 0 or 1 or a unit
/// that is not a positive number of millimetres; I/O errors of `w`.
pub fn rapid(
    t: &Targets,
    motion: Motion,
    job: &str,
    robot: usize,
    module: &str,
    w: impl Write,
) -> Result<()> {
    if robot > 1 {
        return Err(crate::ExportError::Data(format!(
            "the cell has blade robots 0 and 1, not {robot}"
        )));
    }
    if !(t.per_mm.is_finite() && t.per_mm > 0.0) {
        return Err(crate::ExportError::Data(format!(
            "units per millimetre must be positive, got {:?}",
            t.per_mm
        )));
    }
    let mm = 1.0 / t.per_mm;
    let approach = motion.approach;
    let blocks: Vec<RapidBlock> = t
        .blocks
        .iter()
        .filter(|b| !b.poses.is_empty())
        .map(|b| {
            let frame_q = uq(&b.rotation);
            let origin = Vector3::from(b.origin);
            let local = |p: Vector3<f64>, q: &[f64; 4]| RapidTarget {
                position: (frame_q.inverse() * (p - origin) * mm).into(),
                rotation: wxyz(&(frame_q.inverse() * uq(q))),
            };
            let at = |k: usize, shift: f64| {
                let pose = &b.poses[k];
                let e = &pose.ends[robot];
                local(
                    Vector3::from(e.position) + Vector3::from(pose.plane_normal) * shift,
                    &e.rotation,
                )
            };
            let n = b.poses.len();
            RapidBlock {
                number: b.block,
                frame: RapidTarget {
                    position: (origin * mm).into(),
                    rotation: b.rotation,
                },
                approach: at(0, -approach),
                targets: (0..n).map(|k| at(k, 0.0)).collect(),
                retreat: at(n - 1, approach),
            }
        })
        .collect();
    let comment = vec![
        format!("hotcut job \"{job}\": hot-blade cut, robot task T_ROB{} holds blade end {} ({}).", robot + 1, robot + 1, if robot == 0 { "the blade's start" } else { "the blade's end" }),
        "The cell's world frame is the job frame. Each block has a work object wBlock<n> whose user".into(),
        "frame is the block's min corner with the block axes (along the cut, across it, up).".into(),
        "Targets are in that frame, in mm; orientation [q1,q2,q3,q4] = [w,x,y,z]: tool x along the".into(),
        "blade's tangent at the held end (from the blade's start to its end), tool z normal to the".into(),
        "cutting plane. Calibrate the tool (the blade holder's TCP at the blade end) before running.".into(),
        format!("Blade length {} {}; {} block(s); both tasks must run this program's twin.", fmt_float(t.blade_length, 6), t.unit_symbol, blocks.len()),
    ];
    let m = RapidModule {
        name: module,
        comment: &comment,
        tasks: ["T_ROB1", "T_ROB2"],
        tool: &format!("tBladeEnd{}", robot + 1),
        speed: motion.speed * mm,
        air_speed: (motion.speed * mm * 5.0).max(20.0),
        blocks: &blocks,
    };
    write_module(&m, w)
}
