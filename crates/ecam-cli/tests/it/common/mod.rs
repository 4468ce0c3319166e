//! Helpers every test that drives the real `ecam` binary shares.
// Each test file uses its own subset of these helpers.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `ecam ARGS` and returns what it did.
pub fn ecam(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(args)
        .output()
        .expect("run ecam")
}

/// Asserts `ecam` succeeded; returns its stdout.
pub fn ok(out: Output) -> String {
    assert!(
        out.status.success(),
        "ecam failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Asserts `ecam` failed with a message; returns its stderr.
pub fn fails(out: Output) -> String {
    assert!(!out.status.success(), "ecam should have failed");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!err.is_empty());
    err
}

/// A fresh, empty directory under the target's test scratch area.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
