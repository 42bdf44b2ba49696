//! Runs every job in `jobs/`: its `report.json` is snapshot-tested (snapshots live in the
//! top-level `snapshots/`), a second run must give byte-identical output files (but for
//! `report.html`'s run time), and the
//! files are checked as their readers see them ([`outputs_check`]): glTF bounds in metres
//! against the report, every JSON file against its schema, and no drawing's text off the
//! page, on other text or crossed by a line.

use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::NoProgress;
use hotcut_workspace_tests::{read_tree, root, third_party_jobs};

mod outputs_check;

/// `report.html` with the run time (`<span id="run-time">…</span>`) blanked.
fn without_run_time(page: &[u8]) -> Vec<u8> {
    let text = String::from_utf8(page.to_vec()).unwrap();
    let open = "<span id=\"run-time\">";
    let Some(i) = text.find(open) else {
        return page.to_vec();
    };
    let rest = &text[i + open.len()..];
    let end = rest.find("</span>").unwrap();
    format!("{}{}{}", &text[..i + open.len()], "…", &rest[end..]).into_bytes()
}

/// Runs the job at `path` twice and checks its outputs (see the module docs); its report
/// is snapshot-tested under the current insta settings.
fn run_and_check(path: &std::path::Path) {
    let job = load_job(path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let a = tempfile::tempdir().unwrap();
    let b = tempfile::tempdir().unwrap();
    let first = run_job(&job, a.path(), &NoProgress).unwrap();
    let second = run_job(&job, b.path(), &NoProgress).unwrap();
    let (ta, tb) = (read_tree(&first.dir), read_tree(&second.dir));
    assert!(!ta.is_empty());
    assert_eq!(ta.len(), tb.len());
    for ((na, ba), (nb, bb)) in ta.iter().zip(&tb) {
        assert_eq!(na, nb);
        // the page's run time is the one thing that may differ
        let (ba, bb) = if na.ends_with("report.html") {
            (without_run_time(ba), without_run_time(bb))
        } else {
            (ba.clone(), bb.clone())
        };
        assert!(
            ba == bb,
            "{}: {na} differs between two runs",
            path.display()
        );
    }
    let what = path.display().to_string();
    // the output estimate validation checks against `--max-output` is an upper bound
    let written: usize = ta.iter().map(|(_, b)| b.len()).sum();
    let estimated = job.estimate.output;
    assert!(
        estimated == 0.0 || written as f64 <= estimated,
        "{what}: wrote {written} bytes, more than the {estimated} estimated"
    );
    outputs_check::gltf_bounds_match_the_report(&first.dir, &what);
    outputs_check::json_files_validate(&first.dir, &root(), &what);
    let svg = outputs_check::svg_problems(&first.dir);
    assert!(svg.is_empty(), "{what}: drawings:\n{}", svg.join("\n"));
    let report = std::fs::read_to_string(first.dir.join("report.json")).unwrap();
    insta::assert_snapshot!("report", report);
}

fn snapshot_settings() -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings
}

#[test]
fn every_job_runs_matches_its_snapshot_and_is_reproducible() {
    snapshot_settings().bind(|| {
        insta::glob!("../jobs", "*.ron", run_and_check);
    });
}

/// The jobs on third-party benchmark meshes (`jobs/third-party/`), the same way, when the
/// data is present (skipped loudly otherwise; `HOTCUT_REQUIRE_DATA=1` makes it required).
#[test]
fn every_third_party_job_runs_matches_its_snapshot_and_is_reproducible() {
    let Some((_dir, paths)) = third_party_jobs("every_third_party_job_runs") else {
        return;
    };
    assert!(!paths.is_empty());
    for path in &paths {
        let mut settings = snapshot_settings();
        // the same snapshot name insta::glob! gives a job of jobs/
        settings.set_snapshot_suffix(path.file_name().unwrap().to_string_lossy().into_owned());
        settings.bind(|| run_and_check(path));
    }
}

/// The drawing checks on any output folder: with `HOTCUT_CHECK_DIR` set (e.g. after
/// `hotcut run jobs/*.ron --out DIR`), every folder under it must pass
/// [`outputs_check::svg_problems`]; without it there is nothing to check.
/// `HOTCUT_CHECK_DIR=/tmp/out cargo test --test jobs -- drawings_in --nocapture`
#[test]
fn drawings_in_hotcut_check_dir() {
    let Some(root) = std::env::var_os("HOTCUT_CHECK_DIR") else {
        return;
    };
    let mut dirs: Vec<_> = std::fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    let mut problems = Vec::new();
    for d in dirs {
        for p in outputs_check::svg_problems(&d) {
            problems.push(format!("{}: {p}", d.display()));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
