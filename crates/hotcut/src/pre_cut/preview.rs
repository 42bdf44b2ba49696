//! `wire_dD_cC.svg`: one program drawn in the machine's plane (along → right, up → up,
//! millimetres): tower A's path (blue) and tower B's (red) over one another, the rapids
//! (light), the block's outline, the machine's travel and a scale bar.

use export::svg::{bounds, SvgDoc, Viewport};
use ruled::wire::{Machine, Program, WireParams, WirePath};

/// Page size of a preview.
const PAGE: (f64, f64) = (900.0, 560.0);
/// Margins: left/right, top (title), bottom (scale and legend).
const MARGIN: (f64, f64, f64) = (30.0, 50.0, 60.0);

/// A scale bar's length: 1, 2 or 5 × 10ᵏ mm, about a fifth of `span`.
fn scale_length(span: f64) -> f64 {
    let target = (span / 5.0).max(1e-9);
    let k = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * k)
        .find(|&l| l <= target)
        .unwrap_or(k)
}

/// Draws one program. `(floor, top)` are the block's floor and top (job units).
pub(super) fn preview(
    path: &WirePath,
    program: &Program,
    p: &WireParams,
    m: &Machine,
    (floor, top): (f64, f64),
    title: &str,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let mm = p.mm_per_unit;
    let safe = (p.origin[1] + top - floor + p.clearance) * mm;
    let (first, last) = (path.steps[0], path.steps[path.steps.len() - 1]);
    let cut_a: Vec<(f64, f64)> = path.steps.iter().map(|s| (s.a[0], s.a[1])).collect();
    let cut_b: Vec<(f64, f64)> = path.steps.iter().map(|s| (s.b[0], s.b[1])).collect();
    // the rapids down to the lead-in and up from the lead-out
    let rapid = |q: [f64; 2]| vec![(q[0], safe), (q[0], q[1])];
    let (rapid_a0, rapid_b0) = (rapid(first.a), rapid(first.b));
    let (rapid_a1, rapid_b1) = (rapid(last.a), rapid(last.b));
    let block = [
        p.origin[0] * mm,
        p.origin[1] * mm,
        (p.origin[0] + path.u.1 - path.u.0) * mm,
        (p.origin[1] + top - floor) * mm,
    ];
    let block_pts = [
        (block[0], block[1]),
        (block[2], block[1]),
        (block[2], block[3]),
        (block[0], block[3]),
    ];
    let travel_pts: Vec<(f64, f64)> = m
        .travel
        .iter()
        .flat_map(|t| {
            [
                (t[0].0, t[1].0),
                (t[0].1, t[1].1),
                (t[2].0, t[3].0),
                (t[2].1, t[3].1),
            ]
        })
        .collect();
    let (lo, hi) = bounds(
        cut_a
            .iter()
            .chain(&cut_b)
            .chain(&rapid_a0)
            .chain(&rapid_b0)
            .chain(&rapid_a1)
            .chain(&rapid_b1)
            .chain(&block_pts)
            .chain(&travel_pts)
            .copied(),
    );
    let pad = 0.03 * (hi.0 - lo.0).max(hi.1 - lo.1);
    let vp = Viewport::fit(
        (lo.0 - pad, lo.1 - pad),
        (hi.0 + pad, hi.1 + pad),
        (
            MARGIN.0,
            MARGIN.1,
            PAGE.0 - 2.0 * MARGIN.0,
            PAGE.1 - MARGIN.1 - MARGIN.2,
        ),
    );
    let map = |pts: &[(f64, f64)]| pts.iter().map(|&(x, y)| vp.map(x, y)).collect::<Vec<_>>();
    let mut doc = SvgDoc::new(PAGE.0, PAGE.1);
    let [a0, a1, b0, b1] = m.axes;
    doc.text((MARGIN.0, 20.0), 13.0, "#000", title);
    doc.text(
        (MARGIN.0, 38.0),
        11.0,
        "#333",
        &format!(
            "{}: tower A {a0}/{a1} (blue), tower B {b0}/{b1} (red), rapids (light), block (black), travel (grey); along → right, up ↑, mm",
            m.profile
        ),
    );
    if let Some(t) = &m.travel {
        // once when both towers travel alike
        let boxes = if (t[0], t[1]) == (t[2], t[3]) { 1 } else { 2 };
        for (x, y) in [(t[0], t[1]), (t[2], t[3])].into_iter().take(boxes) {
            let rect = [(x.0, y.0), (x.1, y.0), (x.1, y.1), (x.0, y.1)];
            doc.polygon(&map(&rect), "none", "#9a9a9a", 1.0, Some("machine travel"));
        }
    }
    doc.polygon(&map(&block_pts), "#f4f0e6", "#000", 1.0, Some("block"));
    doc.text(
        (MARGIN.0, PAGE.1 - 10.0),
        10.0,
        "#555",
        "the paths are the wire's ends at the tower planes: the wire extended beyond the block",
    );
    for (pts, colour, name) in [
        (&rapid_a0, "#9db8e8", "tower A rapid"),
        (&rapid_a1, "#9db8e8", "tower A rapid"),
        (&rapid_b0, "#eba3a3", "tower B rapid"),
        (&rapid_b1, "#eba3a3", "tower B rapid"),
        (&cut_a, "#1f5fd0", "tower A cut"),
        (&cut_b, "#d02424", "tower B cut"),
    ] {
        doc.polyline(&map(pts), colour, 1.4, Some(name));
    }
    doc.circle(
        vp.map(first.a[0], first.a[1]),
        3.0,
        "#1f5fd0",
        Some("tower A lead-in: heat on"),
    );
    doc.circle(
        vp.map(first.b[0], first.b[1]),
        3.0,
        "#d02424",
        Some("tower B lead-in: heat on"),
    );
    scale_and_times(&mut doc, &vp, hi.0 - lo.0, &program.summary);
    doc.write(buf)
}

/// The scale bar under the drawing, and the program's moves and times.
fn scale_and_times(doc: &mut SvgDoc, vp: &Viewport, span: f64, s: &ruled::wire::ProgramSummary) {
    let len = scale_length(span);
    let y = PAGE.1 - 30.0;
    let (x0, x1) = (MARGIN.0, MARGIN.0 + len * vp.scale());
    doc.polyline(
        &[(x0, y - 5.0), (x0, y), (x1, y), (x1, y - 5.0)],
        "#000",
        1.2,
        Some("scale"),
    );
    doc.text((x1 + 8.0, y + 4.0), 11.0, "#000", &format!("{len} mm"));
    doc.text(
        (x1 + 90.0, y + 4.0),
        11.0,
        "#333",
        &format!(
            "{} cutting moves, {:.1} mm, {:.2} min at the set speed + {} s preheat",
            s.cutting_moves, s.cut_length_mm, s.cut_minutes, s.preheat_s
        ),
    );
}

#[cfg(test)]
mod tests {
    use super::scale_length;

    #[test]
    fn scale_bars_are_round_numbers() {
        assert_eq!(scale_length(1000.0), 200.0);
        assert_eq!(scale_length(2600.0), 500.0);
        assert_eq!(scale_length(40.0), 5.0);
        assert_eq!(scale_length(0.9), 0.1);
    }
}
