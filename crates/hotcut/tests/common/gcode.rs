//! An independent reader of hot-wire G-code: it knows nothing of hotcut's writer. It
//! reads a program under one controller's rules (the axis letters, the codes the
//! controller supports, `%`, comments, feed modes, dwell unit, heat commands) and replays
//! it: every position of both towers, every move's duration under that controller's feed
//! rule, the heat state and the dwell before each cut.

/// What a controller accepts and how it reads the program.
#[derive(Debug, Clone)]
pub struct Rules {
    /// Tower A along, up; tower B along, up.
    pub axes: [char; 4],
    /// GRBL 1.1 (and its forks, FluidNC): only its G/M codes and words, no `%`, lines of
    /// at most 80 characters, `F` over the Euclidean length of all axes in `G94`.
    pub grbl: bool,
    /// The program must be wrapped in `%` lines (LinuxCNC's optional wrapper, which then
    /// must be on the first and the last line).
    pub percent: bool,
    /// `G4 P` in milliseconds.
    pub dwell_ms: bool,
    /// The heat-on and heat-off commands, as words: `["M3"]`, `["M64", "P0"]`.
    pub heat_on: Vec<String>,
    /// Heat off.
    pub heat_off: Vec<String>,
}

/// One motion the program commands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// `G0` or `G1`.
    pub cutting: bool,
    /// Both towers after the move: A along, A up, B along, B up (mm).
    pub to: [f64; 4],
    /// Both towers before it.
    pub from: [f64; 4],
    /// Duration of a cutting move under the controller's feed rule, minutes.
    pub minutes: f64,
    /// Heat on during the move.
    pub heat: bool,
    /// Seconds of dwell with the heat on since the heat went on, before this move.
    pub heated_s: f64,
}

/// A replayed program.
#[derive(Debug, Clone, Default)]
pub struct Replay {
    /// Every motion, in order.
    pub motions: Vec<Motion>,
    /// The heat is off at the end.
    pub cold_at_end: bool,
    /// The program ended with `M2` or `M30`.
    pub ended: bool,
}

/// GRBL 1.1's G codes (its `doc/markdown/commands.md` and `gcode.c`).
const GRBL_G: &[f64] = &[
    0.0, 1.0, 2.0, 3.0, 4.0, 10.0, 17.0, 18.0, 19.0, 20.0, 21.0, 28.0, 28.1, 30.0, 30.1, 38.2,
    38.3, 38.4, 38.5, 40.0, 43.1, 49.0, 53.0, 54.0, 55.0, 56.0, 57.0, 58.0, 59.0, 61.0, 80.0, 90.0,
    91.0, 91.1, 92.0, 92.1, 93.0, 94.0,
];
/// GRBL 1.1's M codes.
const GRBL_M: &[f64] = &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 8.0, 9.0, 30.0, 56.0];
/// GRBL 1.1's non-axis words.
const GRBL_WORDS: &str = "FGIJKLMNPRST";

/// Splits a line into words, checking its comments: `( )` must close and not nest, `;`
/// ends the line.
fn words(line: &str) -> Result<Vec<(char, f64)>, String> {
    let mut code = String::new();
    let mut open = false;
    for c in line.chars() {
        match c {
            '(' if open => return Err("a comment inside a comment".into()),
            '(' => open = true,
            ')' if !open => return Err("`)` without `(`".into()),
            ')' => open = false,
            ';' if !open => break,
            c if !open => code.push(c),
            _ => {}
        }
    }
    if open {
        return Err("a comment left open".into());
    }
    let code: String = code.chars().filter(|c| !c.is_whitespace()).collect();
    let mut out = Vec::new();
    let mut rest = code.as_str();
    while let Some(letter) = rest.chars().next() {
        if !letter.is_ascii_alphabetic() {
            return Err(format!("{letter:?} where a letter belongs"));
        }
        let body = &rest[1..];
        let end = body
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+'))
            .unwrap_or(body.len());
        let value: f64 = body[..end]
            .parse()
            .map_err(|_| format!("{letter} without a number"))?;
        if !value.is_finite() {
            return Err(format!("{letter}{value} is not finite"));
        }
        out.push((letter.to_ascii_uppercase(), value));
        rest = &body[end..];
    }
    Ok(out)
}

