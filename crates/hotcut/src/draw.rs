//! The `sections.svg` drawing of an `Analyze` run, after thesis fig. 5.13: a plan view
//! (looking down −z) of the sections with inflection points in red and curvature maxima in
//! blue, and below it the section profiles in their planes' `(u, v)` coordinates, overlaid.
//! Sections that break a constraint are drawn in orange and thicker. The `fit.svg`
//! drawing of a `FitCurves` run ([`fit_svg`](crate::draw::fit_svg)) overlays every curve and its fit.

use export::svg::{SvgDoc, Viewport};

use crate::analyze::{sample_world, Analysis};
use geom::planar::PlanarCurve;

const WIDTH: f64 = 1000.0;
const MARGIN: f64 = 40.0;
const SAMPLES: usize = 200;

pub(crate) fn bounds(pts: impl Iterator<Item = (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    pts.fold(
        (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |((x0, y0), (x1, y1)), (x, y)| ((x0.min(x), y0.min(y)), (x1.max(x), y1.max(y))),
    )
}

/// Draws the analysis.
pub fn sections_svg(a: &Analysis, units: &str) -> SvgDoc {
    let plan: Vec<Vec<(f64, f64)>> = a
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
    let (pmin, pmax) = bounds(plan.iter().flatten().copied());
    let (qmin, qmax) = bounds(profiles.iter().flatten().copied());
    let inner = WIDTH - 2.0 * MARGIN;
    let plan_h = (inner * (pmax.1 - pmin.1) / (pmax.0 - pmin.0).max(1e-9)).clamp(150.0, 700.0);
    let prof_h = (inner * (qmax.1 - qmin.1) / (qmax.0 - qmin.0).max(1e-9)).clamp(120.0, 400.0);
    let height = MARGIN * 4.0 + plan_h + prof_h + 30.0;
    let mut doc = SvgDoc::new(WIDTH, height);
    let r = &a.report;
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
    doc.text(
        (MARGIN, MARGIN + 12.0),
        12.0,
        "#444",
        "plan (x right, y up): inflections red, curvature maxima blue, offending sections orange",
    );
    let plan_page = (MARGIN, MARGIN + 20.0, inner, plan_h);
    doc.rect(plan_page, "#ccc", "none");
    let vp = Viewport::fit(pmin, pmax, plan_page);
    let prof_top = MARGIN * 2.0 + 20.0 + plan_h + 20.0;
    doc.text(
        (MARGIN, prof_top - 8.0),
        12.0,
        "#444",
        &format!("section profiles in (u, v), overlaid ({units})"),
    );
    let prof_page = (MARGIN, prof_top, inner, prof_h);
    doc.rect(prof_page, "#ccc", "none");
    let vq = Viewport::fit(qmin, qmax, prof_page);

    for (k, ((s, an), rep)) in a.sections.iter().zip(&r.sections).enumerate() {
        let bad = !rep.violations.is_empty();
        let (stroke, w) = if bad { ("#e07000", 1.6) } else { ("#333", 0.8) };
        let title = format!(
            "section {} piece {}: length {:.1}, {} inflections",
            s.index,
            s.piece,
            rep.length,
            rep.inflections.len()
        );
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

/// Panels per row of `fit.svg`.
const FIT_COLUMNS: usize = 4;
/// Input points drawn per curve at most (every k-th point beyond that).
const FIT_DOTS: usize = 120;

/// The `fit.svg` drawing of a `FitCurves` run, after fig. 15 of "Hot Blade Cuttings": one
/// panel per curve with the input points (grey dots) and the fitted segment overlaid
/// (elastica blue, arc green, line purple; inflection points red), titled with the id,
/// family and RMS distance. Failed curves show their points and the error.
pub fn fit_svg(run: &crate::fit_curves::FitRun, units: &str) -> SvgDoc {
    let r = &run.report;
    let n = run.curves.len();
    let cols = n.clamp(1, FIT_COLUMNS);
    let rows = n.div_ceil(cols).max(1);
    let inner = WIDTH - 2.0 * MARGIN;
    let cell_w = inner / cols as f64;
    let cell_h = cell_w * 0.75;
    let top = MARGIN + 30.0;
    let height = top + rows as f64 * cell_h + MARGIN;
    let mut doc = SvgDoc::new(WIDTH, height);
    let s = &r.summary;
    doc.text(
        (MARGIN, 24.0),
        16.0,
        "black",
        &format!(
            "{} — {} curves, {:?}: {} elastica, {} arc(s), {} line(s), {} failed",
            r.job,
            s.curves,
            r.constraint,
            s.inflectional + s.noninflectional,
            s.arcs,
            s.lines,
            s.failed,
        ),
    );
    doc.text(
        (MARGIN, MARGIN + 14.0),
        12.0,
        "#444",
        &format!(
            "RMS median {:.3e}, max {:.3e} {units} · input points grey; fit: elastica blue, arc green, line purple; inflections red",
            s.median_rms, s.max_rms
        ),
    );
    for (k, (c, e)) in run.curves.iter().zip(&r.curves).enumerate() {
        let (col, row) = (k % cols, k / cols);
        let (x0, y0) = (MARGIN + col as f64 * cell_w, top + row as f64 * cell_h);
        doc.rect(
            (x0 + 2.0, y0 + 2.0, cell_w - 4.0, cell_h - 4.0),
            "#ccc",
            "none",
        );
        let fitted: &[[f64; 2]] = e.fit.as_ref().map_or(&[], |f| &f.fitted);
        let (lo, hi) = bounds(c.points.iter().chain(fitted).map(|p| (p[0], p[1])));
        let vp = Viewport::fit(lo, hi, (x0 + 10.0, y0 + 24.0, cell_w - 20.0, cell_h - 34.0));
        let title = match &e.fit {
            Some(f) => format!("{}: {}, RMS {:.2e}", e.id, f.family, f.rms),
            None => format!("{}: failed", e.id),
        };
        doc.text((x0 + 8.0, y0 + 16.0), 10.0, "black", &title);
        let step = c.points.len().div_ceil(FIT_DOTS).max(1);
        for p in c.points.iter().step_by(step) {
            doc.circle(vp.map(p[0], p[1]), 1.4, "#999", None);
        }
        match &e.fit {
            Some(f) => {
                let colour = match f.family.as_str() {
                    "arc" => "#10a040",
                    "line" => "#8030c0",
                    _ => "#1060e0",
                };
                let detail = format!(
                    "{}: {} · RMS {:.3e}, max {:.3e} {units} · length {:.4} {units} · max |κ| {:.4e} /{units}",
                    e.id, f.family, f.rms, f.max, f.length, f.max_abs_curvature
                );
                let pts: Vec<(f64, f64)> = f.fitted.iter().map(|p| vp.map(p[0], p[1])).collect();
                doc.polyline(&pts, colour, 1.2, Some(&detail));
                for p in &f.inflection_points {
                    doc.circle(vp.map(p[0], p[1]), 2.4, "#e01010", None);
                }
            }
            None => {
                let msg = e.error.as_deref().unwrap_or("");
                doc.text((x0 + 8.0, y0 + cell_h - 10.0), 9.0, "#c00000", msg);
            }
        }
    }
    doc
}
