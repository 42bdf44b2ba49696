//! `wire_dD_cC.svg`: one program drawn in the machine's plane (along → right, up → up,
//! millimetres): tower A's path (blue) and tower B's (red) over one another, the rapids
//! (light), the block's outline, the machine's travel, a legend, the axes and a scale bar
//! (`export::svg::nice_length`, tested there).

use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};
use ruled::wire::{Machine, Program, WireParams, WirePath};

/// Page size of a preview.
const PAGE: (f64, f64) = (900.0, 560.0);
/// Margins: left/right, top (title and legend), bottom (scale, times, axes).
const MARGIN: (f64, f64, f64) = (30.0, 72.0, 70.0);

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
    header(&mut doc, m, title);
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
    let y = PAGE.1 - 34.0;
    doc.scale_bar(&vp, (MARGIN.0, y), PAGE.0 - 2.0 * MARGIN.0, "mm");
    let s = &program.summary;
    doc.text(
        (MARGIN.0 + 260.0, y),
        11.0,
        "#333",
        &format!(
            "{} cutting moves, {:.1} mm, {:.2} min at the set speed + {} s preheat",
            s.cutting_moves, s.cut_length_mm, s.cut_minutes, s.preheat_s
        ),
    );
    doc.write(buf)
}

/// The title, legend and axes of a preview.
fn header(doc: &mut SvgDoc, m: &Machine, title: &str) {
    let [a0, a1, b0, b1] = m.axes;
    doc.text(
        (MARGIN.0, 20.0),
        13.0,
        "#000",
        &format!("{title} · {}, mm", m.profile),
    );
    let (tower_a, tower_b) = (
        format!("tower A {a0}/{a1} cut"),
        format!("tower B {b0}/{b1} cut"),
    );
    doc.legend(
        (MARGIN.0, 28.0),
        PAGE.0 - 2.0 * MARGIN.0,
        &[
            Legend::new(Mark::Line, "#1f5fd0", &tower_a),
            Legend::new(Mark::Line, "#d02424", &tower_b),
            Legend::new(Mark::Line, "#9db8e8", "tower A rapid"),
            Legend::new(Mark::Line, "#eba3a3", "tower B rapid"),
            Legend::new(Mark::Dot, "#1f5fd0", "lead-in: heat on"),
            Legend::new(Mark::Swatch, "#f4f0e6", "block"),
            Legend::new(Mark::Line, "#9a9a9a", "machine travel"),
        ],
    );
    doc.axes_key(
        (PAGE.0 - MARGIN.0 - 110.0, PAGE.1 - 16.0),
        &format!("along ({a0}, {b0})"),
        &format!("up ({a1}, {b1})"),
    );
}
