//! Issue 35 item 3: every JSON reader of hotcut gets numbers back bit for bit.
//!
//! serde_json parses floats "best effort" (up to one unit in the last place off) unless
//! its `float_roundtrip` feature is on; the workspace turns it on. Each property below
//! writes random doubles — every bit of the mantissa random, values within a few ulps of
//! 1, subnormals — into a file of the kind a user gives hotcut (design files, curve files
//! in JSON and CSV, spline control grids), reads it with hotcut's own reader, and compares
//! the bits: 10 cases × 1000 doubles per reader. Reports go the other way: hotcut rounds
//! every float to 9 significant digits, and what it writes is what a reader gets back.

use std::path::Path;

use hotcut::design_task::file::{read, BlocksSpec, CurveSpec};
use hotcut::fit_curves::curves::read_curves;
use hotcut::load::load_job;
use proptest::prelude::*;

/// Doubles with every bit random: any finite bit pattern, values within 64 ulps of 1, and
/// subnormals.
fn any_double() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<u64>()
            .prop_map(f64::from_bits)
            .prop_filter("finite", |x| x.is_finite()),
        (-64i64..64).prop_map(|k| f64::from_bits((1.0f64.to_bits() as i64 + k) as u64)),
        (1u64..(1u64 << 52)).prop_map(f64::from_bits),
    ]
}

/// Doubles with every mantissa bit random but a moderate exponent (|x| in 2⁻⁶⁰..2²³, or a
/// subnormal): the coordinates of a surface, which is evaluated when loaded and must lie
/// within `load::MAX_SURFACE_MM` (10⁷ mm > 2²³) of the origin.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        (any::<u64>(), -60i32..23, any::<bool>()).prop_map(|(bits, e, neg)| {
            let m = bits & ((1u64 << 52) - 1);
            let x = f64::from_bits(((1023 + e) as u64) << 52 | m);
            if neg {
                -x
            } else {
                x
            }
        }),
        (-64i64..64).prop_map(|k| f64::from_bits((1.0f64.to_bits() as i64 + k) as u64)),
        (1u64..(1u64 << 52)).prop_map(f64::from_bits),
    ]
}

/// The shortest text that reads back as `x` (Rust's `{:?}`), as JSON and CSV accept it.
fn text(x: f64) -> String {
    format!("{x:?}")
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits()
}

