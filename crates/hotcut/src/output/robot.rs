//! The robot files of every task that poses the blade: `targets.json` and `targets.csv`
//! (every pose in job coordinates), and per blade robot an ABB RAPID module and `.pgf`
//! (MultiMove, a work object per block, targets in mm in the block's frame).

use elastica::sweep::BladePose;
use export::csv::Table;
use export::fmt_float;
use export::rapid::{write_module, write_pgf, RapidBlock, RapidModule, RapidTarget};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::Serialize;

use super::Files;
use crate::spec::{OutputKind, Units};

/// Significant digits of `targets.json` (finer than the report: robot data).
pub const TARGET_DIGITS: usize = 12;

/// `targets.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetsFile {
    /// Length unit of every position.
    pub units: Units,
    /// Physical blade length.
    pub blade_length: f64,
    /// Blocks in cutting order.
    pub blocks: Vec<TargetsBlock>,
}

/// One block of `targets.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetsBlock {
    /// Block number.
    pub block: usize,
    /// The block's min corner, the work object's origin (job coordinates).
    pub origin: [f64; 3],
    /// Orientation `[w, x, y, z]` of the block axes (work object frame).
    pub rotation: [f64; 4],
    /// Poses in cutting order, positions in job coordinates.
    pub poses: Vec<BladePose>,
}

/// Blade motion settings of a RAPID program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Cutting speed, job units per second.
    pub speed: f64,
    /// Approach and retreat distance along the cut.
    pub approach: f64,
}

/// Writes the robot files of output `kind` for the poses in `t`: `targets.json` and
/// `targets.csv` (`RobotTargets`), or one RAPID module and `.pgf` per blade robot named
/// `<prefix>_T_ROB<n>` (`Rapid`); nothing for other kinds.
///
/// # Errors
/// Serialisation or formatting failures.
pub fn write(
    files: &mut Files,
    t: &TargetsFile,
    motion: Motion,
    job: &str,
    prefix: &str,
    kind: OutputKind,
) -> export::Result<()> {
    match kind {
        OutputKind::RobotTargets => {
            files.json("targets.json", t, TARGET_DIGITS)?;
            files.text("targets.csv", targets_csv(t))
        }
        OutputKind::Rapid => {
            for robot in 0..2 {
                let module = format!("{prefix}_T_ROB{}", robot + 1);
                let mod_file = format!("{module}.mod");
                files.add(&mod_file, |buf| rapid(t, motion, job, robot, &module, buf))?;
                files.add(format!("{module}.pgf"), |buf| write_pgf(&mod_file, buf))?;
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

fn targets_csv(targets: &TargetsFile) -> String {
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

fn rapid(
    t: &TargetsFile,
    motion: Motion,
    job: &str,
    robot: usize,
    module: &str,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let mm = 1.0 / t.units.per_mm();
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
        format!("Blade length {} {}; {} block(s); both tasks must run this program's twin.", fmt_float(t.blade_length, 6), t.units.symbol(), blocks.len()),
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
    write_module(&m, buf)
}
