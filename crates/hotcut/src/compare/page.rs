//! The comparison made from the processes' outcomes ([`compare`]), what `report.html` and
//! the CLI show of it, and the cost-versus-deviation chart.

use export::html::{Body, Constraint, Row, Table, Verdict};
use export::svg::{Legend, Mark, SvgDoc};

use super::cost::{self, Costed, Rates};
use super::report::{CompareReport, Plausibility, ProcessRow, RateRow, Sensitivity, Status};
use super::{Compare, CompareParams, CompareRun, Kind, Outcome, Planned};
use crate::context::Context;
use crate::output::Files;
use crate::process::Cutter;
use crate::spec::compare::RATE_DEFAULTS;
use crate::spec::OutputSpec;
use crate::task::Finished;

/// A process's name in the ranking.
fn label<P>(p: &Planned<P>) -> String {
    p.id.clone()
}

/// One process's row: status, fidelity, material, hours and cost.
fn row<P>(p: &Planned<P>, o: &Outcome, rates: &Rates, (tolerance, rms): (f64, f64)) -> ProcessRow {
    let mut r = ProcessRow {
        id: p.id.clone(),
        process: p.kind.name().into(),
        // a process that wrote nothing has no folder
        folder: p.folder.clone().filter(|_| !o.files.is_empty()),
        status: Status::NotApplicable,
        reason: p.not_applicable.clone(),
        figures: o.figures.clone(),
        tool: p.tool,
        deviation: None,
        eps_m3: None,
        waste_m3: None,
        hours: None,
        cut_speed: None,
        cost: None,
        rank: None,
    };
    if r.reason.is_some() {
        return r;
    }
    let Some(f) = &o.figures else {
        r.status = Status::Infeasible;
        r.reason = Some(format!(
            "its run failed: {}",
            o.failed.as_deref().unwrap_or("no figures")
        ));
        return r;
    };
    r.deviation = match &p.tool {
        Some(t) => Some(cost::scallop(t)),
        None => f.deviation,
    };
    let mut why = f.why_not.clone();
    if let (None, Some(t), Some(d)) = (&why, &p.tool, &r.deviation) {
        if d.max > tolerance {
            why = Some(format!(
                "the tool's scallop ({:.4}: {} diameter, {} stepover) exceeds tolerance.max ({tolerance})",
                d.max, t.diameter, t.stepover
            ));
        } else if d.rms > rms {
            why = Some(format!(
                "the tool's scallop has an RMS of {:.4} ({} diameter, {} stepover), above tolerance.rms ({rms})",
                d.rms, t.diameter, t.stepover
            ));
        }
    }
    r.status = if why.is_some() {
        Status::Infeasible
    } else {
        Status::Feasible
    };
    r.reason = why;
    r.eps_m3 = Some(f.stock_volume * rates.m3_per_unit3);
    r.waste_m3 = Some((f.stock_volume - f.part_volume).max(0.0) * rates.m3_per_unit3);
    if f.cutter != Cutter::None && f.programs == 0 {
        // no program to time: a run that refused to cut
        if r.status == Status::Feasible {
            r.status = Status::Infeasible;
            r.reason = Some("its task wrote no machine program".into());
        }
        return r;
    }
    let h = cost::hours(f, p.tool.as_ref(), rates);
    let c = cost::cost(f, &h, rates);
    if !(c.total.is_finite() && h.total.is_finite()) {
        r.status = Status::Infeasible;
        r.reason = Some("its time or cost is not a finite number: a rate far out of range".into());
        return r;
    }
    r.cost = Some(c);
    r.hours = Some(h);
    if f.cut_length > 0.0 {
        let k = if f.cutter == Cutter::Blade {
            cost::rate::BLADE_SPEED
        } else {
            cost::rate::WIRE_SPEED
        };
        r.cut_speed = Some(rates.speed(k, f.cut_speed));
    }
    r
}

