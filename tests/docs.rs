//! The docs name what the workspace has (issue 38): ARCHITECTURE.md's crate table and
//! dependency graph name every workspace member, README.md's layout table every crate
//! folder, and every publishable crate carries the metadata and the README a registry
//! page needs.

use std::path::Path;
use std::process::Command;

/// `cargo metadata --no-deps` of the workspace (offline: it reads only our manifests).
fn metadata() -> serde_json::Value {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .output()
        .expect("cargo metadata");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn read(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap()
}

/// The indented block after the line that starts with `heading`.
fn block_after(text: &str, heading: &str) -> String {
    let start = text
        .find(heading)
        .unwrap_or_else(|| panic!("no {heading:?}"));
    text[start..]
        .lines()
        .skip(1)
        .skip_while(|l| !l.starts_with("    "))
        .take_while(|l| l.starts_with("    ") || l.trim().is_empty())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Whether `text` names the package `name` as a whole word (not as part of a longer
/// package name such as `hotcut-geom` inside `hotcut-geometry`).
fn names(text: &str, name: &str) -> bool {
    text.match_indices(name).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + name.len()..].chars().next();
        let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '-' || c == '_');
        !word(before) && !word(after)
    })
}

#[test]
fn the_architecture_graph_names_every_workspace_member() {
    let m = metadata();
    let arch = read("ARCHITECTURE.md");
    let graph = block_after(&arch, "Dependency direction");
    let members: Vec<&str> = m["packages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert!(members.len() >= 12, "{members:?}");
    let missing: Vec<&&str> = members
        .iter()
        .filter(|n| !names(&graph, n) || !names(&arch, &format!("`{n}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md's crate table and graph must name {missing:?}:\n{graph}"
    );
}

#[test]
fn the_readme_layout_lists_every_crate_folder() {
    let m = metadata();
    let readme = read("README.md");
    let layout = &readme[readme.find("## Layout").expect("a Layout section")..];
    let root = format!("{}/", env!("CARGO_MANIFEST_DIR"));
    for p in m["packages"].as_array().unwrap() {
        let manifest = p["manifest_path"].as_str().unwrap();
        let dir = manifest
            .strip_prefix(&root)
            .unwrap()
            .trim_end_matches("Cargo.toml")
            .trim_end_matches('/');
        if dir.is_empty() {
            continue; // the root package: tests/
        }
        let name = p["name"].as_str().unwrap();
        assert!(
            layout.contains(&format!("`{dir}`")) && names(layout, name),
            "README's layout must list {dir} ({name})"
        );
    }
}

#[test]
fn every_publishable_crate_has_registry_metadata_and_a_readme() {
    let m = metadata();
    let mut checked = 0;
    for p in m["packages"].as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        // publish = false packages list no registry
        if p["publish"].as_array().is_some_and(|r| r.is_empty()) {
            continue;
        }
        for field in [
            "description",
            "repository",
            "license",
            "readme",
            "rust_version",
        ] {
            assert!(p[field].is_string(), "{name}: no {field}");
        }
        for field in ["keywords", "categories"] {
            let list = p[field].as_array().unwrap();
            assert!(
                !list.is_empty() && list.len() <= 5,
                "{name}: {field} {list:?}"
            );
        }
        let dir = Path::new(p["manifest_path"].as_str().unwrap())
            .parent()
            .unwrap()
            .to_path_buf();
        let readme = std::fs::read_to_string(dir.join(p["readme"].as_str().unwrap())).unwrap();
        assert!(readme.contains(name), "{name}: its README does not name it");
        for licence in ["LICENSE-MIT", "LICENSE-APACHE"] {
            assert!(dir.join(licence).is_file(), "{name}: no {licence}");
        }
        // path dependencies carry a version, or `cargo package` refuses them
        for d in p["dependencies"].as_array().unwrap() {
            if d["path"].is_string() && d["kind"].as_str() != Some("dev") {
                assert!(
                    d["req"].as_str() != Some("*"),
                    "{name}: path dependency {} has no version",
                    d["name"]
                );
            }
        }
        checked += 1;
    }
    assert_eq!(
        checked, 11,
        "the eleven library and CLI crates are publishable"
    );
}
