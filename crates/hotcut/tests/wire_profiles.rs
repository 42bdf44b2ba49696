//! Replays the `PreCut` programs of every machine profile with an independent reader
//! (`common/gcode.rs`, which knows each controller's rules, not hotcut's writer), for an
//! axis-aligned, a rotated and a two-direction job, and checks what the machine would do:
//! - the controller accepts every line (GRBL: only GRBL 1.1's codes and words, no `%`,
//!   lines within its buffer; LinuxCNC: the `%` wrappers; every profile: its own axes);
//! - both towers move together, the faster one at the set speed, under the controller's
//!   own feed rule (`G93`, or `G94` over all axes);
//! - the wire passes the planned rulings (`precut.json`) at both block sides at half the
//!   kerf, on the removed side; with a kerf table, at the kerf of the speed the replay
//!   measures at that side;
//! - nothing leaves the machine's travel;
//! - the heat is on, after its preheat dwell, during every cutting move, and off after.

mod common;
#[path = "common/gcode.rs"]
mod gcode;

use common::{hotcut, stderr, write};
use gcode::{replay, Rules};
use geom::bspline::BSplineCurve;
use nalgebra::{Vector2, Vector3};
use serde_json::Value;

const SPEED: f64 = 250.0;
const LEAD: f64 = 30.0;
const TOWERS: f64 = 950.0;
/// Where the block stands on the machine: along, up.
const ORIGIN: (f64, f64) = (40.0, 20.0);
/// The machine's travel: along, up.
const TRAVEL: ((f64, f64), (f64, f64)) = ((0.0, 1000.0), (0.0, 950.0));
const PREHEAT: f64 = 2.5;
const SURFACE: &str = "120 + 110*exp(-3*((x/300)^2 + (y/300)^2)) + 30*x/300";
/// Kerf by speed: `(speed, kerf)`.
const TABLE: [(f64, f64); 3] = [(100.0, 2.0), (200.0, 1.5), (250.0, 1.2)];

/// A profile under test: its job text and the rules of its controller.
struct Profile {
    machine: &'static str,
    rules: Rules,
    /// The kerf: constant, or the table.
    table: bool,
}

fn rules(axes: &str, grbl: bool, percent: bool, on: &[&str], off: &[&str]) -> Rules {
    let a: Vec<char> = axes.chars().collect();
    Rules {
        axes: [a[0], a[1], a[2], a[3]],
        grbl,
        percent,
        dwell_ms: false,
        heat_on: on.iter().map(|s| s.to_string()).collect(),
        heat_off: off.iter().map(|s| s.to_string()).collect(),
    }
}

fn profiles() -> Vec<Profile> {
    let m3 = (&["M3", "S1000"][..], &["M5"][..]);
    vec![
        Profile {
            machine: "LinuxCncXyuv",
            rules: rules("XYUV", false, true, m3.0, m3.1),
            table: false,
        },
        Profile {
            machine: "Grbl4Axis",
            rules: rules("XYZA", true, false, m3.0, m3.1),
            table: false,
        },
        Profile {
            machine: "FluidNc(XYZA)",
            rules: rules("XYZA", true, false, m3.0, m3.1),
            table: true,
        },
        Profile {
            machine: "FluidNc(XYAB)",
            rules: rules("XYAB", true, false, m3.0, m3.1),
            table: false,
        },
        Profile {
            machine: "Mach3",
            rules: rules("XYZA", false, false, &["M3"], &["M5"]),
            table: false,
        },
        // a GRBL-like controller with the heat on the coolant relay, units-per-minute feed
        // over all four axes, 3 decimals, dwell in milliseconds read as such
        Profile {
            machine: r#"Custom(axes: "XYZA", header: ["G17 G21 G90 G94"], heat_on: "M8", heat_off: "M9", feed_mode: UnitsPerMinute, decimals: 3, dwell: Milliseconds)"#,
            rules: Rules {
                dwell_ms: true,
                ..rules("XYZA", true, false, &["M8"], &["M9"])
            },
            table: true,
        },
        // LinuxCNC with the heat on a digital output and units-per-minute feed as
        // rs274ngc reads it (F along X/Y while they move), 3 decimals, % wrappers
        Profile {
            machine: r#"Custom(axes: "XYUV", header: ["G17 G21 G90 G94 G61"], heat_on: "M64 P0", heat_off: "M65 P0", feed_mode: UnitsPerMinuteXyz, decimals: 3, percent: true)"#,
            rules: rules("XYUV", false, true, &["M64", "P0"], &["M65", "P0"]),
            table: false,
        },
    ]
}

