//! `block_<id>.svg` of a `Design` run: the cut's piece in its block at every station
//! (design curve, control polygon, elastica, blade extension, block outline) with a legend,
//! the axes and a scale bar; below, the distance from each station's design curve to its
//! elastica against arc length, so a fraction of a millimetre can be read.

use crate::output::chart::{deviation_chart, DeviationLine};
use design::cut::CutResult;
use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};

use design::assembly::{Block, ResolvedCut};

/// A station's design curve and its elastica, sampled alike.
type DesignAndElastica = (Vec<[f64; 2]>, Vec<[f64; 2]>);

const STATION_COLOURS: [&str; 4] = ["#000000", "#1f5fbf", "#2a8a2a", "#8a4a00"];

/// The drawing of piece `piece` of cut `r` (result `res`) in block `b`, `n` points per
/// curve.
pub(super) fn block_svg(
    b: &Block,
    r: &ResolvedCut,
    res: &CutResult,
    piece: usize,
    n: usize,
    job: &str,
    units: &str,
) -> SvgDoc {
    const W: f64 = 900.0;
    const H: f64 = 860.0;
    let mut doc = SvgDoc::new(W, H);
    let (lo, hi) = (r.faces[piece], r.faces[piece + 1]);
    let outline = [
        [lo, b.min.z],
        [hi, b.min.z],
        [hi, b.max.z],
        [lo, b.max.z],
        [lo, b.min.z],
    ];
    let curves: Vec<_> = res.stations.iter().map(|c| c.sampled(piece, n)).collect();
    let polygons: Vec<[[f64; 2]; 4]> = res
        .stations
        .iter()
        .map(|c| c.pieces[piece].design.p)
        .collect();
    let blades: Vec<Vec<[f64; 2]>> = res
        .stations
        .iter()
        .map(|c| {
            c.pieces[piece]
                .blade
                .segment
                .sample(200)
                .unwrap_or_default()
        })
        .collect();
    // the viewport holds everything drawn, the blade's extension included
    let (wlo, whi) = bounds(
        outline
            .iter()
            .chain(curves.iter().flat_map(|(d, e)| d.iter().chain(e)))
            .chain(polygons.iter().flatten())
            .chain(blades.iter().flatten())
            .map(|p| (p[0], p[1])),
    );
    let vp = Viewport::fit(wlo, whi, (40.0, 104.0, W - 80.0, 400.0));
    let map = |pts: &[[f64; 2]]| pts.iter().map(|p| vp.map(p[0], p[1])).collect::<Vec<_>>();
    block_header(&mut doc, (job, b), r, res, piece, units);
    doc.dashed_polyline(&map(&outline), "#888888", 1.0, 5.0, Some("block outline"));
    for (i, ((c, (design, elastica)), blade)) in
        res.stations.iter().zip(&curves).zip(&blades).enumerate()
    {
        let p = &c.pieces[piece];
        doc.polyline(
            &map(blade),
            "#cccccc",
            1.0,
            Some("blade extended to its length"),
        );
        doc.polyline(&map(&p.design.p), "#999999", 0.6, Some("control polygon"));
        for q in &p.design.p {
            doc.circle(vp.map(q[0], q[1]), 2.5, "#999999", Some("control point"));
        }
        let colour = STATION_COLOURS[i % STATION_COLOURS.len()];
        doc.polyline(
            &map(design),
            colour,
            2.2,
            Some(&format!("design curve, station {i}")),
        );
        doc.dashed_polyline(
            &map(elastica),
            "#e01010",
            1.4,
            6.0,
            Some(&format!("elastica, station {i}")),
        );
    }
    doc.scale_bar(&vp, (40.0, 540.0), W - 80.0, units);
    doc.text(
        (40.0, 560.0),
        11.0,
        "#444",
        &format!("faces at {lo:.1} and {hi:.1} {units} across the cut"),
    );
    doc.axes_key((W - 130.0, 556.0), "across the cut", "z");
    deviation_panel(&mut doc, &curves, (90.0, 640.0, W - 130.0, 170.0), units);
    doc
}

/// The distance from each station's design curve to its elastica against arc length along
/// the design, one line per station in its colour, in the frame `(left, top, w, h)`.
fn deviation_panel(
    doc: &mut SvgDoc,
    curves: &[DesignAndElastica],
    frame: (f64, f64, f64, f64),
    units: &str,
) {
    let lines: Vec<DeviationLine<'_>> = curves
        .iter()
        .enumerate()
        .map(|(i, (design, elastica))| DeviationLine {
            points: design,
            reference: elastica,
            colour: STATION_COLOURS[i % STATION_COLOURS.len()],
            label: format!("station {i}"),
        })
        .collect();
    let title = |top: f64| {
        format!(
            "design vs elastica along the curve: largest {} {units}",
            if top >= 0.01 {
                format!("{top:.3}")
            } else {
                format!("{top:.3e}")
            }
        )
    };
    deviation_chart(
        doc,
        frame,
        &lines,
        title,
        (
            &format!("arc length along the design curve ({units})"),
            &format!("distance from the design curve to its elastica ({units})"),
        ),
    );
}

/// The title and legend lines of a design block's drawing.
fn block_header(
    doc: &mut SvgDoc,
    (job, b): (&str, &Block),
    r: &ResolvedCut,
    res: &CutResult,
    piece: usize,
    units: &str,
) {
    let worst = res
        .stations
        .iter()
        .map(|c| &c.pieces[piece].proxy)
        .fold((0.0f64, 0.0f64), |(d, e), p| {
            (d.max(p.max_deviation), e.max(p.eq11_residual))
        });
    doc.text(
        (30.0, 28.0),
        16.0,
        "black",
        &format!(
            "{job} · block {} — cut `{}` through {} block(s), piece {} of {}",
            b.id,
            r.id,
            r.blocks.len(),
            piece + 1,
            r.blocks.len()
        ),
    );
    doc.text(
        (30.0, 50.0),
        12.0,
        "#444",
        &format!(
            "design vs elastica: max {:.4} {units} ({:.3} % of the length) · eq. (11) residual ≤ {:.3} · {} station(s), entry black",
            worst.0,
            100.0 * worst.0 / res.stations[0].pieces[piece].proxy.length.max(f64::MIN_POSITIVE),
            worst.1,
            res.stations.len()
        ),
    );
    let stations: Vec<String> = (0..res.stations.len().min(STATION_COLOURS.len()))
        .map(|i| {
            if i == 0 {
                "design, station 0 (entry)".to_string()
            } else {
                format!("station {i}")
            }
        })
        .collect();
    let mut legend: Vec<Legend<'_>> = stations
        .iter()
        .enumerate()
        .map(|(i, label)| Legend::new(Mark::Line, STATION_COLOURS[i], label))
        .collect();
    legend.extend([
        Legend::new(Mark::Dashed, "#e01010", "elastica"),
        Legend::new(Mark::Line, "#999999", "control polygon"),
        Legend::new(Mark::Line, "#cccccc", "blade extension"),
        Legend::new(Mark::Dashed, "#888888", "block outline"),
    ]);
    doc.legend((30.0, 58.0), 840.0, &legend);
}
