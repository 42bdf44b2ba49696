//! Deterministic JSON: values are serialised through `serde_json::Value`, every float is
//! rounded to `digits` significant digits (half away from zero) and values smaller in
//! magnitude than [`ZERO_BELOW`](crate::json::ZERO_BELOW) become `0` (so round-off noise around zero, e.g. the
//! curvature at an inflection, prints the same on every machine; `-0` becomes `0`),
//! objects keep their field order, output is pretty-printed with two-space indentation and
//! a final newline. Non-finite floats become `null` (as in `serde_json`).
//!
//! Entry points: [`to_json_string`](crate::json::to_json_string), [`write_json`](crate::json::write_json), [`round_value`](crate::json::round_value).

use std::io::Write;

use serde::Serialize;
use serde_json::{Number, Value};

use crate::Result;

/// The precision hotcut uses for report files: 9 significant digits.
pub const REPORT_DIGITS: usize = 9;

/// Magnitudes below this print as `0` (a nanometre in a millimetre job).
pub const ZERO_BELOW: f64 = 1e-9;

/// Rounds a float to `digits` significant digits; magnitudes below [`ZERO_BELOW`] and `-0`
/// become `0`.
pub fn round_float(x: f64, digits: usize) -> f64 {
    if !x.is_finite() {
        return x;
    }
    if x.abs() < ZERO_BELOW {
        return 0.0;
    }
    let e = x.abs().log10().floor() as i32;
    let p = digits as i32 - 1 - e;
    let r = if p >= 0 {
        let s = 10f64.powi(p);
        (x * s).round() / s
    } else {
        let s = 10f64.powi(-p);
        (x / s).round() * s
    };
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// Rounds every float inside a JSON value in place.
pub fn round_value(v: &mut Value, digits: usize) {
    match v {
        Value::Number(n) if n.is_f64() => {
            if let Some(x) = n.as_f64() {
                let r = round_float(x, digits);
                *v = if r.fract() == 0.0 && r.abs() < 9.0e15 {
                    // integral floats print without a fraction, as integers
                    Value::Number(Number::from(r as i64))
                } else {
                    Number::from_f64(r)
                        .map(Value::Number)
                        .unwrap_or(Value::Null)
                };
            }
        }
        Value::Array(a) => a.iter_mut().for_each(|x| round_value(x, digits)),
        Value::Object(o) => o.values_mut().for_each(|x| round_value(x, digits)),
        _ => {}
    }
}

/// Serialises `value` to deterministic pretty JSON with floats rounded to `digits`.
///
/// # Errors
/// When `value` cannot be represented in JSON (e.g. maps with non-string keys).
pub fn to_json_string<T: Serialize + ?Sized>(value: &T, digits: usize) -> Result<String> {
    let mut v = serde_json::to_value(value)?;
    round_value(&mut v, digits);
    let mut s = serde_json::to_string_pretty(&v)?;
    s.push('\n');
    Ok(s)
}

/// Writes `value` as deterministic JSON (see [`to_json_string`]).
///
/// # Errors
/// Serialisation or I/O failures.
pub fn write_json<T: Serialize + ?Sized>(
    mut w: impl Write,
    value: &T,
    digits: usize,
) -> Result<()> {
    w.write_all(to_json_string(value, digits)?.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn rounds_and_keeps_order() {
        let v =
            json!({"b": 1.23456789, "a": [-0.0000000001, 2.0, 1.234567e-3, 123456.7], "c": "x"});
        let s = to_json_string(&v, 4).unwrap();
        assert_eq!(
            s,
            "{\n  \"b\": 1.235,\n  \"a\": [\n    0,\n    2,\n    0.001235,\n    123500\n  ],\n  \"c\": \"x\"\n}\n"
        );
    }
}
