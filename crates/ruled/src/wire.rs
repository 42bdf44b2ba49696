//! Wire paths of the cuts for a 4-axis hot-wire machine, and their G-code.
//!
//! The machine has two towers `tower_distance` apart, on either side of the block along
//! the across direction `w` and centred on the block; each tower moves the wire's end in
//! its plane: horizontally along the cut (`X` for tower A at the low-`w` side, `U` for
//! tower B) and vertically (`Y`, `V`). Machine coordinates are the frame's `u − u0` and
//! `z − z_floor` of the block, in millimetres.
//!
//! Per cut (leg) the wire follows the leg's rulings from `lead` before the block to `lead`
//! after it. The kerf is applied first: each ruling's two points at the block's sides are
//! moved by half the kerf along the cut surface's upward normal there (into the removed
//! material), and the wire is the line through them, extended to both tower planes.
//! G-code is absolute (`G90`), millimetres (`G21`), inverse-time feed (`G93`): every
//! `G1` gives `F = 1 / minutes` for the move, so both towers start and finish each move
//! together.

use std::fmt::Write as _;

use nalgebra::Vector3;
use serde::Serialize;

use crate::error::{PreCutError, Result};
use crate::DirectionCut;

/// The machine and the cut's settings (lengths in the job's unit, `mm_per_unit` to mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WireParams {
    /// Distance between the tower planes (> the block's width across the cut).
    pub tower_distance: f64,
    /// Kerf width (≥ 0): material the wire burns away.
    pub kerf: f64,
    /// Wire speed through the material, job units per minute (> 0).
    pub speed: f64,
    /// Lead-in and lead-out length along the cut outside the block (≥ 0).
    pub lead: f64,
    /// Clearance above the block for rapid moves (> 0).
    pub clearance: f64,
    /// Steps per cut along the block.
    pub steps: usize,
    /// Millimetres per job unit.
    pub mm_per_unit: f64,
}

/// One wire position: the two tower points (machine coordinates, mm) and the 3D points
/// where the wire crosses the block's sides (model coordinates, job units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WireStep {
    /// Position along the cut (frame `u`, job units).
    pub u: f64,
    /// Tower A `(X, Y)`.
    pub a: [f64; 2],
    /// Tower B `(U, V)`.
    pub b: [f64; 2],
    /// Wire point at the block's low-`w` side (after kerf), model coordinates.
    pub side0: [f64; 3],
    /// Wire point at the block's high-`w` side (after kerf), model coordinates.
    pub side1: [f64; 3],
}

/// The path of one cut.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WirePath {
    /// Direction index.
    pub direction: usize,
    /// Leg (cut) index.
    pub leg: usize,
    /// Steps: lead-in start, the block from end to end, lead-out end.
    pub steps: Vec<WireStep>,
    /// `w` of tower A's and tower B's planes.
    pub towers: (f64, f64),
}

/// Fastest wire speed a program may ask for, mm/min (hot-wire foam cutters run at tens to
/// a few thousand mm/min; 1 m/s is far beyond any).
pub const MAX_SPEED_MM_PER_MIN: f64 = 60_000.0;
/// Slowest wire speed, mm/min (slower, the wire melts a channel, not a cut).
pub const MIN_SPEED_MM_PER_MIN: f64 = 1.0;
/// Longest lead, clearance or tower distance, mm (beyond any cutter's travel).
pub const MAX_TRAVEL_MM: f64 = 20_000.0;

