//! Replays a `PreCut` job's G-code: every line is parsed, the wire rebuilt between the
//! two towers at every step, and checked against the planned cut from `precut.json`:
//! inverse-time feed on every cutting move (both towers start and finish together), the
//! set wire speed never exceeded, and at every step (its position along the cut from
//! the CSV) the wire passing the planned ruling's points at both block sides at half the
//! kerf, on the removed side.

mod common;

use common::{hotcut, stderr, write};
use geom::bspline::BSplineCurve;
use nalgebra::Vector2;
use serde_json::Value;

const KERF: f64 = 1.5;
const SPEED: f64 = 250.0;
const LEAD: f64 = 30.0;

const BUMP: &str = "200 + 250*exp(-3*((x/500)^2 + (y/500)^2)) + 40*x/500";
/// The surface of `jobs/precut-wavy-30.ron`, where a 30° cut once sent the wire 116 m up.
const WAVY: &str = "300 + 72*sin(3*x/500)*cos(2*y/500) + 60*x/500";
const TOWERS: f64 = 1500.0;
const CLEARANCE: f64 = 50.0;
const HEIGHT: f64 = 600.0;

fn job(z: &str, direction: &str) -> String {
    format!(
        r#"Job(
    name: "g",
    units: Millimetre,
    surface: HeightField(z: "{z}", x: (-500, 500), y: (-500, 500)),
    block: Block(size: (1000, 1000, {HEIGHT}), origin: (-500, -500, 0)),
    wire: Wire(tower_distance: {TOWERS}, kerf: {KERF}, speed: {SPEED}, lead: {LEAD}, clearance: {CLEARANCE}),
    task: PreCut(legs: 3, directions: [{direction}], sections: 12, samples: 12, controls: 5),
    outputs: [Report, PreCut, GCode, Csv],
)"#
    )
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// Parses `G1 X.. Y.. U.. V.. F..` style words of one line (comments stripped).
fn words(line: &str) -> Vec<(char, f64)> {
    let code = line.split(';').next().unwrap_or("").trim();
    code.split_whitespace()
        .map(|w| {
            let (letter, num) = w.split_at(1);
            (
                letter.chars().next().unwrap(),
                num.parse::<f64>()
                    .unwrap_or_else(|_| panic!("bad word {w:?}")),
            )
        })
        .collect()
}

#[test]
fn gcode_replays_onto_the_planned_rulings() {
    replay(BUMP, "Degrees(20)");
}

#[test]
fn rotated_cut_stays_within_the_block_and_towers() {
    replay(WAVY, "Degrees(30)");
}

#[test]
fn diagonal_cut_stays_within_the_block_and_towers() {
    replay(WAVY, "Vector(1, 1)");
    replay(BUMP, "Degrees(-135)");
}

