//! The grammar of a dialect's fixed lines: what a `Custom` profile's header, footer,
//! heat and end lines may say. None of them may move the machine, change its offsets or
//! its feed mode behind the program's checks, or switch the heat anywhere but where the
//! program does.
//!
//! - **Header, footer and end**: modal words only, those of [`SAFE_G`](crate::wire::dialect::SAFE_G) (plane, units,
//!   cutter compensation off, work offsets, path mode, absolute distance,
//!   units-per-minute), `P`/`Q` with `G64` (its tolerances), the words of the profile's
//!   own heat-off line, and in `end` one program end (`M2` or `M30`). Comments are free.
//! - **Heat on**: one switch-on of one output, nothing else: `M3`/`M4` (spindle, with an
//!   optional `S`), `M7`/`M8` (coolant), `M62`/`M64 P<n>` (digital output `n`),
//!   `M67`/`M68 E<n> Q<v>` (analog output `n`). `{power}` may stand for a number.
//! - **Heat off**: the switch-off of that same output: `M5`, `M9`, `M63`/`M65 P<n>`,
//!   `M67`/`M68 E<n> Q0`.
//! - Every number, `{power}` filled in, within ±10⁶ (what the read-back accepts).

/// G codes a header, footer or end line may hold: modal settings that neither move the
/// machine nor change its offsets or feed mode against the profile — `G17` (XY plane),
/// `G21` (mm), `G40` (no cutter compensation), `G49` (no tool length offset), `G54`–`G59.3`
/// (choose a work offset, not change one), `G61`/`G61.1`/`G64` (path mode), `G90`
/// (absolute), `G94` (units per minute).
pub const SAFE_G: &[f64] = &[
    17.0, 21.0, 40.0, 49.0, 54.0, 55.0, 56.0, 57.0, 58.0, 59.0, 59.1, 59.2, 59.3, 61.0, 61.1, 64.0,
    90.0, 94.0,
];

/// Largest number a fixed line may hold (the read-back's bound on any word).
pub const MAX_WORD: f64 = 1e6;

/// The output that heats the wire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HeatOutput {
    /// The spindle (`M3`/`M4` … `M5`).
    Spindle,
    /// Coolant (`M7`/`M8` … `M9`).
    Coolant,
    /// Digital output `P` (`M62`/`M64` … `M63`/`M65`).
    Digital(f64),
    /// Analog output `E` (`M67`/`M68 … Q<v>` … `Q0`).
    Analog(f64),
}

/// The words of `line`, each once, as `(letter, value)`.
type Words = [(char, f64)];

fn only(ws: &Words, allowed: &str) -> Result<(), String> {
    for (i, (l, _)) in ws.iter().enumerate() {
        if !allowed.contains(*l) {
            return Err(format!("{l} has no place here (only {allowed})"));
        }
        if ws[..i].iter().any(|(k, _)| k == l) {
            return Err(format!("{l} is given twice"));
        }
    }
    Ok(())
}

fn value(ws: &Words, letter: char) -> Option<f64> {
    ws.iter().find(|(l, _)| *l == letter).map(|w| w.1)
}

/// What `heat_on`'s words switch on.
///
/// # Errors
/// Why they are not one switch-on of one output (module doc).
pub fn heat_on_output(ws: &Words) -> Result<HeatOutput, String> {
    let m = value(ws, 'M').ok_or("the heat needs an M code")?;
    let need = |l: char| value(ws, l).ok_or(format!("M{m} needs {l}"));
    let positive = |l: char| match value(ws, l) {
        Some(v) if !(v > 0.0) => Err(format!("{l}{v} would leave the wire cold")),
        _ => Ok(()),
    };
    match m {
        3.0 | 4.0 => {
            only(ws, "MS")?;
            positive('S')?;
            Ok(HeatOutput::Spindle)
        }
        7.0 | 8.0 => only(ws, "M").map(|_| HeatOutput::Coolant),
        62.0 | 64.0 => {
            only(ws, "MP")?;
            Ok(HeatOutput::Digital(need('P')?))
        }
        67.0 | 68.0 => {
            only(ws, "MEQ")?;
            need('Q')?;
            positive('Q')?;
            Ok(HeatOutput::Analog(need('E')?))
        }
        _ => Err(format!(
            "M{m} is not a heat switch: use M3/M4 [S], M7/M8, M62/M64 P<n> or M67/M68 E<n> Q<v>"
        )),
    }
}

/// What `heat_off`'s words switch off.
///
/// # Errors
/// Why they are not one switch-off of one output (module doc).
pub fn heat_off_output(ws: &Words) -> Result<HeatOutput, String> {
    let m = value(ws, 'M').ok_or("the heat needs an M code")?;
    let need = |l: char| value(ws, l).ok_or(format!("M{m} needs {l}"));
    match m {
        5.0 => only(ws, "M").map(|_| HeatOutput::Spindle),
        9.0 => only(ws, "M").map(|_| HeatOutput::Coolant),
        63.0 | 65.0 => {
            only(ws, "MP")?;
            Ok(HeatOutput::Digital(need('P')?))
        }
        67.0 | 68.0 if value(ws, 'Q') == Some(0.0) => {
            only(ws, "MEQ")?;
            Ok(HeatOutput::Analog(need('E')?))
        }
        _ => Err(format!(
            "M{m} is not a heat switch-off: use M5, M9, M63/M65 P<n> or M67/M68 E<n> Q0"
        )),
    }
}

