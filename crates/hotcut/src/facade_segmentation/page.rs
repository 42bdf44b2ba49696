//! What `report.html` shows of a `FacadeSegmentation` run.

use crate::robot_cell::report::CellReport;
use export::html::{Body, Constraint, Row, Table, Verdict};

use super::report::SegmentationReport;
use crate::context::Context;
use crate::output::page::{blade_verdict, curv, len, num};

/// The verdict, the four constraints of thesis §5.1 (and the cell), and a row per piece.
pub fn body(r: &SegmentationReport, job: &Context) -> Body {
    let c = &r.counts;
    let s = &r.settings;
    let f = &c.failing;
    let verdict = verdict(r);
    let mut counts = vec![
        ("pieces".to_string(), c.pieces.to_string()),
        ("blocks".into(), c.blocks.to_string()),
        ("bands × rows".into(), format!("{} × {}", c.bands, c.rows)),
        ("section parts".into(), c.parts.to_string()),
        ("algorithm".into(), s.algorithm.name().to_string()),
    ];
    if s.rationalized {
        counts.push(("blade poses".into(), c.poses.to_string()));
        counts.push(("slivers not posed".into(), c.unposed.to_string()));
    }
    let sections = || r.pieces.iter().flat_map(|p| &p.sections);
    let longest = sections().map(|x| x.length).fold(0.0, f64::max);
    let inflections = sections().map(|x| x.inflections).max().unwrap_or(0);
    // what strains the blade: the bent blade's curvature where the piece was posed, else
    // the section's own
    let kappa = sections().map(strain).fold(0.0, f64::max);
    let rms = sections()
        .filter_map(|x| x.blade_fit.as_ref().map(|f| f.rms))
        .fold(0.0, f64::max);
    let fit = r
        .pieces
        .iter()
        .filter_map(|p| p.max_blade_fit)
        .fold(0.0, f64::max);
    let of = |n: usize| format!("{n} of {} piece(s) fail", c.pieces);
    let mut constraints = vec![
        Constraint {
            name: "dimension: piece fits its block".into(),
            limit: format!(
                "block {} × {} × {}",
                len(s.block[0], job),
                len(s.block[1], job),
                len(s.block[2], job)
            ),
            measured: format!(
                "{}; longest section part {}",
                of(f.dimension),
                len(longest, job)
            ),
            ok: f.dimension == 0,
        },
        Constraint {
            name: "approximation: elastica fit".into(),
            limit: format!(
                "RMS {}, max {}",
                len(s.tolerance_rms, job),
                len(s.tolerance_max, job)
            ),
            measured: if s.rationalized {
                format!(
                    "{}; largest blade fit distance {}, RMS {}",
                    of(f.approximation),
                    len(fit, job),
                    len(rms, job)
                )
            } else {
                of(f.approximation)
            },
            ok: f.approximation == 0,
        },
        Constraint {
            name: "shape: inflections per section part".into(),
            limit: format!("≤ {}", s.max_inflections),
            measured: format!("{}; most {inflections}", of(f.shape)),
            ok: f.shape == 0,
        },
        Constraint {
            name: "dimension: section part within the blade".into(),
            limit: len(s.blade_length, job),
            measured: format!("longest section part {}", len(longest, job)),
            ok: longest <= s.blade_length,
        },
        Constraint {
            name: if s.rationalized {
                "blade strain: |curvature| of the bent blade".into()
            } else {
                "blade strain: |curvature| of the sections".into()
            },
            limit: format!("≤ {}", curv(s.max_curvature, job)),
            measured: format!("{}; largest {}", of(f.blade_strain), curv(kappa, job)),
            ok: f.blade_strain == 0,
        },
    ];
    if s.rationalized {
        let least = r
            .pieces
            .iter()
            .filter_map(|p| p.min_margin)
            .fold(f64::INFINITY, f64::min);
        constraints.push(crate::output::page::stability_constraint(
            of(f.stability),
            least,
            job.blade.min_margin,
            f.stability == 0,
        ));
    }
    constraints.extend(clearance(r, job));
    let mut tables = vec![pieces(r, job)];
    CellReport::add_to_page(r.cell.as_ref(), &mut constraints, &mut tables);
    Body {
        verdict,
        counts,
        constraints,
        notes: r
            .surface
            .warnings
            .iter()
            .cloned()
            .chain(super::report::unresolved_lines(r, job.units.symbol()))
            .collect(),
        tables,
    }
}

