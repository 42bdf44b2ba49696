//! ABB RAPID for a MultiMove cell in which robots hold the ends of a hot blade ("Robotic
//! Hot-Blade Cutting" §4): one module per robot task. The whole program runs in one
//! synchronized block (`SyncMoveOn` … `SyncMoveOff`), so every move of every task carries
//! the same `\ID` sequence and the blade's ends always move in step — through the cuts
//! and through the moves between blocks.
//!
//! The first task (the "master") also switches the blade's heat (`SetDO`, then a preheat
//! `WaitTime`) and asks the operator to change blocks (`TPReadFK`); the other tasks wait
//! for it at their next synchronized move. Positions are written in mm with 3 decimals,
//! orientations as `[q1, q2, q3, q4] = [w, x, y, z]` with 7 decimals (renormalised, as
//! RAPID demands unit quaternions), and each robtarget carries the configuration data of
//! the joint solution it was planned with; the joints themselves follow in a comment.

use std::io::Write;

use crate::{fmt_float, Result};

/// A frame: position (mm) and orientation `[w, x, y, z]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapidTarget {
    /// Position in mm.
    pub position: [f64; 3],
    /// Orientation `[w, x, y, z]`.
    pub rotation: [f64; 4],
}

/// A tool held by the robot (`tooldata` with `robhold = TRUE`).
#[derive(Debug, Clone, PartialEq)]
pub struct RapidTool {
    /// Its name.
    pub name: String,
    /// The TCP in the flange's frame.
    pub frame: RapidTarget,
    /// Mass, kg.
    pub mass: f64,
    /// Centre of gravity in the flange's frame, mm.
    pub cog: [f64; 3],
}

/// A work object the program declares (`wobjdata`).
#[derive(Debug, Clone, PartialEq)]
pub struct RapidWobj {
    /// Its name.
    pub name: String,
    /// Where the work object is: for a fixed one its user frame in the world; for a moving
    /// one its object frame in the user frame, which the system attaches to the
    /// mechanical unit that moves it.
    pub frame: RapidTarget,
    /// The mechanical unit that moves it (coordinated motion, e.g. `ROB_3`), or `None`
    /// for a fixed one.
    pub held_by: Option<String>,
}

/// One move of the program.
#[derive(Debug, Clone, PartialEq)]
pub struct RapidMove {
    /// The robtarget's name (a RAPID identifier, unique in the module).
    pub name: String,
    /// Where the TCP goes, in the work object.
    pub target: RapidTarget,
    /// `[cf1, cf4, cf6, cfx]` of the planned joints.
    pub conf: [i32; 4],
    /// The planned joints, degrees (`None`: out of reach, written as a warning comment).
    pub joints: Option<[f64; 6]>,
    /// Cutting speed (else air speed).
    pub cut: bool,
    /// Stop exactly at the target (`fine`), else pass it within 1 mm (`z1`).
    pub fine: bool,
    /// The blade is heated during the move.
    pub heat: bool,
    /// Before the move, the operator removes a block (if any) and places one.
    pub change: Option<(Option<usize>, usize)>,
    /// The target is in the world (`wobj0`), not in the program's work object: the first
    /// move of a task that then moves with a carried work object, so that it goes there
    /// in a straight line in the world from wherever it stands.
    pub world: bool,
}

/// What a module needs to know.
#[derive(Debug, Clone, PartialEq)]
pub struct RapidProgram<'a> {
    /// Module name (also the program's identity on the controller).
    pub name: &'a str,
    /// Lines of the header comment.
    pub comment: &'a [String],
    /// The tasks that move in synchronization, this one among them.
    pub tasks: &'a [String],
    /// Whether this task switches the heat and talks to the operator.
    pub master: bool,
    /// This robot's tool.
    pub tool: &'a RapidTool,
    /// The work object the moves are in (`None`: the predefined `wobj0`, the world).
    pub wobj: Option<&'a RapidWobj>,
    /// The blocks cut in turn, `(number, size)`, mm along their axes from their min
    /// corner, the work object's origin (documentation for the operator and the replay).
    pub blocks: &'a [(usize, [f64; 3])],
    /// Cutting speed, mm/s.
    pub cut_speed: f64,
    /// Air speed, mm/s.
    pub air_speed: f64,
    /// The heat's digital output.
    pub heat_signal: &'a str,
    /// Preheat wait, s.
    pub preheat_s: f64,
    /// The moves, in order.
    pub moves: &'a [RapidMove],
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