/// Checks the wire settings for a block `width` wide across the cut (job units): the
/// towers clear the block, the kerf is under a tenth of the width, and speed, lead,
/// clearance and tower distance are finite and within the bounds above (converted by
/// `mm_per_unit`). [`paths`] makes the same checks; validation calls this first.
///
/// # Errors
/// [`PreCutError::InvalidParameter`] naming the first setting out of range.
pub fn check(width: f64, p: &WireParams) -> Result<()> {
    let bad = |name, reason: String| Err(PreCutError::InvalidParameter { name, reason });
    let mm = |v: f64| v * p.mm_per_unit;
    if !(p.mm_per_unit.is_finite() && p.mm_per_unit > 0.0) {
        return bad("mm_per_unit", format!("{} must be positive", p.mm_per_unit));
    }
    if !(p.tower_distance.is_finite() && p.tower_distance > width) {
        return bad(
            "tower_distance",
            format!(
                "{} must exceed the block's width across the cut, {width}",
                p.tower_distance
            ),
        );
    }
    if !(mm(p.tower_distance) <= MAX_TRAVEL_MM) {
        return bad(
            "tower_distance",
            format!(
                "{} is beyond any cutter ({MAX_TRAVEL_MM} mm at most)",
                p.tower_distance
            ),
        );
    }
    if !(p.kerf.is_finite() && p.kerf >= 0.0 && p.kerf < width / 10.0) {
        return bad(
            "kerf",
            format!(
                "{} must be in [0, width/10) for a block {width} wide across the cut",
                p.kerf
            ),
        );
    }
    if !(mm(p.speed) >= MIN_SPEED_MM_PER_MIN && mm(p.speed) <= MAX_SPEED_MM_PER_MIN) {
        return bad(
            "speed",
            format!(
                "{} must be within {MIN_SPEED_MM_PER_MIN}–{MAX_SPEED_MM_PER_MIN} mm/min",
                p.speed
            ),
        );
    }
    if !(p.lead.is_finite() && p.lead >= 0.0 && mm(p.lead) <= MAX_TRAVEL_MM) {
        return bad(
            "lead",
            format!("{} must be within 0–{MAX_TRAVEL_MM} mm", p.lead),
        );
    }
    if !(p.clearance.is_finite() && p.clearance > 0.0 && mm(p.clearance) <= MAX_TRAVEL_MM) {
        return bad(
            "clearance",
            format!(
                "{} must be positive and at most {MAX_TRAVEL_MM} mm",
                p.clearance
            ),
        );
    }
    Ok(())
}

/// The wire paths of every leg of one direction.
///
/// # Errors
/// [`PreCutError::InvalidParameter`] when the towers do not clear the block or a
/// setting is out of range.
pub fn paths(d: &DirectionCut, index: usize, floor: f64, p: &WireParams) -> Result<Vec<WirePath>> {
    let width = d.w.1 - d.w.0;
    let bad = |name, reason: String| Err(PreCutError::InvalidParameter { name, reason });
    check(width, p)?;
    if p.steps < 2 {
        return bad("steps", format!("{} must be at least 2", p.steps));
    }
    let mid = (d.w.0 + d.w.1) / 2.0;
    let towers = (mid - p.tower_distance / 2.0, mid + p.tower_distance / 2.0);
    let curves = leg_curves(d)?;
    let along = Vector3::from(d.direction);
    let across = Vector3::from(d.across);
    let mut out = Vec::new();
    for (leg, curve) in curves.iter().enumerate() {
        // z of the leg and its partial derivatives at (u, w).
        let z = |u: f64, w: f64| {
            let am = curve.eval(u.clamp(d.u.0, d.u.1));
            am[0] + am[1] * (w - d.w_mid) / d.w_half
        };
        let h = 1e-6 * (d.u.1 - d.u.0);
        // The cut surface continues unchanged (a cylinder) outside the block along u.
        let point = |u: f64, w: f64| -> Vector3<f64> {
            let uc = u.clamp(d.u.0, d.u.1);
            let (u0, u1) = ((uc - h).max(d.u.0), (uc + h).min(d.u.1));
            let dz_du = if u < d.u.0 || u > d.u.1 {
                0.0
            } else {
                (z(u1, w) - z(u0, w)) / (u1 - u0)
            };
            let dz_dw = {
                let am = curve.eval(uc);
                am[1] / d.w_half
            };
            let n = Vector3::new(-dz_du, -dz_dw, 1.0).normalize();
            // Frame coordinates (u, w, z) offset by half the kerf along n.
            Vector3::new(u, w, z(u, w)) + n * (p.kerf / 2.0)
        };
        let mut us = vec![d.u.0 - p.lead];
        us.extend((0..p.steps).map(|i| d.u.0 + (d.u.1 - d.u.0) * i as f64 / (p.steps - 1) as f64));
        us.push(d.u.1 + p.lead);
        let steps = us
            .iter()
            .map(|&u| {
                let (q0, q1) = (point(u, d.w.0), point(u, d.w.1));
                let at = |w: f64| q0 + (q1 - q0) * ((w - q0.y) / (q1.y - q0.y));
                let (ta, tb) = (at(towers.0), at(towers.1));
                let model = |q: Vector3<f64>| {
                    let xy = along * q.x + across * q.y;
                    [xy.x, xy.y, q.z]
                };
                let mm = p.mm_per_unit;
                WireStep {
                    u,
                    a: [(ta.x - d.u.0 + p.lead) * mm, (ta.z - floor) * mm],
                    b: [(tb.x - d.u.0 + p.lead) * mm, (tb.z - floor) * mm],
                    side0: model(q0),
                    side1: model(q1),
                }
            })
            .collect();
        out.push(WirePath {
            direction: index,
            leg,
            steps,
            towers,
        });
    }
    Ok(out)
}

