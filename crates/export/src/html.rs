//! A self-contained HTML report page: a [`Page`](crate::html::Page) (plain data a task fills
//! in) rendered by [`render`](crate::html::render) into one file that needs no network and
//! no script: styles are inlined, drawings are embedded as `data:` images, and every other
//! file is a relative link.
//!
//! ```
//! use export::html::{Body, Page, Verdict, Constraint, Table, Row, Drawing, render};
//! let body = Body {
//!     verdict: Verdict { ok: true, text: "cuttable with one blade".into() },
//!     counts: vec![("sections".into(), "26".into())],
//!     constraints: vec![Constraint {
//!         name: "blade length".into(),
//!         limit: "1000 mm".into(),
//!         measured: "812.3 mm".into(),
//!         ok: true,
//!     }],
//!     notes: vec![],
//!     tables: vec![Table {
//!         title: "Sections".into(),
//!         columns: vec!["plane".into(), "length".into()],
//!         rows: vec![Row { cells: vec!["0".into(), "812.3".into()], flag: None }],
//!     }],
//! };
//! let page = Page {
//!     title: "demo".into(),
//!     subtitle: "Analyze · Millimetre · hotcut 0.1.0".into(),
//!     body,
//!     drawings: vec![Drawing { name: "sections.svg".into(), svg: b"<svg xmlns='http://www.w3.org/2000/svg'/>".to_vec() }],
//!     tables_first: false,
//!     files: vec![("report.json".into(), 1234)],
//!     run_time: "0.42 s".into(),
//!     job: "Job(name: \"demo\")".into(),
//!     job_as_written: None,
//! };
//! let html = render(&page);
//! assert!(html.starts_with("<!DOCTYPE html>"));
//! assert!(html.contains("data:image/svg+xml;base64,"));
//! assert!(!html.contains("<script"));
//! ```

use base64::Engine;

/// What a report page shows, top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// The job's name.
    pub title: String,
    /// Task, units and version, one line.
    pub subtitle: String,
    /// What the task found.
    pub body: Body,
    /// The drawings, inlined in order.
    pub drawings: Vec<Drawing>,
    /// Whether the tables come before the drawings (a page that opens on its table).
    pub tables_first: bool,
    /// Every other file written: (name relative to the page, bytes).
    pub files: Vec<(String, u64)>,
    /// How long the run took, as shown (in an element with id `run-time`).
    pub run_time: String,
    /// The job as read, pretty-printed (defaults filled in).
    pub job: String,
    /// The job file as written, when it was read from a file.
    pub job_as_written: Option<String>,
}

/// What a task found, as its page shows it: filled in by each task from its report.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Can it be cut.
    pub verdict: Verdict,
    /// Counts beside the verdict: (what, how many), e.g. ("blocks", "12").
    pub counts: Vec<(String, String)>,
    /// The constraints checked, one row each.
    pub constraints: Vec<Constraint>,
    /// Warnings and notes of the run.
    pub notes: Vec<String>,
    /// Per-block, per-piece or per-curve tables.
    pub tables: Vec<Table>,
}

/// The answer to "can it be cut".
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Whether it can, as asked.
    pub ok: bool,
    /// One or two sentences.
    pub text: String,
}

/// One constraint: its limit, the worst measured value, and whether it holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    /// What is constrained.
    pub name: String,
    /// The limit, with its unit.
    pub limit: String,
    /// The worst value measured, or a count of what breaks it.
    pub measured: String,
    /// Whether the constraint holds everywhere.
    pub ok: bool,
}

/// A table of blocks, pieces or curves.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Its heading.
    pub title: String,
    /// Column headings.
    pub columns: Vec<String>,
    /// Rows, one cell per column.
    pub rows: Vec<Row>,
}

/// A table row.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Cells, one per column.
    pub cells: Vec<String>,
    /// Why the row is flagged (highlighted), if it is.
    pub flag: Option<String>,
}

