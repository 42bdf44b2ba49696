//! What a foam cutter's controller reads: the axis letters of the two towers, the setup
//! lines, the heat commands, the feed mode, the number format and the travel of each axis
//! ([`Machine`]), and the built-in profiles. The conventions and their sources are in
//! `docs/wire-controllers.md`.

use super::dialect;
use crate::error::{PreCutError, Result};

/// How a cutting move's `F` is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum FeedMode {
    /// `G93`: `F` is 1 / minutes for the whole move, whatever axes move. Both towers start
    /// and finish together on every controller.
    #[default]
    InverseTime,
    /// `G94`: `F` is the speed along the Euclidean length over all four axes (GRBL,
    /// grbl-Mega-5X, FluidNC). hotcut writes `F = v · √(a² + b²) / max(a, b)` per move
    /// (`a`, `b` the towers' travels), so the faster tower runs at the set speed.
    UnitsPerMinute,
    /// `G94` as rs274ngc (LinuxCNC) reads it: `F` is the speed along the X/Y/Z axes when
    /// any of them moves, else along U/V/W, else along A/B/C. hotcut writes `F` = that
    /// length / the move's time, so the faster tower runs at the set speed.
    UnitsPerMinuteXyz,
}

impl FeedMode {
    /// The length `F` is the speed along, for a move of `d` on the axes `axes`.
    pub fn feed_length(self, axes: &[char; 4], d: [f64; 4]) -> f64 {
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        match self {
            Self::InverseTime => 1.0,
            Self::UnitsPerMinute => norm(&d),
            Self::UnitsPerMinuteXyz => {
                for group in ["XYZ", "UVW", "ABC"] {
                    let part: Vec<f64> = (0..4)
                        .filter(|&k| group.contains(axes[k]))
                        .map(|k| d[k])
                        .collect();
                    let l = norm(&part);
                    if l > 0.0 {
                        return l;
                    }
                }
                0.0
            }
        }
    }
}

/// The unit of the dwell word `G4 P`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum DwellUnit {
    /// `G4 P2` waits 2 s (LinuxCNC, GRBL, FluidNC, Mach3 by default).
    #[default]
    Seconds,
    /// `G4 P2000` waits 2 s (Mach3 with "G04 dwell param in ms" ticked, Fanuc-style).
    Milliseconds,
}

/// Most header and footer lines of a dialect together.
pub const MAX_LINES: usize = 64;

/// Least and most number of decimals of a coordinate.
pub const DECIMALS: (usize, usize) = (2, 6);

/// A controller dialect and the machine's travel, everything a program needs beyond the
/// wire's path. Lengths in millimetres.
///
/// ```
/// use ruled::wire::Machine;
/// let mut m = Machine::grbl_4axis();
/// m.travel = Some([(0.0, 900.0), (0.0, 800.0), (0.0, 900.0), (0.0, 800.0)]);
/// assert!(m.check().is_ok());
/// assert_eq!(m.axes, ['X', 'Y', 'Z', 'A']);
/// assert_eq!(m.heat_on_line(), "M3 S1000");
/// assert_eq!(m.preheat_line().as_deref(), Some("G4 P2"));
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Machine {
    /// The profile's name, written in the program's header.
    pub profile: String,
    /// Axis letters: tower A along the cut, tower A up, tower B along, tower B up.
    pub axes: [char; 4],
    /// Wrap the program in `%` lines (LinuxCNC: the end of the program is then certain).
    pub percent: bool,
    /// Setup lines after the header comments (units, distance mode, plane, exact path).
    pub header: Vec<String>,
    /// Lines after the last move, before `end`.
    pub footer: Vec<String>,
    /// The program end: `M2` or `M30`.
    pub end: String,
    /// Heat on, `{power}` replaced by `power`.
    pub heat_on: String,
    /// Heat off.
    pub heat_off: String,
    /// The value of `{power}` in `heat_on`.
    pub power: f64,
    /// Wait after heat on, before the first cutting move, seconds (≥ 0; 0 writes no dwell).
    pub preheat_s: f64,
    /// The unit of `G4 P`.
    pub dwell: DwellUnit,
    /// How `F` is written.
    pub feed: FeedMode,
    /// Decimals of coordinates (2–6).
    pub decimals: usize,
    /// `(min, max)` travel of each axis in the order of `axes`, mm; `None`: not checked.
    pub travel: Option<[(f64, f64); 4]>,
    /// Fastest feed the machine takes on one axis, mm/min.
    pub max_speed: f64,
    /// Comment lines for the operator: what the controller must be set to.
    pub notes: Vec<String>,
}