/// Runs the job, replays every program and checks it against the plan, the block and the
/// towers.
fn replay(z: &str, direction: &str) {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "job.ron", &job(z, direction));
    let o = hotcut(&["run", "job.ron", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = dir.path().join("out/g");
    let pc: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("precut.json")).unwrap()).unwrap();
    let d = &pc["directions"][0];
    let along = Vector2::new(f(&d["direction"][0]), f(&d["direction"][1]));
    let across = Vector2::new(f(&d["across"][0]), f(&d["across"][1]));
    let (u0, u1) = (f(&d["u"][0]), f(&d["u"][1]));
    let (w0, w1) = (f(&d["w"][0]), f(&d["w"][1]));
    let (w_mid, w_half) = (f(&d["w_mid"]), f(&d["w_half"]));
    let knots: Vec<f64> = d["knots"].as_array().unwrap().iter().map(f).collect();
    let degree = d["degree"].as_u64().unwrap() as usize;
    let towers = (
        (w0 + w1) / 2.0 - TOWERS / 2.0,
        (w0 + w1) / 2.0 + TOWERS / 2.0,
    );
    // Every coordinate against the block and the towers: X and U run along the cut from
    // the lead-in point to the lead-out point; Y and V (the wire's heights at the towers)
    // stay above the table (the block's floor) and within a block height above its top,
    // up to the kerf's offset.
    let along_max = u1 - u0 + 2.0 * LEAD;
    let (z_lo, z_hi) = (0.0, 2.0 * HEIGHT);
    let floor = 0.0;
    let legs = d["legs"].as_array().unwrap();
    assert_eq!(legs.len(), 3);
    let _ = (along, across);
    for (j, leg) in legs.iter().enumerate() {
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
        let name = format!("wire_d1_c{}.gcode", j + 1);
        let text = std::fs::read_to_string(out.join(&name)).unwrap();
        let (mut mm, mut absolute, mut inverse) = (false, false, false);
        let mut pos: Option<[f64; 4]> = None;
        let mut positions: Vec<[f64; 4]> = Vec::new();
        let mut cutting_moves = 0;
        let mut ended = false;
        for line in text.lines() {
            let ws = words(line);
            if ws.is_empty() {
                continue;
            }
            assert!(!ended, "{name}: a line after M2: {line}");
            let g: Vec<i64> = ws
                .iter()
                .filter(|(c, _)| *c == 'G')
                .map(|(_, v)| *v as i64)
                .collect();
            for code in &g {
                match code {
                    21 => mm = true,
                    90 => absolute = true,
                    93 => inverse = true,
                    94 => inverse = false,
                    0 | 1 => {}
                    other => panic!("{name}: unexpected G{other}"),
                }
            }
            if ws.iter().any(|(c, v)| *c == 'M' && *v == 2.0) {
                ended = true;
                continue;
            }
            let get = |c: char| ws.iter().find(|(l, _)| *l == c).map(|(_, v)| *v);
            let axes = [get('X'), get('Y'), get('U'), get('V')];
            if axes.iter().all(Option::is_none) {
                continue;
            }
            assert!(mm && absolute, "{name}: a move before G21 G90: {line}");
            let next = axes.map(|a| a.expect("every move gives all four axes"));
            for (i, v) in next.iter().enumerate() {
                let ok = if i % 2 == 0 {
                    (-1e-3..=along_max + 1e-3).contains(v)
                } else {
                    (z_lo - KERF..=z_hi.max(HEIGHT + CLEARANCE) + KERF).contains(v)
                };
                assert!(
                    ok,
                    "{direction}: {name}: {line}: {} out of the machine's range",
                    ["X", "Y", "U", "V"][i]
                );
            }
            if g.contains(&1) {
                assert!(inverse, "{name}: G1 outside inverse-time mode: {line}");
                let feed = get('F').expect("every G1 has F");
                assert!(feed > 0.0);
                let p = pos.expect("a G1 after a position");
                // One F for both towers: both take 1/F minutes; the faster one runs at SPEED.
                let da = (next[0] - p[0]).hypot(next[1] - p[1]);
                let db = (next[2] - p[2]).hypot(next[3] - p[3]);
                // F is computed from the coordinates as written, to 8 digits
                let fastest = da.max(db) * feed;
                assert!(
                    (fastest - SPEED).abs() < 1e-6 * SPEED,
                    "{name}: tower speed {fastest}"
                );
                cutting_moves += 1;
            }
            pos = Some(next);
            positions.push(next);
        }
        assert!(ended, "{name}: no M2");
        // The planned position of each step along the cut, from the CSV.
        let csv = std::fs::read_to_string(out.join(format!("wire_d1_c{}.csv", j + 1))).unwrap();
        let steps_u: Vec<f64> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        // Positions: rapid to safe height, the lead-in point, one per cutting move, the
        // retract; the middle ones are the CSV's steps in order.
        assert_eq!(positions.len(), steps_u.len() + 2, "{name}");
        for (next, &u) in positions[1..positions.len() - 1].iter().zip(&steps_u) {
            // The wire in frame coordinates (u, w, z), tower A to tower B.
            let a = nalgebra::Vector3::new(next[0] + u0 - LEAD, towers.0, next[1] + floor);
            let b = nalgebra::Vector3::new(next[2] + u0 - LEAD, towers.1, next[3] + floor);
            let dir = (b - a).normalize();
            for w in [w0, w1] {
                let p = nalgebra::Vector3::new(u, w, plan(u, w));
                let off = (p - a) - dir * (p - a).dot(&dir);
                let dist = off.norm();
                assert!(
                    (dist - KERF / 2.0).abs() <= 0.01 * KERF / 2.0 + 2e-3,
                    "{name}: wire {dist:.4} mm from the planned ruling at u = {u:.2}, w = {w:.1} (kerf/2 = {})",
                    KERF / 2.0
                );
                // On the removed side: the wire passes above the ruling point.
                assert!(off.z < 0.0, "{name}: wire below the ruling at u = {u:.2}");
            }
        }
        // Lead-in to the block, the section steps through it (short ones merged), lead-out.
        assert!(cutting_moves >= 3, "{name}");
        let _ = legs.len();
    }
}
