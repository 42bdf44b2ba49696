//! One cut's G-code in a controller's dialect ([`Machine`]), checked before it exists:
//! every position within the machine's travel, every cutting move's speed within bounds.
//!
//! A program: `%` (if the dialect wraps), comment lines stating the cut, the profile, which
//! tower stands on which side of the block, the frame of the axes and the travel; the
//! setup lines; a rapid to safe height above the lead-in point and down to it; heat on and
//! the preheat dwell; the cut (`G1`, inverse-time or per-move units-per-minute feed); heat
//! off after the lead-out; back to `G94`; a rapid up; the footer, the end, `%`.

use std::fmt::Write as _;

use super::machine::{FeedMode, Machine};
use super::{WireParams, WirePath, MAX_SPEED_MM_PER_MIN, MIN_SPEED_MM_PER_MIN};
use crate::error::{PreCutError, Result};

/// A written program and what it makes the machine do.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// The G-code.
    pub text: String,
    /// Its extents and times.
    pub summary: ProgramSummary,
}

/// What one program makes the machine do (for the report).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct ProgramSummary {
    /// Direction index (0-based).
    pub direction: usize,
    /// Cut (leg) index (0-based).
    pub cut: usize,
    /// Range of each axis over the whole program, rapids included, mm (before the
    /// program's rounding to its decimals).
    pub extents: Vec<AxisExtent>,
    /// Cutting moves (`G1`).
    pub cutting_moves: usize,
    /// The faster tower's path while cutting, mm (before rounding).
    pub cut_length_mm: f64,
    /// Time of the cutting moves at the set speed, minutes (before rounding).
    pub cut_minutes: f64,
    /// Preheat dwell, seconds.
    pub preheat_s: f64,
}

/// The range of one axis in a program.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct AxisExtent {
    /// The axis letter.
    pub axis: char,
    /// Least coordinate, mm.
    pub min: f64,
    /// Greatest coordinate, mm.
    pub max: f64,
}

/// Formats `v` with `decimals` decimals, `-0` as `0`.
pub fn num(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').into()
    } else {
        s
    }
}

/// Formats a feed with 8 significant digits (at least 4 decimals): a slow cut's
/// inverse-time feed is far below 1, and a fixed 4 decimals would round its speed by
/// percents. Always a plain decimal (controllers read no exponents).
pub fn feed(v: f64) -> String {
    if !(v > 0.0) || !v.is_finite() {
        num(v, 4)
    } else {
        let decimals = (7.0 - v.log10().floor()).clamp(4.0, 15.0) as usize;
        format!("{v:.decimals$}")
    }
}

/// Shortest cutting move a program holds at `decimals`, mm: 0.05 mm, or 50 steps of the
/// last digit. A shorter move is left to the next one: its inverse-time feed would be huge,
/// and its length, rounded in the program, too uncertain.
pub fn min_move_mm(decimals: usize) -> f64 {
    (50.0 * 10f64.powi(-(decimals as i32))).max(0.05)
}

/// A comment in parentheses ([`geom::text::gcode_comment`]).
fn comment(text: &str) -> String {
    geom::text::gcode_comment(text)
}

/// The program of one cut. `top` and `floor` are the block's top and floor (job units),
/// `name` the job's name for the header.
///
/// # Errors
/// - [`PreCutError::OutOfTravel`] when a position leaves the machine's travel (naming the
///   cut and the axis);
/// - [`PreCutError::InvalidParameter`] when the dialect is invalid or a move's speed is out
///   of bounds.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use ruled::wire::{check_program, paths, program, Machine, WireParams};
/// use ruled::{pre_cut, Block, Params};
///
/// // a bump on a 400 × 300 × 200 mm block, two cuts along x
/// let bump = HeightField::try_new(
///     Expr::parse("100 + 50*exp(-((x - 200)^2 + (y - 150)^2)/8000)")?, (0.0, 400.0), (0.0, 300.0))?;
/// let block = Block { min: [0.0, 0.0, 0.0], max: [400.0, 300.0, 200.0] };
/// let params = Params { legs: 2, sections: 8, samples: 8, ..Params::default() };
/// let cut = pre_cut(&Surface::HeightField(bump), &block, &params, &|_| {})?;
///
/// let wire = WireParams {
///     tower_distance: 500.0, kerf: 1.0, kerf_table: Vec::new(), speed: 300.0, lead: 20.0,
///     clearance: 50.0, origin: [20.0, 0.0], steps: 6, mm_per_unit: 1.0,
/// };
/// let cuts = paths(&cut.directions[0], 0, block.min[2], &wire)?;
/// assert_eq!(cuts.len(), 2); // one wire path per leg
/// let machine = Machine::linuxcnc_xyuv();
/// let p = program(&cuts[0], &wire, &machine, block.max[2], block.min[2], "bump")?;
/// // the G-code reads back clean against the same machine
/// check_program(&p.text, &machine)?;
/// assert!(p.text.contains("G1"));
/// assert!(p.summary.cutting_moves > 0 && p.summary.cut_minutes > 0.0);
/// // the towers travel at least the block's length plus both leads while cutting
/// assert!(p.summary.cut_length_mm >= 400.0 + 2.0 * 20.0 - 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn program(
    path: &WirePath,
    p: &WireParams,
    m: &Machine,
    top: f64,
    floor: f64,
    name: &str,
) -> Result<Program> {
    program_labelled(path, p, m, top, floor, &Labels::pre_cut(path, p, name))
}