/// Setup lines shared by the profiles: XY plane, millimetres, absolute, units-per-minute
/// feed until the cut, exact path.
const SETUP: &str = "G17 G21 G90 G94 G61";

impl Machine {
    /// LinuxCNC 2.9 configured like its `sim/axis/foam` sample: `trivkins
    /// coordinates=xyuv`, tower A on X/Y and tower B on U/V. `%` wrappers, `G17 G21 G90
    /// G61`, inverse-time feed, heat by the spindle output (`M3 S{power}` / `M5`).
    pub fn linuxcnc_xyuv() -> Self {
        Self {
            profile: "LinuxCncXyuv".into(),
            axes: ['X', 'Y', 'U', 'V'],
            percent: true,
            header: vec![format!("{SETUP} G54")],
            footer: Vec::new(),
            end: "M2".into(),
            heat_on: "M3 S{power}".into(),
            heat_off: "M5".into(),
            power: 1000.0,
            preheat_s: 2.0,
            dwell: DwellUnit::Seconds,
            feed: FeedMode::InverseTime,
            decimals: 4,
            travel: None,
            max_speed: super::MAX_SPEED_MM_PER_MIN,
            notes: vec![
                "LinuxCNC XYUV: trivkins coordinates=xyuv, all axes linear in mm".into(),
                "heat: the spindle output M3/M5 switches the wire's supply".into(),
            ],
        }
    }

    /// A 4-axis GRBL 1.1 fork (grbl-Mega-5X, as in rcKeith's foam cutter): tower A on X/Y,
    /// tower B on Z/A. No `%` (GRBL answers `error:1`), inverse-time feed (GRBL 1.1 has
    /// `G93`), heat `M3 S{power}` / `M5` with laser mode off (`$32=0`).
    pub fn grbl_4axis() -> Self {
        Self {
            profile: "Grbl4Axis".into(),
            axes: ['X', 'Y', 'Z', 'A'],
            percent: false,
            header: vec![SETUP.into()],
            notes: vec![
                "GRBL 4-axis fork such as grbl-Mega-5X: stock GRBL has no A".into(),
                "tower B is Z along, A up; set A linear in mm".into(),
                "set $32=0: in laser mode M3 is off during the preheat dwell".into(),
                "coordinates are work coordinates: set the work zero first".into(),
            ],
            ..Self::linuxcnc_xyuv()
        }
    }

    /// FluidNC with four linear axes: tower B on Z/A (`xyza: true`) or A/B.
    pub fn fluidnc(xyza: bool) -> Self {
        let axes = if xyza {
            ['X', 'Y', 'Z', 'A']
        } else {
            ['X', 'Y', 'A', 'B']
        };
        Self {
            profile: "FluidNc".into(),
            axes,
            notes: vec![
                format!(
                    "FluidNC: tower B is {} along, {} up; set both linear in mm",
                    axes[2], axes[3]
                ),
                if xyza {
                    "the config defines axes X Y Z A".into()
                } else {
                    "B needs five axes in the config: define Z too, unused".into()
                },
                "heat: the spindle output M3/M5 switches the wire's supply".into(),
            ],
            ..Self::grbl_4axis()
        }
    }