/// The comparison of a run's outcomes: rows, ranking, sensitivity and the seed's claims.
pub fn compare<P>(p: &CompareParams<P>, outcomes: &[Outcome], job: &Context) -> CompareReport {
    let mut rows: Vec<ProcessRow> = p
        .processes
        .iter()
        .zip(outcomes)
        .map(|(planned, o)| row(planned, o, &p.rates, (p.tolerance, p.tolerance_rms)))
        .collect();
    let feasible: Vec<usize> = (0..rows.len())
        .filter(|&i| rows[i].status == Status::Feasible)
        .collect();
    let costed: Vec<Costed<'_>> = feasible
        .iter()
        .filter_map(|&i| {
            outcomes[i].figures.as_ref().map(|f| Costed {
                figures: f,
                tool: p.processes[i].tool.as_ref(),
            })
        })
        .collect();
    let name = |k: usize| label(&p.processes[feasible[k]]);
    let order = cost::ranking(&costed, &p.rates);
    for (place, &k) in order.iter().enumerate() {
        rows[feasible[k]].rank = Some(place + 1);
    }
    let totals: Vec<f64> = order
        .iter()
        .filter_map(|&k| rows[feasible[k]].cost.map(|c| c.total))
        .collect();
    let margin_percent = (totals.len() >= 2 && totals[0] > 0.0)
        .then(|| 100.0 * (totals[1] - totals[0]).max(0.0) / totals[0]);
    if order.is_empty() {
        // nothing feasible: the run writes its report and page only
        rows.iter_mut().for_each(|r| r.folder = None);
    }
    let sensitivity = RATE_DEFAULTS
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let winner = |f: f64| {
                cost::ranking(&costed, &p.rates.scaled(k, f))
                    .first()
                    .map(|&w| name(w))
            };
            let (halved, raised) = (winner(0.5), winner(1.5));
            let now = order.first().map(|&w| name(w));
            let ranked = |f: f64| -> Vec<String> {
                cost::ranking(&costed, &p.rates.scaled(k, f))
                    .into_iter()
                    .map(name)
                    .collect()
            };
            let (ranking_halved, ranking_raised) = (ranked(0.5), ranked(1.5));
            let base: Vec<String> = order.iter().map(|&w| name(w)).collect();
            let (flip_below, flip_above) = cost::flip_factors(&costed, &p.rates, k);
            Sensitivity {
                rate: d.field.into(),
                flips: halved != now || raised != now,
                ranking_changes: ranking_halved != base || ranking_raised != base,
                ranking_halved,
                ranking_raised,
                halved,
                raised,
                flip_below,
                flip_above,
            }
        })
        .collect();
    CompareReport {
        job: job.name.clone(),
        task: "Compare".into(),
        units: job.units,
        hotcut_version: crate::report::VERSION.into(),
        design: p.design.into(),
        tolerance: p.tolerance,
        tolerance_rms: p.tolerance_rms,
        rates: rate_rows(p, job),
        plausibility: plausibility(p, &rows),
        ranking: order.iter().map(|&k| name(k)).collect(),
        winner: order.first().map(|&k| name(k)),
        margin_percent,
        sensitivity,
        processes: rows,
    }
}

/// The rates table of the report.
fn rate_rows<P>(p: &CompareParams<P>, job: &Context) -> Vec<RateRow> {
    let unit = job.units.name();
    RATE_DEFAULTS
        .iter()
        .enumerate()
        .map(|(k, d)| RateRow {
            field: d.field.into(),
            value: p.rates.values[k],
            unit: super::rate_unit(d, unit),
            set_by_job: p.written[k].is_some(),
            assumed: p.written[k].is_none() && d.assumed,
            source: d.source.into(),
        })
        .collect()
}

/// The seed's claims measured on this comparison.
fn plausibility<P>(p: &CompareParams<P>, rows: &[ProcessRow]) -> Plausibility {
    let machine = |r: &ProcessRow| r.hours.map(|h| h.wire + h.blade + h.roughing + h.finishing);
    let find = |pred: &dyn Fn(Kind) -> bool| {
        p.processes
            .iter()
            .zip(rows)
            .find(|(pl, r)| pred(pl.kind) && r.hours.is_some())
            .map(|(_, r)| r)
    };
    let milling = find(&|k| matches!(k, Kind::Milling | Kind::MillingSegmented));
    let blade = find(&|k| k.blade());
    let precut = find(&|k| k == Kind::PreCutThenMilling);
    let grid = find(&|k| k == Kind::Milling);
    let seg = find(&|k| k == Kind::MillingSegmented);
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b),
        _ => None,
    };
    Plausibility {
        blade_speedup: ratio(milling.and_then(machine), blade.and_then(machine)),
        precut_saving_percent: ratio(precut.and_then(machine), milling.and_then(machine))
            .map(|r| 100.0 * (1.0 - r)),
        precut_roughing_saving_percent: ratio(
            precut.and_then(|r| r.hours.map(|h| h.wire + h.roughing)),
            milling.and_then(|r| r.hours.map(|h| h.roughing)),
        )
        .map(|r| 100.0 * (1.0 - r)),
        blocks_segmented_vs_grid: match (seg, grid) {
            (Some(s), Some(g)) => Some([
                s.figures.as_ref().map_or(0, |f| f.blocks),
                g.figures.as_ref().map_or(0, |f| f.blocks),
            ]),
            _ => None,
        },
    }
}

/// A number for people (four significant digits).
fn g(v: f64) -> String {
    crate::output::page::num(v)
}