/// What a program's header says of its cut: a title line, the cut's name (also in error
/// messages) and the lines that tell how the block lies between the towers.
#[derive(Debug, Clone, PartialEq)]
pub struct Labels {
    /// First comment line.
    pub title: String,
    /// The cut's name, e.g. `direction 1 cut 2`.
    pub cut: String,
    /// How the block stands on the machine.
    pub frame: Vec<String>,
}

impl Labels {
    /// A pre-cut's labels: the cut's direction and which side each tower stands on.
    pub fn pre_cut(path: &WirePath, p: &WireParams, name: &str) -> Self {
        let n = |v: f64| num(v, 3);
        let (cx, cy) = (path.across[0], path.across[1]);
        Self {
            title: format!(
                "hotcut pre-cut {}: direction {} cut {}",
                name.chars().take(30).collect::<String>(),
                path.direction + 1,
                path.leg + 1
            ),
            cut: format!("direction {} cut {}", path.direction + 1, path.leg + 1),
            frame: vec![
                format!(
                    "cut along ({}, {}); tower A on the side of ({}, {})",
                    n(path.along[0]),
                    n(path.along[1]),
                    n(-cx),
                    n(-cy)
                ),
                format!(
                    "tower B on the side of ({}, {}), {} mm apart",
                    n(cx),
                    n(cy),
                    n(p.tower_distance * p.mm_per_unit)
                ),
            ],
        }
    }
}

