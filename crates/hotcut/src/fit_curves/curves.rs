//! Reading a curves file: JSON `{"curves": [{"id", "points": [[x, y], ...]}, ...]}` or CSV
//! with the header `id,x,y`. The file is checked when the job is loaded.

use std::path::Path;

use serde::Deserialize;

/// A planar curve to fit.
#[derive(Debug, Clone, PartialEq)]
pub struct InputCurve {
    /// Its id.
    pub id: String,
    /// The points, in job units.
    pub points: Vec<[f64; 2]>,
    /// Arc length at every point when known exactly (surface sections); `None` uses the
    /// polyline's chord lengths.
    pub arc_length: Option<Vec<f64>>,
}

#[derive(Deserialize)]
struct JsonCurves {
    curves: Vec<JsonCurve>,
}

#[derive(Deserialize)]
struct JsonCurve {
    id: serde_json::Value,
    points: Vec<[f64; 2]>,
}

/// Reads a curves file: JSON `{"curves": [{"id", "points": [[x, y], ...]}, ...]}` (other
/// fields ignored; ids may be strings or numbers) or, for a `.csv` name, CSV with the header
/// `id,x,y` and one row per point, a curve's rows consecutive.
///
/// # Errors
/// A message naming the file and, where it applies, the line or curve: unreadable file,
/// malformed JSON or CSV, no curves, a repeated id, a curve with fewer than 3 points, a
/// non-finite coordinate, or two equal consecutive points.
pub fn read_curves(path: &Path) -> std::result::Result<Vec<InputCurve>, String> {
    // a regular file of at most 256 MiB (not a device, not a runaway export)
    let text = crate::input::read_text(path, 256 << 20, "curve file")?;
    let csv = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    let curves = if csv {
        parse_csv(&text)
    } else {
        parse_json(&text)
    }
    .map_err(|e| format!("{}: {e}", path.display()))?;
    check(&curves).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(curves)
}

fn parse_json(text: &str) -> std::result::Result<Vec<InputCurve>, String> {
    let file: JsonCurves = serde_json::from_str(text).map_err(|e| e.to_string())?;
    file.curves
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            let id = match c.id {
                serde_json::Value::String(s) => s,
                serde_json::Value::Number(n) => n.to_string(),
                other => {
                    return Err(format!(
                        "curve {i}: id must be a string or number, got {}",
                        geom::text::clip(&other.to_string(), 200)
                    ))
                }
            };
            Ok(InputCurve {
                id,
                points: c.points,
                arc_length: None,
            })
        })
        .collect()
}

fn parse_csv(text: &str) -> std::result::Result<Vec<InputCurve>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header = lines.next().map(|(_, l)| l).unwrap_or_default();
    let cols: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    if cols != ["id", "x", "y"] {
        return Err(format!(
            "the first line must be the header `id,x,y`, got `{header}`"
        ));
    }
    let mut curves: Vec<InputCurve> = Vec::new();
    for (n, line) in lines {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 3 {
            return Err(format!(
                "line {}: expected 3 fields `id,x,y`, got {}",
                n + 1,
                f.len()
            ));
        }
        let num = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("line {}: `{s}` is not a number", n + 1))
        };
        let p = [num(f[1])?, num(f[2])?];
        match curves.last_mut() {
            Some(c) if c.id == f[0] => c.points.push(p),
            _ => curves.push(InputCurve {
                id: f[0].to_string(),
                points: vec![p],
                arc_length: None,
            }),
        }
    }
    Ok(curves)
}

fn check(curves: &[InputCurve]) -> std::result::Result<(), String> {
    if curves.is_empty() {
        return Err("no curves".into());
    }
    let mut seen = std::collections::BTreeSet::new();
    for c in curves {
        if !seen.insert(c.id.as_str()) {
            return Err(format!(
                "curve `{}` appears twice (CSV rows of a curve must be consecutive)",
                c.id
            ));
        }
        if c.points.len() < 3 {
            return Err(format!(
                "curve `{}` has {} point(s); a fit needs at least 3",
                c.id,
                c.points.len()
            ));
        }
        for (i, p) in c.points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(format!("curve `{}`: point {i} is not finite", c.id));
            }
            if i > 0 && *p == c.points[i - 1] {
                return Err(format!(
                    "curve `{}`: points {} and {i} coincide",
                    c.id,
                    i - 1
                ));
            }
        }
    }
    Ok(())
}
