//! What `report.html` shows of a `RuledBlocks` run: the verdict, the deviation against the
//! tolerance, a row per region and per block (cuttable, added volume, cuts).

use export::html::{Body, Constraint, Row, Table, Verdict};

use super::RuledBlocksReport;
use crate::context::Context;
use crate::output::page::{len, num};

/// The page's body.
pub fn body(r: &RuledBlocksReport, job: &Context) -> Body {
    let u = job.units.symbol();
    let d = &r.deviation;
    let hulls = r.blocks.len() - r.totals.cuttable;
    let ok = r.nothing_to_cut.is_none();
    let text = if let Some(why) = r.nothing_to_cut.as_ref().filter(|_| d.within_tolerance) {
        format!("Nothing to cut, no program written: {why}.")
    } else if ok {
        format!(
            "Rationalized within the tolerance ({} regions, deviation max {}) and cut in {} block(s): {} by their ruled strips, {} to their convex hulls, adding {} {u}³.",
            r.regions.len(),
            len(d.max, job),
            r.blocks.len(),
            r.totals.cuttable,
            hulls,
            num(r.totals.added_volume)
        )
    } else {
        format!(
            "No piecewise ruled surface of these settings comes within the tolerance: deviation max {} > {}; add sections or max_strips, or raise tolerance.max.",
            len(d.max, job),
            len(r.tolerance, job)
        )
    };
    let counts = vec![
        ("regions".to_string(), r.regions.len().to_string()),
        ("sections".into(), r.sections.to_string()),
        ("blocks".into(), r.blocks.len().to_string()),
        ("cut by their strips".into(), r.totals.cuttable.to_string()),
        ("cuts".into(), r.totals.cuts.to_string()),
        (
            "cutting time".into(),
            format!("{} min", num(r.totals.cut_minutes)),
        ),
    ];
    let constraints = vec![
        Constraint {
            name: "deviation from the model (max)".into(),
            limit: format!("≤ {}", len(r.tolerance, job)),
            measured: format!(
                "{} ({:.3e} of the diagonal)",
                len(d.max, job),
                d.max_fraction
            ),
            ok: d.within_tolerance,
        },
        Constraint {
            name: "deviation from the model (RMS)".into(),
            limit: "reported".into(),
            measured: format!(
                "{} ({:.3e} of the diagonal)",
                len(d.rms, job),
                d.rms_fraction
            ),
            ok: true,
        },
    ];
    let (regions, blocks, comparison) = (regions(r, job), blocks(r, job), comparison(r, job));
    Body {
        verdict: Verdict { ok, text },
        counts,
        constraints,
        notes: Vec::new(),
        tables: vec![comparison, regions, blocks],
    }
}

fn regions(r: &RuledBlocksReport, job: &Context) -> Table {
    Table {
        title: "Regions".into(),
        columns: ["region", "sections", "strips", "controls", "RMS", "max"]
            .map(String::from)
            .to_vec(),
        rows: r
            .regions
            .iter()
            .map(|g| {
                Row::new(
                    vec![
                        g.index.to_string(),
                        g.sections.to_string(),
                        g.strips.to_string(),
                        g.controls.to_string(),
                        len(g.deviation.rms, job),
                        len(g.deviation.max, job),
                    ],
                    if g.deviation.within_tolerance {
                        vec![]
                    } else {
                        vec!["beyond the tolerance"]
                    },
                )
            })
            .collect(),
    }
}

fn blocks(r: &RuledBlocksReport, job: &Context) -> Table {
    let u = job.units.symbol();
    Table {
        title: "Blocks".into(),
        columns: [
            "block",
            "cuttable",
            "cuts",
            &format!("added volume ({u}³)"),
            "added depth",
            "why not",
        ]
        .map(String::from)
        .to_vec(),
        rows: r
            .blocks
            .iter()
            .map(|b| {
                Row::new(
                    vec![
                        b.index.to_string(),
                        if b.cuttable { "yes" } else { "hull" }.into(),
                        b.cuts.len().to_string(),
                        num(b.added_volume),
                        len(b.added_depth, job),
                        b.reason.clone().unwrap_or_default(),
                    ],
                    if b.cuttable {
                        vec![]
                    } else {
                        vec!["cut to its convex hull"]
                    },
                )
            })
            .collect(),
    }
}

fn comparison(r: &RuledBlocksReport, job: &Context) -> Table {
    let u = job.units.symbol();
    Table {
        title: "Whole model or per block (§4.1): both strategies on this model".into(),
        columns: [
            "strategy",
            "block pairs that meet",
            "largest C⁰ gap",
            "largest ruling jump (°)",
            "median ruling jump (°)",
            "deviation max",
            &format!("added ({u}³)"),
            "cuts",
            "cut by strips",
        ]
        .map(String::from)
        .to_vec(),
        rows: r
            .comparison
            .iter()
            .map(|c| {
                Row::new(
                    vec![
                        format!(
                            "{:?}{}",
                            c.strategy,
                            if c.strategy == r.strategy {
                                " (cut)"
                            } else {
                                ""
                            }
                        ),
                        c.seams.to_string(),
                        len(c.max_gap, job),
                        num(c.max_jump_deg),
                        num(c.median_jump_deg),
                        len(c.deviation.max, job),
                        num(c.added_volume),
                        c.cuts.to_string(),
                        format!("{} of {}", c.cuttable, c.blocks),
                    ],
                    if c.deviation.within_tolerance {
                        vec![]
                    } else {
                        vec!["beyond the tolerance"]
                    },
                )
            })
            .collect(),
    }
}
