//! `report.html`: every job in `jobs/` that asks for `Html` writes a page that stands
//! alone and that a real browser shows without complaint.
//!
//! - Read as text: no script, no address outside the output folder, every link leads to a
//!   file of the run and every file of the run is linked, every drawing is inlined as a
//!   `data:` image equal byte for byte to the job's `.svg` file, the verdict, the run
//!   time and the job are there, and the highlighted rows are exactly the pieces, blocks
//!   or sections the report fails (`seg-wavy-45-longest` and `wave-facade` have some).
//! - In a browser: Debian's `chromium`, headless, loads each page and saves a screenshot
//!   under `target/html-screenshots/<job>.png`; any console message (a script error, a
//!   refused resource) fails the test. When no chromium is found the browser part is
//!   skipped, loudly; with `HOTCUT_REQUIRE_BROWSER=1` (set by `.ci/run` after installing
//!   chromium) it fails instead. A page with a script error must be caught, so the check
//!   is known to bite.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine;
use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::spec::OutputSpec;
use hotcut::NoProgress;
use hotcut_workspace_tests::root;

/// A headless chromium, if one is installed (`HOTCUT_CHROMIUM` names one explicitly).
fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("HOTCUT_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    [
        "chromium",
        "chromium-browser",
        "google-chrome",
        "google-chrome-stable",
    ]
    .into_iter()
    .find(|name| {
        Command::new(name)
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    })
    .map(PathBuf::from)
}

/// Opens `page` in headless `browser`, saving a screenshot to `png`; returns the console
/// messages the page logged. Killed after two minutes.
fn open_in_browser(browser: &Path, page: &Path, png: &Path) -> Vec<String> {
    let profile = tempfile::tempdir().unwrap();
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--hide-scrollbars",
            "--no-first-run",
            "--disable-extensions",
            "--enable-logging=stderr",
            "--v=0",
            "--window-size=1280,2400",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starting chromium");
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        use std::io::Read;
        let mut s = String::new();
        let _ = std::io::BufReader::new(stderr).read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("chromium did not finish {} in two minutes", page.display());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let log = reader.join().unwrap();
    log.lines()
        .filter(|l| l.contains(":CONSOLE"))
        .map(str::to_string)
        .collect()
}

/// The value of every `attr="…"` in `html`.
fn attributes<'a>(html: &'a str, attr: &str) -> Vec<&'a str> {
    let key = format!(" {attr}=\"");
    html.match_indices(&key)
        .filter_map(|(i, _)| {
            let rest = &html[i + key.len()..];
            rest.find('"').map(|end| &rest[..end])
        })
        .collect()
}

