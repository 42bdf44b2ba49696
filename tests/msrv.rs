//! The workspace's `rust-version` is a true minimum (issue 38): no locked dependency that
//! the host's build uses declares a higher `rust-version` than the workspace does. Read from
//! `cargo metadata` (offline first: a build has fetched every host dependency already).

use std::process::Command;

/// A version `a.b[.c]` as numbers, for comparing.
fn parse(v: &str) -> Vec<u64> {
    v.split('.').map(|x| x.parse().unwrap_or(0)).collect()
}

/// Whether `a` is higher than `b` (missing parts are 0).
fn higher(a: &str, b: &str) -> bool {
    let (a, b) = (parse(a), parse(b));
    for i in 0..a.len().max(b.len()) {
        let (x, y) = (
            a.get(i).copied().unwrap_or(0),
            b.get(i).copied().unwrap_or(0),
        );
        if x != y {
            return x > y;
        }
    }
    false
}

fn metadata() -> serde_json::Value {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let host = Command::new(&rustc).arg("-vV").output().expect("rustc -vV");
    let host = String::from_utf8_lossy(&host.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("the host triple");
    let dir = env!("CARGO_MANIFEST_DIR");
    let run = |offline: bool| {
        let mut c = Command::new(&cargo);
        c.current_dir(dir).args([
            "metadata",
            "--format-version",
            "1",
            "--locked",
            "--filter-platform",
            &host,
        ]);
        if offline {
            c.arg("--offline");
        }
        c.output().expect("cargo metadata")
    };
    let out = Some(run(true))
        .filter(|o| o.status.success())
        .unwrap_or_else(|| run(false));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn no_dependency_needs_a_newer_rust_than_the_workspace_declares() {
    let m = metadata();
    let members: Vec<&serde_json::Value> =
        m["workspace_members"].as_array().unwrap().iter().collect();
    let packages = m["packages"].as_array().unwrap();
    let declared: Vec<&str> = packages
        .iter()
        .filter(|p| members.contains(&&p["id"]))
        .map(|p| {
            p["rust_version"]
                .as_str()
                .expect("every member declares rust-version")
        })
        .collect();
    assert!(!declared.is_empty());
    // every member inherits the workspace's
    assert!(declared.windows(2).all(|w| w[0] == w[1]), "{declared:?}");
    let ours = declared[0];
    let needs: Vec<String> = packages
        .iter()
        .filter(|p| !members.contains(&&p["id"]))
        .filter_map(|p| {
            let v = p["rust_version"].as_str()?;
            let (name, version) = (p["name"].as_str()?, p["version"].as_str()?);
            higher(v, ours).then(|| format!("{name} {version} needs {v}"))
        })
        .collect();
    assert!(
        needs.is_empty(),
        "rust-version = {ours}, but {}: raise it in Cargo.toml and README.md",
        needs.join(", ")
    );
    // the README states the same minimum
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(
        readme.contains(&format!("stable ≥ {ours}")),
        "README.md must say `stable ≥ {ours}`"
    );
}

#[test]
fn versions_compare_by_their_numbers() {
    assert!(higher("1.90", "1.85"));
    assert!(higher("1.89.1", "1.89"));
    assert!(!higher("1.89.0", "1.89"));
    assert!(!higher("1.85", "1.90.0"));
    assert!(higher("1.100", "1.99"));
}
