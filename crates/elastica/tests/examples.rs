//! The cross-check programs of `examples/` (issue 3): one JSON line piped through each.
//!
//! Each example is built (`cargo build --example`, a no-op when current) and run as the
//! user runs it, with one request on stdin.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use proptest::prelude::*;
use serde_json::Value;

/// The example `name`, built first (a no-op when it is current) by the cargo that runs
/// this test, into this test's own target folder, profile and target triple: `cargo test`
/// builds the examples too, but `cargo test --test examples` alone would find a stale
/// binary.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("test executable");
    // <target dir>[/<triple>]/<profile>/deps/examples-<hash>
    let profile_dir = exe
        .parent()
        .and_then(|d| d.parent())
        .expect("target profile folder")
        .to_path_buf();
    let profile = profile_dir
        .file_name()
        .and_then(|d| d.to_str())
        .unwrap_or("debug")
        .to_string();
    let above = profile_dir.parent().expect("target folder").to_path_buf();
    // cargo marks the root of a target folder with CACHEDIR.TAG; a triple folder has none
    let (target_dir, triple) = if above.join("CACHEDIR.TAG").is_file() {
        (above, None)
    } else {
        let triple = above
            .file_name()
            .and_then(|d| d.to_str())
            .map(str::to_string);
        (above.parent().expect("target folder").to_path_buf(), triple)
    };
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut build = Command::new(cargo);
    build.args(["build", "-q", "-p", "hotcut-elastica", "--example", name]);
    build.arg("--target-dir").arg(&target_dir);
    match profile.as_str() {
        "debug" => {}
        "release" => {
            build.arg("--release");
        }
        other => {
            build.args(["--profile", other]);
        }
    }
    if let Some(t) = &triple {
        build.args(["--target", t]);
    }
    let status = build.status().expect("cargo runs");
    assert!(status.success(), "building example {name} failed");
    profile_dir
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX))
}

/// Pipes `line` through example `name` and returns the one JSON line it answers.
fn pipe(name: &str, line: &str) -> Value {
    serde_json::from_str(&pipe_text(name, line)).expect("a JSON line")
}

/// The answer line as text.
fn pipe_text(name: &str, line: &str) -> String {
    let lines = pipe_lines(name, &[line.to_string()]);
    assert_eq!(lines.len(), 1, "{lines:?}");
    lines[0].clone()
}

/// Pipes `lines` through example `name` in one run; its answer lines.
fn pipe_lines(name: &str, lines: &[String]) -> Vec<String> {
    let mut child = Command::new(example(name))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("example starts");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(format!("{}\n", lines.join("\n")).as_bytes())
        .expect("write");
    let out = child.wait_with_output().expect("example ends");
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).expect("utf-8");
    text.lines().map(str::to_string).collect()
}

