//! Cross-check program: reads JSON lines `{"id", "u", "m"}` on stdin and writes
//! `{"id", "sn", "cn", "dn", "am", "eps", "K", "E"}` (eps = E(u|m), E = complete E(m)) with
//! 17 significant digits, one line per input line.
//!
//! `cargo run --release -p hotcut-elastica --example elliptic < cases.jsonl`

mod common;

use common::{num, number};
use elastica::elliptic::Elliptic;
use serde_json::Value;

fn answer(v: &Value) -> Result<Vec<(&'static str, String)>, String> {
    let (u, m) = (number(v, "u")?, number(v, "m")?);
    let e = Elliptic::new(m).map_err(|e| e.to_string())?;
    let r = e.eval(u);
    Ok(vec![
        ("sn", num(r.sn)),
        ("cn", num(r.cn)),
        ("dn", num(r.dn)),
        ("am", num(r.am)),
        ("eps", num(r.eps)),
        ("K", num(e.k())),
        ("E", num(e.e())),
    ])
}

fn main() {
    common::serve(answer);
}
