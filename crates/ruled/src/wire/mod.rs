//! Wire paths of the cuts for a 4-axis hot-wire machine, and their programs.
//!
//! The machine has two towers `tower_distance` apart, on either side of the block along
//! the across direction `w` and centred on the block; each tower moves the wire's end in
//! its plane: along the cut and up. Tower A stands at the low-`w` side, tower B at the
//! high-`w` side. Machine coordinates, in millimetres: along = `origin.0 + u − u0`
//! (`u0` the block's start along the cut), up = `origin.1 + z − z_floor`.
//!
//! Per cut (leg) the wire follows the leg's rulings from `lead` before the block to `lead`
//! after it. The kerf is applied first: each ruling's two points at the block's sides are
//! moved by half the kerf along the cut surface's upward normal there (into the removed
//! material), and the wire is the line through them, extended to both tower planes. With a
//! kerf table, each side's kerf follows the wire's speed at that side.
//!
//! [`program()`] writes a cut's G-code in a controller's dialect ([`Machine`]).

/// What a dialect's fixed lines (header, footer, heat, end) may say.
pub mod dialect;
/// Controller dialects and the built-in profiles.
pub mod machine;
/// One cut's G-code, checked against the machine's travel and feed.
pub mod program;

use std::fmt::Write as _;

use nalgebra::Vector3;

use crate::error::{PreCutError, Result};
use crate::DirectionCut;
pub use machine::{DwellUnit, FeedMode, Machine};
pub use program::{check_program, program, program_labelled, Labels, Program, ProgramSummary};

/// The machine and the cut's settings (lengths in the job's unit, `mm_per_unit` to mm).
#[derive(Debug, Clone, PartialEq)]
pub struct WireParams {
    /// Distance between the tower planes (> the block's width across the cut).
    pub tower_distance: f64,
    /// Kerf width (≥ 0): material the wire burns away (without a `kerf_table`).
    pub kerf: f64,
    /// Kerf by wire speed: `(speed, kerf)` pairs in increasing speed, interpolated
    /// linearly and held at the ends; empty: `kerf` everywhere.
    pub kerf_table: Vec<(f64, f64)>,
    /// Wire speed through the material, job units per minute (> 0).
    pub speed: f64,
    /// Lead-in and lead-out length along the cut outside the block (≥ 0).
    pub lead: f64,
    /// Clearance above the block for rapid moves (> 0).
    pub clearance: f64,
    /// Machine coordinates `(along, up)` of the block's start at its floor.
    pub origin: [f64; 2],
    /// Steps per cut along the block.
    pub steps: usize,
    /// Millimetres per job unit.
    pub mm_per_unit: f64,
}

impl WireParams {
    /// The kerf at wire speed `v` (job units per minute).
    pub fn kerf_at(&self, v: f64) -> f64 {
        kerf_from_table(&self.kerf_table, v).unwrap_or(self.kerf)
    }
}

/// The kerf at speed `v` from `(speed, kerf)` rows with speeds increasing: interpolated
/// linearly, held beyond the table's ends; `None` for an empty table. (A hot wire's and a
/// hot blade's kerf alike: a slower tool melts wider.)
pub fn kerf_from_table(t: &[(f64, f64)], v: f64) -> Option<f64> {
    let (&(v0, k0), &(v1, k1)) = (t.first()?, t.last()?);
    Some(if v <= v0 {
        k0
    } else if v >= v1 {
        k1
    } else {
        let i = t.partition_point(|&(s, _)| s <= v).clamp(1, t.len() - 1);
        let ((s0, c0), (s1, c1)) = (t[i - 1], t[i]);
        c0 + (c1 - c0) * (v - s0) / (s1 - s0)
    })
}

