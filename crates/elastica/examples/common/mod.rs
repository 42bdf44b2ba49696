//! Shared by the cross-check examples: a JSON-lines loop and 17-digit number output.

use serde_json::{json, Value};
use std::io::{BufRead, Write};

/// A finite number with 17 significant digits (round-trips every f64); ±inf/NaN as strings.
pub fn num(x: f64) -> Value {
    if x.is_finite() {
        serde_json::from_str(&format!("{x:.16e}")).unwrap_or(Value::Null)
    } else {
        Value::String(format!("{x}"))
    }
}

/// The number `key` of a request.
pub fn number(v: &Value, key: &str) -> Result<f64, String> {
    v.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("missing number {key}"))
}

/// Reads JSON lines on stdin and answers each with `answer(request)` (an object to which the
/// request's `id` is added, or `{"id", "error"}`), one line per request; blank lines are
/// skipped, and a line that is not JSON gets `{"error": "line N: ..."}`.
pub fn serve(answer: impl Fn(&Value) -> Result<Value, String>) {
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    for (lineno, line) in stdin.lock().lines().enumerate() {
        let Ok(line) = line else { break };
        if line.trim().is_empty() {
            continue;
        }
        let reply = match serde_json::from_str::<Value>(&line) {
            Ok(v) => {
                let id = v.get("id").cloned().unwrap_or(Value::Null);
                match answer(&v) {
                    Ok(mut r) => {
                        r["id"] = id;
                        r
                    }
                    Err(e) => json!({"id": id, "error": e}),
                }
            }
            Err(e) => json!({"error": format!("line {}: {e}", lineno + 1)}),
        };
        // a closed stdout (`| head -1`) ends the loop quietly
        if writeln!(out, "{reply}").is_err() {
            break;
        }
    }
}
