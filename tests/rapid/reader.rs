//! An independent reader of the RAPID modules of a hot-blade cell: it knows RAPID's data
//! formats and MultiMove's rules, not hotcut's writer. It reads the work objects, tools,
//! robtargets (with the joints each was planned with, from the comment that follows it)
//! and block sizes, follows `main` through its procedure calls, and lists every move of
//! the task with its TCP pose in the cell's world frame (mm), its `\ID`, whether it runs
//! between `SyncMoveOn` and `SyncMoveOff`, the state of the heat output (`SetDO`) and the
//! block at the fixture (`change_block remove, place`).

use std::collections::HashMap;

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};

/// One move of a task.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// `MoveL` (true) or `MoveJ`.
    pub linear: bool,
    /// The target's name.
    pub target: String,
    /// The TCP pose in the work object's parent frame (see `wobj`): work object × target.
    pub pose: Isometry3<f64>,
    /// The work object's frame: in the world, or for a work object held by another
    /// mechanical unit (coordinated motion), in that unit's flange frame.
    pub wobj: Isometry3<f64>,
    /// The mechanical unit holding the work object (`None`: fixed in the world).
    pub held_by: Option<String>,
    /// The TCP in the flange's frame (the move's tooldata).
    pub tool: Isometry3<f64>,
    /// `\ID`, when given.
    pub id: Option<u32>,
    /// Between `SyncMoveOn` and `SyncMoveOff`.
    pub synced: bool,
    /// The robtarget's `[cf1, cf4, cf6, cfx]`.
    pub conf: [i32; 4],
    /// The joints stated with the robtarget, degrees.
    pub joints: Option<[f64; 6]>,
    /// The heat output during the move (as this task set it; `None`: never set here).
    pub heat: Option<bool>,
    /// The block at the fixture during the move (as this task's block changes say).
    pub block: Option<usize>,
    /// Its speeddata's name.
    pub speed: String,
    /// Whether it stops at its target (`fine`).
    pub fine: bool,
}

/// A task's program.
#[derive(Debug, Clone, Default)]
pub struct Task {
    /// Every move, in execution order.
    pub moves: Vec<Move>,
    /// `SyncMoveOn` blocks, in order: the `\ID`s of their moves.
    pub segments: Vec<Vec<u32>>,
    /// Block sizes (`posBlock<n>`), mm.
    pub blocks: HashMap<usize, [f64; 3]>,
    /// Heat state when the operator is asked to change blocks, per change.
    pub heat_at_changes: Vec<bool>,
    /// Heat state at the end.
    pub heat_at_end: Option<bool>,
    /// The digital outputs `SetDO` sets.
    pub signals: Vec<String>,
    /// Whether the operator's procedure asks for a confirmation (`TPReadFK`).
    pub asks_operator: bool,
}

/// The numbers of a RAPID aggregate `[[1,2,3],[4,5,6,7]]`, flattened.
fn numbers(s: &str) -> Result<Vec<f64>, String> {
    s.split(['[', ']', ','])
        .map(str::trim)
        .filter(|t| !t.is_empty() && !t.starts_with('"'))
        .filter(|t| !matches!(*t, "TRUE" | "FALSE"))
        .map(|t| t.parse::<f64>().map_err(|_| format!("not a number: {t}")))
        .collect()
}

/// A pose from 7 numbers `x y z q1 q2 q3 q4` (`q1` the scalar), checking that the
/// quaternion is a unit one to RAPID's precision.
fn pose(v: &[f64]) -> Result<Isometry3<f64>, String> {
    let q = Quaternion::new(v[3], v[4], v[5], v[6]);
    if (q.norm() - 1.0).abs() > 1e-5 {
        return Err(format!("quaternion {v:?} is not a unit one"));
    }
    Ok(Isometry3::from_parts(
        Translation3::new(v[0], v[1], v[2]),
        UnitQuaternion::from_quaternion(q),
    ))
}

/// `NAME := value;` of a declaration line.
fn declaration<'a>(line: &'a str, kind: &str) -> Option<(&'a str, &'a str)> {
    let rest = line
        .trim()
        .strip_prefix("CONST ")
        .or_else(|| line.trim().strip_prefix("PERS "))
        .or_else(|| line.trim().strip_prefix("VAR "))?;
    let rest = rest.strip_prefix(kind)?.trim_start();
    let (name, value) = rest.split_once(":=")?;
    Some((name.trim(), value.trim().trim_end_matches(';')))
}

/// The joints of a `! joints [a,b,c,d,e,f]` comment.
fn joints(comment: &str) -> Option<[f64; 6]> {
    let v = numbers(comment.trim().strip_prefix("joints")?).ok()?;
    (v.len() == 6).then(|| [v[0], v[1], v[2], v[3], v[4], v[5]])
}

/// A robtarget: pose, configuration data, stated joints.
type Target = (Isometry3<f64>, [i32; 4], Option<[f64; 6]>);

