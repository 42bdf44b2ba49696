//! What `report.html` shows of an `Analyze` run.

use export::html::{Body, Constraint, Row, Table, Verdict};
use facade_seg::survey::Violation;

use super::report::AnalyzeReport;
use crate::context::Context;
use crate::output::page::{curv, len, num};

/// The verdict (one blade from one block, or segmentation needed), the constraints of
/// thesis §5.1, and a row per section piece.
pub fn body(r: &AnalyzeReport, job: &Context) -> Body {
    let s = &r.summary;
    let c = &r.constraints;
    let ok = s.cuttable_without_segmentation;
    let sections_ok =
        s.sections_too_long + s.sections_too_many_inflections + s.sections_too_curved == 0;
    let text = if ok {
        "Cuttable with one blade from one block: every section meets every constraint.".to_string()
    } else if sections_ok {
        "Needs more than one block: the surface is larger than the block (see below); every section is within the blade's limits.".to_string()
    } else {
        "Needs segmentation or another tool: the flagged constraints below break.".to_string()
    };
    let counts = vec![
        (
            "planes with sections".to_string(),
            s.planes_with_sections.to_string(),
        ),
        ("section pieces".into(), s.pieces.to_string()),
        ("inflections in all".into(), s.total_inflections.to_string()),
    ];
    let surface: Vec<String> = s
        .surface_violations
        .iter()
        .filter_map(|v| match v {
            Violation::Dimension { what, value, limit } => Some(format!(
                "{}: {} vs {}",
                what.replace('_', " "),
                len(*value, job),
                len(*limit, job)
            )),
            _ => None,
        })
        .collect();
    let mut constraints = vec![Constraint {
        name: "dimension: section within the blade".into(),
        limit: len(c.blade_length, job),
        measured: format!(
            "{} section(s) longer; longest {}",
            s.sections_too_long,
            len(s.max_length, job)
        ),
        ok: s.sections_too_long == 0,
    }];
    constraints.push(Constraint {
        name: "dimension: surface within the block".into(),
        limit: c
            .block_size
            .map_or("no block given: not checked".into(), |b| {
                format!(
                    "{} × {} × {}",
                    len(b[0], job),
                    len(b[1], job),
                    len(b[2], job)
                )
            }),
        measured: if surface.is_empty() {
            "fits".into()
        } else {
            surface.join("; ")
        },
        ok: surface.is_empty(),
    });
    constraints.push(Constraint {
        name: "shape: inflections per section".into(),
        limit: format!("≤ {}", c.max_inflections),
        measured: format!(
            "{} section(s) with more; most {}",
            s.sections_too_many_inflections, s.max_inflections
        ),
        ok: s.sections_too_many_inflections == 0,
    });
    constraints.push(Constraint {
        name: "blade strain: |curvature|".into(),
        limit: format!("≤ {}", curv(c.max_curvature, job)),
        measured: format!(
            "{} section(s) above; largest {}",
            s.sections_too_curved,
            curv(s.max_abs_curvature, job)
        ),
        ok: s.sections_too_curved == 0,
    });
    Body {
        verdict: Verdict { ok, text },
        counts,
        constraints,
        notes: r.surface.warnings.clone(),
        tables: vec![sections(r, job)],
    }
}

fn sections(r: &AnalyzeReport, job: &Context) -> Table {
    let u = job.units.symbol();
    let rows = r
        .sections
        .iter()
        .map(|x| {
            let mut why = Vec::new();
            for v in &x.violations {
                why.push(match v {
                    Violation::Dimension { .. } => "dimension",
                    Violation::Shape { .. } => "shape",
                    Violation::BladeStrain { .. } => "blade strain",
                });
            }
            why.dedup();
            Row::new(
                vec![
                    (x.index + 1).to_string(),
                    (x.piece + 1).to_string(),
                    num(x.offset),
                    num(x.length),
                    x.inflections.len().to_string(),
                    num(x.max_abs_curvature),
                    if x.closed { "yes".into() } else { "no".into() },
                ],
                why,
            )
        })
        .collect();
    Table {
        title: "Sections".into(),
        columns: vec![
            "plane".into(),
            "piece".into(),
            format!("offset ({u})"),
            format!("length ({u})"),
            "inflections".into(),
            format!("max |κ| (/{u})"),
            "closed".into(),
        ],
        rows,
    }
}