/// One wire position: the two tower points (machine coordinates, mm) and the 3D points
/// where the wire crosses the block's sides (model coordinates, job units).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct WireStep {
    /// Position along the cut (frame `u`, job units).
    pub u: f64,
    /// Tower A `(along, up)`.
    pub a: [f64; 2],
    /// Tower B `(along, up)`.
    pub b: [f64; 2],
    /// Wire point at the block's low-`w` side (after kerf), model coordinates.
    pub side0: [f64; 3],
    /// Wire point at the block's high-`w` side (after kerf), model coordinates.
    pub side1: [f64; 3],
    /// Kerf applied at the low-`w` and the high-`w` side (job units).
    pub kerf: [f64; 2],
}

/// The path of one cut.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct WirePath {
    /// Direction index.
    pub direction: usize,
    /// Leg (cut) index.
    pub leg: usize,
    /// Steps: lead-in start, the block from end to end, lead-out end.
    pub steps: Vec<WireStep>,
    /// `w` of tower A's and tower B's planes.
    pub towers: (f64, f64),
    /// The cutting direction in the model's xy plane.
    pub along: [f64; 2],
    /// The across direction `w` (tower A → tower B) in the model's xy plane.
    pub across: [f64; 2],
    /// The block's extent along the cut, `(u0, u1)`.
    pub u: (f64, f64),
}

/// Fastest wire speed a program may ask for, mm/min (hot-wire foam cutters run at tens to
/// a few thousand mm/min; 1 m/s is far beyond any).
pub const MAX_SPEED_MM_PER_MIN: f64 = 60_000.0;
/// Slowest wire speed, mm/min (slower, the wire melts a channel, not a cut).
pub const MIN_SPEED_MM_PER_MIN: f64 = 1.0;
/// Longest lead, clearance or tower distance, and farthest travel, mm (beyond any
/// cutter's).
pub const MAX_TRAVEL_MM: f64 = 20_000.0;
/// Most rows of a kerf table.
pub const MAX_KERF_ROWS: usize = 64;

