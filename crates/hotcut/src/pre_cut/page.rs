//! What `report.html` shows of a `PreCut` run.

use export::html::{Body, Constraint, Row, Table, Verdict};

use super::PreCutReport;
use crate::context::Context;
use crate::output::page::{len, num};

/// The verdict (how many wire cuts, what is left for milling), the clearance above the
/// design, a row per direction and per wire program.
pub fn body(r: &PreCutReport, job: &Context) -> Body {
    let v = &r.volumes;
    let cuts = r.directions.len() * r.params.legs;
    let clearance = r
        .directions
        .iter()
        .map(|d| d.clearance)
        .fold(f64::INFINITY, f64::min);
    let ok = clearance > 0.0 && cuts > 0;
    let text = if ok {
        format!(
            "Cuttable: {cuts} hot-wire cut(s) in {} direction(s) leave {} % of the block's volume for milling, against {} % milling from the block alone: {} % less foam to mill.",
            r.directions.len(),
            num(100.0 * v.ruled),
            num(100.0 * v.bounding_box),
            num(v.more_than_box_percent)
        )
    } else {
        "Not cuttable as planned: a cut reaches the design (see the clearance).".to_string()
    };
    let u = job.units.symbol();
    let pct = |f: f64| format!("{} % of the block", num(100.0 * f));
    let counts = vec![
        ("wire cuts".to_string(), cuts.to_string()),
        ("directions".into(), r.directions.len().to_string()),
        ("programs".into(), r.programs.len().to_string()),
        ("left for milling".into(), pct(v.ruled)),
        ("after cutting the convex hull".into(), pct(v.convex_hull)),
        ("milling from the block".into(), pct(v.bounding_box)),
        ("model".into(), pct(v.model)),
    ];
    let constraints = vec![Constraint {
        name: "no cut into the design: least height of a cut above it".into(),
        limit: "> 0".into(),
        measured: len(clearance, job),
        ok: clearance > 0.0,
    }];
    let directions = Table {
        title: "Directions".into(),
        columns: vec![
            "direction".into(),
            "unit vector".into(),
            "QP rounds".into(),
            "QPs".into(),
            "constraint points".into(),
            format!("clearance ({u})"),
        ],
        rows: r
            .directions
            .iter()
            .enumerate()
            .map(|(i, d)| {
                Row::new(
                    vec![
                        (i + 1).to_string(),
                        format!(
                            "{}, {}, {}",
                            num(d.direction[0]),
                            num(d.direction[1]),
                            num(d.direction[2])
                        ),
                        d.rounds.to_string(),
                        d.qps.to_string(),
                        d.constraint_points.to_string(),
                        num(d.clearance),
                    ],
                    if d.clearance > 0.0 {
                        vec![]
                    } else {
                        vec!["cuts into the design"]
                    },
                )
            })
            .collect(),
    };
    let mut tables = vec![directions];
    if !r.programs.is_empty() {
        tables.push(programs(r));
    }
    let mut notes = Vec::new();
    if let Some(m) = &r.machine {
        notes.push(format!("G-code for {m}"));
    }
    Body {
        verdict: Verdict { ok, text },
        counts,
        constraints,
        notes,
        tables,
    }
}

fn programs(r: &PreCutReport) -> Table {
    Table {
        title: "Wire programs".into(),
        columns: vec![
            "file".into(),
            "direction".into(),
            "cut".into(),
            "cutting moves".into(),
            "cut length (mm)".into(),
            "cut time (min)".into(),
            "preheat (s)".into(),
            "axis ranges (mm)".into(),
        ],
        rows: r
            .programs
            .iter()
            .map(|p| {
                let s = &p.summary;
                let ranges: Vec<String> = s
                    .extents
                    .iter()
                    .map(|e| format!("{} {}…{}", e.axis, num(e.min), num(e.max)))
                    .collect();
                Row::new(
                    vec![
                        p.file.clone(),
                        (s.direction + 1).to_string(),
                        (s.cut + 1).to_string(),
                        s.cutting_moves.to_string(),
                        num(s.cut_length_mm),
                        num(s.cut_minutes),
                        num(s.preheat_s),
                        ranges.join(", "),
                    ],
                    Vec::new(),
                )
            })
            .collect(),
    }
}