fn robtarget(m: &RapidMove) -> String {
    let p = pose(&m.target);
    let c = m.conf;
    // a robtarget is [trans, rot, robconf, extax]: the pose without its outer brackets
    format!(
        "[{},[{},{},{},{}],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]",
        &p[1..p.len() - 1],
        c[0],
        c[1],
        c[2],
        c[3]
    )
}

fn joints_comment(m: &RapidMove) -> String {
    match m.joints {
        Some(j) => {
            let v: Vec<String> = j.iter().map(|a| num(*a, 6)).collect();
            format!("! joints [{}]", v.join(","))
        }
        None => "! OUT OF REACH: no joint solution within the limits".into(),
    }
}

fn declarations(p: &RapidProgram<'_>, line: &mut dyn FnMut(String)) {
    let tasks: Vec<String> = p.tasks.iter().map(|t| format!("[\"{t}\"]")).collect();
    line(format!(
        "    PERS tasks tlBlade{{{}}} := [{}];",
        p.tasks.len(),
        tasks.join(",")
    ));
    for id in ["idStart", "idSyncOn", "idSyncOff", "idEnd"] {
        line(format!("    VAR syncident {id};"));
    }
    if p.master {
        line("    VAR num nAnswer;".into());
    }
    let t = p.tool;
    line(format!(
        "    PERS tooldata {} := [TRUE,{},[{},[{},{},{}],[1,0,0,0],0,0,0]];",
        t.name,
        pose(&t.frame),
        num(t.mass, 3),
        num(t.cog[0], 3),
        num(t.cog[1], 3),
        num(t.cog[2], 3)
    ));
    if let Some(w) = p.wobj {
        // [robhold, ufprog, ufmec, uframe, oframe]: a moving user frame is defined by the
        // system from the unit's position, so the offset goes into the object frame
        let identity = "[[0,0,0],[1,0,0,0]]";
        let (prog, unit, user, object) = match &w.held_by {
            Some(unit) => ("FALSE", unit.as_str(), identity.to_string(), pose(&w.frame)),
            None => ("TRUE", "", pose(&w.frame), identity.to_string()),
        };
        line(format!(
            "    PERS wobjdata {} := [FALSE,{prog},\"{unit}\",{user},{object}];",
            w.name
        ));
    }
    line(format!(
        "    CONST speeddata vCut := [{},30,200,15];",
        num(p.cut_speed, 3)
    ));
    line(format!(
        "    CONST speeddata vAir := [{},60,200,15];",
        num(p.air_speed, 3)
    ));
    for (b, size) in p.blocks {
        line(format!(
            "    CONST pos posBlock{b} := [{},{},{}]; ! block {b}'s size along its own axes",
            num(size[0], 3),
            num(size[1], 3),
            num(size[2], 3),
        ));
    }
    line(String::new());
    for m in p.moves {
        line(format!(
            "    CONST robtarget {} := {}; {}",
            m.name,
            robtarget(m),
            joints_comment(m)
        ));
    }
}

fn wobj_name<'a>(p: &'a RapidProgram<'_>) -> &'a str {
    p.wobj.map_or("wobj0", |w| w.name.as_str())
}

fn body(p: &RapidProgram<'_>, line: &mut dyn FnMut(String)) {
    let tool = &p.tool.name;
    line("    PROC main()".into());
    line("        ConfJ \\On;".into());
    line("        ConfL \\On;".into());
    if p.master {
        line(format!("        SetDO {}, 0;", p.heat_signal));
    }
    line("        WaitSyncTask idStart, tlBlade;".into());
    line("        SyncMoveOn idSyncOn, tlBlade;".into());
    let mut heat = false;
    for (k, m) in p.moves.iter().enumerate() {
        if p.master {
            if m.heat != heat && !m.heat {
                line(format!("        SetDO {}, 0;", p.heat_signal));
            }
            if let Some((remove, place)) = m.change {
                line(format!(
                    "        change_block {}, {place};",
                    remove.unwrap_or(0)
                ));
            }
            if m.heat != heat && m.heat {
                line(format!("        SetDO {}, 1;", p.heat_signal));
                line(format!("        WaitTime {};", num(p.preheat_s, 3)));
            }
        }
        heat = m.heat;
        line(format!(
            "        MoveL {} \\ID:={}, {}, {}, {tool} \\WObj:={};",
            m.name,
            10 * (k + 1),
            if m.cut { "vCut" } else { "vAir" },
            if m.fine { "fine" } else { "z1" },
            if m.world { "wobj0" } else { wobj_name(p) }
        ));
    }
    if p.master && heat {
        line(format!("        SetDO {}, 0;", p.heat_signal));
    }
    line("        SyncMoveOff idSyncOff;".into());
    line("        WaitSyncTask idEnd, tlBlade;".into());
    line("    ENDPROC".into());
    if p.master {
        line(String::new());
        line("    PROC change_block(num remove, num place)".into());
        line(
            "        ! the blade is cold and clear of the block: the operator changes blocks"
                .into(),
        );
        line("        TPErase;".into());
        line("        IF remove > 0 TPWrite \"Remove block \" \\Num:=remove;".into());
        line("        TPWrite \"Place block \" \\Num:=place;".into());
        line(format!(
            "        TPReadFK nAnswer, \"Block placed ({}), blade clear?\", stEmpty, stEmpty, stEmpty, stEmpty, \"Go\";",
            wobj_name(p)
        ));
        line("    ENDPROC".into());
    }
}

