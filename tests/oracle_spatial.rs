//! The CasADi oracle for SPATIAL mechanisms (`tests/oracle/mbd_oracle/spatial.py`, built from the
//! "Spatial bodies" section of `docs/formulation.md`), proved on hand-written model JSON fixtures
//! (`tests/oracle/fixtures/spatial/`) before the macro emits spatial models:
//!
//! - `python -m mbd_oracle.spatial_check`: the rebuild against independent means — a NumPy
//!   re-implementation of every joint row and force element on quaternion-sandwich rotations,
//!   finite differences along the exact flow of q̇ = B(q) v (D v, γ, every generalized force,
//!   (∂h/∂q) B, ∂h/∂v, Coulomb friction, potentials), a torque-free body's invariants and
//!   intermediate-axis instability, a heavy top's closed-form steady precession, and the KKT
//!   forward dynamics with Baumgarte integrated by CVODES staying on Φ = 0;
//! - `python -m mbd_oracle.selftest --spatial`: the comparison rejects a spatial sample with a D
//!   entry or a γ entry off by a relative 1e-9 or a dropped structural non-zero (and h, ∂h/∂v,
//!   friction and v̇ perturbations), naming mechanism, function, row and column.
//!
//! The Python environment (pinned CasADi and NumPy) comes from `tests/oracle/ensure_env.sh`, as
//! for `tests/oracle.rs`. A missing Python or CasADi, or a non-zero exit, fails this test: it
//! never skips.
mod oracle_env;

use std::process::Command;

use oracle_env::{python, repo};

/// Runs `python -m <args>` in `tests/oracle`; returns (success, stdout + stderr).
fn oracle(args: &[&str]) -> (bool, String) {
    let out =
        Command::new(python()).arg("-m").args(args).current_dir(repo().join("tests/oracle")).output().expect("the oracle's Python runs");
    (out.status.success(), format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr)))
}

#[test]
fn spatial_oracle_is_right_on_the_fixtures() {
    let (ok, text) = oracle(&["mbd_oracle.spatial_check"]);
    println!("{text}");
    assert!(ok, "the spatial CasADi oracle failed its self-check on the fixtures:\n{text}");
}

#[test]
fn spatial_oracle_rejects_wrong_samples() {
    let (ok, text) = oracle(&["mbd_oracle.selftest", "--spatial"]);
    println!("{text}");
    assert!(ok, "the spatial oracle's self-test failed: it accepted a wrong value or did not say where:\n{text}");
}