fn leg_curves(d: &DirectionCut) -> Result<Vec<geom::bspline::BSplineCurve<2>>> {
    d.legs
        .iter()
        .map(|l| {
            let ctrl =
                l.a.iter()
                    .zip(&l.m)
                    .map(|(a, m)| nalgebra::Vector2::new(*a, *m))
                    .collect();
            Ok(geom::bspline::BSplineCurve::try_new(
                d.degree,
                d.knots.clone(),
                ctrl,
            )?)
        })
        .collect()
}

/// Shortest cutting move a program holds, mm.
const MIN_MOVE_MM: f64 = 0.05;

/// Formats an inverse-time feed with 8 significant digits (at least 4 decimals): a slow
/// cut's feed is far below 1, and a fixed 4 decimals would round its speed by percents.
/// Always a plain decimal (controllers read no exponents).
fn feed(v: f64) -> String {
    if !(v > 0.0) || !v.is_finite() {
        num(v)
    } else {
        let decimals = (7.0 - v.log10().floor()).clamp(4.0, 15.0) as usize;
        format!("{v:.decimals$}")
    }
}

/// A coordinate as the program holds it: [`num`] read back.
fn written(v: f64) -> f64 {
    num(v).parse().unwrap_or(v)
}

/// Formats a coordinate with 4 decimals (0.1 µm), `-0` as `0`.
fn num(v: f64) -> String {
    let s = format!("{v:.4}");
    if s == "-0.0000" {
        "0.0000".into()
    } else {
        s
    }
}