/// Writes the module of one robot task.
///
/// ```
/// use export::rapid::{write_module, RapidMove, RapidProgram, RapidTarget, RapidTool, RapidWobj};
/// let t = RapidTarget { position: [0.0, 100.0, 50.0], rotation: [1.0, 0.0, 0.0, 0.0] };
/// let tool = RapidTool { name: "tBlade1".into(), frame: t, mass: 2.0, cog: [0.0, 0.0, 75.0] };
/// let mv = |name: &str, heat| RapidMove { name: name.into(), target: t, conf: [0, 0, 0, 1],
///     joints: Some([0.0; 6]), cut: heat, fine: true, heat, change: None, world: false };
/// let moves = [mv("pB1_D", false), mv("pB1_C1", true)];
/// let tasks = ["T_ROB1".to_string(), "T_ROB2".to_string()];
/// let fixture = RapidWobj { name: "wFixture".into(), frame: t, held_by: None };
/// let p = RapidProgram { name: "facade_T_ROB1", comment: &[], tasks: &tasks, master: true,
///     tool: &tool, wobj: Some(&fixture), blocks: &[(1, [600.0; 3])], cut_speed: 7.0,
///     air_speed: 100.0, heat_signal: "doBladeHeat", preheat_s: 2.0, moves: &moves };
/// let mut out = Vec::new();
/// write_module(&p, &mut out).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("SyncMoveOn idSyncOn, tlBlade;"));
/// assert!(text.contains("SetDO doBladeHeat, 1;"));
/// assert!(text.contains("MoveL pB1_C1 \\ID:=20, vCut, fine, tBlade1 \\WObj:=wFixture;"));
/// ```
///
/// # Errors
/// I/O errors of `w`.
pub fn write_module(p: &RapidProgram<'_>, mut w: impl Write) -> Result<()> {
    let mut s = String::new();
    let mut line = |t: String| {
        s.push_str(&t);
        s.push('\n');
    };
    line(format!("MODULE {}", p.name));
    for c in p.comment {
        line(format!("    ! {}", geom::text::rapid_comment(c)));
    }
    line(String::new());
    declarations(p, &mut line);
    line(String::new());
    body(p, &mut line);
    line("ENDMODULE".into());
    w.write_all(s.as_bytes())?;
    Ok(())
}

/// A RAPID identifier made of `text`: letters, digits and `_` (others become `_`), a
/// letter first (`J` is put before anything else), at most `max` characters (a long name
/// keeps its start and ends in a 6-digit hash of the whole, so two long names stay
/// apart).
///
/// ```
/// use export::rapid::identifier;
/// assert_eq!(identifier("hot-blade-facade", 25), "hot_blade_facade");
/// assert_eq!(identifier("3 blocks", 25), "J3_blocks");
/// assert_eq!(identifier("a-very-long-job-name-that-goes-on", 25).len(), 25);
/// ```
pub fn identifier(text: &str, max: usize) -> String {
    let mut id: String = text
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_alphabetic()) {
        id.insert(0, 'J');
    }
    if id.len() > max {
        // FNV-1a: stable across runs and platforms
        let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        });
        id.truncate(max.saturating_sub(7));
        id.push_str(&format!("_{:06}", hash % 1_000_000));
    }
    id
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
