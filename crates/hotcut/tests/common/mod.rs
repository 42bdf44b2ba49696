//! Helpers shared by the binary's end-to-end tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the `hotcut` binary in `cwd`; fails on any panic message.
pub fn hotcut(args: &[&str], cwd: &Path) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_hotcut"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "panic in stderr: {err}");
    out
}

pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Validates `text` as a job and expects exit 1 with every `needle` in stderr.
pub fn expect_invalid(text: &str, needles: &[&str]) {
    expect_invalid_with(text, &[], needles);
}

/// [`expect_invalid`] with other files (name, text) beside the job.
pub fn expect_invalid_with(text: &str, files: &[(&str, &str)], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    for (name, body) in files {
        write(dir.path(), name, body);
    }
    write(dir.path(), "job.ron", text);
    for cmd in ["validate", "run"] {
        let o = hotcut(&[cmd, "job.ron"], dir.path());
        assert_eq!(o.status.code(), Some(1), "{cmd}: {}", stderr(&o));
        for n in needles {
            assert!(
                stderr(&o).contains(n),
                "{cmd}: missing {n:?} in: {}",
                stderr(&o)
            );
        }
        assert!(
            !dir.path().join("out").join("t").exists(),
            "an invalid job wrote output"
        );
    }
}
