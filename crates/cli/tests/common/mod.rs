//! What every CLI test file needs: run the built `iridis` as a user would, read its JSON, and check that bad
//! input fails the way the project promises (exit code 2, one `error:` line, no panic).
#![allow(dead_code)] // each test file uses its own subset

use std::process::{Command, Output};

/// Runs the built binary from the repository root (so `data/…` paths in examples work).
pub fn iridis(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_iridis"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .expect("cannot run iridis")
}

/// Runs a command that must succeed and print JSON.
pub fn json_of(args: &[&str]) -> serde_json::Value {
    let out = iridis(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e})"))
}

/// Asserts a clean failure: exit code 2, a single `error:` line that contains every needle, no panic.
pub fn assert_fails(args: &[&str], needles: &[&str]) {
    let out = iridis(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
    for n in needles {
        assert!(errors[0].contains(n), "{args:?}: '{}' lacks '{n}'", errors[0]);
    }
}