/// Reads and replays `text`.
///
/// # Errors
/// The first line the controller would refuse, or a program that is not well formed:
/// a move before `G21 G90`, a `G1` without its feed, a line after the end.
pub fn replay(text: &str, rules: &Rules) -> Result<Replay, String> {
    let lines: Vec<&str> = text.lines().collect();
    let code_lines: Vec<(usize, &str)> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| (i, *l))
        .collect();
    if rules.percent {
        let first = code_lines.first().map(|l| l.1.trim());
        let last = code_lines.last().map(|l| l.1.trim());
        if first != Some("%") || last != Some("%") {
            return Err("the program must begin and end with `%`".into());
        }
    }
    let heat_words = |ws: &[(char, f64)], cmd: &[String]| {
        cmd.iter().all(|c| {
            let (l, v) = c.split_at(1);
            let v: f64 = v.parse().unwrap_or(f64::NAN);
            ws.iter().any(|&(a, b)| a.to_string() == l && b == v)
        })
    };
    let mut r = Replay::default();
    let (mut mm, mut absolute, mut inverse) = (false, false, false);
    let mut pos: Option<[f64; 4]> = None;
    let (mut heat, mut heated_s) = (false, 0.0);
    let mut motion_mode: Option<bool> = None;
    for (n, line) in code_lines {
        let at = |e: String| format!("line {}: {line:?}: {e}", n + 1);
        if line.trim() == "%" {
            if !rules.percent {
                return Err(at("`%` (GRBL: error:1)".into()));
            }
            continue;
        }
        if r.ended {
            return Err(at("a line after the program's end".into()));
        }
        if rules.grbl && line.len() > 80 {
            return Err(at("longer than GRBL's 80-character line buffer".into()));
        }
        let ws = words(line).map_err(at)?;
        let mut next = pos.unwrap_or([f64::NAN; 4]);
        let mut moved = false;
        let mut feed = None;
        let mut dwell = None;
        for &(letter, v) in &ws {
            if let Some(k) = rules.axes.iter().position(|&a| a == letter) {
                next[k] = v;
                moved = true;
                continue;
            }
            if rules.grbl && !GRBL_WORDS.contains(letter) {
                return Err(at(format!("{letter}: unsupported word (GRBL: error:20)")));
            }
            match letter {
                'G' => {
                    if rules.grbl && !GRBL_G.contains(&v) {
                        return Err(at(format!("G{v}: not a GRBL 1.1 code (error:20)")));
                    }
                    match v as i64 {
                        0 => motion_mode = Some(false),
                        1 => motion_mode = Some(true),
                        4 => dwell = Some(()),
                        20 => mm = false,
                        21 => mm = true,
                        90 => absolute = true,
                        91 => absolute = false,
                        93 => inverse = true,
                        94 => inverse = false,
                        // modal settings that neither move nor offset: plane, no cutter
                        // compensation, no tool length offset, a work offset, path mode
                        17 | 40 | 49 | 54..=59 | 61 | 64 => {}
                        other => return Err(at(format!("G{other}: unexpected in a wire program"))),
                    }
                }
                'M' if rules.grbl && !GRBL_M.contains(&v) => {
                    return Err(at(format!("M{v}: not a GRBL 1.1 code (error:20)")));
                }
                'M' if v == 2.0 || v == 30.0 => r.ended = true,
                // an M code is the heat's, or the program's end: anything else (M47, M99,
                // a user macro) could do what no replay sees
                'M' if !rules
                    .heat_on
                    .iter()
                    .chain(&rules.heat_off)
                    .any(|c| c == &format!("M{v}")) =>
                {
                    return Err(at(format!("M{v}: neither the heat's code nor the end")));
                }
                'F' => feed = Some(v),
                'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W' => {
                    return Err(at(format!("axis {letter} is not one of the machine's")));
                }
                _ => {}
            }
        }
        if heat_words(&ws, &rules.heat_on) && !rules.heat_on.is_empty() {
            heat = true;
            heated_s = 0.0;
        }
        if heat_words(&ws, &rules.heat_off) && !rules.heat_off.is_empty() {
            heat = false;
        }
        if dwell.is_some() {
            let p = ws.iter().find(|w| w.0 == 'P').map(|w| w.1);
            let p = p.ok_or_else(|| at("G4 without P".into()))?;
            if heat {
                heated_s += if rules.dwell_ms { p / 1000.0 } else { p };
            }
        }
        if !moved {
            continue;
        }
        if !(mm && absolute) {
            return Err(at("a move before G21 and G90".into()));
        }
        if next.iter().any(|v| v.is_nan()) {
            return Err(at("the first move must give all four axes".into()));
        }
        let cutting = motion_mode.ok_or_else(|| at("a move without G0/G1".into()))?;
        let from = pos.unwrap_or(next);
        let mut minutes = 0.0;
        if cutting {
            let f = feed.ok_or_else(|| at("G1 without F on its line".into()))?;
            if !(f > 0.0) {
                return Err(at("F must be positive".into()));
            }
            let d: Vec<f64> = (0..4).map(|k| next[k] - from[k]).collect();
            minutes = if inverse {
                1.0 / f
            } else if rules.grbl {
                d.iter().map(|v| v * v).sum::<f64>().sqrt() / f
            } else {
                // rs274ngc, G94: F along X Y Z when any of them moves, else along U V W,
                // else along A B C
                let group = |letters: &str| {
                    (0..4)
                        .filter(|&k| letters.contains(rules.axes[k]))
                        .map(|k| d[k] * d[k])
                        .sum::<f64>()
                        .sqrt()
                };
                let l = ["XYZ", "UVW", "ABC"]
                    .map(group)
                    .into_iter()
                    .find(|&l| l > 0.0)
                    .unwrap_or(0.0);
                l / f
            };
        }
        r.motions.push(Motion {
            cutting,
            to: next,
            from,
            minutes,
            heat,
            heated_s,
        });
        pos = Some(next);
    }
    r.cold_at_end = !heat;
    Ok(r)
}