fn job(p: &Profile, directions: &str) -> String {
    let kerf = if p.table {
        let rows: Vec<String> = TABLE.iter().map(|(v, k)| format!("({v}, {k})")).collect();
        format!("kerf_table: [{}]", rows.join(", "))
    } else {
        "kerf: 1.5".into()
    };
    let ((a0, a1), (u0, u1)) = TRAVEL;
    format!(
        r#"Job(
    name: "g",
    units: Millimetre,
    surface: HeightField(z: "{SURFACE}", x: (-300, 300), y: (-300, 300)),
    block: Block(size: (600, 600, 300), origin: (-300, -300, 0)),
    wire: Wire(machine: {}, tower_distance: {TOWERS}, {kerf}, speed: {SPEED}, lead: {LEAD}, origin: {ORIGIN:?}, preheat_s: {PREHEAT}, travel: Travel(along: ({a0}, {a1}), up: ({u0}, {u1}))),
    task: PreCut(legs: 3, directions: [{directions}], sections: 10, samples: 10, controls: 5),
    outputs: [Report, PreCut, GCode, Csv],
)"#,
        p.machine
    )
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// The kerf of `TABLE` at speed `v`, held beyond its ends.
fn table_kerf(v: f64) -> f64 {
    let (first, last) = (TABLE[0], TABLE[TABLE.len() - 1]);
    if v <= first.0 {
        return first.1;
    }
    if v >= last.0 {
        return last.1;
    }
    let i = TABLE.iter().position(|r| r.0 > v).unwrap();
    let (a, b) = (TABLE[i - 1], TABLE[i]);
    a.1 + (b.1 - a.1) * (v - a.0) / (b.0 - a.0)
}

#[test]
fn axis_aligned_programs_replay_on_every_controller() {
    for p in profiles() {
        check(&p, "X");
    }
}

#[test]
fn rotated_programs_replay_on_every_controller() {
    for p in profiles() {
        check(&p, "Degrees(30)");
    }
}

#[test]
fn two_direction_programs_replay_on_every_controller() {
    for p in profiles() {
        check(&p, "Y, Degrees(-60)");
    }
}

/// Runs the job and replays every program against the plan, the travel and the heat.
fn check(p: &Profile, directions: &str) {
    check_lead(p, directions, LEAD);
}