fn write(dir: &Path, name: &str, body: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10, ..ProptestConfig::default() })]

    /// Design files: block corners (any double) and a station's `at` (in [0, 1]).
    #[test]
    fn design_files_read_every_double_exactly(
        xs in proptest::collection::vec(any_double(), 996),
        at in proptest::collection::vec(0.0f64..=1.0, 4),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let blocks: Vec<String> = xs
            .chunks(6)
            .enumerate()
            .map(|(i, c)| {
                format!(
                    r#"{{"id": "b{i}", "min": [{}, {}, {}], "max": [{}, {}, {}]}}"#,
                    text(c[0]), text(c[1]), text(c[2]), text(c[3]), text(c[4]), text(c[5])
                )
            })
            .collect();
        let stations: Vec<String> = at
            .iter()
            .map(|a| format!(r#"{{"at": {}, "curve": {{"Bezier": [[[0, 1], [2, 3], [4, 5], [6, 7]]]}}}}"#, text(*a)))
            .collect();
        let body = format!(
            r#"{{"blocks": {{"List": [{}]}}, "cuts": [{{"id": "c", "direction": "X", "blocks": ["b0"], "stations": [{}]}}]}}"#,
            blocks.join(", "),
            stations.join(", ")
        );
        let file = read(&write(dir.path(), "design.json", &body)).unwrap();
        let BlocksSpec::List(list) = &file.blocks else {
            panic!("a list of blocks");
        };
        prop_assert_eq!(list.len(), xs.len() / 6);
        for (b, c) in list.iter().zip(xs.chunks(6)) {
            for (got, want) in b.min.iter().chain(&b.max).zip(c) {
                prop_assert!(same(*got, *want), "{} read as {}", want, got);
            }
        }
        for (s, a) in file.cuts[0].stations.iter().zip(&at) {
            prop_assert!(same(s.at, *a), "at {} read as {}", a, s.at);
            prop_assert!(matches!(s.curve, CurveSpec::Bezier(_)));
        }
    }

    /// Curve files, JSON and CSV: every coordinate.
    #[test]
    fn curve_files_read_every_double_exactly(xs in proptest::collection::vec(any_double(), 1000)) {
        let dir = tempfile::tempdir().unwrap();
        let points: Vec<String> = xs.chunks(2).map(|p| format!("[{}, {}]", text(p[0]), text(p[1]))).collect();
        let json = write(dir.path(), "c.json", &format!(r#"{{"curves": [{{"id": "a", "points": [{}]}}]}}"#, points.join(", ")));
        let rows: Vec<String> = xs.chunks(2).map(|p| format!("a,{},{}", text(p[0]), text(p[1]))).collect();
        let csv = write(dir.path(), "c.csv", &format!("id,x,y\n{}\n", rows.join("\n")));
        for path in [json, csv] {
            let curves = read_curves(&path).unwrap();
            prop_assert_eq!(curves.len(), 1);
            let got: Vec<f64> = curves[0].points.iter().flatten().copied().collect();
            prop_assert_eq!(got.len(), xs.len());
            for (g, w) in got.iter().zip(&xs) {
                prop_assert!(same(*g, *w), "{}: {} read as {}", path.display(), w, g);
            }
        }
    }

    /// Spline control grids (a `Spline` surface's file), read through the job loader.
    #[test]
    fn spline_grids_read_every_double_exactly(xs in proptest::collection::vec(coordinate(), 972)) {
        let dir = tempfile::tempdir().unwrap();
        // 18 × 18 control points, 3 coordinates each
        let rows: Vec<String> = xs
            .chunks(18 * 3)
            .map(|row| {
                let pts: Vec<String> = row.chunks(3).map(|p| format!("[{}, {}, {}]", text(p[0]), text(p[1]), text(p[2]))).collect();
                format!("[{}]", pts.join(", "))
            })
            .collect();
        write(dir.path(), "grid.json", &format!(r#"{{"degree_u": 3, "degree_v": 3, "points": [{}]}}"#, rows.join(", ")));
        let job = write(dir.path(), "j.ron", r#"Job(name: "g", surface: Spline(path: "grid.json"), task: Analyze)"#);
        let job = load_job(&job).map_err(|e| format!("{e:?}")).unwrap();
        let Some(geom::surface::Surface::Spline(s)) = job.context.surface.as_ref() else {
            panic!("a spline surface");
        };
        let got: Vec<f64> = s.control_points().iter().flat_map(|p| [p.x, p.y, p.z]).collect();
        prop_assert_eq!(got.len(), xs.len());
        for (g, w) in got.iter().zip(&xs) {
            prop_assert!(same(*g, *w), "{} read as {}", w, g);
        }
    }

    /// Reports: hotcut's JSON writer rounds every float to 9 significant digits, and a
    /// reader gets exactly the rounded double back.
    #[test]
    fn report_numbers_read_back_exactly(xs in proptest::collection::vec(any_double(), 1000)) {
        let text = export::json::to_json_string(&xs, export::json::REPORT_DIGITS).unwrap();
        let back: Vec<f64> = serde_json::from_str::<Vec<Option<f64>>>(&text)
            .unwrap()
            .into_iter()
            .map(|x| x.unwrap_or(f64::NAN))
            .collect();
        prop_assert_eq!(back.len(), xs.len());
        for (b, x) in back.iter().zip(&xs) {
            let want = export::json::round_float(*x, export::json::REPORT_DIGITS);
            prop_assert!(same(*b, want), "{} rounds to {} but reads back as {}", x, want, b);
        }
    }
}
