//! The files of an `Analyze` run: `sections.svg`, after thesis fig. 5.13 — a plan view
//! (looking down −z) of the sections with inflection points in red and curvature maxima in
//! blue, and below it the section profiles in their planes' `(u, v)` coordinates, overlaid;
//! sections that break a constraint in orange and thicker — and `sections.obj`, the
//! sections as 3D polylines.

use export::json::REPORT_DIGITS;
use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};
use geom::planar::PlanarCurve;
use geom::slice::PlaneFrame;
use geom::surface::Section;

use super::report::AnalyzeReport;
use super::{Analysis, Analyze};
use crate::output::Files;
use crate::spec::OutputSpec;
use crate::task::Finished;

const WIDTH: f64 = 1000.0;
const MARGIN: f64 = 40.0;
const SAMPLES: usize = 200;

/// `sections.svg`.
pub(super) fn svg(
    done: &Finished<'_, Analyze>,
    _: &OutputSpec,
    files: &mut Files,
) -> export::Result<()> {
    let units = done.job.units.symbol();
    files.add("sections.svg", |buf| {
        sections_svg(done.run, done.report, units).write(buf)
    })
}

/// `sections.obj`.
pub(super) fn obj(
    done: &Finished<'_, Analyze>,
    o: &OutputSpec,
    files: &mut Files,
) -> export::Result<()> {
    files.add("sections.obj", |buf| {
        let mut w = crate::output::obj_writer(REPORT_DIGITS, done.job.units, o);
        for (s, _) in &done.run.survey.sections {
            w.polyline(
                &format!("section_{}_{}", s.index, s.piece),
                &sample_world(&done.run.frame, s, 400),
            );
        }
        w.write(buf)
    })
}

/// Points along a section in world coordinates, `n + 1` equally spaced in parameter.
fn sample_world(frame: &PlaneFrame, s: &Section, n: usize) -> Vec<nalgebra::Vector3<f64>> {
    let (a, b) = s.curve.domain();
    (0..=n)
        .map(|i| frame.to_world(s.offset, &s.curve.point(a + (b - a) * i as f64 / n as f64)))
        .collect()
}

/// Draws the analysis.
fn sections_svg(a: &Analysis, r: &AnalyzeReport, units: &str) -> SvgDoc {
    let plan: Vec<Vec<(f64, f64)>> = a
        .survey
        .sections
        .iter()
        .map(|(s, _)| {
            sample_world(&a.frame, s, SAMPLES)
                .iter()
                .map(|p| (p.x, p.y))
                .collect()
        })
        .collect();
    let profiles: Vec<Vec<(f64, f64)>> = a
        .survey
        .sections
        .iter()
        .map(|(s, _)| {
            let (t0, t1) = s.curve.domain();
            (0..=SAMPLES)
                .map(|i| {
                    let p = s.curve.point(t0 + (t1 - t0) * i as f64 / SAMPLES as f64);
                    (p.x, p.y)
                })
                .collect()
        })
        .collect();
    let block_outline = block_outline(r);
    let (pmin, pmax) = bounds(
        plan.iter()
            .flatten()
            .copied()
            .chain(block_outline.iter().flatten().copied()),
    );
    let (qmin, qmax) = bounds(profiles.iter().flatten().copied());
    let inner = WIDTH - 2.0 * MARGIN;
    let plan_h = (inner * (pmax.1 - pmin.1) / (pmax.0 - pmin.0).max(1e-9)).clamp(150.0, 700.0);
    let prof_h = (inner * (qmax.1 - qmin.1) / (qmax.0 - qmin.0).max(1e-9)).clamp(120.0, 400.0);
    let lines = reason_lines(&surface_reasons(r, units));
    let extra = 16.0 * lines.len().saturating_sub(1) as f64;
    let height = MARGIN * 4.0 + plan_h + prof_h + 46.0 + 14.0 + 40.0 + extra;
    let mut doc = SvgDoc::new(WIDTH, height);
    sections_header(&mut doc, r, &lines, units);
    let plan_page = (MARGIN, MARGIN + 46.0 + extra, inner, plan_h);
    doc.rect(plan_page, "#ccc", "none");
    let vp = Viewport::fit(pmin, pmax, plan_page);
    if let Some(outline) = block_outline {
        let pts: Vec<(f64, f64)> = outline.iter().map(|&(x, y)| vp.map(x, y)).collect();
        doc.dashed_polyline(
            &pts,
            "#c00000",
            1.4,
            6.0,
            Some("the block, at the surface's corner"),
        );
    }
    let prof_top = MARGIN * 2.0 + 46.0 + extra + plan_h + 20.0;
    doc.text(
        (MARGIN, prof_top - 8.0),
        12.0,
        "#444",
        &format!("section profiles in (u, v), overlaid ({units})"),
    );
    let prof_page = (MARGIN, prof_top, inner, prof_h);
    doc.rect(prof_page, "#ccc", "none");
    let vq = Viewport::fit(qmin, qmax, prof_page);
    doc.scale_bar(&vp, (MARGIN, plan_page.1 + plan_h + 20.0), inner, units);
    doc.scale_bar(&vq, (MARGIN, prof_top + prof_h + 24.0), inner, units);
    doc.axes_key(
        (WIDTH - MARGIN - 60.0, plan_page.1 + plan_h + 46.0),
        "x",
        "y (plan)",
    );
    doc.axes_key(
        (WIDTH - MARGIN - 60.0, prof_top + prof_h + 50.0),
        "u",
        "v (section plane)",
    );

    for (k, ((s, an), rep)) in a.survey.sections.iter().zip(&r.sections).enumerate() {
        let bad = !rep.violations.is_empty();
        let (stroke, w) = if bad { ("#e07000", 1.6) } else { ("#333", 0.8) };
        let mut title = format!(
            "section {} piece {}: length {:.1}, {} inflections",
            s.index,
            s.piece,
            rep.length,
            rep.inflections.len()
        );
        for v in &rep.violations {
            title.push_str("; ");
            title.push_str(&violation(v, units));
        }
        let pts: Vec<(f64, f64)> = plan[k].iter().map(|&(x, y)| vp.map(x, y)).collect();
        doc.polyline(&pts, stroke, w, Some(&title));
        let pts: Vec<(f64, f64)> = profiles[k].iter().map(|&(x, y)| vq.map(x, y)).collect();
        doc.polyline(&pts, stroke, w * 0.7, Some(&title));
        for (list, colour) in [
            (&an.curvature_maxima, "#1060e0"),
            (&an.inflections, "#e01010"),
        ] {
            for p in list.iter() {
                let world = a.frame.to_world(s.offset, &p.point);
                doc.circle(vp.map(world.x, world.y), 2.6, colour, None);
                doc.circle(vq.map(p.point.x, p.point.y), 2.0, colour, None);
            }
        }
    }
    doc
}