/// What a module declares.
struct Data {
    wobj: HashMap<String, (Isometry3<f64>, Option<String>)>,
    tools: HashMap<String, Isometry3<f64>>,
    targets: HashMap<String, Target>,
    blocks: HashMap<usize, [f64; 3]>,
}

impl Default for Data {
    fn default() -> Self {
        // wobj0, the world, is predefined
        let wobj = HashMap::from([("wobj0".to_string(), (Isometry3::identity(), None))]);
        Data {
            wobj,
            tools: HashMap::new(),
            targets: HashMap::new(),
            blocks: HashMap::new(),
        }
    }
}

fn declare(raw: &str, line: &str, d: &mut Data) -> Result<bool, String> {
    if let Some((name, value)) = declaration(line, "wobjdata") {
        // [robhold, ufprog, ufmec, uframe, oframe]: the object frame in the user frame; not
        // held by this robot; fixed (ufprog TRUE, no unit) or moved by the unit ufmec
        let held_by = if value.starts_with("[FALSE,TRUE,\"\",") {
            None
        } else if let Some(rest) = value.strip_prefix("[FALSE,FALSE,\"") {
            let unit = rest.split('"').next().unwrap_or("");
            if unit.is_empty() {
                return Err(format!("wobjdata {name}: moved by no unit: {value}"));
            }
            Some(unit.to_string())
        } else {
            return Err(format!(
                "wobjdata {name}: neither fixed nor held by a unit: {value}"
            ));
        };
        let v = numbers(value)?;
        if v.len() != 14 {
            return Err(format!("wobjdata {name}: {} numbers", v.len()));
        }
        if name == "wobj0" {
            return Err("wobj0 is predefined".into());
        }
        d.wobj
            .insert(name.into(), (pose(&v[..7])? * pose(&v[7..])?, held_by));
    } else if let Some((name, value)) = declaration(line, "tooldata") {
        // [robhold, tframe, tload]: tload = [mass, cog, aom, ix, iy, iz]; the robot holds it
        if !value.starts_with("[TRUE,") {
            return Err(format!("tooldata {name}: not held by the robot: {value}"));
        }
        let v = numbers(value)?;
        if v.len() != 18 || !(v[7] > 0.0) {
            return Err(format!(
                "tooldata {name}: {} numbers, mass {:?}",
                v.len(),
                v.get(7)
            ));
        }
        d.tools.insert(name.into(), pose(&v[..7])?);
    } else if let Some((name, value)) = declaration(line, "robtarget") {
        let v = numbers(value)?;
        if v.len() != 17 {
            return Err(format!("robtarget {name}: {} numbers", v.len()));
        }
        let conf = [v[7] as i32, v[8] as i32, v[9] as i32, v[10] as i32];
        let j = raw.split_once('!').and_then(|(_, c)| joints(c));
        d.targets.insert(name.into(), (pose(&v[..7])?, conf, j));
    } else if let Some((name, value)) = declaration(line, "pos") {
        if let Some(n) = name.strip_prefix("posBlock") {
            let v = numbers(value)?;
            let n: usize = n.parse().map_err(|_| format!("block name {name}"))?;
            d.blocks.insert(n, [v[0], v[1], v[2]]);
        }
    } else {
        return Ok(false);
    }
    Ok(true)
}

/// Reads one module.
///
/// # Errors
/// What does not read as the data and instructions of a blade program.
pub fn read(text: &str) -> Result<Task, String> {
    let mut data = Data::default();
    let mut procs: HashMap<String, Vec<String>> = HashMap::new();
    let mut current: Option<(String, Vec<String>)> = None;
    for raw in text.lines() {
        let line = raw.split('!').next().unwrap_or("").trim();
        if declare(raw, line, &mut data)? {
        } else if let Some(name) = line.strip_prefix("PROC ") {
            let name = name.split('(').next().unwrap_or("").trim().to_string();
            current = Some((name, Vec::new()));
        } else if line == "ENDPROC" {
            if let Some((name, body)) = current.take() {
                procs.insert(name, body);
            }
        } else if let Some((_, body)) = current.as_mut() {
            if !line.is_empty() {
                body.push(line.trim_end_matches(';').to_string());
            }
        }
    }
    let mut state = State::default();
    let mut depth = 0;
    run(
        "main",
        &procs,
        &mut |line| step(line, &data, &mut state),
        &mut depth,
    )?;
    if state.synced {
        return Err("the program ends in synchronized motion".into());
    }
    let mut task = state.task;
    task.blocks = data.blocks;
    task.heat_at_end = state.heat;
    task.asks_operator = procs
        .get("change_block")
        .is_some_and(|b| b.iter().any(|l| l.starts_with("TPReadFK ")));
    Ok(task)
}

/// Runs procedure `name`, calling `each` on every instruction and following calls.
fn run(
    name: &str,
    procs: &HashMap<String, Vec<String>>,
    each: &mut dyn FnMut(&str) -> Result<(), String>,
    depth: &mut usize,
) -> Result<(), String> {
    *depth += 1;
    if *depth > 16 {
        return Err("procedure calls nested too deep".into());
    }
    let body = procs.get(name).ok_or(format!("no PROC {name}"))?;
    for line in body {
        let word = line.split_whitespace().next().unwrap_or("");
        if procs.contains_key(word) && !line.contains(' ') {
            run(word, procs, each, depth)?;
        } else {
            each(line)?;
        }
    }
    *depth -= 1;
    Ok(())
}