/// [`program`] with the header's labels given: for cuts other than a pre-cut's.
///
/// # Errors
/// As [`program`].
pub fn program_labelled(
    path: &WirePath,
    p: &WireParams,
    m: &Machine,
    top: f64,
    floor: f64,
    labels: &Labels,
) -> Result<Program> {
    m.check()?;
    let mm = p.mm_per_unit;
    let dec = m.decimals;
    let written = |v: f64| num(v, dec).parse::<f64>().unwrap_or(v);
    let w4 = |a: [f64; 2], b: [f64; 2]| [a[0], a[1], b[0], b[1]].map(written);
    let safe = (p.origin[1] + top - floor + p.clearance) * mm;
    let Some(first) = path.steps.first() else {
        return Err(PreCutError::InvalidParameter {
            name: "steps",
            reason: "a cut without steps".into(),
        });
    };
    let speed = p.speed * mm;
    let slowest = MIN_SPEED_MM_PER_MIN;
    let fastest = m.max_speed.min(MAX_SPEED_MM_PER_MIN);
    if !(speed >= slowest && speed <= fastest) {
        return Err(PreCutError::InvalidParameter {
            name: "speed",
            reason: format!("{speed} mm/min is outside the machine's {slowest}–{fastest} mm/min"),
        });
    }
    // positions as the program holds them
    let start = w4([first.a[0], safe], [first.b[0], safe]);
    let lead_in = w4(first.a, first.b);
    let mut cuts: Vec<([f64; 4], f64)> = Vec::new();
    let mut at = lead_in;
    // the same positions before rounding, for the report: its numbers then scale with the
    // job, free of the program's last digit
    let raw = |a: [f64; 2], b: [f64; 2]| [a[0], a[1], b[0], b[1]];
    let mut exact = vec![
        raw([first.a[0], safe], [first.b[0], safe]),
        raw(first.a, first.b),
    ];
    let (mut length, mut minutes) = (0.0, 0.0);
    for s in &path.steps[1..] {
        let next = w4(s.a, s.b);
        let da = (next[0] - at[0]).hypot(next[1] - at[1]);
        let db = (next[2] - at[2]).hypot(next[3] - at[3]);
        let travel = da.max(db);
        if travel < min_move_mm(dec) {
            continue;
        }
        let t = travel / speed;
        let d = [0, 1, 2, 3].map(|k| next[k] - at[k]);
        let f = match m.feed {
            FeedMode::InverseTime => 1.0 / t,
            upm => upm.feed_length(&m.axes, d) / t,
        };
        cuts.push((next, f));
        let (e, from) = (raw(s.a, s.b), exact[exact.len() - 1]);
        let ea = (e[0] - from[0]).hypot(e[1] - from[1]);
        let eb = (e[2] - from[2]).hypot(e[3] - from[3]);
        length += ea.max(eb);
        minutes += ea.max(eb) / speed;
        exact.push(e);
        at = next;
    }
    if cuts.is_empty() {
        return Err(PreCutError::InvalidParameter {
            name: "steps",
            reason: format!("{}: no move of {} mm or more", labels.cut, min_move_mm(dec)),
        });
    }
    let end = [at[0], written(safe), at[2], written(safe)];
    let all: Vec<[f64; 4]> = [start, lead_in]
        .into_iter()
        .chain(cuts.iter().map(|c| c.0))
        .chain([end])
        .collect();
    let last = exact[exact.len() - 1];
    exact.push([last[0], safe, last[2], safe]);
    let extents = |pts: &[[f64; 4]]| -> Vec<AxisExtent> {
        (0..4)
            .map(|k| AxisExtent {
                axis: m.axes[k],
                min: pts.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min),
                max: pts.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max),
            })
            .collect()
    };
    check_travel(&labels.cut, m, &extents(&all))?;
    let mut g = String::new();
    let line = |g: &mut String, s: &str| {
        g.push_str(s);
        g.push('\n');
    };
    if m.percent {
        line(&mut g, "%");
    }
    for c in header_comments(labels, p, m) {
        line(&mut g, &comment(&c));
    }
    for h in &m.header {
        line(&mut g, h);
    }
    let n = |v: f64| num(v, dec);
    let mv = |g: &mut String, code: &str, q: [f64; 4], f: Option<f64>| {
        let _ = write!(g, "{code}");
        for (letter, v) in m.axes.iter().zip(q) {
            let _ = write!(g, " {letter}{}", n(v));
        }
        if let Some(f) = f {
            let _ = write!(g, " F{}", feed(f));
        }
        g.push('\n');
    };
    mv(&mut g, "G0", start, None);
    mv(&mut g, "G0", lead_in, None);
    line(&mut g, &m.heat_on_line());
    if let Some(d) = m.preheat_line() {
        line(&mut g, &d);
    }
    if m.feed == FeedMode::InverseTime {
        line(&mut g, "G93");
    }
    for (q, f) in &cuts {
        mv(&mut g, "G1", *q, Some(*f));
    }
    line(&mut g, &m.heat_off);
    if m.feed == FeedMode::InverseTime {
        line(&mut g, "G94");
    }
    mv(&mut g, "G0", end, None);
    for f in &m.footer {
        line(&mut g, f);
    }
    line(&mut g, &m.end);
    if m.percent {
        line(&mut g, "%");
    }
    Ok(Program {
        text: g,
        summary: ProgramSummary {
            direction: path.direction,
            cut: path.leg,
            extents: extents(&exact),
            cutting_moves: cuts.len(),
            cut_length_mm: length,
            cut_minutes: minutes,
            preheat_s: m.preheat_s,
        },
    })
}

/// Every axis's range within the machine's travel (to half the last digit).
fn check_travel(cut: &str, m: &Machine, extents: &[AxisExtent]) -> Result<()> {
    let Some(travel) = &m.travel else {
        return Ok(());
    };
    let half = 0.5 * 10f64.powi(-(m.decimals as i32));
    for (e, &(lo, hi)) in extents.iter().zip(travel) {
        let out = if e.min < lo - half {
            Some(e.min)
        } else if e.max > hi + half {
            Some(e.max)
        } else {
            None
        };
        if let Some(value) = out {
            return Err(PreCutError::OutOfTravel {
                program: cut.to_string(),
                axis: e.axis,
                value,
                min: lo,
                max: hi,
                extent: (e.min, e.max),
            });
        }
    }
    Ok(())
}