/// [`check`] with a lead of `lead` mm.
fn check_lead(p: &Profile, directions: &str, lead: f64) {
    let dir = tempfile::tempdir().unwrap();
    let text = job(p, directions).replace(&format!("lead: {LEAD}"), &format!("lead: {lead}"));
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}: {}", p.machine, stderr(&o));
    let out = dir.path().join("out/g");
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    let pc: Value = serde_json::from_str(&read("precut.json")).unwrap();
    let report: Value = serde_json::from_str(&read("report.json")).unwrap();
    let floor = 0.0;
    let mut programs = 0;
    for (i, d) in pc["directions"].as_array().unwrap().iter().enumerate() {
        let (u0, u1) = (f(&d["u"][0]), f(&d["u"][1]));
        let (w0, w1) = (f(&d["w"][0]), f(&d["w"][1]));
        let (w_mid, w_half) = (f(&d["w_mid"]), f(&d["w_half"]));
        let knots: Vec<f64> = d["knots"].as_array().unwrap().iter().map(f).collect();
        let degree = d["degree"].as_u64().unwrap() as usize;
        let towers = ((w0 + w1 - TOWERS) / 2.0, (w0 + w1 + TOWERS) / 2.0);
        assert!(u1 > u0);
        for (j, leg) in d["legs"].as_array().unwrap().iter().enumerate() {
            let ctrl = leg["a"]
                .as_array()
                .unwrap()
                .iter()
                .zip(leg["m"].as_array().unwrap())
                .map(|(a, m)| Vector2::new(f(a), f(m)))
                .collect();
            let curve = BSplineCurve::try_new(degree, knots.clone(), ctrl).unwrap();
            let plan = |u: f64, w: f64| {
                let am = curve.eval(u.clamp(u0, u1));
                am[0] + am[1] * (w - w_mid) / w_half
            };
            let name = format!("wire_d{}_c{}", i + 1, j + 1);
            let what = format!("{} [{directions}] {name}", p.machine);
            let r = replay(&read(&format!("{name}.gcode")), &p.rules)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(
                r.ended && r.cold_at_end,
                "{what}: no end, or the heat left on"
            );
            programs += 1;
            // travel: every position, rapids included
            for m in &r.motions {
                for (k, v) in m.to.iter().enumerate() {
                    let (lo, hi) = if k % 2 == 0 { TRAVEL.0 } else { TRAVEL.1 };
                    assert!(
                        (lo - 1e-9..=hi + 1e-9).contains(v),
                        "{what}: axis {} at {v}, outside {lo}..{hi}",
                        p.rules.axes[k]
                    );
                }
            }
            // heat: off on the way in, on (after the preheat) for every cut, off after
            let first_cut = r.motions.iter().position(|m| m.cutting).unwrap();
            let last_cut = r.motions.iter().rposition(|m| m.cutting).unwrap();
            for (k, m) in r.motions.iter().enumerate() {
                if m.cutting {
                    assert!(m.heat, "{what}: a cutting move with a cold wire");
                    assert!(
                        m.heated_s >= PREHEAT - 1e-9,
                        "{what}: cut after {} s of preheat",
                        m.heated_s
                    );
                } else {
                    assert!(!m.heat, "{what}: a rapid with the wire hot (move {k})");
                    assert!(k < first_cut || k > last_cut, "{what}: a rapid mid-cut");
                }
            }
            // timing: one coordinated move, the faster tower at the set speed
            let cuts: Vec<_> = r.motions.iter().filter(|m| m.cutting).collect();
            for m in &cuts {
                let da = (m.to[0] - m.from[0]).hypot(m.to[1] - m.from[1]);
                let db = (m.to[2] - m.from[2]).hypot(m.to[3] - m.from[3]);
                let (va, vb) = (da / m.minutes, db / m.minutes);
                assert!(
                    (va.max(vb) - SPEED).abs() <= 1e-6 * SPEED,
                    "{what}: towers at {va:.6} and {vb:.6} mm/min, planned {SPEED}"
                );
            }
            // geometry: the wire at every step, against the plan at the CSV's u
            let csv = read(&format!("{name}.csv"));
            let rows: Vec<Vec<f64>> = csv
                .lines()
                .skip(1)
                .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
                .collect();
            let positions: Vec<[f64; 4]> = std::iter::once(cuts[0].from)
                .chain(cuts.iter().map(|m| m.to))
                .collect();
            // each position is a step of the CSV (`u`, then both towers): in order, the
            // steps of moves too short to write left out
            let mut next_row = 0;
            let steps_u: Vec<f64> = positions
                .iter()
                .map(|q| {
                    let found = rows[next_row..]
                        .iter()
                        .position(|r| (0..4).all(|k| (r[3 + k] - q[k]).abs() <= 1e-3))
                        .unwrap_or_else(|| panic!("{what}: {q:?} is no planned step"));
                    next_row += found + 1;
                    rows[next_row - 1][2]
                })
                .collect();
            assert!(positions.len() + 2 >= rows.len(), "{what}: steps left out");
            // the wire heats outside the block: the lead-in and lead-out at `lead` from
            // its faces, both towers (the kerf does not move the wire along the cut there)
            let (first, last) = (positions[0], positions[positions.len() - 1]);
            let length = u1 - u0;
            for (q, along) in [(first, ORIGIN.0 - lead), (last, ORIGIN.0 + length + lead)] {
                for k in [0, 2] {
                    assert!(
                        (q[k] - along).abs() <= 1e-3,
                        "{what}: a lead end at {} along, not {along}",
                        q[k]
                    );
                }
            }
            // the wire in the frame (u, w, z), tower A to tower B
            let wire = |q: &[f64; 4]| {
                let a = Vector3::new(q[0] - ORIGIN.0 + u0, towers.0, q[1] - ORIGIN.1 + floor);
                let b = Vector3::new(q[2] - ORIGIN.0 + u0, towers.1, q[3] - ORIGIN.1 + floor);
                (a, (b - a).normalize(), b)
            };
            // the wire's point at a side plane w
            let side = |q: &[f64; 4], w: f64| {
                let (a, _, b) = wire(q);
                a + (b - a) * ((w - towers.0) / (towers.1 - towers.0))
            };
            for (s, (q, &u)) in positions.iter().zip(&steps_u).enumerate() {
                let (a, dir, _) = wire(q);
                for (k, w) in [w0, w1].into_iter().enumerate() {
                    let kerf = if p.table {
                        // the speed of this side over the move into the step (the first
                        // step: out of it)
                        let m = s.max(1);
                        let travel = (side(&positions[m], w) - side(&positions[m - 1], w)).norm();
                        table_kerf(travel / cuts[m - 1].minutes)
                    } else {
                        1.5
                    };
                    let pt = Vector3::new(u, w, plan(u, w));
                    let off = (pt - a) - dir * (pt - a).dot(&dir);
                    let dist = off.norm();
                    // 1 % of the offset (the surface's slope across a kerf) and the
                    // program's rounding (3 decimals, leveraged by the towers' distance
                    // over the block's width)
                    assert!(
                        (dist - kerf / 2.0).abs() <= 0.01 * kerf / 2.0 + 2e-3,
                        "{what}: wire {dist:.4} mm from the planned ruling at u = {u:.2}, side {k} (kerf/2 = {})",
                        kerf / 2.0
                    );
                    assert!(off.z < 0.0, "{what}: wire below the ruling at u = {u:.2}");
                }
            }
        }
    }
    // the report's programs: one per file, extents within the travel
    let listed = report["programs"].as_array().unwrap();
    assert_eq!(listed.len(), programs, "{}", p.machine);
    for prog in listed {
        assert!(f(&prog["cut_minutes"]) > 0.0);
        for e in prog["extents"].as_array().unwrap() {
            assert!(f(&e["min"]) >= TRAVEL.0 .0.min(TRAVEL.1 .0) - 1e-9);
        }
    }
}