/// The G-code of one cut: header, rapid to safe height above the lead-in point, down,
/// the cut in inverse-time feed, rapid up after the lead-out.
pub fn gcode(path: &WirePath, p: &WireParams, top: f64, floor: f64, name: &str) -> String {
    let mm = p.mm_per_unit;
    let safe = (top - floor + p.clearance) * mm;
    let mut g = String::new();
    let _ = writeln!(
        g,
        "; hotcut pre-cut {name}: direction {} cut {}",
        path.direction + 1,
        path.leg + 1
    );
    let _ = writeln!(
        g,
        "; towers {} mm apart; kerf {} mm; speed {} mm/min; X/U along the cut from the lead-in, Y/V above the block floor",
        num(p.tower_distance * mm),
        num(p.kerf * mm),
        num(p.speed * mm)
    );
    let _ = writeln!(g, "G21 G90 G94");
    let first = &path.steps[0];
    let _ = writeln!(
        g,
        "G0 X{} Y{} U{} V{}",
        num(first.a[0]),
        num(safe),
        num(first.b[0]),
        num(safe)
    );
    let _ = writeln!(
        g,
        "G0 X{} Y{} U{} V{}",
        num(first.a[0]),
        num(first.a[1]),
        num(first.b[0]),
        num(first.b[1])
    );
    let _ = writeln!(g, "G93");
    let mut at = first;
    for t in &path.steps[1..] {
        let s = at;
        // the travel the controller will see: between the coordinates as written (the
        // 0.1 µm rounding is up to 0.2 % of the shortest move)
        let w = |p: [f64; 2]| [written(p[0]), written(p[1])];
        let (ta, tb, sa, sb) = (w(t.a), w(t.b), w(s.a), w(s.b));
        let da = (ta[0] - sa[0]).hypot(ta[1] - sa[1]);
        let db = (tb[0] - sb[0]).hypot(tb[1] - sb[1]);
        // a move shorter than 0.05 mm (500 steps of the program's 0.1 µm resolution) is
        // left to the next one: its inverse-time feed would be huge, and its length,
        // rounded in the program, too uncertain to read back
        if da.max(db) < MIN_MOVE_MM {
            continue;
        }
        at = t;
        let minutes = da.max(db) / (p.speed * mm);
        let _ = writeln!(
            g,
            "G1 X{} Y{} U{} V{} F{}",
            num(t.a[0]),
            num(t.a[1]),
            num(t.b[0]),
            num(t.b[1]),
            feed(1.0 / minutes)
        );
    }
    let last = &path.steps[path.steps.len() - 1];
    let _ = writeln!(g, "G94");
    let _ = writeln!(
        g,
        "G0 X{} Y{} U{} V{}",
        num(last.a[0]),
        num(safe),
        num(last.b[0]),
        num(safe)
    );
    let _ = writeln!(g, "M2");
    g
}

/// Largest coordinate a program may hold, mm.
const MAX_COORDINATE_MM: f64 = 1e6;

/// Reads back a program [`gcode`] wrote and checks what it would make the machine do:
/// every number finite, every coordinate within ±10⁶ mm, and every cutting move's speed
/// (inverse-time feed × the longer tower's travel) within
/// [`MIN_SPEED_MM_PER_MIN`]–[`MAX_SPEED_MM_PER_MIN`] (within 1 %: the program's rounding).
///
/// # Errors
/// [`PreCutError::InvalidParameter`] naming the first offending line.
pub fn check_gcode(text: &str) -> Result<()> {
    let bad = |line: usize, reason: String| {
        Err(PreCutError::InvalidParameter {
            name: "G-code",
            reason: format!("line {}: {reason}", line + 1),
        })
    };
    let mut pos = [0.0f64; 4];
    let mut inverse_time = false;
    for (i, line) in text.lines().enumerate() {
        let code = line.split(';').next().unwrap_or("").trim();
        let mut next = pos;
        let mut feed = None;
        let mut cut = false;
        for word in code.split_whitespace() {
            let (letter, value) = word.split_at(1);
            let Ok(v) = value.parse::<f64>() else {
                return bad(i, format!("unreadable word {word}"));
            };
            // a feed is not a coordinate: only finite
            let bounded = letter == "F" || v.abs() <= MAX_COORDINATE_MM;
            if !(v.is_finite() && bounded) {
                return bad(
                    i,
                    format!("{word} is not a finite number within ±{MAX_COORDINATE_MM} mm"),
                );
            }
            match letter {
                "G" if v == 93.0 => inverse_time = true,
                "G" if v == 94.0 => inverse_time = false,
                "G" if v == 1.0 => cut = true,
                "X" => next[0] = v,
                "Y" => next[1] = v,
                "U" => next[2] = v,
                "V" => next[3] = v,
                "F" => feed = Some(v),
                _ => {}
            }
        }
        if cut && inverse_time {
            let travel = (next[0] - pos[0])
                .hypot(next[1] - pos[1])
                .max((next[2] - pos[2]).hypot(next[3] - pos[3]));
            let Some(f) = feed else {
                return bad(i, "a cutting move without a feed".into());
            };
            let speed = travel * f;
            // the program's rounding: 0.1 µm per coordinate on moves of at least
            // MIN_MOVE_MM (< 0.3 %), and the feed's digits
            let slack = 1.0 + 1e-2;
            if !(speed >= MIN_SPEED_MM_PER_MIN / slack && speed <= MAX_SPEED_MM_PER_MIN * slack) {
                return bad(
                    i,
                    format!("the wire would move at {speed:.4} mm/min, outside {MIN_SPEED_MM_PER_MIN}–{MAX_SPEED_MM_PER_MIN}"),
                );
            }
        }
        pos = next;
    }
    Ok(())
}