#[derive(Default)]
struct State {
    synced: bool,
    heat: Option<bool>,
    block: Option<usize>,
    task: Task,
}

/// One instruction.
fn step(line: &str, d: &Data, s: &mut State) -> Result<(), String> {
    let word = line.split_whitespace().next().unwrap_or("");
    let args: Vec<&str> = line[word.len()..].split(',').map(str::trim).collect();
    match word {
        "SyncMoveOn" => {
            if s.synced {
                return Err("SyncMoveOn inside synchronized motion".into());
            }
            s.synced = true;
            s.task.segments.push(Vec::new());
        }
        "SyncMoveOff" => {
            if !s.synced {
                return Err("SyncMoveOff outside synchronized motion".into());
            }
            s.synced = false;
        }
        "SetDO" => {
            let v: u8 = args
                .get(1)
                .and_then(|v| v.parse().ok())
                .ok_or(format!("{line}: value"))?;
            // after a corner zone the controller would switch it while still moving
            stopped(s, line)?;
            s.task.signals.push(args[0].to_string());
            s.heat = Some(v == 1);
        }
        "change_block" => {
            stopped(s, line)?;
            let place: usize = args
                .get(1)
                .and_then(|v| v.parse().ok())
                .ok_or(format!("{line}: block"))?;
            let remove: usize = args[0].parse().map_err(|_| format!("{line}: block"))?;
            if remove != s.block.unwrap_or(0) {
                return Err(format!(
                    "{line}: block {remove} is not the one at the fixture ({:?})",
                    s.block
                ));
            }
            s.task.heat_at_changes.push(s.heat.unwrap_or(false));
            s.block = Some(place);
        }
        "MoveL" | "MoveJ" => {
            let (target, id) = match args[0].split_once("\\ID:=") {
                Some((t, id)) => (
                    t.trim(),
                    Some(id.trim().parse::<u32>().map_err(|e| e.to_string())?),
                ),
                None => (args[0], None),
            };
            // MultiMove: every move in synchronized motion has an \ID, no other move has one
            if id.is_some() != s.synced {
                return Err(format!(
                    "{line}: \\ID must be given exactly in synchronized motion"
                ));
            }
            let tool_frame = args.last().ok_or(format!("{line}: no tool"))?;
            let (tool, frame) = tool_frame
                .split_once("\\WObj:=")
                .map(|(t, w)| (t.trim(), w.trim()))
                .ok_or(format!("{line}: no work object"))?;
            let (w, held_by) = d.wobj.get(frame).ok_or(format!("no wobjdata {frame}"))?;
            let tool = d.tools.get(tool).ok_or(format!("no tooldata {tool}"))?;
            let (t, conf, joints) = d
                .targets
                .get(target)
                .ok_or(format!("no robtarget {target}"))?;
            if let (Some(id), Some(seg)) = (id, s.task.segments.last_mut()) {
                seg.push(id);
            }
            let zone = args
                .get(args.len().saturating_sub(2))
                .copied()
                .unwrap_or("");
            s.task.moves.push(Move {
                speed: args.get(1).copied().unwrap_or("").to_string(),
                fine: zone == "fine",
                linear: word == "MoveL",
                target: target.into(),
                pose: w * t,
                wobj: *w,
                held_by: held_by.clone(),
                tool: *tool,
                id,
                synced: s.synced,
                conf: *conf,
                joints: *joints,
                heat: s.heat,
                block: s.block,
            });
        }
        _ => {}
    }
    Ok(())
}

/// An instruction that must run with the robot standing: the move before it ends `fine`.
fn stopped(s: &State, line: &str) -> Result<(), String> {
    match s.task.moves.last() {
        Some(m) if !m.fine => Err(format!(
            "{line}: after {}, which does not stop there (zone)",
            m.target
        )),
        _ => Ok(()),
    }
}

/// `module` with one group of robtarget `name`'s numbers replaced by `edit` of them: group
/// 0 its position, 1 its orientation (for tests that spoil a program on purpose).
pub fn edit_robtarget(
    module: &str,
    name: &str,
    group: usize,
    edit: impl Fn(&[f64]) -> String,
) -> String {
    let line = module
        .lines()
        .find(|l| l.contains(&format!("robtarget {name} ")))
        .unwrap_or_else(|| panic!("no robtarget {name}"))
        .to_string();
    let mut start = line.find(":= [[").unwrap() + 5;
    for _ in 0..group {
        start += line[start..].find("],[").unwrap() + 3;
    }
    let end = start + line[start..].find(']').unwrap();
    let values: Vec<f64> = line[start..end]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let new = edit(&values);
    module.replace(&line, &format!("{}{new}{}", &line[..start], &line[end..]))
}