    /// Mach3 with a fourth linear axis: tower A on X/Y, tower B on Z/A. `M3` / `M5` on the
    /// spindle relay, `G4 P` in seconds (General Config: "G04 dwell param in ms" off),
    /// `M30` at the end.
    pub fn mach3() -> Self {
        Self {
            profile: "Mach3".into(),
            axes: ['X', 'Y', 'Z', 'A'],
            percent: false,
            header: vec![SETUP.into()],
            end: "M30".into(),
            heat_on: "M3".into(),
            notes: vec![
                "Mach3: tower B is Z along, A up; set A linear in mm".into(),
                "G4 P in seconds: untick G04 dwell param in ms".into(),
                "heat: the spindle relay M3/M5 switches the wire's supply".into(),
            ],
            ..Self::linuxcnc_xyuv()
        }
    }

    /// `heat_on` with `{power}` filled in.
    pub fn heat_on_line(&self) -> String {
        self.heat_on.replace("{power}", &trim_number(self.power))
    }

    /// The dwell line for the preheat (`None` for no preheat).
    pub fn preheat_line(&self) -> Option<String> {
        (self.preheat_s > 0.0).then(|| {
            let p = match self.dwell {
                DwellUnit::Seconds => self.preheat_s,
                DwellUnit::Milliseconds => self.preheat_s * 1000.0,
            };
            format!("G4 P{}", trim_number(p))
        })
    }

    /// Checks the dialect: four distinct axis letters, lines of printable ASCII without
    /// comments' parentheses problems, `{power}` the only placeholder, decimals and times
    /// in range, travel ordered.
    ///
    /// # Errors
    /// [`PreCutError::InvalidParameter`] naming the field.
    pub fn check(&self) -> Result<()> {
        let bad = |name, reason: String| Err(PreCutError::InvalidParameter { name, reason });
        let letters = "XYZABCUVW";
        for (i, c) in self.axes.iter().enumerate() {
            if !letters.contains(*c) || self.axes[..i].contains(c) {
                return bad(
                    "axes",
                    format!(
                        "{:?} must be four different letters of {letters}",
                        self.axes.iter().collect::<String>()
                    ),
                );
            }
        }
        let count = self.header.len() + self.footer.len();
        if count > MAX_LINES {
            return bad(
                "header",
                format!("{count} header and footer lines, at most {MAX_LINES}"),
            );
        }
        // `{power}` is written to 3 decimals: S0 would leave the wire cold
        if self.heat_on.contains("{power}")
            && !(self.power.is_finite() && (0.001..=1e6).contains(&self.power))
        {
            return bad(
                "power",
                format!(
                    "{} must be within 0.001–1e6: heat on would write S{}{}",
                    self.power,
                    trim_number(self.power),
                    if self.power.abs() < 0.001 {
                        ", a cold wire"
                    } else {
                        ""
                    }
                ),
            );
        }
        self.check_lines()?;
        if !(DECIMALS.0..=DECIMALS.1).contains(&self.decimals) {
            return bad(
                "decimals",
                format!(
                    "{} must be within {}–{}",
                    self.decimals, DECIMALS.0, DECIMALS.1
                ),
            );
        }
        // the dwell is written to 3 decimals of its unit: 0, or at least 10 ms
        let p = self.preheat_s;
        if !(p.is_finite() && (p == 0.0 || (0.01..=600.0).contains(&p))) {
            return bad(
                "preheat_s",
                format!("{p} must be 0 (no dwell) or within 0.01–600 s"),
            );
        }
        if !(self.max_speed.is_finite() && self.max_speed > 0.0) {
            return bad("max_speed", format!("{} must be positive", self.max_speed));
        }
        if let Some(t) = &self.travel {
            for ((lo, hi), axis) in t.iter().zip(self.axes) {
                let ok = lo.is_finite()
                    && hi.is_finite()
                    && lo < hi
                    && lo.abs().max(hi.abs()) <= super::MAX_TRAVEL_MM;
                if !ok {
                    return bad(
                        "travel",
                        format!(
                            "axis {axis}: ({lo}, {hi}) must be finite, min < max, within ±{} mm",
                            super::MAX_TRAVEL_MM
                        ),
                    );
                }
            }
        }
        Ok(())
    }
}

