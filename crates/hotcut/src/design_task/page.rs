//! What `report.html` shows of a `Design` run.

use crate::robot_cell::report::CellReport;
use export::html::{Body, Constraint, Row, Table};

use super::report::DesignReport;
use crate::context::Context;
use crate::output::page::{blade_verdict, curv, num};

/// The verdict (every blade within its limits), the blade constraints and the design's
/// closeness to its elastica, a row per design curve and per block.
pub fn body(r: &DesignReport, job: &Context) -> Body {
    let s = &r.summary;
    let set = &r.settings;
    let verdict = blade_verdict(
        s.all_ok,
        r.cell.as_ref().map(|k| k.clean),
        format!(
            "{} cut(s) over {} block(s), {} blade pose(s); every blade within its curvature and inflection limits and holding its shape",
            s.cuts,
            r.blocks.len(),
            s.poses
        ),
        || {
            format!(
                "Not cuttable as designed: blades break a limit (strain {}, inflections {}, stability {}).",
                s.strain_flags, s.inflection_flags, s.stability_flags
            )
        },
    );
    let counts = vec![
        ("cuts".to_string(), s.cuts.to_string()),
        ("blocks".into(), r.blocks.len().to_string()),
        ("design curves".into(), s.curves.to_string()),
        ("blade poses".into(), s.poses.to_string()),
        ("resolution".into(), format!("{:?}", set.resolution)),
        (
            "elastica vs design".into(),
            format!("≤ {} % of the curve's length", num(s.max_deviation_percent)),
        ),
        (
            "Bézier proxy residual, eq. (11)".into(),
            format!("≤ {} (within 1 % below 0.19)", num(s.max_eq11_residual)),
        ),
    ];
    let inflections = r
        .cuts
        .iter()
        .map(|c| c.planes.blade_inflections)
        .max()
        .unwrap_or(0);
    let mut constraints = vec![
        Constraint {
            name: "blade strain: |curvature| of the extended blade".into(),
            limit: format!("≤ {}", curv(set.max_curvature, job)),
            measured: format!(
                "{} plane(s) above; largest {}",
                s.strain_flags,
                curv(s.blade_max_curvature, job)
            ),
            ok: s.strain_flags == 0,
        },
        Constraint {
            name: "shape: inflections on the blade".into(),
            limit: format!("≤ {}", set.max_inflections),
            measured: format!("{} plane(s) above; most {inflections}", s.inflection_flags),
            ok: s.inflection_flags == 0,
        },
        crate::output::page::stability_constraint(
            format!("{} plane(s) fail", s.stability_flags),
            r.cuts
                .iter()
                .filter_map(|c| c.planes.min_margin)
                .fold(f64::INFINITY, f64::min),
            job.blade.min_margin,
            s.stability_flags == 0,
        ),
    ];
    let mut tables = vec![curves(r, job), blocks(r, job)];
    CellReport::add_to_page(r.cell.as_ref(), &mut constraints, &mut tables);
    let notes = r
        .blocks
        .iter()
        .flat_map(|b| {
            b.cuts.iter().filter_map(move |c| {
                c.note
                    .as_ref()
                    .map(|n| format!("block {}: cut `{}` dropped: {n}", b.id, c.cut))
            })
        })
        .collect();
    Body {
        verdict,
        counts,
        constraints,
        notes,
        tables,
    }
}

fn curves(r: &DesignReport, job: &Context) -> Table {
    let u = job.units.symbol();
    let rows = r
        .cuts
        .iter()
        .flat_map(|c| c.curves.iter().map(move |x| (c, x)))
        .map(|(c, x)| {
            let mut why = Vec::new();
            if x.strain_flag {
                why.push("blade strain");
            }
            if x.inflection_flag {
                why.push("shape");
            }
            if x.stability_flag {
                why.push("blade stability");
            }
            Row::new(
                vec![
                    c.id.clone(),
                    x.station.to_string(),
                    x.block.clone(),
                    num(x.length),
                    num(x.max_deviation),
                    num(x.max_deviation_percent),
                    num(x.eq11_residual),
                    num(x.blade_max_curvature),
                    x.blade_inflections.to_string(),
                ],
                why,
            )
        })
        .collect();
    Table {
        title: "Design curves and their elastica".into(),
        columns: vec![
            "cut".into(),
            "station".into(),
            "block".into(),
            format!("length ({u})"),
            format!("max deviation ({u})"),
            "max deviation (% of length)".into(),
            "eq. (11) residual".into(),
            format!("blade max |κ| (/{u})"),
            "blade inflections".into(),
        ],
        rows,
    }
}

fn blocks(r: &DesignReport, job: &Context) -> Table {
    let u = job.units.symbol();
    Table {
        title: "Blocks".into(),
        columns: vec![
            "block".into(),
            format!("size ({u})"),
            "cuts (primary first)".into(),
            format!("top: elastica vs design ({u})"),
            format!("crease moved ({u})"),
        ],
        rows: r
            .blocks
            .iter()
            .map(|b| {
                let kept: Vec<&str> = b
                    .cuts
                    .iter()
                    .filter(|c| c.note.is_none())
                    .map(|c| c.cut.as_str())
                    .collect();
                let e = b.envelope.as_ref();
                Row::new(
                    vec![
                        b.id.clone(),
                        format!(
                            "{} × {} × {}",
                            num(b.max[0] - b.min[0]),
                            num(b.max[1] - b.min[1]),
                            num(b.max[2] - b.min[2])
                        ),
                        kept.join(" → "),
                        e.map_or("—".into(), |e| num(e.max_deviation)),
                        e.and_then(|e| e.crease_deviation).map_or("—".into(), num),
                    ],
                    Vec::new(),
                )
            })
            .collect(),
    }
}
