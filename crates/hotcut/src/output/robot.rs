//! The robot files of every task that poses the blade, written with [`export::robot`]:
//! `targets.json` and `targets.csv` (every pose in job coordinates), and per blade robot an
//! ABB RAPID module and `.pgf`.

use elastica::sweep::BladePose;
use export::rapid::write_pgf;
use export::robot::TARGET_DIGITS;
use export::robot::{rapid, targets_csv, EndPose, Motion, Pose, Targets, TargetsBlock};

use super::Files;
use crate::spec::{OutputKind, Units};

/// The targets of `blocks` (poses in job units `units`) for a blade of `blade_length`.
pub fn targets(units: Units, blade_length: f64, blocks: Vec<TargetsBlock>) -> Targets {
    Targets {
        units: units.name().into(),
        per_mm: units.per_mm(),
        unit_symbol: units.symbol(),
        blade_length,
        blocks,
    }
}

/// A pose as the robot files take it.
pub fn pose(p: &BladePose) -> Pose {
    let end = |k: usize| EndPose {
        position: p.ends[k].position,
        tangent: p.ends[k].tangent,
        rotation: p.ends[k].rotation,
    };
    Pose {
        plane_normal: p.plane_normal,
        ends: [end(0), end(1)],
    }
}

/// Writes the robot files of output `kind` for the poses in `t`: `targets.json` and
/// `targets.csv` (`RobotTargets`), or one RAPID module and `.pgf` per blade robot named
/// `<prefix>_T_ROB<n>` (`Rapid`); nothing for other kinds.
///
/// # Errors
/// Serialisation, formatting or file-system failures.
pub fn write(
    files: &mut Files,
    t: &Targets,
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