/// The blades outside their parts against the blocks (rationalized runs): gouges and
/// holder collisions.
fn clearance(r: &SegmentationReport, job: &Context) -> Option<Constraint> {
    let (c, s) = (&r.counts, &r.settings);
    if !s.rationalized {
        return None;
    }
    let deepest = r
        .pieces
        .iter()
        .filter_map(|p| p.max_gouge_depth)
        .fold(0.0, f64::max);
    let nearest = r
        .pieces
        .iter()
        .filter_map(|p| p.min_holder_clearance)
        .fold(f64::INFINITY, f64::min);
    Some(Constraint {
        name: "clearance: the blade outside its part".into(),
        limit: format!(
            "no gouge below the design; held ends ≥ {} from the block",
            len(elastica::clearance::HOLDER_MARGIN * s.blade_length, job)
        ),
        measured: format!(
            "{} piece(s) gouge (deepest {}), {} with a holder on its block (nearest end {})",
            c.gouges,
            len(deepest, job),
            c.collisions,
            if nearest.is_finite() {
                len(nearest, job)
            } else {
                "—".into()
            }
        ),
        ok: c.gouges == 0 && c.collisions == 0,
    })
}

/// Can it be cut: every piece meets every constraint, and the robots reach every move.
fn verdict(r: &SegmentationReport) -> Verdict {
    let c = &r.counts;
    let f = &c.failing;
    blade_verdict(
        c.all_ok,
        r.cell.as_ref().map(|k| k.clean),
        format!(
            "{} piece(s) from {} block(s), every piece meets every constraint",
            c.pieces, c.blocks
        ),
        || {
            format!(
                "Not cuttable as asked: pieces break a constraint (dimension {}, approximation {}, shape {}, blade strain {}; gouge {}, holder collision {}) of {} piece(s).",
                f.dimension, f.approximation, f.shape, f.blade_strain, c.gouges, c.collisions, c.pieces
            )
        },
    )
}

/// The curvature that strains the blade on a section part: the bent blade's when the
/// part was posed, else the part's own.
fn strain(x: &facade_seg::report::PieceSection) -> f64 {
    x.blade_fit
        .as_ref()
        .map_or(x.max_abs_curvature, |f| f.max_abs_curvature)
}

fn pieces(r: &SegmentationReport, job: &Context) -> Table {
    let u = job.units.symbol();
    let rows = r
        .pieces
        .iter()
        .map(|p| {
            let v = &p.verdicts;
            let mut why = Vec::new();
            if !v.dimension {
                why.push("dimension");
            }
            if v.approximation == Some(false) {
                why.push("approximation");
            }
            if !v.shape {
                why.push("shape");
            }
            if !v.stability {
                why.push("blade stability");
            }
            if !v.blade_strain {
                why.push("blade strain");
            }
            if p.max_gouge_depth.is_some_and(|d| d > 0.0) {
                why.push("gouge");
            }
            if p.holders_clear == Some(false) {
                why.push("holder collision");
            }
            let longest = p.sections.iter().map(|x| x.length).fold(0.0, f64::max);
            let kappa = p
                .sections
                .iter()
                .map(|x| x.max_abs_curvature)
                .fold(0.0, f64::max);
            let infl = p.sections.iter().map(|x| x.inflections).max().unwrap_or(0);
            let used = p.block.used;
            Row::new(
                vec![
                    p.id.to_string(),
                    p.band.to_string(),
                    p.row.to_string(),
                    p.block.number.to_string(),
                    format!("{} × {} × {}", num(used[0]), num(used[1]), num(used[2])),
                    p.sections.len().to_string(),
                    num(longest),
                    infl.to_string(),
                    num(kappa),
                    p.max_blade_fit.map_or("—".into(), num),
                    p.max_gouge_depth.map_or("—".into(), num),
                    p.min_holder_clearance.map_or("—".into(), num),
                    p.min_margin.map_or("—".into(), num),
                ],
                why,
            )
        })
        .collect();
    Table {
        title: "Pieces".into(),
        columns: vec![
            "piece".into(),
            "band".into(),
            "row".into(),
            "block".into(),
            format!("block used ({u})"),
            "sections".into(),
            format!("longest part ({u})"),
            "most inflections".into(),
            format!("blade max |κ| (/{u})"),
            format!("blade fit max ({u})"),
            format!("gouge ({u})"),
            format!("holder clearance ({u})"),
            "least blade margin".into(),
        ],
        rows,
    }
}
