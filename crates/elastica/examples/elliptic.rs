//! Cross-check helper: reads JSON lines `{"id", "u", "m"}` on stdin and writes
//! `{"id", "sn", "cn", "dn", "am", "eps", "K", "E"}` (eps = E(u|m), E = complete E(m)) with
//! 17 significant digits, one line per input line.
//!
//! `cargo run --release -p elastica --example elliptic < cases.jsonl`

use elastica::elliptic::Elliptic;
use serde_json::{json, Value};
use std::io::{BufRead, Write};

fn num(x: f64) -> Value {
    if x.is_finite() {
        // 17 significant digits round-trip every f64
        let s = format!("{x:.16e}");
        serde_json::from_str(&s).unwrap_or(Value::Null)
    } else {
        Value::String(format!("{x}"))
    }
}

fn main() {
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
                let u = v.get("u").and_then(Value::as_f64);
                let m = v.get("m").and_then(Value::as_f64);
                match (u, m) {
                    (Some(u), Some(m)) => match Elliptic::new(m) {
                        Ok(e) => {
                            let r = e.eval(u);
                            json!({"id": id, "sn": num(r.sn), "cn": num(r.cn), "dn": num(r.dn),
                                   "am": num(r.am), "eps": num(r.eps), "K": num(e.k()), "E": num(e.e())})
                        }
                        Err(err) => json!({"id": id, "error": err.to_string()}),
                    },
                    _ => json!({"id": id, "error": "need numbers u and m"}),
                }
            }
            Err(err) => json!({"error": format!("line {}: {err}", lineno + 1)}),
        };
        if writeln!(out, "{reply}").is_err() {
            break;
        }
    }
}
