//! `fit.svg`, after fig. 15 of "Hot Blade Cuttings": every curve with its fit overlaid.

use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};

use super::report::FitCurvesReport;
use super::{FitCurves, FitRun};
use crate::output::Files;
use crate::spec::OutputSpec;
use crate::task::Finished;

const WIDTH: f64 = 1000.0;
const MARGIN: f64 = 40.0;

/// `fit.svg`.
pub(super) fn svg(
    done: &Finished<'_, FitCurves>,
    _: &OutputSpec,
    files: &mut Files,
) -> export::Result<()> {
    let units = done.job.units.symbol();
    files.add("fit.svg", |buf| {
        fit_svg(done.run, done.report, units).write(buf)
    })
}

/// Panels per row of `fit.svg`.
const FIT_COLUMNS: usize = 4;
/// Input points drawn per curve at most (every k-th point beyond that).
const FIT_DOTS: usize = 120;

/// The `fit.svg` drawing of a `FitCurves` run, after fig. 15 of "Hot Blade Cuttings": one
/// panel per curve with the input points (grey dots) and the fitted segment overlaid
/// (elastica blue, arc green, line purple; inflection points red), titled with the id,
/// family and RMS distance. Failed curves show their points and the error.
fn fit_svg(run: &FitRun, r: &FitCurvesReport, units: &str) -> SvgDoc {
    let n = run.curves.len();
    let cols = n.clamp(1, FIT_COLUMNS);
    let rows = n.div_ceil(cols).max(1);
    let inner = WIDTH - 2.0 * MARGIN;
    let cell_w = inner / cols as f64;
    let cell_h = cell_w * 0.75;
    let top = MARGIN + 66.0;
    let height = top + rows as f64 * cell_h + MARGIN;
    let mut doc = SvgDoc::new(WIDTH, height);
    fit_header(&mut doc, r, units);
    for (k, (c, e)) in run.curves.iter().zip(&r.curves).enumerate() {
        let (col, row) = (k % cols, k / cols);
        let (x0, y0) = (MARGIN + col as f64 * cell_w, top + row as f64 * cell_h);
        doc.rect(
            (x0 + 2.0, y0 + 2.0, cell_w - 4.0, cell_h - 4.0),
            "#ccc",
            "none",
        );
        let fitted: &[[f64; 2]] = e.fit.as_ref().map_or(&[], |f| &f.fitted);
        let numerical: &[[f64; 2]] = run
            .numerical
            .as_ref()
            .and_then(|n| n.get(k))
            .and_then(|n| n.as_ref().ok())
            .map_or(&[], |n| &n.samples);
        let (lo, hi) = bounds(
            c.points
                .iter()
                .chain(fitted)
                .chain(numerical)
                .map(|p| (p[0], p[1])),
        );
        let vp = Viewport::fit(lo, hi, (x0 + 10.0, y0 + 38.0, cell_w - 20.0, cell_h - 64.0));
        doc.scale_bar(&vp, (x0 + 10.0, y0 + cell_h - 10.0), cell_w - 20.0, units);
        // the panel's title on two lines, inside its frame
        let title = match &e.fit {
            Some(f) => format!("{}, RMS {:.2e} {units}", f.family, f.rms),
            None => "failed".to_string(),
        };
        doc.text((x0 + 8.0, y0 + 16.0), 10.0, "black", &e.id);
        doc.text((x0 + 8.0, y0 + 30.0), 9.0, "#444", &title);
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
                // as much of the error as fits the panel (the report has all of it)
                let fits = ((cell_w - 16.0) / (0.6 * 9.0)) as usize;
                let msg = e.error.as_deref().unwrap_or("");
                let shown: String = if msg.chars().count() > fits {
                    msg.chars()
                        .take(fits.saturating_sub(1))
                        .chain(std::iter::once('…'))
                        .collect()
                } else {
                    msg.to_string()
                };
                doc.text((x0 + 8.0, y0 + cell_h - 26.0), 9.0, "#c00000", &shown);
            }
        }
        // drawn last: it lies on the fit where the two agree
        if !numerical.is_empty() {
            let pts: Vec<(f64, f64)> = numerical.iter().map(|p| vp.map(p[0], p[1])).collect();
            doc.dashed_polyline(&pts, "#f08000", 1.2, 4.0, Some("numerical spline (eq. 13)"));
        }
    }
    doc
}

/// The title and legend lines of `fit.svg`.
fn fit_header(doc: &mut SvgDoc, r: &FitCurvesReport, units: &str) {
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
            "RMS median {:.3e}, max {:.3e} {units}",
            s.median_rms, s.max_rms
        ),
    );
    // only what is drawn
    let mut legend = vec![Legend::new(Mark::Dot, "#999999", "input points")];
    for (n, colour, label) in [
        (s.inflectional + s.noninflectional, "#1060e0", "elastica"),
        (s.arcs, "#10a040", "arc"),
        (s.lines, "#8030c0", "line"),
    ] {
        if n > 0 {
            legend.push(Legend::new(Mark::Line, colour, label));
        }
    }
    if s.inflectional > 0 {
        legend.push(Legend::new(Mark::Dot, "#e01010", "inflection"));
    }
    if r.numerical.is_some() {
        legend.push(Legend::new(
            Mark::Dashed,
            "#f08000",
            "numerical spline (eq. 13)",
        ));
    }
    doc.legend(
        (MARGIN, MARGIN + 22.0),
        WIDTH - 2.0 * MARGIN - 140.0,
        &legend,
    );
    doc.axes_key((WIDTH - MARGIN - 60.0, MARGIN + 56.0), "x", "y");
}