impl Row {
    /// A row, flagged with `why` when `why` is not empty.
    pub fn new(cells: Vec<String>, why: Vec<&str>) -> Self {
        Self {
            cells,
            flag: (!why.is_empty()).then(|| why.join(", ")),
        }
    }
}

/// A drawing to inline.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Its file name (the link under it).
    pub name: String,
    /// The SVG document.
    pub svg: Vec<u8>,
}

/// Text with `&`, `<`, `>`, `"` and `'` escaped, for element content and attribute values,
/// and no character XML forbids ([`geom::text::xml`]).
pub fn escape(text: &str) -> String {
    geom::text::xml(text)
}

/// A relative link target: characters outside the URL-safe set percent-encoded.
fn href(name: &str) -> String {
    let mut out = String::new();
    for b in name.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

const STYLE: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,sans-serif;margin:0 auto;max-width:1100px;padding:1em 1.5em;color:#222;line-height:1.4}
h1{margin:.2em 0;font-size:1.6em}h2{margin-top:1.6em;border-bottom:1px solid #ccc;font-size:1.25em}
.meta{color:#555;margin:0}
#verdict{border-radius:6px;padding:.8em 1.2em;margin-top:1em}
#verdict.ok{background:#e6f4e6;border:2px solid #3a8a3a}#verdict.bad{background:#fbe9e7;border:2px solid #c0392b}
#verdict p.answer{font-size:1.25em;font-weight:600;margin:.2em 0}
dl.counts{display:flex;flex-wrap:wrap;gap:.4em 2em;margin:.6em 0 0}dl.counts div{display:flex;gap:.4em}dl.counts dt{color:#555}dl.counts dd{margin:0;font-weight:600}
table{border-collapse:collapse;margin:.5em 0;font-size:.9em}th,td{border:1px solid #ccc;padding:.2em .6em;text-align:right}
th{background:#f2f2f2}td:first-child,th:first-child{text-align:left}#constraints td,#constraints th{text-align:left}
tr.flagged td{background:#fde2dd}td.why{text-align:left;color:#a02a1a}
td.ok{color:#276b27;font-weight:600;text-align:center}td.bad{color:#b03020;font-weight:600;text-align:center}
.scroll{overflow-x:auto;max-width:100%}td{white-space:nowrap}td.why{white-space:normal}#constraints td{white-space:normal}
@media print{.scroll{overflow:visible}}
.grid{display:grid;grid-template-columns:1fr 1fr;gap:0 1.5em}figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd;background:#fff}figcaption{font-size:.9em;color:#555}
pre{background:#f6f6f6;padding:.8em;overflow:auto;font-size:.85em}
ul.notes li{color:#8a5a00}
";

/// The page as one HTML document.
pub fn render(page: &Page) -> String {
    let mut h = String::new();
    h.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    h.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    h.push_str(&format!(
        "<title>{} — hotcut report</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n",
        escape(&page.title)
    ));
    h.push_str(&format!(
        "<header>\n<h1>{}</h1>\n<p class=\"meta\">{} · run time <span id=\"run-time\">{}</span></p>\n</header>\n",
        escape(&page.title),
        escape(&page.subtitle),
        escape(&page.run_time)
    ));
    let body = &page.body;
    verdict(&mut h, body);
    // a page that opens on its table: the tables and drawings first, then the constraints
    // and notes
    if !page.tables_first {
        constraints(&mut h, &body.constraints);
        notes(&mut h, &body.notes);
        drawings(&mut h, &page.drawings, &page.files);
    }
    for (i, t) in body.tables.iter().enumerate() {
        table(&mut h, i, t);
    }
    if page.tables_first {
        drawings(&mut h, &page.drawings, &page.files);
        constraints(&mut h, &body.constraints);
        notes(&mut h, &body.notes);
    }
    files(&mut h, &page.files);
    h.push_str(
        "<section id=\"job\">\n<h2>The job</h2>\n<p>As hotcut read it: every field with its value or default; <code>None</code> where the job leaves it to the task (its default is in the README and the schema).</p>\n",
    );
    h.push_str(&format!("<pre>{}</pre>\n", escape(&page.job)));
    if let Some(text) = &page.job_as_written {
        h.push_str(&format!(
            "<details>\n<summary>The job file as written</summary>\n<pre>{}</pre>\n</details>\n",
            escape(text)
        ));
    }
    h.push_str("</section>\n</body>\n</html>\n");
    h
}

/// The run's notes, when it has any.
fn notes(h: &mut String, notes: &[String]) {
    if notes.is_empty() {
        return;
    }
    h.push_str("<section id=\"notes\">\n<h2>Notes</h2>\n<ul class=\"notes\">\n");
    for n in notes {
        h.push_str(&format!("<li>{}</li>\n", escape(n)));
    }
    h.push_str("</ul>\n</section>\n");
}

fn verdict(h: &mut String, body: &Body) {
    let v = &body.verdict;
    h.push_str(&format!(
        "<section id=\"verdict\" class=\"{}\">\n<p class=\"answer\">{} {}</p>\n",
        if v.ok { "ok" } else { "bad" },
        if v.ok { "✔" } else { "✘" },
        escape(&v.text)
    ));
    if !body.counts.is_empty() {
        h.push_str("<dl class=\"counts\">\n");
        for (what, n) in &body.counts {
            h.push_str(&format!(
                "<div><dt>{}</dt><dd>{}</dd></div>\n",
                escape(what),
                escape(n)
            ));
        }
        h.push_str("</dl>\n");
    }
    h.push_str("</section>\n");
}

fn constraints(h: &mut String, list: &[Constraint]) {
    if list.is_empty() {
        return;
    }
    h.push_str("<section id=\"constraints\">\n<h2>Constraints</h2>\n<table>\n");
    h.push_str("<thead><tr><th>constraint</th><th>limit</th><th>measured (worst)</th><th>holds</th></tr></thead>\n<tbody>\n");
    for c in list {
        h.push_str(&format!(
            "<tr{}><td>{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>\n",
            if c.ok { "" } else { " class=\"flagged\"" },
            escape(&c.name),
            escape(&c.limit),
            escape(&c.measured),
            if c.ok { "ok" } else { "bad" },
            if c.ok { "yes" } else { "no" }
        ));
    }
    h.push_str("</tbody>\n</table>\n</section>\n");
}

/// At most this many drawings are inlined; the rest are linked under "Files".
pub const MAX_DRAWINGS: usize = 48;

/// The drawings, each captioned with its name, a link when the run wrote its file
/// (`files`; a page can show a drawing its run did not write as a file).
fn drawings(h: &mut String, list: &[Drawing], files: &[(String, u64)]) {
    if list.is_empty() {
        return;
    }
    h.push_str("<section id=\"drawings\">\n<h2>Drawings</h2>\n");
    // many drawings (one per block) two to a row
    let grid = list.len() > 2;
    if grid {
        h.push_str("<div class=\"grid\">\n");
    }
    for d in list.iter().take(MAX_DRAWINGS) {
        let caption = if files.iter().any(|(f, _)| f == &d.name) {
            format!("<a href=\"{}\">{}</a>", href(&d.name), escape(&d.name))
        } else {
            escape(&d.name)
        };
        h.push_str(&format!(
            "<figure>\n<img alt=\"{}\" src=\"data:image/svg+xml;base64,{}\">\n<figcaption>{caption}</figcaption>\n</figure>\n",
            escape(&d.name),
            base64::engine::general_purpose::STANDARD.encode(&d.svg),
        ));
    }
    if grid {
        h.push_str("</div>\n");
    }
    if list.len() > MAX_DRAWINGS {
        h.push_str(&format!(
            "<p>{} more drawing(s) are linked under Files.</p>\n",
            list.len() - MAX_DRAWINGS
        ));
    }
    h.push_str("</section>\n");
}

fn table(h: &mut String, index: usize, t: &Table) {
    let flagged = t.rows.iter().filter(|r| r.flag.is_some()).count();
    h.push_str(&format!(
        "<section id=\"table-{index}\">\n<h2>{}</h2>\n<p>{} row(s), {} flagged{}</p>\n<div class=\"scroll\"><table>\n<thead><tr>",
        escape(&t.title),
        t.rows.len(),
        flagged,
        if flagged > 0 { " (highlighted, with the reason in the last column)" } else { "" }
    ));
    for c in &t.columns {
        h.push_str(&format!("<th>{}</th>", escape(c)));
    }
    h.push_str("<th>flag</th></tr></thead>\n<tbody>\n");
    for r in &t.rows {
        h.push_str(if r.flag.is_some() {
            "<tr class=\"flagged\">"
        } else {
            "<tr>"
        });
        for c in &r.cells {
            h.push_str(&format!("<td>{}</td>", escape(c)));
        }
        h.push_str(&format!(
            "<td class=\"why\">{}</td></tr>\n",
            escape(r.flag.as_deref().unwrap_or(""))
        ));
    }
    h.push_str("</tbody>\n</table></div>\n</section>\n");
}

fn files(h: &mut String, list: &[(String, u64)]) {
    h.push_str("<section id=\"files\">\n<h2>Files</h2>\n<ul>\n");
    for (name, bytes) in list {
        h.push_str(&format!(
            "<li><a href=\"{}\">{}</a> ({})</li>\n",
            href(name),
            escape(name),
            size(*bytes)
        ));
    }
    h.push_str("</ul>\n</section>\n");
}

/// A byte count for people: `812 B`, `12.3 kB`, `4.5 MB`.
fn size(bytes: u64) -> String {
    match bytes {
        b if b < 1000 => format!("{b} B"),
        b if b < 1_000_000 => format!("{:.1} kB", b as f64 / 1e3),
        b => format!("{:.1} MB", b as f64 / 1e6),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped_everywhere() {
        let evil = "<script>alert('x')</script>&\"";
        let page = Page {
            title: evil.into(),
            subtitle: evil.into(),
            body: Body {
                verdict: Verdict {
                    ok: false,
                    text: evil.into(),
                },
                counts: vec![(evil.into(), evil.into())],
                constraints: vec![Constraint {
                    name: evil.into(),
                    limit: evil.into(),
                    measured: evil.into(),
                    ok: false,
                }],
                notes: vec![evil.into()],
                tables: vec![Table {
                    title: evil.into(),
                    columns: vec![evil.into()],
                    rows: vec![Row::new(vec![evil.into()], vec![evil])],
                }],
            },
            drawings: vec![Drawing {
                name: "a b<.svg".into(),
                svg: evil.as_bytes().to_vec(),
            }],
            tables_first: false,
            files: vec![("x\"y.csv".into(), 12_345), ("a b<.svg".into(), 10)],
            run_time: evil.into(),
            job: evil.into(),
            job_as_written: Some(evil.into()),
        };
        let html = render(&page);
        assert!(!html.contains("<script"), "{html}");
        assert!(!html.contains("alert('x')"));
        assert!(html.contains("href=\"a%20b%3C.svg\""));
        assert!(html.contains("href=\"x%22y.csv\""));
        assert!(html.contains("12.3 kB"));
        assert!(html.contains("class=\"flagged\""));
        assert!(html.contains("id=\"verdict\" class=\"bad\""));
    }

    #[test]
    fn sizes_read_well() {
        assert_eq!(size(999), "999 B");
        assert_eq!(size(1000), "1.0 kB");
        assert_eq!(size(4_500_000), "4.5 MB");
    }

    #[test]
    fn many_drawings_are_capped() {
        let d = Drawing {
            name: "d.svg".into(),
            svg: b"<svg/>".to_vec(),
        };
        let mut h = String::new();
        drawings(&mut h, &vec![d; MAX_DRAWINGS + 3], &[]);
        assert_eq!(h.matches("<img").count(), MAX_DRAWINGS);
        assert!(h.contains("3 more drawing(s)"));
    }
}