/// The header's comment texts: the cut, the profile and its axes, the towers' sides, the
/// frame, the travel, the heat, the operator's notes.
fn header_comments(labels: &Labels, p: &WireParams, m: &Machine) -> Vec<String> {
    let mm = p.mm_per_unit;
    let [a0, a1, b0, b1] = m.axes;
    let n = |v: f64| num(v, 3);
    let mut c = vec![
        labels.title.clone(),
        format!(
            "profile {}: tower A {a0} along {a1} up, tower B {b0} along {b1} up",
            m.profile
        ),
    ];
    c.extend(labels.frame.iter().cloned());
    c.extend([
        format!(
            "{a0} {b0} = {} at the block's start, {a1} {b1} = {} at its floor",
            n(p.origin[0] * mm),
            n(p.origin[1] * mm)
        ),
        format!(
            "kerf {} mm{}, speed {} mm/min, mm, absolute",
            n(p.kerf_at(p.speed) * mm),
            if p.kerf_table.is_empty() {
                ""
            } else {
                " by speed"
            },
            n(p.speed * mm)
        ),
    ]);
    match &m.travel {
        Some(t) => {
            for (tower, k) in [("A", 0), ("B", 2)] {
                c.push(format!(
                    "travel tower {tower}: {} {}..{}, {} {}..{} mm",
                    m.axes[k],
                    n(t[k].0),
                    n(t[k].1),
                    m.axes[k + 1],
                    n(t[k + 1].0),
                    n(t[k + 1].1)
                ));
            }
        }
        None => c.push("travel not given: not checked".into()),
    }
    c.push(format!(
        "heat on {} before the lead-in, off {} after the lead-out",
        m.heat_on_line(),
        m.heat_off
    ));
    c.extend(m.notes.iter().cloned());
    c
}