/// Checks the wire settings for a block `width` wide across the cut (job units): the
/// towers clear the block, every kerf is under a tenth of the width, the kerf table's
/// speeds increase, and speed, lead, clearance, origin and tower distance are finite and
/// within the bounds above (converted by `mm_per_unit`). [`paths`] makes the same checks;
/// validation calls this first.
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
                "{} ({} mm) is beyond any cutter ({MAX_TRAVEL_MM} mm at most)",
                p.tower_distance,
                mm(p.tower_distance)
            ),
        );
    }
    let kerf_ok = |k: f64| k.is_finite() && k >= 0.0 && k < width / 10.0;
    if !kerf_ok(p.kerf) {
        return bad(
            "kerf",
            format!(
                "{} must be in [0, width/10) for a block {width} wide across the cut",
                p.kerf
            ),
        );
    }
    if p.kerf_table.len() > MAX_KERF_ROWS {
        return bad(
            "kerf_table",
            format!("{} rows, at most {MAX_KERF_ROWS}", p.kerf_table.len()),
        );
    }
    for (i, &(v, k)) in p.kerf_table.iter().enumerate() {
        let rising = i == 0 || v > p.kerf_table[i - 1].0;
        if !(v.is_finite() && v > 0.0 && rising) {
            return bad(
                "kerf_table",
                format!(
                    "row {}: speeds must be positive and increasing, got {v}",
                    i + 1
                ),
            );
        }
        if !kerf_ok(k) {
            return bad(
                "kerf_table",
                format!("row {}: kerf {k} must be in [0, width/10) for a block {width} wide across the cut", i + 1),
            );
        }
    }
    if !(mm(p.speed) >= MIN_SPEED_MM_PER_MIN && mm(p.speed) <= MAX_SPEED_MM_PER_MIN) {
        return bad(
            "speed",
            format!(
                "{} ({} mm/min) must be within {MIN_SPEED_MM_PER_MIN}–{MAX_SPEED_MM_PER_MIN} mm/min",
                p.speed,
                mm(p.speed)
            ),
        );
    }
    if !(p.lead.is_finite() && p.lead >= 0.0 && mm(p.lead) <= MAX_TRAVEL_MM) {
        return bad(
            "lead",
            format!(
                "{} ({} mm) must be within 0–{MAX_TRAVEL_MM} mm",
                p.lead,
                mm(p.lead)
            ),
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
    if !p
        .origin
        .iter()
        .all(|o| o.is_finite() && mm(o.abs()) <= MAX_TRAVEL_MM)
    {
        return bad(
            "origin",
            format!("{:?} must be within ±{MAX_TRAVEL_MM} mm", p.origin),
        );
    }
    Ok(())
}

/// Checks that the speed is within the machine's fastest feed, and that a block `length`
/// long along the cut and `height` high fits the machine's travel (job units): along, the
/// lead-in and lead-out; up, the floor and the safe height above the block. The run
/// checks each program's real extents, which also hold the wire's slope out to the
/// towers.
///
/// # Errors
/// [`PreCutError::InvalidParameter`] for the speed, [`PreCutError::OutOfTravel`] naming
/// the axis.
pub fn check_fit(length: f64, height: f64, p: &WireParams, m: &Machine) -> Result<()> {
    if !(p.speed * p.mm_per_unit <= m.max_speed) {
        return Err(PreCutError::InvalidParameter {
            name: "speed",
            reason: format!(
                "{} mm/min is faster than the machine's max_speed, {} mm/min",
                p.speed * p.mm_per_unit,
                m.max_speed
            ),
        });
    }
    let Some(travel) = &m.travel else {
        return Ok(());
    };
    let mm = p.mm_per_unit;
    // the kerf's offset along the surface's normal moves the wire along the cut by up to
    // half the kerf at the block's ends: beyond the lead when the lead is shorter
    let kerf = p.kerf_table.iter().map(|r| r.1).fold(p.kerf, f64::max);
    let reach = p.lead.max(kerf / 2.0);
    let along = (
        (p.origin[0] - reach) * mm,
        (p.origin[0] + length + reach) * mm,
    );
    let up = (p.origin[1] * mm, (p.origin[1] + height + p.clearance) * mm);
    for (k, need) in [along, up, along, up].into_iter().enumerate() {
        let (lo, hi) = travel[k];
        let out = if need.0 < lo {
            Some(need.0)
        } else if need.1 > hi {
            Some(need.1)
        } else {
            None
        };
        if let Some(value) = out {
            return Err(PreCutError::OutOfTravel {
                program: "the block with its lead and clearance".into(),
                axis: m.axes[k],
                value,
                min: lo,
                max: hi,
                extent: need,
            });
        }
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
    let mut us = vec![d.u.0 - p.lead];
    us.extend((0..p.steps).map(|i| d.u.0 + (d.u.1 - d.u.0) * i as f64 / (p.steps - 1) as f64));
    us.push(d.u.1 + p.lead);
    let mut out = Vec::new();
    for (leg, curve) in curves.iter().enumerate() {
        // the lead-in and lead-out steps, first and last, are outside the block even at
        // lead 0: there the cut surface continues as a cylinder, so the kerf's offset does
        // not move the wire along the cut (into the foam, before the heat is on)
        let lead = |i: usize| i == 0 || i + 1 == us.len();
        let at = |i: usize, kerf: [f64; 2]| {
            wire_step(d, curve, (towers, floor), p, (us[i], lead(i)), kerf)
        };
        let k = p.kerf_at(p.speed);
        let mut steps: Vec<WireStep> = (0..us.len()).map(|i| at(i, [k, k])).collect();
        if !p.kerf_table.is_empty() {
            // each side's kerf at its own speed along the path at the set kerf (the
            // kerf's change moves the sides by a kerf's fraction of a step: its effect
            // on the speeds is of second order)
            let speeds = side_speeds(&steps, p.speed, p.mm_per_unit);
            steps = speeds
                .into_iter()
                .enumerate()
                .map(|(i, v)| at(i, v.map(|v| p.kerf_at(v))))
                .collect();
        }
        out.push(WirePath {
            direction: index,
            leg,
            steps,
            towers,
            along: [d.direction[0], d.direction[1]],
            across: [d.across[0], d.across[1]],
            u: d.u,
        });
    }
    Ok(out)
}

/// The wire's speed at both block sides at every step (job units per minute): the speed
/// of the move into the step (the first step: the move out of it), where the faster tower
/// runs at `speed`. Tower points are in mm, side points in job units.
fn side_speeds(steps: &[WireStep], speed: f64, mm_per_unit: f64) -> Vec<[f64; 2]> {
    let dist = |a: [f64; 3], b: [f64; 3]| (Vector3::from(a) - Vector3::from(b)).norm();
    let tower = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let moves: Vec<[f64; 2]> = steps
        .windows(2)
        .map(|w| {
            let t = tower(w[1].a, w[0].a).max(tower(w[1].b, w[0].b));
            let s = [dist(w[1].side0, w[0].side0), dist(w[1].side1, w[0].side1)];
            s.map(|s| {
                if t > 0.0 {
                    (s * mm_per_unit / t).min(1.0)
                } else {
                    1.0
                }
            })
        })
        .collect();
    (0..steps.len())
        .map(|i| moves[i.max(1) - 1].map(|r| speed * r))
        .collect()
}

/// The wire at `u` (`lead`: a lead-in or lead-out step, outside the block) with kerfs
/// `kerf` at the low- and high-`w` sides; `towers` the towers' `w`, `floor` the block's.
fn wire_step(
    d: &DirectionCut,
    curve: &geom::bspline::BSplineCurve<2>,
    (towers, floor): ((f64, f64), f64),
    p: &WireParams,
    (u, lead): (f64, bool),
    kerf: [f64; 2],
) -> WireStep {
    // z of the leg at (u, w)
    let z = |u: f64, w: f64| {
        let am = curve.eval(u.clamp(d.u.0, d.u.1));
        am[0] + am[1] * (w - d.w_mid) / d.w_half
    };
    let h = 1e-6 * (d.u.1 - d.u.0);
    // The cut surface continues unchanged (a cylinder) outside the block along u.
    let point = |u: f64, w: f64, kerf: f64| -> Vector3<f64> {
        let uc = u.clamp(d.u.0, d.u.1);
        let (u0, u1) = ((uc - h).max(d.u.0), (uc + h).min(d.u.1));
        let dz_du = if lead || u < d.u.0 || u > d.u.1 {
            0.0
        } else {
            (z(u1, w) - z(u0, w)) / (u1 - u0)
        };
        let dz_dw = curve.eval(uc)[1] / d.w_half;
        let n = Vector3::new(-dz_du, -dz_dw, 1.0).normalize();
        // Frame coordinates (u, w, z) offset by half the kerf along n.
        Vector3::new(u, w, z(u, w)) + n * (kerf / 2.0)
    };
    let (q0, q1) = (point(u, d.w.0, kerf[0]), point(u, d.w.1, kerf[1]));
    let at = |w: f64| q0 + (q1 - q0) * ((w - q0.y) / (q1.y - q0.y));
    let (ta, tb) = (at(towers.0), at(towers.1));
    let (along, across) = (Vector3::from(d.direction), Vector3::from(d.across));
    let model = |q: Vector3<f64>| {
        let xy = along * q.x + across * q.y;
        [xy.x, xy.y, q.z]
    };
    let mm = p.mm_per_unit;
    let machine = |t: Vector3<f64>| {
        [
            (t.x - d.u.0 + p.origin[0]) * mm,
            (t.z - floor + p.origin[1]) * mm,
        ]
    };
    WireStep {
        u,
        a: machine(ta),
        b: machine(tb),
        side0: model(q0),
        side1: model(q1),
        kerf,
    }
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

/// The CSV of one cut: one row per step, with the time from the lead-in start (minutes,
/// the faster tower at the set speed), both tower points (mm), the wire's points at the
/// block's sides (model coordinates) and the kerf there.
///
/// ```
/// use geom::{expr::Expr, heightfield::HeightField, surface::Surface};
/// use ruled::wire::{csv, paths, WireParams};
/// use ruled::{pre_cut, Block, Params};
///
/// // a tilted plane in a 200 × 100 × 100 mm block: one straight cut removes everything above it
/// let plane = HeightField::try_new(Expr::parse("40 + 0.1*x")?, (0.0, 200.0), (0.0, 100.0))?;
/// let block = Block { min: [0.0, 0.0, 0.0], max: [200.0, 100.0, 100.0] };
/// let params = Params { legs: 1, sections: 4, samples: 4, ..Params::default() };
/// let cut = pre_cut(&Surface::HeightField(plane), &block, &params, &|_| {})?;
/// let wire = WireParams {
///     tower_distance: 300.0, kerf: 0.0, kerf_table: Vec::new(), speed: 300.0, lead: 10.0,
///     clearance: 20.0, origin: [0.0, 0.0], steps: 4, mm_per_unit: 1.0,
/// };
/// let path = &paths(&cut.directions[0], 0, block.min[2], &wire)?[0];
/// let text = csv(path, &wire);
/// // a header and one row per step
/// assert_eq!(text.lines().count(), 1 + path.steps.len());
/// // over the block the wire runs just above the plane z = 40 + 0.1·x, never below it
/// let over: Vec<_> = path.steps.iter().filter(|s| (0.0..=200.0).contains(&s.u)).collect();
/// assert_eq!(over.len(), wire.steps);
/// for s in over {
///     for p in [s.side0, s.side1] {
///         let above = p[2] - (40.0 + 0.1 * p[0]);
///         assert!((0.0..0.1).contains(&above), "{p:?}");
///     }
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn csv(path: &WirePath, p: &WireParams) -> String {
    let mut c = String::from(
        "step,t_min,u,a_along,a_up,b_along,b_up,side0_x,side0_y,side0_z,side1_x,side1_y,side1_z,kerf0,kerf1\n",
    );
    let n = |v: f64| program::num(v, 4);
    let speed = p.speed * p.mm_per_unit;
    let mut t = 0.0;
    for (i, s) in path.steps.iter().enumerate() {
        if i > 0 {
            let q = path.steps[i - 1];
            let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
            t += d(s.a, q.a).max(d(s.b, q.b)) / speed;
        }
        let _ = write!(c, "{i},{}", program::num(t, 6));
        for v in [s.u, s.a[0], s.a[1], s.b[0], s.b[1]]
            .into_iter()
            .chain(s.side0)
            .chain(s.side1)
            .chain(s.kerf)
        {
            let _ = write!(c, ",{}", n(v));
        }
        c.push('\n');
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
            kerf_table: Vec::new(),
            origin: [20.0, 0.0],
            steps: 4,
            mm_per_unit: 1.0,
        }
    }

    proptest::proptest! {
        /// The kerf table is read as a piecewise-linear function held at its ends: its
        /// rows are on it, it stays within the rows' kerfs, and it is continuous (a step of
        /// `h` in speed moves it by at most the steepest row-to-row slope times `h`).
        #[test]
        fn kerf_tables_interpolate(
            rows in proptest::collection::vec((1.0f64..50.0, 0.0f64..5.0), 1..8),
            v in 0.0f64..500.0,
        ) {
            let mut speed = 0.0;
            let table: Vec<(f64, f64)> = rows
                .iter()
                .map(|&(dv, k)| {
                    speed += dv;
                    (speed, k)
                })
                .collect();
            let p = WireParams { kerf_table: table.clone(), ..params() };
            for &(s, k) in &table {
                proptest::prop_assert!((p.kerf_at(s) - k).abs() <= 1e-12 * (1.0 + k));
            }
            let (lo, hi) = table.iter().fold((f64::MAX, f64::MIN), |(a, b), r| (a.min(r.1), b.max(r.1)));
            let k = p.kerf_at(v);
            proptest::prop_assert!(k >= lo - 1e-12 && k <= hi + 1e-12);
            let slope = table
                .windows(2)
                .map(|w| (w[1].1 - w[0].1).abs() / (w[1].0 - w[0].0))
                .fold(0.0, f64::max);
            let h = 1e-6;
            proptest::prop_assert!((p.kerf_at(v + h) - k).abs() <= slope * h * (1.0 + 1e-6) + 1e-12);
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
}
