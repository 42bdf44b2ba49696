//! Shared by the cross-check examples: a JSON-lines loop whose answers print every number
//! with 17 significant digits (enough to round-trip any f64), the request's `id` first.
//!
//! A request with `"echo": true` is answered with every number it holds as read (in its
//! order, 17 digits), instead of being computed: a check that numbers reach the program
//! bit for bit (JSON is parsed with serde_json's `float_roundtrip`).

use std::io::{BufRead, Write};

use serde_json::Value;

/// A finite number with 17 significant digits, as JSON text (`4.7421562271182080e-1`);
/// ±inf and NaN as the strings `"inf"`, `"-inf"`, `"NaN"`.
pub fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.16e}")
    } else {
        format!("\"{x}\"")
    }
}

/// The number `key` of a request.
pub fn number(v: &Value, key: &str) -> Result<f64, String> {
    v.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("missing number {key}"))
}

/// One answer line: `{"id": <the request's id>, "<name>": <value>, ...}` in the given order.
fn line(id: &Value, fields: &[(&str, String)]) -> String {
    let mut s = format!("{{\"id\":{id}");
    for (k, v) in fields {
        // keys echoed from a request are escaped as JSON strings
        s.push_str(&format!(",{}:{v}", Value::String(k.to_string())));
    }
    s.push('}');
    s
}

/// Every number of a request but its id, as read, with 17 significant digits.
fn echo(v: &Value) -> Vec<(String, String)> {
    let Some(o) = v.as_object() else {
        return Vec::new();
    };
    o.iter()
        .filter(|(k, _)| k.as_str() != "id")
        .filter_map(|(k, x)| Some((k.clone(), num(x.as_f64()?))))
        .collect()
}

/// Reads JSON lines on stdin and answers each with `answer(request)`: the fields it
/// returns (values as JSON text, see [`num`]) after the request's `id`, or
/// `{"id", "error"}`; blank lines are skipped, and a line that is not JSON gets
/// `{"id": null, "error": "line N: ..."}`.
pub fn serve(answer: impl Fn(&Value) -> Result<Vec<(&'static str, String)>, String>) {
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    for (lineno, text) in stdin.lock().lines().enumerate() {
        let Ok(text) = text else { break };
        if text.trim().is_empty() {
            continue;
        }
        let reply = match serde_json::from_str::<Value>(&text) {
            Ok(v) => {
                let id = v.get("id").cloned().unwrap_or(Value::Null);
                if v.get("echo") == Some(&Value::Bool(true)) {
                    let numbers = echo(&v);
                    let fields: Vec<(&str, String)> = numbers
                        .iter()
                        .map(|(k, x)| (k.as_str(), x.clone()))
                        .collect();
                    line(&id, &fields)
                } else {
                    match answer(&v) {
                        Ok(fields) => line(&id, &fields),
                        Err(e) => line(&id, &[("error", Value::String(e).to_string())]),
                    }
                }
            }
            Err(e) => {
                let message = Value::String(format!("line {}: {e}", lineno + 1));
                line(&Value::Null, &[("error", message.to_string())])
            }
        };
        // a closed stdout (`| head -1`) ends the loop quietly
        if writeln!(out, "{reply}").is_err() {
            break;
        }
    }
}
