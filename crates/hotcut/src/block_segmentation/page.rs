//! What `report.html` shows of a `BlockSegmentation` run.

use blocks::StopReason;
use export::html::{Body, Constraint, Row, Table, Verdict};

use super::BlockSegReport;
use crate::context::Context;
use crate::output::page::{len, num};

/// The verdict (how many blocks cover the model), the coverage and count against the lower
/// bound, a row per block and per restart.
pub fn body(r: &BlockSegReport, job: &Context) -> Body {
    let s = &r.segmentation;
    let size = r.params.block_size;
    let samples =
        s.sampling.counts.vertices + s.sampling.counts.surface + s.sampling.counts.interior;
    let capped = s.restarts.iter().any(|x| x.stop != StopReason::Converged);
    let text = format!(
        "Covered by {} block(s) of {} × {} × {} ({} fewer than the initial grid of {}; no cover can use fewer than {}){}.",
        s.final_blocks,
        len(size[0], job),
        len(size[1], job),
        len(size[2], job),
        s.initial_blocks.saturating_sub(s.final_blocks),
        s.initial_blocks,
        s.lower_bound,
        if capped {
            "; a restart stopped at its iteration or time cap, so more iterations may find fewer blocks"
        } else {
            ""
        }
    );
    let counts = vec![
        ("blocks".to_string(), s.final_blocks.to_string()),
        ("initial grid".into(), s.initial_blocks.to_string()),
        (
            "reduction".into(),
            format!("{} %", num(s.reduction_percent)),
        ),
        (
            "lower bound (model volume / block volume)".into(),
            s.lower_bound.to_string(),
        ),
        ("restarts".into(), s.restarts.len().to_string()),
        (
            "model volume".into(),
            format!("{} {}³", num(r.model.volume), job.units.symbol()),
        ),
    ];
    let constraints = vec![Constraint {
        name: format!(
            "coverage: every sample of the model in a block ({:?})",
            r.params.coverage
        ),
        limit: format!(
            "{samples} samples, blocks shrunk by {}",
            len(s.sampling.margin, job)
        ),
        measured: "all covered (kept by every operation)".into(),
        ok: true,
    }];
    Body {
        verdict: Verdict { ok: true, text },
        counts,
        constraints,
        notes: Vec::new(),
        tables: vec![blocks(r, job), restarts(r)],
    }
}

fn blocks(r: &BlockSegReport, job: &Context) -> Table {
    let u = job.units.symbol();
    let rows = r
        .segmentation
        .blocks
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let q = b.rotation;
            let angle = 2.0 * q[0].abs().clamp(0.0, 1.0).acos();
            let sign = if q[0] < 0.0 { -1.0 } else { 1.0 };
            let axis = [sign * q[1], sign * q[2], sign * q[3]];
            let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
            let turn = if norm > 1e-12 && angle > 1e-9 {
                format!(
                    "{}° about ({:.2}, {:.2}, {:.2})",
                    num(angle.to_degrees()),
                    axis[0] / norm,
                    axis[1] / norm,
                    axis[2] / norm
                )
            } else {
                "0°".into()
            };
            Row::new(
                vec![
                    (i + 1).to_string(),
                    format!(
                        "{}, {}, {}",
                        num(b.center[0]),
                        num(b.center[1]),
                        num(b.center[2])
                    ),
                    turn,
                    format!(
                        "{} × {} × {}",
                        num(b.size[0]),
                        num(b.size[1]),
                        num(b.size[2])
                    ),
                ],
                Vec::new(),
            )
        })
        .collect();
    Table {
        title: "Blocks (blocks.json holds their exact frames)".into(),
        columns: vec![
            "block".into(),
            format!("centre ({u})"),
            "turned (block axes to model axes)".into(),
            format!("size ({u})"),
        ],
        rows,
    }
}

fn restarts(r: &BlockSegReport) -> Table {
    let s = &r.segmentation;
    Table {
        title: "Restarts".into(),
        columns: vec![
            "restart".into(),
            "seed".into(),
            "blocks".into(),
            "energy E".into(),
            "iterations".into(),
            "stopped by".into(),
        ],
        rows: s
            .restarts
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let why = match x.stop {
                    StopReason::Converged => vec![],
                    StopReason::IterationCap => vec!["stopped at max_iterations before converging"],
                    StopReason::TimeCap => vec!["stopped at time_limit before converging"],
                };
                Row::new(
                    vec![
                        format!(
                            "{}{}",
                            i + 1,
                            if i == s.best_restart { " (kept)" } else { "" }
                        ),
                        x.seed.to_string(),
                        x.blocks.to_string(),
                        num(x.energy),
                        x.iterations.to_string(),
                        format!("{:?}", x.stop),
                    ],
                    why,
                )
            })
            .collect(),
    }
}
