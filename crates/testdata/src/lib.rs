//! # testdata — the data hotcut's tests and benchmarks use, reached one way
//!
//! Two kinds of data:
//!
//! - **Vendored**: what the project generated itself lives in the repository, so a fresh
//!   clone has it. [`curves_json`] (72 planar test curves with their truth, see
//!   `curves/README.md`), [`meshes_json`] (the recorded facts — counts, volume, area,
//!   source, licence — of every benchmark mesh) and the generated torus,
//!   `jobs/models/torus.obj` ([`mesh`]`("torus.obj")`).
//! - **Third-party**: the benchmark meshes of thesis Table 3.1 (armadillo, dancer,
//!   fertility, hand, neptune, octopus) are other people's models under research-only or
//!   unstated licences, so they are not in the repository. They are looked for in
//!   `$HOTCUT_DATA/meshes/` ([`data_dir`]; by default the `shared/data` folder beside the
//!   repository). `scripts/fetch-data` downloads them from their public sources, checks
//!   their SHA-256 and names each licence.
//!
//! A test that needs a third-party mesh asks [`mesh`] or [`third_party_meshes`]. When the
//! mesh is absent they print a loud `SKIPPED` line naming the test, the file and how to
//! get it, and return `None`, so the test passes on a clone with nothing beside it; with
//! `HOTCUT_REQUIRE_DATA=1` (what `.ci/run` sets) they panic instead, so CI cannot skip.
//!
//! No other file of the repository names the data's default location:
//! `tests/guard.rs` fails when one does.
//!
//! ```
//! // the vendored curves are always there
//! let text = std::fs::read_to_string(testdata::curves_json()).unwrap();
//! assert!(text.contains("elastica_exact"));
//! // a third-party mesh may not be: handle None
//! if let Some(hand) = testdata::mesh("hand.obj", "doc example") {
//!     assert!(hand.exists());
//! }
//! ```

use std::path::{Path, PathBuf};

/// The environment variable naming the folder of the third-party data (its `meshes/`
/// holds the OBJ files).
pub const DATA_VAR: &str = "HOTCUT_DATA";

/// The environment variable that turns a missing third-party mesh from a skip into a
/// failure (set to `1` by `.ci/run`).
pub const REQUIRE_VAR: &str = "HOTCUT_REQUIRE_DATA";

/// The third-party benchmark meshes, by file name.
pub const THIRD_PARTY_MESHES: [&str; 6] = [
    "armadillo.obj",
    "dancer.obj",
    "fertility.obj",
    "hand.obj",
    "neptune.obj",
    "octopus.obj",
];

/// Meshes the project generated itself, vendored in `jobs/models/`.
pub const VENDORED_MESHES: [&str; 1] = ["torus.obj"];

/// The workspace root.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The 72 planar test curves (`{"meta", "curves": [{"id", "class", "subclass",
/// "points", "truth"}]}`, metres), vendored.
pub fn curves_json() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("curves/curves.json")
}

/// The recorded facts of every benchmark mesh (an array of `{"file", "faces", "volume",
/// "area", "source", "commit", "provenance", ...}`), vendored.
pub fn meshes_json() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes.json")
}

/// The folder of the third-party data: `$HOTCUT_DATA`, else `shared/data` beside the
/// repository.
pub fn data_dir() -> PathBuf {
    match std::env::var_os(DATA_VAR) {
        Some(d) if !d.is_empty() => PathBuf::from(d),
        _ => workspace().join("..").join("shared").join("data"),
    }
}

/// Whether a missing third-party mesh must fail the test (`HOTCUT_REQUIRE_DATA` set to
/// anything but empty or `0`).
pub fn data_required() -> bool {
    std::env::var(REQUIRE_VAR).is_ok_and(|v| !v.is_empty() && v != "0")
}

/// The mesh `name`: a vendored one from the repository; a third-party one from
/// [`data_dir`]`/meshes/`, or `None` after a loud `SKIPPED` line naming `test` when it is
/// absent.
///
/// # Panics
/// When a third-party mesh is absent and [`data_required`]; for a name that is neither
/// vendored nor third-party (a mistake in the test).
pub fn mesh(name: &str, test: &str) -> Option<PathBuf> {
    if VENDORED_MESHES.contains(&name) {
        return Some(workspace().join("jobs/models").join(name));
    }
    assert!(
        THIRD_PARTY_MESHES.contains(&name),
        "testdata: no mesh named {name}"
    );
    let path = data_dir().join("meshes").join(name);
    if path.is_file() {
        return Some(path);
    }
    missing(&[path], test);
    None
}

/// Every third-party mesh, in [`THIRD_PARTY_MESHES`] order, or `None` after a loud
/// `SKIPPED` line naming `test` when any is absent.
///
/// # Panics
/// When one is absent and [`data_required`].
pub fn third_party_meshes(test: &str) -> Option<Vec<PathBuf>> {
    let dir = data_dir().join("meshes");
    let paths: Vec<PathBuf> = THIRD_PARTY_MESHES.iter().map(|n| dir.join(n)).collect();
    let absent: Vec<PathBuf> = paths.iter().filter(|p| !p.is_file()).cloned().collect();
    if absent.is_empty() {
        Some(paths)
    } else {
        missing(&absent, test);
        None
    }
}

/// The folder holding the third-party meshes, or `None` after a loud `SKIPPED` line when
/// any is absent (for tests that point a job file at it).
///
/// # Panics
/// As [`third_party_meshes`].
pub fn third_party_mesh_dir(test: &str) -> Option<PathBuf> {
    third_party_meshes(test).map(|_| data_dir().join("meshes"))
}

fn missing(absent: &[PathBuf], test: &str) {
    let list: Vec<String> = absent.iter().map(|p| p.display().to_string()).collect();
    let message = format!(
        "{test}: third-party benchmark data not found: {}. Run `scripts/fetch-data` (it \
         downloads the meshes from their public sources and checks their SHA-256) or set \
         {DATA_VAR} to a folder whose meshes/ holds them.",
        list.join(", ")
    );
    if data_required() {
        panic!("{message} ({REQUIRE_VAR} is set, so this test may not skip)");
    }
    // straight to the process's stderr: the test harness captures `eprintln!` of a
    // passing test, and a skip must be seen in a plain `cargo test`
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "\n*** SKIPPED *** {message}\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vendored_data_is_present() {
        assert!(curves_json().is_file());
        assert!(meshes_json().is_file());
        for m in VENDORED_MESHES {
            assert!(mesh(m, "vendored_data_is_present").is_some_and(|p| p.is_file()));
        }
    }

    #[test]
    fn every_mesh_has_recorded_facts() {
        let text = std::fs::read_to_string(meshes_json()).unwrap();
        for m in THIRD_PARTY_MESHES.iter().chain(&VENDORED_MESHES) {
            assert!(text.contains(&format!("\"file\": \"{m}\"")), "{m}");
        }
    }
}
