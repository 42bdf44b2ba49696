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
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
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
    /// baseline), labelled with the length and `units` to its right.
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
        self.polyline(
            &[(x, y - 4.0), (x, y), (x + w, y), (x + w, y - 4.0)],
            "black",
            1.0,
            None,
        );
        let label = format!("{} {units}", crate::fmt_float(len, 6));
        self.text((x + w + 6.0, y), 10.0, "black", &label)
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
