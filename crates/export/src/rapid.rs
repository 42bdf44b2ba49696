//! ABB RAPID for a MultiMove cell in which two robots hold the ends of a hot blade
//! ("Robotic Hot-Blade Cutting" §4): one module per robot task, synchronized moves through
//! every block's targets, a work object per block.
//!
//! Both modules have the same structure, the same `\ID` numbers and the same sequence of
//! `SyncMoveOn`/`SyncMoveOff`, which MultiMove requires. Positions are written in mm with
//! 3 decimals, orientations as `[q1, q2, q3, q4] = [w, x, y, z]` with 7 decimals
//! (renormalised first, as RAPID demands unit quaternions).

use std::io::Write;

use crate::{fmt_float, Result};

/// One robot target in a work object's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapidTarget {
    /// Position in mm.
    pub position: [f64; 3],
    /// Orientation `[w, x, y, z]`.
    pub rotation: [f64; 4],
}

/// One block's cut for one robot.
#[derive(Debug, Clone, PartialEq)]
pub struct RapidBlock {
    /// Block number (names `wBlock<n>`, `pB<n>_<k>`).
    pub number: usize,
    /// Work object user frame: origin (mm) and orientation `[w, x, y, z]` in the cell's
    /// world frame.
    pub frame: RapidTarget,
    /// Where the blade waits before entering the block.
    pub approach: RapidTarget,
    /// The cutting targets, in order.
    pub targets: Vec<RapidTarget>,
    /// Where the blade goes after leaving the block.
    pub retreat: RapidTarget,
}

/// What a module needs to know.
#[derive(Debug, Clone, PartialEq)]
pub struct RapidModule<'a> {
    /// Module name, e.g. `HotBlade_T_ROB1`.
    pub name: &'a str,
    /// Lines of the header comment.
    pub comment: &'a [String],
    /// Names of the two robot tasks of the cell.
    pub tasks: [&'a str; 2],
    /// Tool name of this robot's blade holder.
    pub tool: &'a str,
    /// Cutting speed, mm/s.
    pub speed: f64,
    /// Speed through the air (approach and retreat), mm/s.
    pub air_speed: f64,
    /// The blocks, in cutting order.
    pub blocks: &'a [RapidBlock],
}

fn num(x: f64, decimals: usize) -> String {
    fmt_float(x, decimals)
}

fn pose(t: &RapidTarget) -> String {
    let n = t.rotation.iter().map(|v| v * v).sum::<f64>().sqrt();
    let q: Vec<String> = t.rotation.iter().map(|v| num(v / n, 7)).collect();
    format!(
        "[[{},{},{}],[{}]]",
        num(t.position[0], 3),
        num(t.position[1], 3),
        num(t.position[2], 3),
        q.join(",")
    )
}

fn robtarget(t: &RapidTarget) -> String {
    let p = pose(t);
    // drop the outer brackets of the pose: a robtarget is [trans, rot, robconf, extax]
    format!(
        "[{},[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]",
        &p[1..p.len() - 1]
    )
}