/// Reads back a program [`program`] wrote for `m` and replays what it would make the
/// machine do, line by line, the dialect's fixed lines included:
/// - every number finite and within ±10⁶ ([`super::dialect::number_problem`]);
/// - only the codes a program holds: motion `G0`/`G1`, dwell `G4`, feed modes `G93`/`G94`,
///   the modal settings of [`super::dialect::SAFE_G`], the dialect's heat lines and one
///   program end, after which nothing follows;
/// - every move from a known position, and every position within the machine's travel
///   (per axis, to half the last digit) when it has one;
/// - the heat: no rapid (`G0`) while hot, no cutting move (`G1`) while cold, and off at
///   the end;
/// - every cutting move with a feed, its faster tower's speed within
///   [`MIN_SPEED_MM_PER_MIN`]–[`MAX_SPEED_MM_PER_MIN`] (within 1 %: the program's
///   rounding).
///
/// # Errors
/// [`PreCutError::InvalidParameter`] naming the first offending line.
pub fn check_program(text: &str, m: &Machine) -> Result<()> {
    let bad = |line: usize, reason: String| {
        Err(PreCutError::InvalidParameter {
            name: "G-code",
            reason: format!("line {}: {reason}", line + 1),
        })
    };
    let (on, off) = (words(&m.heat_on_line()), words(&m.heat_off));
    let (Ok(on), Ok(off)) = (on, off) else {
        return bad(0, "the dialect's heat lines cannot be read".into());
    };
    let same = |ws: &[(char, f64)], line: &[(char, f64)]| {
        let mut a = ws.to_vec();
        let mut b = line.to_vec();
        let key = |w: &(char, f64)| (w.0, w.1.to_bits());
        a.sort_by_key(key);
        b.sort_by_key(key);
        !a.is_empty() && a == b
    };
    let half = 0.5 * 10f64.powi(-(m.decimals as i32));
    let mut pos = [0.0f64; 4];
    let mut known = [false; 4];
    let mut inverse_time = false;
    let mut motion: Option<bool> = None; // Some(true): G1
    let mut hot = false;
    let mut ended = false;
    for (i, line) in text.lines().enumerate() {
        if line.trim() == "%" {
            continue;
        }
        let ws = match words(line) {
            Ok(ws) => ws,
            Err(e) => return bad(i, e),
        };
        if ws.is_empty() {
            continue;
        }
        if ended {
            return bad(i, "a line after the program's end".into());
        }
        if let Some(p) = ws
            .iter()
            .filter(|w| w.0 != 'F')
            .find_map(|&(l, v)| super::dialect::number_problem(l, v))
        {
            return bad(i, p);
        }
        if same(&on, &ws) {
            hot = true;
            continue;
        }
        if same(&off, &ws) {
            hot = false;
            continue;
        }
        let mut next = pos;
        let mut moved = [false; 4];
        let mut f = None;
        for &(letter, v) in &ws {
            if !v.is_finite() {
                return bad(i, format!("{letter}{v} is not a finite number"));
            }
            let axis = m.axes.iter().position(|&a| a == letter);
            match (letter, axis) {
                (_, Some(k)) => {
                    next[k] = v;
                    moved[k] = true;
                }
                ('G', _) if v == 0.0 => motion = Some(false),
                ('G', _) if v == 1.0 => motion = Some(true),
                ('G', _) if v == 93.0 => inverse_time = true,
                ('G', _) if v == 94.0 => inverse_time = false,
                ('G', _) if v == 4.0 || super::dialect::SAFE_G.contains(&v) => {}
                ('P' | 'Q', _) => {}
                ('F', _) => f = Some(v),
                ('M', _) if v == 2.0 || v == 30.0 => ended = true,
                _ => {
                    return bad(
                        i,
                        format!("{letter}{v} is not a word of this program's dialect"),
                    )
                }
            }
        }
        if ended && hot {
            return bad(i, "the program ends with the wire hot".into());
        }
        if !moved.iter().any(|&k| k) {
            continue;
        }
        let Some(cut) = motion else {
            return bad(i, "axis words before any G0 or G1".into());
        };
        if (0..4).any(|k| !known[k] && !moved[k]) {
            return bad(i, "a move from a position the program has not set".into());
        }
        if cut != hot {
            return bad(
                i,
                if hot {
                    "a rapid move with the wire hot".into()
                } else {
                    "a cutting move with the wire cold".into()
                },
            );
        }
        if let Some(t) = &m.travel {
            for k in 0..4 {
                let (lo, hi) = t[k];
                if next[k] < lo - half || next[k] > hi + half {
                    return bad(
                        i,
                        format!("{}{} is outside the travel {lo}…{hi}", m.axes[k], next[k]),
                    );
                }
            }
        }
        if cut {
            let da = (next[0] - pos[0]).hypot(next[1] - pos[1]);
            let db = (next[2] - pos[2]).hypot(next[3] - pos[3]);
            let Some(f) = f else {
                return bad(i, "a cutting move without a feed".into());
            };
            // the faster tower's speed, F read as the dialect reads it
            let d = [0, 1, 2, 3].map(|k| next[k] - pos[k]);
            let speed = if inverse_time {
                da.max(db) * f
            } else {
                let l = m.feed.feed_length(&m.axes, d);
                let l = if m.feed == FeedMode::InverseTime {
                    da.hypot(db)
                } else {
                    l
                };
                f * da.max(db) / l.max(f64::MIN_POSITIVE)
            };
            let slack = 1.0 + 1e-2;
            if !(speed >= MIN_SPEED_MM_PER_MIN / slack && speed <= MAX_SPEED_MM_PER_MIN * slack) {
                return bad(
                    i,
                    format!("the wire would move at {speed:.4} mm/min, outside {MIN_SPEED_MM_PER_MIN}–{MAX_SPEED_MM_PER_MIN}"),
                );
            }
        }
        // every axis was known or set: all are known now
        known = [true; 4];
        pos = next;
    }
    if hot {
        return bad(
            text.lines().count().saturating_sub(1),
            "the wire is left hot".into(),
        );
    }
    Ok(())
}