#[test]
fn without_a_lead_the_wire_heats_at_the_faces() {
    for p in &profiles()[..2] {
        check_lead(p, "Degrees(30)", 0.0);
    }
}

#[test]
fn a_block_that_does_not_fit_the_machine_is_refused_at_validation() {
    let p = &profiles()[1];
    // 600 mm of block, 2 × 30 mm of lead, placed 40 mm in: 700 mm of travel along
    let text = job(p, "X").replace("along: (0, 1000)", "along: (0, 650)");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["validate", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    for needle in ["/wire/travel", "axis X", "650", "wire.origin"] {
        assert!(e.contains(needle), "{needle:?} missing: {e}");
    }
    // up: 20 mm board + 300 mm block + 50 mm clearance
    let text = job(p, "X").replace("up: (0, 950)", "up: (0, 300)");
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["validate", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("axis Y"), "{}", stderr(&o));
}

#[test]
fn every_direction_a_search_may_keep_must_fit_the_machine() {
    // 950 mm between the towers clear the 600 mm block along x and y, not its 849 mm
    // diagonal at 45°
    let p = &profiles()[0];
    let text = job(p, "X")
        .replace("directions: [X]", "directions: Auto(4)")
        .replace("tower_distance: 950", "tower_distance: 800");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["validate", "job.ron"], dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("/wire/tower_distance") && e.contains("45.0°"),
        "{e}"
    );
    assert!(!e.contains("0.0°:"), "{e}");
}

#[test]
fn a_program_outside_the_travel_fails_naming_the_cut_and_the_axis() {
    // the block fits (20 + 300 + 50 = 370 mm up), but a sloped cut's wire, extended to
    // the towers, climbs higher
    let p = &profiles()[0];
    let text = job(p, "Degrees(30)").replace("up: (0, 950)", "up: (0, 380)");
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &text);
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_ne!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("direction 1 cut"), "{e}");
    assert!(e.contains("axis Y") || e.contains("axis V"), "{e}");
    assert!(!dir.path().join("out/g").exists(), "files written: {e}");
}

#[test]
fn custom_profiles_are_checked_at_validation() {
    let p = &profiles()[5];
    for (bad, needle) in [
        (r#"axes: "XYZA""#, r#"axes: "XYZ""#),
        (r#"axes: "XYZA""#, r#"axes: "XYZX""#),
        (r#"["G17 G21 G90 G94"]"#, r#"["G17 G90 G94"]"#),
        (r#"heat_on: "M8""#, r#"heat_on: "M8 (on""#),
        ("decimals: 3", "decimals: 9"),
    ] {
        let text = job(p, "X").replace(bad, needle);
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "job.ron", &text);
        let o = hotcut(&["validate", "job.ron"], dir.path());
        assert_eq!(o.status.code(), Some(1), "{needle}: {}", stderr(&o));
        assert!(stderr(&o).contains("/wire"), "{needle}: {}", stderr(&o));
    }
}
