//! Guard: no file of the repository but the data helper (`crates/testdata/src/lib.rs`,
//! and its shell counterpart `scripts/fetch-data`) names the third-party data's default
//! location beside the repository. Tests, benches, examples, job files and docs reach the
//! data through `testdata`, so a clone with nothing beside it works, and `HOTCUT_DATA`
//! moves the data for all of them at once.

use std::path::{Path, PathBuf};

/// Files allowed to name the default location, relative to the workspace root.
const HELPER: [&str; 2] = ["crates/testdata/src/lib.rs", "scripts/fetch-data"];

/// Folders not part of the repository's own text.
const SKIP_DIRS: [&str; 4] = ["target", ".git", "out", "node_modules"];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if p.is_dir() {
            if !SKIP_DIRS.contains(&name.as_str()) {
                files(&p, out);
            }
        } else {
            out.push(p);
        }
    }
}

/// Relative paths of the files (text only) that name the `shared` folder beside the
/// repository by a relative path (either slash).
fn offenders(root: &Path) -> Vec<String> {
    // spelled in pieces so this file does not name it
    let patterns = [format!("..{}shared", '/'), format!("..{}shared", '\\')];
    let mut all = Vec::new();
    files(root, &mut all);
    let mut bad: Vec<String> = all
        .iter()
        .filter_map(|p| {
            let rel = p
                .strip_prefix(root)
                .ok()?
                .to_string_lossy()
                .replace('\\', "/");
            if HELPER.contains(&rel.as_str()) {
                return None;
            }
            let text = std::fs::read_to_string(p).ok()?;
            patterns
                .iter()
                .any(|pat| text.contains(pat.as_str()))
                .then_some(rel)
        })
        .collect();
    bad.sort();
    bad
}

#[test]
fn only_the_helper_names_the_data_folder_beside_the_repository() {
    let root = testdata::workspace().canonicalize().unwrap();
    let bad = offenders(&root);
    assert!(
        bad.is_empty(),
        "these files name the data folder beside the repository; reach the data through \
         the `testdata` crate instead:\n{}",
        bad.join("\n")
    );
}

/// The guard can fail: a file naming the folder is found.
#[test]
fn the_guard_finds_an_offender() {
    let dir = std::env::temp_dir().join(format!("testdata-guard-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("tests")).unwrap();
    std::fs::write(
        dir.join("tests/x.rs"),
        format!("let p = \"..{}shared/data/meshes/hand.obj\";", '/'),
    )
    .unwrap();
    std::fs::write(dir.join("tests/y.rs"), "fine").unwrap();
    let bad = offenders(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(bad, vec!["tests/x.rs".to_string()]);
}