/// The words of a line: comments `( )` (closed, not nested) and `;` dropped, then letters
/// each followed by a plain decimal number, spaces anywhere (`G21G90` and `G21 G90` read
/// alike). Letters come back upper case.
///
/// # Errors
/// What cannot be read: a comment left open or nested, a character that is not a letter
/// where a word begins (`#`, `[`, `<`: parameters and expressions), a letter without its
/// number.
pub fn words(line: &str) -> std::result::Result<Vec<(char, f64)>, String> {
    let mut code = String::new();
    let mut open = false;
    for c in line.chars() {
        match c {
            '(' if open => return Err("a comment inside a comment".into()),
            '(' => open = true,
            ')' if !open => return Err("`)` without `(`".into()),
            ')' => open = false,
            ';' if !open => break,
            c if !open && !c.is_whitespace() => code.push(c),
            _ => {}
        }
    }
    if open {
        return Err("a comment without `)`".into());
    }
    let mut out = Vec::new();
    let mut rest = code.as_str();
    while let Some(letter) = rest.chars().next() {
        if !letter.is_ascii_alphabetic() {
            return Err(format!("{letter:?} where a word's letter belongs"));
        }
        let body = &rest[1..];
        let end = body
            .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+')))
            .unwrap_or(body.len());
        let value: f64 = body[..end]
            .parse()
            .map_err(|_| format!("{letter} without a number"))?;
        out.push((letter.to_ascii_uppercase(), value));
        rest = &body[end..];
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn linuxcnc() -> Machine {
        Machine::linuxcnc_xyuv()
    }

    #[test]
    fn programs_are_read_back() {
        let m = linuxcnc();
        let ok = "%\n(c)\nG17 G21 G90 G94 G61\nG0 X0 Y50 U0 V50\nG0 X0 Y10 U0 V10\nM3 S1000\nG4 P2\nG93\nG1 X100 Y10 U100 V10 F3\nM5\nG94\nG0 X100 Y50 U100 V50\nM2\n%\n";
        check_program(ok, &m).unwrap();
        // what the machine would do: heat per move, codes, positions, the end
        for (from, to) in [
            ("M5\n", ""),                          // left hot, and a hot rapid
            ("M3 S1000\n", ""),                    // a cold cut
            ("M5\nG94\n", "G94\n"),                // a rapid while hot
            ("G93\n", "G93\nG92 X-3000 U-3000\n"), // offsets shifted
            ("G93\n", "G93\nG10 L2 P1 X500\n"),    // offsets rewritten
            ("G0 X0 Y50 U0 V50\n", "G0 X0 Y50\n"), // U and V never set
            ("M2\n", "M2\nG0 X0 Y0 U0 V0\n"),      // a move after the end
            ("M2\n", "M99\nM2\n"),                 // a code of no program
            ("G0 X100 Y50", "G53 G0 X100 Y50"),    // machine coordinates
        ] {
            let text = ok.replace(from, to);
            assert!(check_program(&text, &m).is_err(), "{from:?} → {to:?}");
        }
        let mut travel = m.clone();
        travel.travel = Some([(0.0, 100.0), (0.0, 50.0), (0.0, 100.0), (0.0, 50.0)]);
        check_program(ok, &travel).unwrap();
        assert!(check_program(&ok.replace("Y50 U0", "Y50.01 U0"), &travel).is_err());
        // 100 mm at F3 (1/3 min) is 300 mm/min; at F1000, 100 m/min
        assert!(check_program(&ok.replace("F3", "F1000"), &m).is_err());
        assert!(check_program(&ok.replace("F3", "F0.0000"), &m).is_err());
        assert!(check_program(&ok.replace("X100", "Xinf"), &m).is_err());
        assert!(check_program(&ok.replace("X100", "XNaN"), &m).is_err());
        assert!(check_program(&ok.replace(" F3", ""), &m).is_err());
        // a slow cut: 100 mm at 1.5 mm/min, its feed below 1 with its digits
        let slow = |v: f64| ok.replace("F3", &format!("F{}", feed(v / 100.0)));
        assert!(check_program(&slow(1.5), &m).is_ok());
        assert!(check_program(&slow(0.5), &m).is_err());
        // units per minute over four axes: both towers 100 mm, F = 300 √2
        let upm = ok
            .replace("G93\n", "")
            .replace("F3", &format!("F{}", feed(300.0 * 2f64.sqrt())));
        assert!(check_program(&upm, &m).is_ok());
        // read as inverse time, the same F asks for 42 m/min; 100 m/min is too fast
        let f = feed(300.0 * 2f64.sqrt());
        assert!(check_program(&upm.replace(&f, "100000"), &m).is_err());
    }

    #[test]
    fn numbers_are_plain_and_signless_at_zero() {
        assert_eq!(num(-0.00001, 4), "0.0000");
        assert_eq!(num(-0.00001, 2), "0.00");
        assert_eq!(num(-1.5, 2), "-1.50");
        assert_eq!(feed(0.015), "0.015000000");
        assert_eq!(comment("a (b) é"), "(a [b] _)");
        assert_eq!(min_move_mm(4), 0.05);
        assert_eq!(min_move_mm(2), 0.5);
        assert_eq!(
            words("g21G90 (c) X-1.5;rest").unwrap(),
            vec![('G', 21.0), ('G', 90.0), ('X', -1.5)]
        );
        for bad in ["#<_a> = 1", "G64 P[1]", "(a (b))", "X", "(open"] {
            assert!(words(bad).is_err(), "{bad}");
        }
    }
}
