//! What `report.html` shows of a `FitCurves` run.

use export::html::{Body, Constraint, Row, Table, Verdict};

use super::report::FitCurvesReport;
use crate::context::Context;
use crate::output::page::{curv, len, num};

/// The verdict (every curve fitted within the tolerances by a blade it can bend), the
/// tolerance and blade constraints, a row per curve (and per numerical spline).
pub fn body(r: &FitCurvesReport, job: &Context) -> Body {
    let s = &r.summary;
    let t = &job.tolerance;
    let b = &job.blade;
    let fits = || r.curves.iter().filter_map(|c| c.fit.as_ref());
    let kappa = fits().map(|f| f.max_abs_curvature).fold(0.0, f64::max);
    let inflections = fits().map(|f| f.inflections).max().unwrap_or(0);
    let longest = fits().map(|f| f.length).fold(0.0, f64::max);
    let over = |f: &elastica::fit::describe::FittedCurve| f.rms > t.rms || f.max > t.max;
    let off = fits().filter(|f| over(f)).count();
    let strained = fits()
        .filter(|f| f.max_abs_curvature > b.max_curvature)
        .count();
    let shaped = fits()
        .filter(|f| f.inflections > b.max_inflections as usize)
        .count();
    let long = fits().filter(|f| f.length > b.length).count();
    let ok = s.failed == 0 && off + strained + shaped + long == 0;
    let text = if ok {
        format!(
            "Every one of {} curve(s) is fitted by an elastica within the tolerances, and a blade can take it.",
            s.curves
        )
    } else {
        format!(
            "Not every curve can be cut as fitted: {} not fitted, {off} beyond the tolerance, {} beyond the blade (see the flagged rows).",
            s.failed,
            strained + shaped + long
        )
    };
    let counts = vec![
        ("curves".to_string(), s.curves.to_string()),
        ("inflectional".into(), s.inflectional.to_string()),
        ("non-inflectional".into(), s.noninflectional.to_string()),
        ("arcs".into(), s.arcs.to_string()),
        ("lines".into(), s.lines.to_string()),
        ("not fitted".into(), s.failed.to_string()),
    ];
    let n = |k: usize| format!("{k} of {} curve(s)", s.curves);
    let constraints = vec![
        Constraint {
            name: "approximation: fit distance".into(),
            limit: format!("RMS {}, max {}", len(t.rms, job), len(t.max, job)),
            measured: format!(
                "{} beyond; RMS ≤ {}, max ≤ {}",
                n(off),
                len(s.max_rms, job),
                len(s.max_distance, job)
            ),
            ok: off == 0 && s.failed == 0,
        },
        Constraint {
            name: "blade strain: |curvature|".into(),
            limit: format!("≤ {}", curv(b.max_curvature, job)),
            measured: format!("{} above; largest {}", n(strained), curv(kappa, job)),
            ok: strained == 0,
        },
        Constraint {
            name: "shape: inflections".into(),
            limit: format!("≤ {}", b.max_inflections),
            measured: format!("{} above; most {inflections}", n(shaped)),
            ok: shaped == 0,
        },
        Constraint {
            name: "blade length".into(),
            limit: len(b.length, job),
            measured: format!("{} longer; longest {}", n(long), len(longest, job)),
            ok: long == 0,
        },
    ];
    let mut tables = vec![curves(r, job)];
    if let Some(list) = &r.numerical {
        tables.push(numerical(list, job.units.symbol()));
    }
    Body {
        verdict: Verdict { ok, text },
        counts,
        constraints,
        notes: Vec::new(),
        tables,
    }
}

fn curves(r: &FitCurvesReport, job: &Context) -> Table {
    let t = &job.tolerance;
    let b = &job.blade;
    let over = |f: &elastica::fit::describe::FittedCurve| f.rms > t.rms || f.max > t.max;
    let u = job.units.symbol();
    let rows = r
        .curves
        .iter()
        .map(|c| match &c.fit {
            Some(f) => {
                let mut why = Vec::new();
                if over(f) {
                    why.push("beyond the tolerance");
                }
                if f.max_abs_curvature > b.max_curvature {
                    why.push("blade strain");
                }
                if f.inflections > b.max_inflections as usize {
                    why.push("shape");
                }
                if f.length > b.length {
                    why.push("longer than the blade");
                }
                if !f.converged {
                    why.push("fit did not converge");
                }
                Row::new(
                    vec![
                        c.id.clone(),
                        c.points.to_string(),
                        f.family.clone(),
                        num(f.rms),
                        num(f.max),
                        num(f.length),
                        f.inflections.to_string(),
                        num(f.max_abs_curvature),
                    ],
                    why,
                )
            }
            None => Row {
                cells: vec![
                    c.id.clone(),
                    c.points.to_string(),
                    "—".into(),
                    "—".into(),
                    "—".into(),
                    num(c.input_length),
                    "—".into(),
                    "—".into(),
                ],
                flag: Some(format!(
                    "not fitted: {}",
                    c.error.as_deref().unwrap_or("no fit")
                )),
            },
        })
        .collect();
    Table {
        title: "Curves".into(),
        columns: vec![
            "curve".into(),
            "points".into(),
            "elastica".into(),
            format!("RMS ({u})"),
            format!("max distance ({u})"),
            format!("length ({u})"),
            "inflections".into(),
            format!("max |κ| (/{u})"),
        ],
        rows,
    }
}

fn numerical(list: &[super::report::NumericalCurve], u: &str) -> Table {
    Table {
        title: "Numerical spline (eq. 13)".into(),
        columns: vec![
            "curve".into(),
            "control points".into(),
            "active constraints".into(),
            format!("largest control offset ({u})"),
            "energy before → after".into(),
            "eq. (11) residual".into(),
            format!("from the analytic fit ({u})"),
        ],
        rows: list
            .iter()
            .map(|n| {
                let mut why = Vec::new();
                if n.error.is_some() {
                    why.push("failed");
                }
                if !n.converged {
                    why.push("not converged");
                }
                Row::new(
                    vec![
                        n.id.clone(),
                        n.control_points.to_string(),
                        n.active_constraints.to_string(),
                        num(n.max_control_offset),
                        format!("{} → {}", num(n.energy_before), num(n.energy_after)),
                        num(n.eq11_residual),
                        n.distance_to_analytic.map_or("—".into(), num),
                    ],
                    why,
                )
            })
            .collect(),
    }
}