/// A link target, percent-decoded.
fn decode(href: &str) -> String {
    let bytes = href.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            if let Some(Ok(b)) = href.get(i + 1..i + 3).map(|h| u8::from_str_radix(h, 16)) {
                out.push(b);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8(out).unwrap()
}

/// What is wrong with the page `dir/report.html` as text (see the module doc).
fn page_problems(dir: &Path, report: &serde_json::Value) -> Vec<String> {
    let mut out = Vec::new();
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    if !html.starts_with("<!DOCTYPE html>") {
        out.push("does not start with <!DOCTYPE html>".into());
    }
    for bad in [
        "<script", "http://", "https://", "<link", "<iframe", "@import",
    ] {
        if html.to_ascii_lowercase().contains(bad) {
            out.push(format!("contains `{bad}`"));
        }
    }
    let job = report["job"].as_str().unwrap();
    if !html.contains(&format!("<h1>{job}</h1>")) {
        out.push("no title with the job's name".into());
    }
    if !html.contains("id=\"verdict\"") || !html.contains("id=\"run-time\"") {
        out.push("no verdict or run time".into());
    }
    if !html.contains("<section id=\"job\">") || !html.contains("name: &quot;") {
        out.push("no job file".into());
    }
    // links: every one to a file of the run, every file linked
    let mut linked: Vec<String> = attributes(&html, "href").into_iter().map(decode).collect();
    linked.sort();
    linked.dedup();
    for l in &linked {
        if l.contains("..") || l.starts_with('/') || !dir.join(l).is_file() {
            out.push(format!("link `{l}` leads to no file of the run"));
        }
    }
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().to_string_lossy().into_owned();
        if e.path().is_dir() {
            // a folder of a Compare's process: its files are linked, and its own page
            // stands alone too
            let inside = format!("{name}/");
            if !linked.iter().any(|l| l.starts_with(&inside)) {
                out.push(format!("folder {name}: no file of it is linked"));
            }
            let sub = e.path();
            if sub.join("report.html").is_file() {
                let report = serde_json::from_str(
                    &std::fs::read_to_string(sub.join("report.json")).unwrap(),
                )
                .unwrap();
                out.extend(
                    page_problems(&sub, &report)
                        .into_iter()
                        .map(|p| format!("{inside}report.html: {p}")),
                );
            }
        } else if name != "report.html" && !linked.contains(&name) {
            out.push(format!("file {name} is not linked"));
        }
    }
    // drawings: data images, each equal to its file when the job writes it
    let images: Vec<&str> = attributes(&html, "src");
    let alts: Vec<&str> = attributes(&html, "alt");
    for (src, name) in images.iter().zip(&alts) {
        let Some(data) = src.strip_prefix("data:image/svg+xml;base64,") else {
            out.push(format!("image {name} is not an inlined SVG"));
            continue;
        };
        let svg = base64::engine::general_purpose::STANDARD
            .decode(data)
            .unwrap_or_default();
        let text = String::from_utf8_lossy(&svg);
        if !text.contains("<svg") || !text.trim_end().ends_with("</svg>") {
            out.push(format!("image {name} is not an SVG document"));
        }
        if let Ok(file) = std::fs::read(dir.join(name)) {
            if file != svg {
                out.push(format!("image {name} differs from the file"));
            }
        }
    }
    let svgs = std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "svg")
        })
        .count();
    if images.len() < svgs.min(export::html::MAX_DRAWINGS) {
        out.push(format!("{} drawing(s) inlined of {svgs}", images.len()));
    }
    out.extend(flagged_rows_problems(&html, report));
    out
}

/// The rows a page highlights against the report's own verdicts: pieces with a failed
/// constraint, a gouge or a holder collision (FacadeSegmentation), blocks with a flag (HotBlade), sections with a
/// violation (Analyze).
fn flagged_rows_problems(html: &str, report: &serde_json::Value) -> Vec<String> {
    let list = |key: &str| report[key].as_array().cloned().unwrap_or_default();
    let (table, rows, failing) = match report["task"].as_str().unwrap_or("") {
        "FacadeSegmentation" => {
            let p = list("pieces");
            let bad = p
                .iter()
                .filter(|x| {
                    let broken = x["verdicts"]
                        .as_object()
                        .unwrap()
                        .values()
                        .any(|v| v == &serde_json::Value::Bool(false));
                    // or a blade outside its part that gouges, or a holder on the block
                    let gouge = x["max_gouge_depth"].as_f64().is_some_and(|d| d > 0.0);
                    broken || gouge || x["holders_clear"] == serde_json::Value::Bool(false)
                })
                .count();
            ("Pieces", p.len(), bad)
        }
        "HotBlade" => {
            let b = list("blocks");
            let bad = b
                .iter()
                .filter(|x| {
                    x["flags"]
                        .as_object()
                        .unwrap()
                        .values()
                        .any(|v| v == &serde_json::Value::Bool(true))
                })
                .count();
            ("Blocks (drawing block_NNN.svg each)", b.len(), bad)
        }
        "Analyze" => {
            let s = list("sections");
            let bad = s
                .iter()
                .filter(|x| !x["violations"].as_array().unwrap().is_empty())
                .count();
            ("Sections", s.len(), bad)
        }
        _ => return Vec::new(),
    };
    let want = format!("<h2>{table}</h2>\n<p>{rows} row(s), {failing} flagged");
    let mut out = Vec::new();
    if !html.contains(&want) {
        out.push(format!("table {table}: expected `{want}`"));
    }
    let start = html.find(&format!("<h2>{table}</h2>")).unwrap_or(0);
    let end = html[start..]
        .find("</table>")
        .map_or(html.len(), |e| start + e);
    let shown = html[start..end].matches("<tr class=\"flagged\">").count();
    if shown != failing {
        out.push(format!(
            "table {table}: {shown} row(s) highlighted, the report fails {failing}"
        ));
    }
    out
}