/// Why a header, footer or end line's words cannot go into a program (`None`: they can);
/// `off` the heat-off line's words, `end` whether this is the program's end line.
pub fn fixed_line_problem(ws: &Words, off: &Words, end: bool) -> Option<String> {
    let g64 = ws.contains(&('G', 64.0));
    let mut stops = 0;
    for &(l, v) in ws {
        let ok = match l {
            'G' => SAFE_G.contains(&v),
            'P' | 'Q' if g64 => true,
            'M' if end && (v == 2.0 || v == 30.0) => {
                stops += 1;
                true
            }
            _ => off.contains(&(l, v)),
        };
        if !ok {
            let what = match (l, v) {
                ('G', 20.0) | ('G', 91.0) => "programs are absolute millimetres",
                ('G', 0.0) | ('G', 1.0) | ('G', 2.0) | ('G', 3.0) => "it would move the machine",
                ('G', 10.0) | ('G', 92.0) | ('G', 52.0) | ('G', 92.1) => {
                    "it would change the offsets the program is checked in"
                }
                ('G', 28.0) | ('G', 30.0) | ('G', 53.0) => "it would move the machine",
                ('G', 93.0) | ('G', 95.0) => "the program sets its own feed mode",
                ('M', 0.0) | ('M', 1.0) | ('M', 2.0) | ('M', 30.0) | ('M', 60.0) => {
                    "only the end line stops the program"
                }
                ('M', _) => "only the heat lines switch outputs, and only the end line ends",
                ('X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W', _) => {
                    "axis words would move the machine"
                }
                _ => "a fixed line holds modal settings only",
            };
            return Some(format!(
                "{l}{v} is not allowed: {what} (fixed lines may hold G17 G21 G40 G49 G54–G59.3 G61 G61.1 G64 G90 G94, comments, and the heat-off words)"
            ));
        }
    }
    match (end, stops) {
        (true, 1) | (false, 0) => None,
        (true, 0) => Some("must stop the program: M2 or M30".into()),
        (true, _) => Some("stops the program twice".into()),
        (false, _) => Some("stops the program before it ends".into()),
    }
}

/// Why a number cannot stand in a fixed line or a program (`None`: it can).
pub fn number_problem(letter: char, v: f64) -> Option<String> {
    (!(v.is_finite() && v.abs() <= MAX_WORD))
        .then(|| format!("{letter}{v} is not a finite number within ±{MAX_WORD}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(line: &str) -> Vec<(char, f64)> {
        crate::wire::program::words(line).unwrap()
    }

    #[test]
    fn heat_lines_pair_up() {
        for (on, off) in [
            ("M3 S1000", "M5"),
            ("M4", "M5"),
            ("M8", "M9"),
            ("M64 P2", "M65 P2"),
            ("M62 P2", "M65 P2"),
            ("M67 E1 Q5", "M68 E1 Q0"),
        ] {
            let a = heat_on_output(&w(on)).unwrap();
            assert_eq!(a, heat_off_output(&w(off)).unwrap(), "{on} / {off}");
        }
        for bad in [
            "M64 P0 G1 X700",
            "M3 X1",
            "M100",
            "M64",
            "M3 S0",
            "M67 E0 Q0",
            "G1 M3",
        ] {
            assert!(heat_on_output(&w(bad)).is_err(), "{bad}");
        }
        assert_ne!(
            heat_on_output(&w("M64 P0")).unwrap(),
            heat_off_output(&w("M9")).unwrap()
        );
    }

    #[test]
    fn fixed_lines_cannot_move_offset_or_repeat() {
        let off = w("M5");
        for ok in [
            "G17 G21 G90 G94 G61",
            "G54",
            "G64 P0.01 Q0.01",
            "M5",
            "(park)",
        ] {
            assert_eq!(fixed_line_problem(&w(ok), &off, false), None, "{ok}");
        }
        for bad in [
            "G0 X5000 U5000",
            "G92 X-3000",
            "G10 L2 P1 X500",
            "G53 G0 X0",
            "G28 X0",
            "M64 P0",
            "M47",
            "M99",
            "G93",
            "G1 X0 F0.000001",
            "M30",
        ] {
            assert!(fixed_line_problem(&w(bad), &off, false).is_some(), "{bad}");
        }
        assert_eq!(fixed_line_problem(&w("M30"), &off, true), None);
        assert!(fixed_line_problem(&w("M30 G0 X9000"), &off, true).is_some());
        assert!(fixed_line_problem(&w("G90"), &off, true).is_some());
    }
}
