//! Cross-check program: reads JSON lines `{"id", "family": "inflectional" |
//! "noninflectional", "k", "s0", "l", "S", "phi", "x0", "y0", "t"}` on stdin and writes
//! `{"id", "x", "y", "theta", "kappa"}` for the point S·R(φ)·f(s₀ + ℓt) + (x₀, y₀), its
//! tangent angle and signed curvature, with 17 significant digits.
//!
//! `cargo run --release -p hotcut-elastica --example segment < points.jsonl`

mod common;

use common::{num, number};
use elastica::segment::{ElasticaParams, ElasticaSegment};
use elastica::unit::Family;
use serde_json::Value;

fn answer(v: &Value) -> Result<Vec<(&'static str, String)>, String> {
    let family = match v.get("family").and_then(Value::as_str) {
        Some("inflectional") => Family::Inflectional,
        Some("noninflectional") => Family::NonInflectional,
        other => {
            return Err(format!(
                "family must be inflectional or noninflectional, got {other:?}"
            ))
        }
    };
    let params = ElasticaParams {
        one_minus_k: None,
        family,
        k: number(v, "k")?,
        s0: number(v, "s0")?,
        l: number(v, "l")?,
        scale: number(v, "S")?,
        phi: number(v, "phi")?,
        x0: number(v, "x0")?,
        y0: number(v, "y0")?,
    };
    let seg = ElasticaSegment::new(params).map_err(|e| e.to_string())?;
    let p = seg.eval(number(v, "t")?);
    Ok(vec![
        ("x", num(p.p[0])),
        ("y", num(p.p[1])),
        ("theta", num(p.angle)),
        ("kappa", num(p.curvature)),
    ])
}

fn main() {
    common::serve(answer);
}