/// The jobs in `jobs/` that ask for `report.html`.
fn html_jobs() -> Vec<PathBuf> {
    let mut jobs: Vec<PathBuf> = std::fs::read_dir(root().join("jobs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .filter(|p| {
            load_job(p)
                .unwrap_or_else(|e| panic!("{}: {e:?}", p.display()))
                .outputs
                .contains(&OutputSpec::Html)
        })
        .collect();
    jobs.sort();
    jobs
}

#[test]
fn every_html_page_stands_alone_and_shows_in_a_browser() {
    let jobs = html_jobs();
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let main = readme
        .lines()
        .find_map(|l| l.strip_prefix("cargo run --locked -p hotcut -- run "))
        .expect("README gives the main example's run command");
    assert!(
        jobs.iter().any(|j| j.ends_with(main.trim())),
        "the README's main job {main} must ask for Html"
    );
    let browser = chromium();
    if browser.is_none() {
        assert!(
            std::env::var_os("HOTCUT_REQUIRE_BROWSER").is_none(),
            "HOTCUT_REQUIRE_BROWSER is set but no chromium was found"
        );
        eprintln!(
            "\n**********\nSKIPPED: chromium not found; report.html pages were checked as text only, NOT in a browser\n**********\n"
        );
    }
    let shots = root().join("target/html-screenshots");
    std::fs::create_dir_all(&shots).unwrap();
    let out = tempfile::tempdir().unwrap();
    let mut problems = Vec::new();
    for path in &jobs {
        let job = load_job(path).unwrap();
        let r = run_job(&job, out.path(), &NoProgress).unwrap();
        let name = job.context.name.clone();
        for p in page_problems(&r.dir, &r.report) {
            problems.push(format!("{name}: {p}"));
        }
        if let Some(b) = &browser {
            let png = shots.join(format!("{name}.png"));
            let _ = std::fs::remove_file(&png);
            for line in open_in_browser(b, &r.dir.join("report.html"), &png) {
                problems.push(format!("{name}: console: {line}"));
            }
            let size = std::fs::metadata(&png).map_or(0, |m| m.len());
            if size < 10_000 {
                problems.push(format!(
                    "{name}: screenshot missing or blank ({size} bytes)"
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_browser_check_catches_a_broken_page() {
    let Some(browser) = chromium() else {
        eprintln!("\n**********\nSKIPPED: chromium not found\n**********\n");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("broken.html");
    std::fs::write(
        &page,
        "<!DOCTYPE html><html><body><p>x</p><script>no_such_function();</script></body></html>",
    )
    .unwrap();
    let console = open_in_browser(&browser, &page, &dir.path().join("broken.png"));
    assert!(
        console.iter().any(|l| l.contains("no_such_function")),
        "{console:?}"
    );
}

#[test]
fn the_text_check_catches_a_missing_link_and_a_script() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("model.gltf"), "{}").unwrap();
    std::fs::write(
        dir.path().join("report.html"),
        "<!DOCTYPE html><h1>j</h1><a href=\"gone.csv\">x</a><script></script>",
    )
    .unwrap();
    let p = page_problems(dir.path(), &serde_json::json!({"job": "j"}));
    for want in [
        "`<script`",
        "gone.csv",
        "model.gltf is not linked",
        "no verdict",
    ] {
        assert!(p.iter().any(|x| x.contains(want)), "{want}: {p:?}");
    }
}