fn number(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// The answer line's keys in order (checked on the parsed line), and every value but the
/// id written as a JSON number `d.ddddddddddddddddde±x`: 17 significant digits.
fn check_line(line: &str, keys: &[&str]) {
    let v: Value = serde_json::from_str(line).expect("a JSON line");
    let parsed: Vec<&String> = v.as_object().expect("an object").keys().collect();
    assert_eq!(parsed, keys, "{line}");
    let mut rest = line;
    let mut seen = 0;
    while let Some(i) = rest.find("\":") {
        let start = rest[..i].rfind('"').unwrap_or(0);
        let key = &rest[start + 1..i];
        let value = &rest[i + 2..];
        let end = value.find([',', '}']).unwrap_or(value.len());
        let text = &value[..end];
        if key != "id" {
            assert!(
                v[key].is_number(),
                "{key} = {text} is not a number in {line}"
            );
            let body = text.strip_prefix('-').unwrap_or(text);
            let (mantissa, exponent) = body.split_once('e').expect("an exponent");
            let (lead, frac) = mantissa.split_once('.').expect("a point");
            let digits = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
            assert!(
                lead.len() == 1 && digits(lead) && frac.len() == 16 && digits(frac),
                "{text}"
            );
            assert!(
                digits(exponent.strip_prefix('-').unwrap_or(exponent)),
                "{text}"
            );
        }
        seen += 1;
        rest = &value[end..];
    }
    assert_eq!(seen, keys.len(), "{line}");
}

#[test]
fn elliptic_answers_with_every_field() {
    // m = 1/2 at u = K: sn = 1, cn = 0, dn = √(1/2); K(1/2) = 1.8540746773013719...
    let k = 1.854_074_677_301_371_9;
    let v = pipe("elliptic", &format!(r#"{{"id": "q", "u": {k}, "m": 0.5}}"#));
    assert_eq!(v["id"], "q");
    assert!((number(&v, "K") - k).abs() < 1e-15);
    assert!((number(&v, "sn") - 1.0).abs() < 1e-15);
    assert!(number(&v, "cn").abs() < 1e-15);
    assert!((number(&v, "dn") - 0.5f64.sqrt()).abs() < 1e-15);
    assert!((number(&v, "am") - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    // E(K|m) is the complete integral E(1/2) = 1.3506438810476755...
    assert!((number(&v, "E") - 1.350_643_881_047_675_5).abs() < 1e-15);
    assert!((number(&v, "eps") - number(&v, "E")).abs() < 1e-14);
    let text = pipe_text("elliptic", r#"{"id": 2, "u": 0.3, "m": 0.7}"#);
    check_line(&text, &["id", "sn", "cn", "dn", "am", "eps", "K", "E"]);
    // a bad request gets an error with its id, not a crash
    let bad = pipe("elliptic", r#"{"id": 7, "u": 1, "m": 2}"#);
    assert_eq!(bad["id"], 7);
    assert!(bad["error"].is_string());
}

#[test]
fn segment_answers_with_point_angle_and_curvature() {
    // at σ = 0 the inflectional ζ starts at the origin along +x with curvature 2k
    let v = pipe(
        "segment",
        r#"{"id": 3, "family": "inflectional", "k": 0.7, "s0": 0, "l": 2, "S": 1, "phi": 0, "x0": 0, "y0": 0, "t": 0}"#,
    );
    assert_eq!(v["id"], 3);
    let expect = |v: &Value, want: [f64; 4]| {
        for (key, w) in ["x", "y", "theta", "kappa"].into_iter().zip(want) {
            assert!((number(v, key) - w).abs() < 1e-15, "{key}: {v}");
        }
    };
    expect(&v, [0.0, 0.0, 0.0, 1.4]);
    // the non-inflectional γ at σ = 0: curvature 2/k, scaled by 1/S, rotated by φ, moved
    let w = pipe(
        "segment",
        r#"{"id": 4, "family": "noninflectional", "k": 0.5, "s0": 0, "l": 1, "S": 2, "phi": 0.3, "x0": 1, "y0": -1, "t": 0}"#,
    );
    expect(&w, [1.0, -1.0, 0.3, 2.0]);
    let text = pipe_text(
        "segment",
        r#"{"id": "s", "family": "noninflectional", "k": 0.5, "s0": 0.2, "l": 1, "S": 2, "phi": 0.3, "x0": 1, "y0": -1, "t": 0.7}"#,
    );
    check_line(&text, &["id", "x", "y", "theta", "kappa"]);
    let bad = pipe("segment", r#"{"id": 5, "family": "circle"}"#);
    assert!(bad["error"].as_str().unwrap_or("").contains("family"));
}

/// Doubles with every bit of the mantissa random: any finite bit pattern, values within a
/// few ulps of 1 (where `m` of the elliptic functions is most sensitive), and subnormals.
fn any_double() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<u64>()
            .prop_map(f64::from_bits)
            .prop_filter("finite", |x| x.is_finite()),
        (-64i64..64).prop_map(|k| f64::from_bits((1.0f64.to_bits() as i64 + k) as u64)),
        (1u64..(1u64 << 52)).prop_map(f64::from_bits),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10, ..ProptestConfig::default() })]

    /// Issue 35 item 3: every number a cross-check program reads reaches it bit for bit
    /// (serde_json with `float_roundtrip`), and comes back bit for bit through its 17-digit
    /// answers: 10 × 1000 random doubles per program.
    #[test]
    fn the_examples_read_and_write_every_double_exactly(xs in proptest::collection::vec(any_double(), 1000)) {
        for name in ["elliptic", "segment"] {
            let lines: Vec<String> = xs
                .chunks(2)
                .enumerate()
                .map(|(i, p)| format!(r#"{{"id": {i}, "echo": true, "u": {:?}, "m": {:?}}}"#, p[0], p[1]))
                .collect();
            let answers = pipe_lines(name, &lines);
            prop_assert_eq!(answers.len(), lines.len());
            for (i, (a, p)) in answers.iter().zip(xs.chunks(2)).enumerate() {
                let v: Value = serde_json::from_str(a).expect("a JSON line");
                prop_assert_eq!(&v["id"], &Value::from(i));
                for (key, x) in ["u", "m"].into_iter().zip(p) {
                    let got = number(&v, key);
                    prop_assert_eq!(got.to_bits(), x.to_bits(), "{}: {} read as {} ({})", key, x, got, a);
                }
            }
        }
    }
}
