//! Shared helpers for the workspace-level integration tests.

use std::path::{Path, PathBuf};

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// All files under `dir` (recursively) with their bytes, sorted by relative path.
pub fn read_tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if let Ok(bytes) = std::fs::read(&p) {
                let rel = p
                    .strip_prefix(dir)
                    .unwrap_or(&p)
                    .to_string_lossy()
                    .into_owned();
                out.push((rel, bytes));
            }
        }
    }
    out.sort();
    out
}

/// The job files of `jobs/third-party/` (jobs on third-party benchmark meshes), each copied
/// into a temporary folder beside a `meshes/` copy of that data, as `scripts/fetch-data
/// jobs/third-party` would lay them out; the folder lives as long as the returned guard.
/// `None`, after a loud SKIPPED line naming `test`, when the data is absent (see
/// `testdata`; with `HOTCUT_REQUIRE_DATA=1` that panics instead).
pub fn third_party_jobs(test: &str) -> Option<(tempfile::TempDir, Vec<PathBuf>)> {
    let meshes = testdata::third_party_mesh_dir(test)?;
    let dir = tempfile::tempdir().expect("a temporary folder");
    let copy = dir.path().join("meshes");
    std::fs::create_dir_all(&copy).expect("meshes folder");
    for name in testdata::THIRD_PARTY_MESHES {
        std::fs::copy(meshes.join(name), copy.join(name)).expect("copy of a mesh");
    }
    let mut jobs: Vec<PathBuf> = std::fs::read_dir(root().join("jobs/third-party"))
        .expect("jobs/third-party")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .map(|p| {
            let to = dir.path().join(p.file_name().expect("a file name"));
            std::fs::copy(&p, &to).expect("copy of a job");
            to
        })
        .collect();
    jobs.sort();
    Some((dir, jobs))
}