/// What the CLI prints.
pub fn summary(r: &CompareReport, job: &Context) -> String {
    let mut s = format!(
        "{} (Compare): {} process(es), {} feasible",
        job.name,
        r.processes.len(),
        r.ranking.len()
    );
    for p in &r.processes {
        let c = p.cost.map_or("-".into(), |c| g(c.total));
        s += &format!(
            "\n  {:<20} {:<14} cost {c}{}",
            &p.id,
            format!("{:?}", p.status),
            p.reason.as_ref().map_or(String::new(), |w| format!(
                " ({})",
                geom::text::clip(w, 100)
            ))
        );
    }
    if let Some(w) = &r.winner {
        s += &format!(
            "\n  cheapest feasible: {w}{}",
            r.margin_percent.map_or(String::new(), |m| format!(
                " (the next cheapest costs {} % more)",
                g(m)
            ))
        );
    }
    s
}

/// What `report.html` shows: the comparison table first.
pub fn body(r: &CompareReport, job: &Context) -> Body {
    let u = job.units.name();
    let verdict = match &r.winner {
        Some(w) => Verdict {
            ok: true,
            text: format!(
                "Cheapest feasible process: {w}{}. {} of {} processes can make the design within {} {u}.",
                r.margin_percent
                    .map_or(String::new(), |m| format!(" (the next cheapest costs {} % more)", g(m))),
                r.ranking.len(),
                r.processes.len(),
                r.tolerance
            ),
        },
        None => Verdict {
            ok: false,
            text: "No process makes the design within the tolerance: see each one's reason."
                .into(),
        },
    };
    let flips: Vec<&Sensitivity> = r.sensitivity.iter().filter(|s| s.flips).collect();
    let mut notes = vec![format!(
        "Rates marked assumed have no published source: {}.",
        r.rates
            .iter()
            .filter(|x| x.assumed)
            .map(|x| x.field.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    )];
    if r.winner.is_none() {
        // nothing to rank
    } else if flips.is_empty() {
        notes.push("No rate halved or raised by half changes the cheapest process.".into());
    } else {
        notes.push(format!(
            "The cheapest process changes when {} is halved or raised by half.",
            flips
                .iter()
                .map(|s| s.rate.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    Body {
        verdict,
        counts: vec![
            ("processes".into(), r.processes.len().to_string()),
            ("feasible".into(), r.ranking.len().to_string()),
        ],
        constraints: vec![Constraint {
            name: "deviation from the design".into(),
            limit: format!("{} {u}", r.tolerance),
            measured: format!("{} of {} within", r.ranking.len(), r.processes.len()),
            ok: !r.ranking.is_empty(),
        }],
        notes,
        tables: vec![comparison_table(r, u), sensitivity_table(r), rates_table(r)],
    }
}

/// One row per process, the cheapest feasible marked.
fn comparison_table(r: &CompareReport, u: &str) -> Table {
    let dash = || "–".to_string();
    let rows = r
        .processes
        .iter()
        .map(|p| {
            let f = p.figures.as_ref();
            let mark = if p.rank == Some(1) {
                "★ cheapest"
            } else {
                ""
            };
            let cells = vec![
                format!("{} {mark}", &p.id),
                format!("{:?}", p.status),
                f.map_or_else(dash, |f| f.blocks.to_string()),
                p.eps_m3.map_or_else(dash, g),
                p.waste_m3.map_or_else(dash, g),
                f.map_or_else(dash, |f| g(f.milling_volume * r_m3(r, p))),
                f.map_or_else(dash, |f| g(f.cut_length)),
                p.hours.map_or_else(dash, |h| g(h.total)),
                p.deviation
                    .map_or_else(dash, |d| format!("{} / {}", g(d.rms), g(d.max))),
                p.cost.map_or_else(dash, |c| g(c.material)),
                p.cost.map_or_else(dash, |c| g(c.machine)),
                p.cost.map_or_else(dash, |c| g(c.labour)),
                p.cost.map_or_else(dash, |c| g(c.total)),
                p.reason.clone().unwrap_or_default(),
            ];
            let why: Vec<&str> = match p.status {
                Status::Feasible => vec![],
                Status::Infeasible => vec!["infeasible"],
                Status::NotApplicable => vec!["not applicable"],
            };
            Row::new(cells, why)
        })
        .collect();
    Table {
        title: "Processes side by side".into(),
        columns: [
            "process".to_string(),
            "status".into(),
            "blocks".into(),
            "EPS bought m³".into(),
            "waste m³".into(),
            "milled m³".into(),
            format!("cut path {u}"),
            "hours".into(),
            format!("deviation RMS / max {u}"),
            "material".into(),
            "machine".into(),
            "labour".into(),
            "total".into(),
            "why not".into(),
        ]
        .to_vec(),
        rows,
    }
}

/// m³ per job unit³ of a row (from its own numbers).
fn r_m3(_: &CompareReport, p: &ProcessRow) -> f64 {
    match (p.eps_m3, &p.figures) {
        (Some(m3), Some(f)) if f.stock_volume > 0.0 => m3 / f.stock_volume,
        _ => 0.0,
    }
}

/// The winner with each rate halved and raised by half.
fn sensitivity_table(r: &CompareReport) -> Table {
    let opt = |v: &Option<String>| v.clone().unwrap_or_else(|| "–".into());
    let factor = |v: Option<f64>| v.map_or("beyond 1/100–100×".into(), |f| format!("×{}", g(f)));
    Table {
        title: "Sensitivity: each rate ×0.5 and ×1.5".into(),
        columns: [
            "rate",
            "winner ×0.5",
            "winner ×1.5",
            "flips below",
            "flips above",
        ]
        .map(String::from)
        .to_vec(),
        rows: r
            .sensitivity
            .iter()
            .map(|s| {
                Row::new(
                    vec![
                        s.rate.clone(),
                        opt(&s.halved),
                        opt(&s.raised),
                        factor(s.flip_below),
                        factor(s.flip_above),
                    ],
                    if s.flips {
                        vec!["flips the ranking"]
                    } else {
                        vec![]
                    },
                )
            })
            .collect(),
    }
}

/// The rates used, with sources.
fn rates_table(r: &CompareReport) -> Table {
    Table {
        title: "Rates".into(),
        columns: ["rate", "value", "unit", "from", "source"]
            .map(String::from)
            .to_vec(),
        rows: r
            .rates
            .iter()
            .map(|x| {
                Row::new(
                    vec![
                        x.field.clone(),
                        g(x.value),
                        x.unit.clone(),
                        if x.set_by_job {
                            "job".into()
                        } else if x.assumed {
                            "default (assumed)".into()
                        } else {
                            "default".into()
                        },
                        x.source.clone(),
                    ],
                    vec![],
                )
            })
            .collect(),
    }
}

/// `comparison.svg` (cost against deviation, "price and style"), then each process's
/// preview.
pub fn svg<P>(
    done: &Finished<'_, Compare<P>>,
    _: &OutputSpec,
    files: &mut Files,
) -> export::Result<()>
where
    Compare<P>: crate::task::Task<Run = CompareRun, Report = CompareReport>,
{
    let r = done.report;
    files.add("comparison.svg", |buf| {
        chart(r, done.job.units.name()).write(buf)
    })?;
    super::write_previews(done.run, files)
}

/// Cost (up) against largest deviation (right), one dot per process that has both.
fn chart(r: &CompareReport, u: &str) -> SvgDoc {
    let (w, h) = (760.0, 400.0);
    let frame = (70.0, 40.0, 420.0, 300.0);
    let mut doc = SvgDoc::new(w, h);
    let pts: Vec<(&ProcessRow, f64, f64)> = r
        .processes
        .iter()
        .filter_map(|p| Some((p, p.deviation?.max, p.cost?.total)))
        .collect();
    let xmax = pts.iter().map(|p| p.1).fold(r.tolerance, f64::max) * 1.1;
    let ymax = pts.iter().map(|p| p.2).fold(0.0, f64::max).max(1e-9) * 1.1;
    doc.chart_axes(
        frame,
        (0.0, xmax),
        (0.0, ymax),
        &format!("largest deviation, {u}"),
        "cost",
    );
    let (l, t, fw, fh) = frame;
    let map = |x: f64, y: f64| (l + x / xmax * fw, t + fh - y / ymax * fh);
    let tol = map(r.tolerance, 0.0).0;
    doc.dashed_polyline(
        &[(tol, t), (tol, t + fh)],
        "#cc3333",
        1.0,
        4.0,
        Some("tolerance.max"),
    );
    // every process its colour, named in the legend (no text inside the frame, where
    // the tolerance line and the dots are)
    const PALETTE: [&str; 6] = [
        "#1a7f37", "#1f5fbf", "#b35900", "#7b3fa0", "#0f8a8a", "#a0303a",
    ];
    let mut labels = Vec::new();
    for (k, (p, x, y)) in pts.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        let state = match p.status {
            Status::Feasible if p.rank == Some(1) => "cheapest",
            Status::Feasible => "feasible",
            _ => "infeasible",
        };
        doc.circle(
            map(*x, *y),
            5.0,
            colour,
            Some(&format!("{} ({state})", p.id)),
        );
        if !matches!(p.status, Status::Feasible) {
            // a ring marks what cannot make the design
            doc.circle(map(*x, *y), 2.0, "#ffffff", None);
        }
        labels.push((colour, format!("{} ({state})", p.id)));
    }
    let mut entries: Vec<Legend<'_>> = labels
        .iter()
        .map(|(c, l)| Legend::new(Mark::Dot, c, l.as_str()))
        .collect();
    entries.push(Legend::new(Mark::Dashed, "#cc3333", "tolerance"));
    doc.legend((l + fw + 20.0, t), w - (l + fw + 30.0), &entries);
    doc
}