impl Machine {
    /// Checks the dialect's own lines ([`super::dialect`]): every line plain words a
    /// controller reads (no parameters or expressions), `{power}` only in `heat_on`;
    /// header, footer and end modal words that cannot move the machine, change its offsets
    /// or feed mode, `end` stopping the program and no other line; heat on one switch-on
    /// of one output and heat off the switch-off of the same; the header setting `G21` and
    /// `G90`; every number, `{power}` filled in, within the read-back's bounds.
    fn check_lines(&self) -> Result<()> {
        let bad = |name, reason: String| Err(PreCutError::InvalidParameter { name, reason });
        let heat_on = self.heat_on_line();
        let lines = self
            .header
            .iter()
            .map(|l| ("header", l.as_str(), l.clone()))
            .chain(
                self.footer
                    .iter()
                    .map(|l| ("footer", l.as_str(), l.clone())),
            )
            .chain([
                ("heat_on", self.heat_on.as_str(), heat_on.clone()),
                ("heat_off", self.heat_off.as_str(), self.heat_off.clone()),
                ("end", self.end.as_str(), self.end.clone()),
            ]);
        let mut parsed = Vec::new();
        for (name, line, filled) in lines {
            if let Some(reason) = line_problem(line, name == "heat_on") {
                return bad(name, format!("{line:?}: {reason}"));
            }
            let ws = match super::program::words(&filled) {
                Ok(ws) => ws,
                Err(e) => return bad(name, format!("{line:?}: {e}")),
            };
            if let Some(p) = ws.iter().find_map(|&(l, v)| dialect::number_problem(l, v)) {
                return bad(name, format!("{filled:?}: {p}"));
            }
            parsed.push((name, line, ws));
        }
        let words = |n: &str| {
            parsed
                .iter()
                .find(|p| p.0 == n)
                .map(|p| p.2.clone())
                .unwrap_or_default()
        };
        let (on, off) = (words("heat_on"), words("heat_off"));
        let on_output =
            dialect::heat_on_output(&on).map_err(|e| PreCutError::InvalidParameter {
                name: "heat_on",
                reason: format!("{:?}: {e}", self.heat_on),
            })?;
        let off_output =
            dialect::heat_off_output(&off).map_err(|e| PreCutError::InvalidParameter {
                name: "heat_off",
                reason: format!("{:?}: {e}", self.heat_off),
            })?;
        if on_output != off_output {
            return bad(
                "heat_off",
                format!(
                    "{:?} switches off {off_output:?}, but heat_on {:?} switches on {on_output:?}: heat off must switch off what heat on switches on",
                    self.heat_off, self.heat_on
                ),
            );
        }
        let mut header = Vec::new();
        for (name, line, ws) in &parsed {
            if matches!(*name, "heat_on" | "heat_off") {
                continue;
            }
            if let Some(p) = dialect::fixed_line_problem(ws, &off, *name == "end") {
                return bad(name, format!("{line:?}: {p}"));
            }
            if *name == "header" {
                header.extend(ws.iter().copied());
            }
        }
        for needed in [21.0, 90.0] {
            if !header.contains(&('G', needed)) {
                return bad(
                    "header",
                    format!("the setup lines must set G{needed} (programs are absolute millimetres), e.g. \"G17 G21 G90 G94 G61\""),
                );
            }
        }
        Ok(())
    }
}

/// Why a setup line cannot go into a program (`None`: it can); `{power}` is allowed where
/// `power` says.
fn line_problem(line: &str, power: bool) -> Option<String> {
    if line.len() > 70 {
        return Some("longer than 70 characters".into());
    }
    if let Some(c) = line.chars().find(|c| !(' '..='~').contains(c)) {
        return Some(format!("{c:?} is not printable ASCII"));
    }
    if line.contains('%') {
        return Some("`%` is the program's wrapper, not a line's".into());
    }
    let mut open = false;
    let semicolon = line.chars().any(|c| {
        match c {
            '(' => open = true,
            ')' => open = false,
            _ => {}
        }
        c == ';' && !open
    });
    if semicolon {
        // LinuxCNC and GRBL end a line at `;`, but not every controller does, and one
        // that does not would run what follows: comments go in parentheses (where a `;`
        // is only text)
        return Some(
            "`;` does not start a comment on every controller: put comments in parentheses".into(),
        );
    }
    let rest = if power {
        line.replace("{power}", "")
    } else {
        line.to_string()
    };
    if rest.contains('{') || rest.contains('}') {
        return Some(if power {
            "`{power}` is the only placeholder".into()
        } else {
            "placeholders belong in heat_on only".into()
        });
    }
    // comments and words: `program::words`, which the caller applies next
    None
}