/// The CSV of one cut: one row per step.
pub fn csv(path: &WirePath) -> String {
    let mut c = String::from("step,u,X,Y,U,V,side0_x,side0_y,side0_z,side1_x,side1_y,side1_z\n");
    for (i, s) in path.steps.iter().enumerate() {
        let _ = writeln!(
            c,
            "{i},{},{},{},{},{},{},{},{},{},{},{}",
            num(s.u),
            num(s.a[0]),
            num(s.a[1]),
            num(s.b[0]),
            num(s.b[1]),
            num(s.side0[0]),
            num(s.side0[1]),
            num(s.side0[2]),
            num(s.side1[0]),
            num(s.side1[1]),
            num(s.side1[2])
        );
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> WireParams {
        WireParams {
            tower_distance: 900.0,
            kerf: 1.5,
            speed: 300.0,
            lead: 20.0,
            clearance: 50.0,
            steps: 4,
            mm_per_unit: 1.0,
        }
    }

    #[test]
    fn settings_are_bounded_in_millimetres() {
        assert!(check(600.0, &params()).is_ok());
        for (field, p) in [
            (
                "tower_distance",
                WireParams {
                    tower_distance: 500.0,
                    ..params()
                },
            ),
            (
                "tower_distance",
                WireParams {
                    tower_distance: 1e308,
                    ..params()
                },
            ),
            (
                "kerf",
                WireParams {
                    kerf: 61.0,
                    ..params()
                },
            ),
            (
                "speed",
                WireParams {
                    speed: 1e308,
                    ..params()
                },
            ),
            (
                "speed",
                WireParams {
                    speed: 5e-324,
                    ..params()
                },
            ),
            (
                "lead",
                WireParams {
                    lead: 1e308,
                    ..params()
                },
            ),
            (
                "clearance",
                WireParams {
                    clearance: f64::INFINITY,
                    ..params()
                },
            ),
        ] {
            match check(600.0, &p) {
                Err(PreCutError::InvalidParameter { name, .. }) => assert_eq!(name, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        // the same settings in metres: 0.3 m/min is 300 mm/min
        let m = WireParams {
            tower_distance: 0.9,
            kerf: 0.0015,
            speed: 0.3,
            lead: 0.02,
            clearance: 0.05,
            mm_per_unit: 1000.0,
            ..params()
        };
        assert!(check(0.6, &m).is_ok());
    }

    #[test]
    fn programs_are_read_back() {
        let ok = "G21 G90 G94\nG0 X0 Y50 U0 V50\nG0 X0 Y10 U0 V10\nG93\nG1 X100 Y10 U100 V10 F3\nG94\nM2\n";
        assert!(check_gcode(ok).is_ok());
        // 100 mm at F3 (1/3 min) is 300 mm/min; at F1000, 100 m/min
        assert!(check_gcode(&ok.replace("F3", "F1000")).is_err());
        assert!(check_gcode(&ok.replace("F3", "F0.0000")).is_err());
        assert!(check_gcode(&ok.replace("X100", "Xinf")).is_err());
        assert!(check_gcode(&ok.replace("X100", "XNaN")).is_err());
        assert!(check_gcode(&ok.replace(" F3", "")).is_err());
        // a slow cut: 100 mm at 1.5 mm/min, its feed below 1 with its digits
        assert!(check_gcode(&ok.replace("F3", &format!("F{}", feed(1.5 / 100.0)))).is_ok());
        assert!(check_gcode(&ok.replace("F3", &format!("F{}", feed(0.5 / 100.0)))).is_err());
    }
}
