//! The CasADi oracle's Python environment, shared by `tests/oracle.rs` and
//! `tests/oracle_spatial.rs`: `tests/oracle/ensure_env.sh` creates the pinned environment on first
//! use. A missing Python or CasADi fails the test that asked: never a skip.
use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The oracle's Python interpreter, installing the pinned environment on first use (once per
/// test binary: its tests run in parallel and must not both create the environment).
pub fn python() -> PathBuf {
    static PYTHON: OnceLock<PathBuf> = OnceLock::new();
    PYTHON.get_or_init(ensure_env).clone()
}

fn ensure_env() -> PathBuf {
    let out = Command::new("bash").arg(repo().join("tests/oracle/ensure_env.sh")).output().expect("bash runs");
    assert!(
        out.status.success(),
        "the CasADi oracle's Python environment could not be set up (Python 3 with venv and pip is required):\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().rev().find(|l| !l.trim().is_empty()).expect("ensure_env.sh prints the interpreter's path");
    PathBuf::from(last.trim())
}