/// A number as short as it reads exactly to 3 decimals: `1000`, `2.5`.
fn trim_number(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_profiles_are_valid() {
        for m in [
            Machine::linuxcnc_xyuv(),
            Machine::grbl_4axis(),
            Machine::fluidnc(true),
            Machine::fluidnc(false),
            Machine::mach3(),
        ] {
            m.check().unwrap();
            // `;` is text inside a comment, a comment's start nowhere else
            assert!(line_problem("G21 G90 (tower A; tower B)", false).is_none());
            assert!(line_problem("G21 G90 (a) ; G0 X5", false).is_some());
            // a note is written as a comment line
            assert!(m
                .notes
                .iter()
                .all(|n| line_problem(&format!("({n})"), false).is_none()));
        }
        assert_eq!(Machine::linuxcnc_xyuv().heat_on_line(), "M3 S1000");
        assert_eq!(
            Machine::linuxcnc_xyuv().preheat_line().as_deref(),
            Some("G4 P2")
        );
    }

    #[test]
    fn bad_dialects_are_named() {
        let m = Machine::linuxcnc_xyuv;
        let cases = [
            (
                "axes",
                Machine {
                    axes: ['X', 'Y', 'X', 'V'],
                    ..m()
                },
            ),
            (
                "axes",
                Machine {
                    axes: ['X', 'Y', 'Q', 'V'],
                    ..m()
                },
            ),
            (
                "heat_on",
                Machine {
                    heat_on: "M3 S{speed}".into(),
                    ..m()
                },
            ),
            (
                "header",
                Machine {
                    header: vec!["(a (b))".into()],
                    ..m()
                },
            ),
            (
                "footer",
                Machine {
                    footer: vec!["%".into()],
                    ..m()
                },
            ),
            (
                "header",
                Machine {
                    header: vec!["G0\nX1".into()],
                    ..m()
                },
            ),
            ("decimals", Machine { decimals: 9, ..m() }),
            (
                "header",
                Machine {
                    footer: vec!["M9".into(); 65],
                    ..m()
                },
            ),
            (
                "preheat_s",
                Machine {
                    preheat_s: f64::NAN,
                    ..m()
                },
            ),
            (
                "travel",
                Machine {
                    travel: Some([(0.0, 1.0), (1.0, 0.0), (0.0, 1.0), (0.0, 1.0)]),
                    ..m()
                },
            ),
        ];
        let lines = |header: &[&str], footer: &[&str], on: &str, off: &str, end: &str| Machine {
            header: header.iter().map(|s| s.to_string()).collect(),
            footer: footer.iter().map(|s| s.to_string()).collect(),
            heat_on: on.into(),
            heat_off: off.into(),
            end: end.into(),
            ..m()
        };
        let g = ["G17 G21 G90"];
        let more = [
            ("heat_on", lines(&g, &[], "", "M5", "M2")),
            ("heat_on", lines(&g, &[], "(on)", "M5", "M2")),
            ("heat_on", lines(&g, &[], "M100 P1", "M100 P1", "M2")),
            ("heat_off", lines(&g, &[], "M64 P0", "M9", "M2")),
            ("heat_off", lines(&g, &[], "M3", "M3", "M2")),
            (
                "heat_on",
                lines(&g, &[], "M64 P0 G1 X700 Y0 U700 V0 F100", "M65 P0", "M2"),
            ),
            ("heat_on", lines(&g, &[], "M3 S99999999", "M5", "M2")),
            ("heat_on", lines(&g, &[], "M3 S{power}{power}", "M5", "M2")),
            ("footer", lines(&g, &["G0 X5000 U5000"], "M3", "M5", "M2")),
            (
                "header",
                lines(&["G17 G21 G90", "G92 X-3000 U-3000"], &[], "M3", "M5", "M2"),
            ),
            (
                "header",
                lines(
                    &["G17 G21 G90", "G10 L2 P1 X500 U500"],
                    &[],
                    "M3",
                    "M5",
                    "M2",
                ),
            ),
            ("footer", lines(&g, &["G53 G0 X0"], "M3", "M5", "M2")),
            ("footer", lines(&g, &["G28 X0"], "M3", "M5", "M2")),
            (
                "header",
                lines(&["G17 G21 G90", "M64 P0"], &[], "M64 P0", "M65 P0", "M2"),
            ),
            (
                "footer",
                lines(
                    &g,
                    &["M64 P0", "G1 X0 Y0 U0 V0 F100"],
                    "M64 P0",
                    "M65 P0",
                    "M2",
                ),
            ),
            ("end", lines(&g, &[], "M3", "M5", "M30 G0 X9000")),
            ("footer", lines(&g, &["M47"], "M3", "M5", "M2")),
            ("footer", lines(&g, &["M99"], "M3", "M5", "M2")),
            ("header", lines(&["G17 G21 G90 G93"], &[], "M3", "M5", "M2")),
            ("footer", lines(&g, &["G1 X0 F0.000001"], "M3", "M5", "M2")),
            ("heat_on", lines(&g, &[], "M5", "M3 S1000", "M2")),
            ("heat_off", lines(&g, &[], "M64 P0", "M64 P1", "M2")),
            ("heat_off", lines(&g, &[], "M64 P0", "M65 P1", "M2")),
            ("header", lines(&["G17"], &[], "M3", "M5", "M2")),
            ("header", lines(&["( G21 G90 )"], &[], "M3", "M5", "M2")),
            // `;` comments are refused: not every controller reads them as comments
            ("header", lines(&["G21 G90 ; G91"], &[], "M3", "M5", "M2")),
            ("footer", lines(&g, &["; G0 X5000"], "M3", "M5", "M2")),
            ("footer", lines(&g, &["G91"], "M3", "M5", "M2")),
            ("header", lines(&["G21 G90 M2"], &[], "M3", "M5", "M2")),
            (
                "header",
                lines(&["G21 G90 S{power}"], &[], "M3", "M5", "M2"),
            ),
            (
                "header",
                lines(&["G21 G90 G64P[0.01]"], &[], "M3", "M5", "M2"),
            ),
            ("footer", lines(&g, &["#<_park> = 1"], "M3", "M5", "M2")),
            ("end", lines(&g, &[], "M3", "M5", "M5")),
            ("end", lines(&g, &[], "M3", "M5", " ")),
            (
                "power",
                Machine {
                    power: 0.0004,
                    ..m()
                },
            ),
            (
                "preheat_s",
                Machine {
                    preheat_s: 0.0004,
                    ..m()
                },
            ),
        ];
        let cases: Vec<_> = cases.into_iter().chain(more).collect();
        // spaces are optional between words; a heat without {power} needs no power
        assert!(lines(&["G21G90"], &[], "M64 P0", "M65 P0", "M30")
            .check()
            .is_ok());
        assert!(Machine {
            power: 0.0,
            ..lines(&g, &[], "M8", "M9", "M2")
        }
        .check()
        .is_ok());
        for (field, machine) in cases {
            match machine.check() {
                Err(PreCutError::InvalidParameter { name, .. }) => assert_eq!(name, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        let ms = Machine {
            dwell: DwellUnit::Milliseconds,
            preheat_s: 2.5,
            ..m()
        };
        assert_eq!(ms.preheat_line().as_deref(), Some("G4 P2500"));
    }
}
