//! Every `model.gltf` the jobs in `jobs/` write passes the Khronos glTF validator with no
//! errors. The validator (npm package `gltf-validator`, version pinned below) is installed
//! into `target/gltf-validator/` on first use; the test is skipped, loudly, only when
//! `node`/`npm` are not installed.

use std::path::{Path, PathBuf};
use std::process::Command;

use hotcut::load::load_job;
use hotcut::run::run_job;
use hotcut::spec::OutputSpec;
use hotcut::NoProgress;

const VALIDATOR: &str = "gltf-validator@2.0.0-dev.3.10";

fn have(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

fn install(root: &Path) -> PathBuf {
    let dir = root.join("target/gltf-validator");
    if !dir.join("node_modules/gltf-validator").is_dir() {
        std::fs::create_dir_all(&dir).unwrap();
        let status = Command::new("npm")
            .args(["install", "--no-audit", "--no-fund", "--silent", "--prefix"])
            .arg(&dir)
            .arg(VALIDATOR)
            .status()
            .expect("running npm");
        assert!(status.success(), "npm install {VALIDATOR} failed");
    }
    dir
}

#[test]
fn gltf_outputs_pass_the_khronos_validator() {
    if !have("node") || !have("npm") {
        eprintln!("\n**********\nSKIPPED: node/npm not found, the glTF files were NOT validated\n**********\n");
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = install(root);
    let out = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    let mut jobs: Vec<PathBuf> = std::fs::read_dir(root.join("jobs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    jobs.sort();
    for path in jobs {
        let job = load_job(&path).unwrap();
        if !job.outputs.contains(&OutputSpec::Gltf) {
            continue;
        }
        let r = run_job(&job, out.path(), &NoProgress).unwrap();
        files.push(r.dir.join("model.gltf"));
    }
    assert!(!files.is_empty(), "no job writes a glTF file");
    let o = Command::new("node")
        .arg(root.join("tests/support/validate-gltf.mjs"))
        .arg(dir.join("node_modules"))
        .args(&files)
        .output()
        .expect("running node");
    let text = String::from_utf8_lossy(&o.stdout);
    println!("{text}");
    eprintln!("{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "the validator found errors:\n{text}");
    assert_eq!(text.lines().count(), files.len());
}
