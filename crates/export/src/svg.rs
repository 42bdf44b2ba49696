//! A small SVG builder: a page of fixed size, a [`Viewport`](crate::svg::Viewport) that maps a world rectangle
//! into a page rectangle (y up), and elements with coordinates printed to two decimals.
//!
//! Entry points: [`SvgDoc`](crate::svg::SvgDoc), [`Viewport`](crate::svg::Viewport).

use std::io::Write;

use crate::{fmt_float, Result};

const DECIMALS: usize = 2;

/// The bounding rectangle `(min, max)` of points (infinite bounds for none).
pub fn bounds(pts: impl Iterator<Item = (f64, f64)>) -> ((f64, f64), (f64, f64)) {
    pts.fold(
        (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |((x0, y0), (x1, y1)), (x, y)| ((x0.min(x), y0.min(y)), (x1.max(x), y1.max(y))),
    )
}

/// A "nice" length (1, 2 or 5 × 10ᵏ) no longer than `at_most` (> 0), for scale bars.
pub fn nice_length(at_most: f64) -> f64 {
    if !(at_most > 0.0) || !at_most.is_finite() {
        return 0.0;
    }
    let p = 10f64.powf(at_most.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&l| l <= at_most)
        .unwrap_or(p)
}

/// Tick values between `lo` and `hi` at a nice step (about four ticks), each with its
/// place along the axis in `[0, 1]`; none for an empty or non-finite range.
pub fn ticks(lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let span = hi - lo;
    if !(span > 0.0) || !span.is_finite() {
        return Vec::new();
    }
    let step = nice_length(span / 3.0);
    if !(step > 0.0) {
        return Vec::new();
    }
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last.min(first + 20))
        .map(|k| {
            let v = k as f64 * step;
            // -0 and float dust print as 0
            let v = if v.abs() < 1e-9 * step { 0.0 } else { v };
            (v, (v - lo) / span)
        })
        .collect()
}

/// A tick's value printed with as many decimals as the step between `ticks` needs, or in
/// scientific notation for steps below 10⁻³ or from 10⁶.
pub fn tick_label(v: f64, ticks: &[(f64, f64)]) -> String {
    let step = match ticks {
        [a, b, ..] => (b.0 - a.0).abs(),
        _ => v.abs(),
    };
    if v == 0.0 {
        return "0".into();
    }
    if (1e-3..1e6).contains(&step) {
        let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.1e}")
    }
}

/// How a [`Legend`] entry is marked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A solid line.
    Line,
    /// A dashed line.
    Dashed,
    /// A dot.
    Dot,
    /// A filled box.
    Swatch,
}

/// One entry of a legend: its mark, colour and label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Legend<'a> {
    /// How it is marked.
    pub mark: Mark,
    /// The mark's colour.
    pub colour: &'a str,
    /// What it means.
    pub label: &'a str,
}

impl<'a> Legend<'a> {
    /// An entry.
    pub const fn new(mark: Mark, colour: &'a str, label: &'a str) -> Self {
        Self {
            mark,
            colour,
            label,
        }
    }
}

/// Maps world coordinates `(x, y)` (y up) into a page rectangle, preserving aspect ratio.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewport {
    scale: f64,
    ox: f64,
    oy: f64,
}

impl Viewport {
    /// Fits the world rectangle `(min, max)` centred into the page rectangle
    /// `(left, top, width, height)`.
    pub fn fit(world_min: (f64, f64), world_max: (f64, f64), page: (f64, f64, f64, f64)) -> Self {
        let (l, t, w, h) = page;
        let ww = (world_max.0 - world_min.0).max(1e-12);
        let wh = (world_max.1 - world_min.1).max(1e-12);
        let scale = (w / ww).min(h / wh);
        let ox = l + 0.5 * (w - scale * ww) - scale * world_min.0;
        let oy = t + 0.5 * (h + scale * wh) + scale * world_min.1;
        Self { scale, ox, oy }
    }

    /// Page coordinates of a world point.
    pub fn map(&self, x: f64, y: f64) -> (f64, f64) {
        (self.ox + self.scale * x, self.oy - self.scale * y)
    }

    /// Page length of a world length.
    pub fn scale(&self) -> f64 {
        self.scale
    }
}

