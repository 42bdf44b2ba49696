//! What `report.html` shows of a `HotBlade` run.

use crate::robot_cell::report::CellReport;
use export::html::{Body, Constraint, Row, Table};

use super::report::HotBladeReport;
use crate::context::Context;
use crate::output::page::{blade_verdict, curv, deg, len, num};

/// The verdict, the constraints the blocks are flagged by (and the cell), a row per block.
pub fn body(r: &HotBladeReport, job: &Context) -> Body {
    let s = &r.summary;
    let set = &r.settings;
    let verdict = blade_verdict(
        s.all_ok,
        r.cell.as_ref().map(|k| k.clean),
        format!(
            "{} block(s), {} blade section(s), every block meets every constraint",
            s.blocks, s.sections
        ),
        || {
            let bad = r.blocks.iter().filter(|b| flags(b).is_some()).count();
            format!(
                "Not cuttable as asked: {bad} of {} block(s) break a constraint (see the flagged rows).",
                s.blocks
            )
        },
    );
    let counts = vec![
        ("blocks".to_string(), s.blocks.to_string()),
        (
            "rows × columns".into(),
            format!("{} × {}", r.grid.rows, r.grid.columns),
        ),
        ("blade sections".into(), s.sections.to_string()),
        ("column splits".into(), r.splits.len().to_string()),
        ("poses per block".into(), set.targets_per_block.to_string()),
    ];
    let mut constraints = constraints(r, job);
    let mut tables = vec![blocks(r, job)];
    CellReport::add_to_page(r.cell.as_ref(), &mut constraints, &mut tables);
    Body {
        verdict,
        counts,
        constraints,
        notes: r.surface.warnings.clone(),
        tables,
    }
}

/// The constraints the blocks are flagged by, one row each.
fn constraints(r: &HotBladeReport, job: &Context) -> Vec<Constraint> {
    let s = &r.summary;
    let f = &s.flagged;
    let set = &r.settings;
    let n = |k: usize| format!("{k} of {} block(s) flagged", s.blocks);
    vec![
        Constraint {
            name: "approximation: largest fit distance".into(),
            limit: format!(
                "max {}, RMS {}",
                len(set.tolerance_max, job),
                len(set.tolerance_rms, job)
            ),
            measured: format!(
                "{}; fit {}, deviation {}",
                n(f.approximation),
                len(s.max_fit_distance, job),
                len(s.max_deviation, job)
            ),
            ok: f.approximation == 0,
        },
        Constraint {
            name: "blade strain: |curvature|".into(),
            limit: format!("≤ {}", curv(set.max_curvature, job)),
            measured: format!(
                "{}; largest {}",
                n(f.blade_strain),
                curv(s.max_abs_curvature, job)
            ),
            ok: f.blade_strain == 0,
        },
        Constraint {
            name: "shape: inflections on the blade".into(),
            limit: format!("≤ {}", set.max_inflections),
            measured: format!("{}; most {}", n(f.shape), s.max_inflections),
            ok: f.shape == 0,
        },
        Constraint {
            name: "blade length".into(),
            limit: len(set.blade_length, job),
            measured: format!(
                "{}; longest section {}",
                n(f.blade_length),
                len(
                    r.blocks
                        .iter()
                        .map(|b| b.section_length.max)
                        .fold(0.0, f64::max),
                    job
                )
            ),
            ok: f.blade_length == 0,
        },
        Constraint {
            name: "flat blade: plane vs surface normal".into(),
            limit: format!("≤ {}", deg(set.max_plane_angle)),
            measured: format!("{}; largest {}", n(f.flat_blade), deg(s.max_plane_angle)),
            ok: f.flat_blade == 0,
        },
        Constraint {
            name: "block height".into(),
            limit: len(r.grid.size[2], job),
            measured: n(f.block_height),
            ok: f.block_height == 0,
        },
        Constraint {
            name: "overlap of neighbouring cuts".into(),
            limit: "none".into(),
            measured: n(f.overlap),
            ok: f.overlap == 0,
        },
        Constraint {
            name: "blade outside the section vs the block".into(),
            limit: "no gouge, holders outside".into(),
            measured: n(f.gouge),
            ok: f.gouge == 0,
        },
        crate::output::page::stability_constraint(
            n(f.stability),
            r.blocks
                .iter()
                .filter_map(|b| b.min_margin)
                .fold(f64::INFINITY, f64::min),
            job.blade.min_margin,
            f.stability == 0,
        ),
    ]
}

/// The flags a block raises, if any.
fn flags(b: &hotblade::result::BlockReport) -> Option<Vec<&'static str>> {
    let f = &b.flags;
    let why: Vec<&str> = [
        (f.approximation, "approximation"),
        (f.blade_strain, "blade strain"),
        (f.shape, "shape"),
        (f.blade_length, "blade length"),
        (f.flat_blade, "flat blade"),
        (f.block_height, "block height"),
        (f.overlap, "overlap"),
        (f.gouge, "gouge"),
        (f.stability, "blade stability"),
    ]
    .into_iter()
    .filter_map(|(on, what)| on.then_some(what))
    .collect();
    (!why.is_empty()).then_some(why)
}

fn blocks(r: &HotBladeReport, job: &Context) -> Table {
    let u = job.units.symbol();
    let rows = r
        .blocks
        .iter()
        .map(|b| {
            Row::new(
                vec![
                    format!("{:03}", b.block),
                    (b.row + 1).to_string(),
                    (b.column + 1).to_string(),
                    b.sections.to_string(),
                    b.missing_sections.to_string(),
                    num(b.max_rms),
                    num(b.max_fit_distance),
                    num(b.max_deviation),
                    num(b.max_abs_curvature),
                    b.max_inflections.to_string(),
                    num(b.max_plane_angle.to_degrees()),
                ],
                flags(b).unwrap_or_default(),
            )
        })
        .collect();
    Table {
        title: "Blocks (drawing block_NNN.svg each)".into(),
        columns: vec![
            "block".into(),
            "row".into(),
            "column".into(),
            "sections".into(),
            "missing".into(),
            format!("max RMS ({u})"),
            format!("max fit distance ({u})"),
            format!("cut surface vs design ({u})"),
            format!("max |κ| (/{u})"),
            "most inflections".into(),
            "plane angle (°)".into(),
        ],
        rows,
    }
}