/// Writes the module of one robot.
///
/// ```
/// use export::rapid::{write_module, RapidBlock, RapidModule, RapidTarget};
/// let t = RapidTarget { position: [0.0, 100.0, 50.0], rotation: [1.0, 0.0, 0.0, 0.0] };
/// let block = RapidBlock { number: 1, frame: t, approach: t, targets: vec![t, t], retreat: t };
/// let m = RapidModule { name: "HotBlade_T_ROB1", comment: &[], tasks: ["T_ROB1", "T_ROB2"],
///     tool: "tBladeEnd1", speed: 7.0, air_speed: 50.0, blocks: &[block] };
/// let mut out = Vec::new();
/// write_module(&m, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("SyncMoveOn idOn1, tlBlade;"));
/// assert!(text.contains("MoveL pB1_2 \\ID:=30, vCut, fine, tBladeEnd1 \\WObj:=wBlock1;"));
/// ```
///
/// # Errors
/// I/O errors of `w`.
pub fn write_module(m: &RapidModule<'_>, mut w: impl Write) -> Result<()> {
    let mut s = String::new();
    let mut line = |t: &str| {
        s.push_str(t);
        s.push('\n');
    };
    line(&format!("MODULE {}", m.name));
    for c in m.comment {
        line(&format!("    ! {c}"));
    }
    line("");
    line(&format!(
        "    PERS tasks tlBlade{{2}} := [[\"{}\"],[\"{}\"]];",
        m.tasks[0], m.tasks[1]
    ));
    line("    VAR syncident idStart;");
    line("    VAR syncident idEnd;");
    for b in m.blocks {
        line(&format!("    VAR syncident idOn{};", b.number));
        line(&format!("    VAR syncident idOff{};", b.number));
    }
    line(&format!(
        "    PERS tooldata {} := [TRUE,[[0,0,0],[1,0,0,0]],[1,[0,0,1],[1,0,0,0],0,0,0]];",
        m.tool
    ));
    line(&format!(
        "    CONST speeddata vCut := [{},30,200,15];",
        num(m.speed, 3)
    ));
    line(&format!(
        "    CONST speeddata vAir := [{},60,200,15];",
        num(m.air_speed, 3)
    ));
    for b in m.blocks {
        line("");
        line(&format!(
            "    PERS wobjdata wBlock{} := [FALSE,TRUE,\"\",{},[[0,0,0],[1,0,0,0]]];",
            b.number,
            pose(&b.frame)
        ));
        line(&format!(
            "    CONST robtarget pB{}_A := {};",
            b.number,
            robtarget(&b.approach)
        ));
        for (k, t) in b.targets.iter().enumerate() {
            line(&format!(
                "    CONST robtarget pB{}_{} := {};",
                b.number,
                k + 1,
                robtarget(t)
            ));
        }
        line(&format!(
            "    CONST robtarget pB{}_R := {};",
            b.number,
            robtarget(&b.retreat)
        ));
    }
    line("");
    line("    PROC main()");
    line("        ConfL \\Off;");
    line("        WaitSyncTask idStart, tlBlade;");
    for b in m.blocks {
        line(&format!("        cut_block{};", b.number));
    }
    line("        WaitSyncTask idEnd, tlBlade;");
    line("    ENDPROC");
    for b in m.blocks {
        let wobj = format!("{} \\WObj:=wBlock{}", m.tool, b.number);
        line("");
        line(&format!("    PROC cut_block{}()", b.number));
        line(&format!(
            "        MoveJ pB{}_A, vAir, fine, {wobj};",
            b.number
        ));
        line(&format!("        SyncMoveOn idOn{}, tlBlade;", b.number));
        let mut id = 10;
        line(&format!(
            "        MoveL pB{}_A \\ID:={id}, vAir, fine, {wobj};",
            b.number
        ));
        let n = b.targets.len();
        for k in 0..n {
            id += 10;
            let zone = if k + 1 == n || k == 0 { "fine" } else { "z1" };
            line(&format!(
                "        MoveL pB{}_{} \\ID:={id}, vCut, {zone}, {wobj};",
                b.number,
                k + 1
            ));
        }
        id += 10;
        line(&format!(
            "        MoveL pB{}_R \\ID:={id}, vCut, fine, {wobj};",
            b.number
        ));
        line(&format!("        SyncMoveOff idOff{};", b.number));
        line("    ENDPROC");
    }
    line("ENDMODULE");
    w.write_all(s.as_bytes())?;
    Ok(())
}

/// Writes the program file (`.pgf`) that loads one module.
///
/// # Errors
/// I/O errors of `w`.
pub fn write_pgf(module_file: &str, mut w: impl Write) -> Result<()> {
    write!(
        w,
        "<?xml version=\"1.0\" encoding=\"ISO-8859-1\" ?>\n<Program>\n    <Module>{module_file}</Module>\n</Program>\n"
    )?;
    Ok(())
}