/// An SVG document under construction.
#[derive(Debug, Clone)]
pub struct SvgDoc {
    width: f64,
    height: f64,
    body: String,
}

fn esc(s: &str) -> String {
    geom::text::xml(s)
}

fn n(x: f64) -> String {
    fmt_float(x, DECIMALS)
}

/// The `points` attribute of a polyline or polygon.
fn points(pts: &[(f64, f64)]) -> String {
    let p: Vec<String> = pts
        .iter()
        .map(|(x, y)| format!("{},{}", n(*x), n(*y)))
        .collect();
    p.join(" ")
}

impl SvgDoc {
    /// A white page of `width × height` user units.
    pub fn new(width: f64, height: f64) -> Self {
        let mut d = Self {
            width,
            height,
            body: String::new(),
        };
        d.body.push_str(&format!(
            "<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"white\"/>\n",
            n(width),
            n(height)
        ));
        d
    }

    /// Ends an open element `tag`, with an optional tooltip.
    fn close(&mut self, tag: &str, title: Option<&str>) -> &mut Self {
        if let Some(t) = title {
            self.body.push_str(&format!("<title>{}</title>", esc(t)));
        }
        self.body.push_str(&format!("</{tag}>\n"));
        self
    }

    /// A polyline through page points.
    pub fn polyline(
        &mut self,
        pts: &[(f64, f64)],
        stroke: &str,
        width: f64,
        title: Option<&str>,
    ) -> &mut Self {
        if pts.len() < 2 {
            return self;
        }
        self.body.push_str(&format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\">",
            points(pts),
            esc(stroke),
            n(width)
        ));
        self.close("polyline", title)
    }

    /// A dashed polyline through page points: dashes and gaps of `dash` page units.
    pub fn dashed_polyline(
        &mut self,
        pts: &[(f64, f64)],
        stroke: &str,
        width: f64,
        dash: f64,
        title: Option<&str>,
    ) -> &mut Self {
        if pts.len() < 2 {
            return self;
        }
        self.body.push_str(&format!(
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\" stroke-linejoin=\"round\">",
            points(pts),
            esc(stroke),
            n(width),
            n(dash),
            n(dash)
        ));
        self.close("polyline", title)
    }

    /// A closed polygon through page points, filled with `fill` (e.g. `#ff000080`) and
    /// outlined with `stroke` (`none` for no outline).
    pub fn polygon(
        &mut self,
        pts: &[(f64, f64)],
        fill: &str,
        stroke: &str,
        width: f64,
        title: Option<&str>,
    ) -> &mut Self {
        if pts.len() < 3 {
            return self;
        }
        self.body.push_str(&format!(
            "<polygon points=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\">",
            points(pts),
            esc(fill),
            esc(stroke),
            n(width)
        ));
        self.close("polygon", title)
    }

    /// A filled circle at a page point.
    pub fn circle(
        &mut self,
        (x, y): (f64, f64),
        r: f64,
        fill: &str,
        title: Option<&str>,
    ) -> &mut Self {
        self.body.push_str(&format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\">",
            n(x),
            n(y),
            n(r),
            esc(fill)
        ));
        self.close("circle", title)
    }

    /// A rectangle outline (page coordinates).
    pub fn rect(
        &mut self,
        (x, y, w, h): (f64, f64, f64, f64),
        stroke: &str,
        fill: &str,
    ) -> &mut Self {
        self.body.push_str(&format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"0.5\"/>\n",
            n(x),
            n(y),
            n(w),
            n(h),
            esc(fill),
            esc(stroke)
        ));
        self
    }

    /// Text with its baseline start at a page point.
    pub fn text(&mut self, (x, y): (f64, f64), size: f64, fill: &str, text: &str) -> &mut Self {
        self.body.push_str(&format!(
            "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"{}\" fill=\"{}\">{}</text>\n",
            n(x),
            n(y),
            n(size),
            esc(fill),
            esc(text)
        ));
        self
    }

    /// A scale bar under a drawing of viewport `vp`: a bar of a "nice" world length about a
    /// fifth of `max_width` page units, its left end at page point `at` (the bar's
    /// baseline), labelled with the length and `units` to its right. Grouped as
    /// `<g class="scale-bar">`.
    pub fn scale_bar(
        &mut self,
        vp: &Viewport,
        at: (f64, f64),
        max_width: f64,
        units: &str,
    ) -> &mut Self {
        let len = nice_length(max_width / 5.0 / vp.scale().max(1e-300));
        let w = len * vp.scale();
        if !(w > 0.0) {
            return self;
        }
        let (x, y) = at;
        self.body.push_str("<g class=\"scale-bar\">\n");
        self.polyline(
            &[(x, y - 4.0), (x, y), (x + w, y), (x + w, y - 4.0)],
            "black",
            1.0,
            None,
        );
        let label = format!("{} {units}", crate::fmt_float(len, 6));
        self.text((x + w + 6.0, y), 10.0, "black", &label);
        self.body.push_str("</g>\n");
        self
    }

    /// The drawing's world axes: from page point `at`, an arrow to the right labelled
    /// `right` and one up labelled `up` (e.g. `x` and `y` in plan, `y` and `z` in a
    /// section). Grouped as `<g class="axes">`; takes about 40 × 44 page units above and
    /// right of `at`.
    pub fn axes_key(&mut self, at: (f64, f64), right: &str, up: &str) -> &mut Self {
        let (x, y) = at;
        let l = 24.0;
        self.body.push_str("<g class=\"axes\">\n");
        self.polyline(&[(x, y), (x + l, y)], "#333333", 1.0, None);
        self.polygon(
            &[(x + l + 5.0, y), (x + l, y - 2.5), (x + l, y + 2.5)],
            "#333333",
            "none",
            0.0,
            None,
        );
        self.polyline(&[(x, y), (x, y - l)], "#333333", 1.0, None);
        self.polygon(
            &[(x, y - l - 5.0), (x - 2.5, y - l), (x + 2.5, y - l)],
            "#333333",
            "none",
            0.0,
            None,
        );
        self.text((x + l + 8.0, y + 4.0), 10.0, "#333333", right);
        self.text((x - 3.0, y - l - 9.0), 10.0, "#333333", up);
        self.body.push_str("</g>\n");
        self
    }

    /// A legend: `entries` in rows from page point `at` (the top left), wrapped before
    /// `max_width`; each is its mark and its label (10 units high). Grouped as
    /// `<g class="legend">`. Returns the height used.
    pub fn legend(&mut self, at: (f64, f64), max_width: f64, entries: &[Legend<'_>]) -> f64 {
        let (x0, y0) = at;
        let row = 14.0;
        let (mut x, mut y) = (x0, y0 + 10.0);
        self.body.push_str("<g class=\"legend\">\n");
        for e in entries {
            let w = 20.0 + 6.0 * e.label.chars().count() as f64 + 14.0;
            if x > x0 && x + w > x0 + max_width {
                x = x0;
                y += row;
            }
            let mid = y - 3.5;
            match e.mark {
                Mark::Line => {
                    self.polyline(&[(x, mid), (x + 14.0, mid)], e.colour, 2.0, None);
                }
                Mark::Dashed => {
                    self.dashed_polyline(&[(x, mid), (x + 14.0, mid)], e.colour, 1.5, 3.0, None);
                }
                Mark::Dot => {
                    self.circle((x + 7.0, mid), 3.0, e.colour, None);
                }
                Mark::Swatch => {
                    let r = [
                        (x, mid - 4.0),
                        (x + 14.0, mid - 4.0),
                        (x + 14.0, mid + 4.0),
                        (x, mid + 4.0),
                    ];
                    self.polygon(&r, e.colour, "#666666", 0.5, None);
                }
            }
            self.text((x + 18.0, y), 10.0, "#222222", e.label);
            x += w;
        }
        self.body.push_str("</g>\n");
        y - y0 + 4.0
    }

    /// A chart's frame `(left, top, width, height)` with ticks and values on both axes:
    /// `x` and `y` are the world values at the left/right and bottom/top edges; the axis
    /// titles go under the x values (right-aligned) and above the frame (left-aligned).
    /// Grouped as `<g class="chart-axes">`.
    pub fn chart_axes(
        &mut self,
        frame: (f64, f64, f64, f64),
        x: (f64, f64),
        y: (f64, f64),
        x_title: &str,
        y_title: &str,
    ) -> &mut Self {
        let (l, t, w, h) = frame;
        self.body.push_str("<g class=\"chart-axes\">\n");
        self.rect(frame, "#999999", "none");
        let xt = ticks(x.0, x.1);
        for &(v, along) in &xt {
            let px = l + along * w;
            self.polyline(&[(px, t + h), (px, t + h + 4.0)], "#666666", 1.0, None);
            let label = tick_label(v, &xt);
            let half = 3.0 * label.chars().count() as f64;
            self.text((px - half, t + h + 14.0), 9.0, "#444444", &label);
        }
        let yt = ticks(y.0, y.1);
        for &(v, along) in &yt {
            let py = t + h - along * h;
            self.polyline(&[(l - 4.0, py), (l, py)], "#666666", 1.0, None);
            let label = tick_label(v, &yt);
            let width = 5.4 * label.chars().count() as f64;
            self.text((l - 6.0 - width, py + 3.0), 9.0, "#444444", &label);
        }
        let xw = 6.0 * x_title.chars().count() as f64;
        self.text((l + w - xw, t + h + 27.0), 10.0, "#222222", x_title);
        self.text((l, t - 5.0), 10.0, "#222222", y_title);
        self.body.push_str("</g>\n");
        self
    }

    /// Writes the document.
    ///
    /// # Errors
    /// I/O failures.
    pub fn write(&self, mut w: impl Write) -> Result<()> {
        write!(
            w,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">\n{}</svg>\n",
            n(self.width),
            n(self.height),
            n(self.width),
            n(self.height),
            self.body
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viewport_maps_y_up_and_keeps_aspect() {
        let v = Viewport::fit((0.0, 0.0), (10.0, 5.0), (0.0, 0.0, 100.0, 100.0));
        assert_eq!(v.map(0.0, 0.0), (0.0, 75.0));
        assert_eq!(v.map(10.0, 5.0), (100.0, 25.0));
    }

    #[test]
    fn ticks_are_round_and_inside() {
        let t = ticks(0.0, 10.0);
        assert_eq!(
            t.iter().map(|p| p.0).collect::<Vec<_>>(),
            vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]
        );
        assert!(t.iter().all(|p| (0.0..=1.0).contains(&p.1)));
        let t = ticks(-0.013, 0.021);
        assert!(t.iter().any(|p| p.0 == 0.0));
        assert!(ticks(1.0, 1.0).is_empty());
        assert!(ticks(0.0, f64::NAN).is_empty());
        assert!(ticks(0.0, 1e300).len() <= 21);
    }

    #[test]
    fn tick_labels_show_their_step() {
        let t = ticks(0.0, 2.2e-6);
        let labels: Vec<String> = t.iter().map(|p| tick_label(p.0, &t)).collect();
        assert_eq!(labels, vec!["0", "5.0e-7", "1.0e-6", "1.5e-6", "2.0e-6"]);
        let t = ticks(0.0, 0.03);
        let labels: Vec<String> = t.iter().map(|p| tick_label(p.0, &t)).collect();
        assert_eq!(labels, vec!["0", "0.01", "0.02", "0.03"]);
        let t = ticks(0.0, 600.0);
        assert_eq!(tick_label(t[1].0, &t), "200");
    }

    #[test]
    fn nice_lengths() {
        assert_eq!(nice_length(7.0), 5.0);
        assert_eq!(nice_length(0.03), 0.02);
        assert_eq!(nice_length(100.0), 100.0);
        assert_eq!(nice_length(0.0), 0.0);
    }

    #[test]
    fn document_is_well_formed() {
        let mut d = SvgDoc::new(10.0, 10.0);
        d.polyline(&[(0.0, 0.0), (1.0, 1.0)], "black", 0.5, Some("a<b"))
            .circle((1.0, 2.0), 0.5, "red", None)
            .text((0.0, 9.0), 3.0, "black", "x & y");
        let mut buf = Vec::new();
        d.write(&mut buf).unwrap();
        let s = String::from_utf8(buf).unwrap();
        assert!(s.contains("<title>a&lt;b</title>"));
        assert!(s.contains("x &amp; y"));
        assert!(s.ends_with("</svg>\n"));
    }
}