/// The block, placed at the surface's lower corner, in plan, when the surface as a whole
/// breaks the block's size (the reason a surface "needs segmentation" although every
/// section passes); `None` otherwise.
fn block_outline(r: &AnalyzeReport) -> Option<[(f64, f64); 5]> {
    // the block, placed at the surface's lower corner, when the surface breaks it: the
    // reason a surface "needs segmentation" although every section passes
    match (
        r.constraints.block_size,
        r.summary.surface_violations.is_empty(),
    ) {
        (Some(b), false) => {
            let (x0, y0) = (r.surface.bbox_min[0], r.surface.bbox_min[1]);
            Some([
                (x0, y0),
                (x0 + b[0], y0),
                (x0 + b[0], y0 + b[1]),
                (x0, y0 + b[1]),
                (x0, y0),
            ])
        }
        _ => None,
    }
}

/// Why the surface as a whole breaks the rules, one phrase per violation (sections name
/// their own reasons).
fn surface_reasons(r: &AnalyzeReport, units: &str) -> Vec<String> {
    // why the surface as a whole breaks the rules, then how many sections break which rule
    let s = &r.summary;
    let mut out: Vec<String> = s
        .surface_violations
        .iter()
        .map(|v| violation(v, units))
        .collect();
    for (n, what) in [
        (s.sections_too_long, "longer than the blade"),
        (s.sections_too_many_inflections, "with too many inflections"),
        (s.sections_too_curved, "too curved for the blade"),
    ] {
        if n > 0 {
            out.push(format!("{n} section(s) {what} (orange)"));
        }
    }
    out
}

/// The reasons joined into lines that fit the page (12-unit text).
fn reason_lines(reasons: &[String]) -> Vec<String> {
    let fits = ((WIDTH - 2.0 * MARGIN) / (0.6 * 12.0)) as usize;
    let mut lines: Vec<String> = Vec::new();
    for r in reasons {
        match lines.last_mut() {
            Some(l) if l.chars().count() + 2 + r.chars().count() <= fits => {
                l.push_str("; ");
                l.push_str(r);
            }
            _ => lines.push(r.clone()),
        }
    }
    lines
}

/// What a violation says, for people.
fn violation(v: &facade_seg::survey::Violation, units: &str) -> String {
    use facade_seg::survey::Violation;
    match v {
        Violation::Dimension { what, value, limit } => {
            format!(
                "{}: {value:.1} vs {limit:.1} {units}",
                what.replace('_', " ")
            )
        }
        Violation::Shape { inflections, limit } => {
            format!("{inflections} inflections, the blade takes {limit}")
        }
        Violation::BladeStrain {
            max_abs_curvature,
            limit,
            ..
        } => format!("|curvature| {max_abs_curvature:.3e} /{units} above {limit:.3e} /{units}"),
    }
}

/// The title, the surface's reasons (if any) and the legend of `sections.svg`.
fn sections_header(doc: &mut SvgDoc, r: &AnalyzeReport, reasons: &[String], units: &str) {
    doc.text(
        (MARGIN, 24.0),
        16.0,
        "black",
        &format!(
            "{} — {} sections, {} inflections, max |κ| {:.4} /{units}, {}",
            r.job,
            r.summary.pieces,
            r.summary.total_inflections,
            r.summary.max_abs_curvature,
            if r.summary.cuttable_without_segmentation {
                "cuttable in one piece"
            } else {
                "needs segmentation"
            }
        ),
    );
    for (i, line) in reasons.iter().enumerate() {
        doc.text((MARGIN, 44.0 + 16.0 * i as f64), 12.0, "#c00000", line);
    }
    let extra = 16.0 * reasons.len().saturating_sub(1) as f64;
    // only what is drawn
    let mut legend = vec![Legend::new(Mark::Line, "#333333", "section")];
    if r.sections.iter().any(|x| !x.violations.is_empty()) {
        legend.push(Legend::new(
            Mark::Line,
            "#e07000",
            "section breaking a constraint",
        ));
    }
    legend.extend([
        Legend::new(Mark::Dot, "#e01010", "inflection"),
        Legend::new(Mark::Dot, "#1060e0", "curvature maximum"),
    ]);
    if block_outline(r).is_some() {
        legend.push(Legend::new(
            Mark::Dashed,
            "#c00000",
            "block, at the surface's corner",
        ));
    }
    doc.legend((MARGIN, 50.0 + extra), WIDTH - 2.0 * MARGIN, &legend);
}