#[test]
fn the_reader_refuses_what_controllers_refuse() {
    let grbl = Rules {
        axes: ['X', 'Y', 'Z', 'A'],
        grbl: true,
        percent: false,
        dwell_ms: false,
        heat_on: vec!["M3".into()],
        heat_off: vec!["M5".into()],
    };
    let ok = "G21 G90\nG0 X0 Y0 Z0 A0\nM3 S1000\nG4 P2\nG93\nG1 X10 Y0 Z10 A0 F30\nM5\nG94\nM2\n";
    let r = replay(ok, &grbl).unwrap();
    assert_eq!(r.motions.len(), 2);
    assert!(r.motions[1].heat && r.motions[1].heated_s == 2.0 && r.cold_at_end);
    assert!((r.motions[1].minutes - 1.0 / 30.0).abs() < 1e-15);
    for bad in [
        ok.replace("G21 G90", "%\nG21 G90"),
        ok.replace("Z0 A0\n", "U0 V0\n"),
        ok.replace("G93", "G64"),
        ok.replace(" F30", ""),
        ok.replace("G21 G90\n", ""),
        ok.replace("M2\n", "M2\nG0 X0\n"),
        ok.replace("G4 P2", "(open"),
        ok.replace("M3 S1000", "M62 P0"),
    ] {
        assert!(replay(&bad, &grbl).is_err(), "{bad}");
    }
}
