//! The deviation chart of the drawings: how far a curve's points lie from the polyline
//! they are compared with, against arc length along the curve. One chart for every task
//! that draws one (a HotBlade section against its fit, a Design curve against its
//! elastica).

use export::svg::SvgDoc;
use geom::polyline::{chord_lengths, distance_to_polyline};

/// One line of a deviation chart.
pub struct DeviationLine<'a> {
    /// The points measured, in order along the curve.
    pub points: &'a [[f64; 2]],
    /// The polyline they are measured against.
    pub reference: &'a [[f64; 2]],
    /// The line's colour.
    pub colour: &'a str,
    /// The line's label (its SVG title).
    pub label: String,
}

/// Draws each line's distances against arc length in `frame` (`left, top, width,
/// height`): a title above it, `title(largest distance)`, and the axes labelled
/// `axes = (along, distance)`; the lines only when the curves have length and some
/// distance.
pub fn deviation_chart(
    doc: &mut SvgDoc,
    frame: (f64, f64, f64, f64),
    lines: &[DeviationLine<'_>],
    title: impl FnOnce(f64) -> String,
    axes: (&str, &str),
) {
    let (x0, y0, pw, ph) = frame;
    let measured: Vec<(Vec<f64>, Vec<f64>)> = lines
        .iter()
        .map(|l| {
            let dev = l
                .points
                .iter()
                .map(|p| distance_to_polyline(*p, l.reference))
                .collect();
            (chord_lengths(l.points), dev)
        })
        .collect();
    let len = measured
        .iter()
        .filter_map(|(s, _)| s.last().copied())
        .fold(0.0, f64::max);
    let top = measured
        .iter()
        .flat_map(|(_, d)| d.iter().copied())
        .fold(0.0, f64::max);
    doc.text((30.0, y0 - 24.0), 12.0, "black", &title(top));
    doc.chart_axes(frame, (0.0, len), (0.0, top), axes.0, axes.1);
    if !(len > 0.0 && top > 0.0) {
        return;
    }
    for (l, (s, dev)) in lines.iter().zip(&measured) {
        let pts: Vec<(f64, f64)> = s
            .iter()
            .zip(dev)
            .map(|(a, d)| (x0 + pw * a / len, y0 + ph - ph * d / top))
            .collect();
        doc.polyline(&pts, l.colour, 1.2, Some(&l.label));
    }
}
