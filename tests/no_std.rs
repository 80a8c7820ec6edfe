//! `mbd-runtime` and the `mbd` facade build without the standard library (`--no-default-features`:
//! `#![no_std]`, elementary functions from `libm`). Runs cargo itself, like trybuild does, in
//! `target/nested`, the target directory the nested builds (`tests/docs.rs`, `tests/embedded.rs`)
//! share so that what they have in common (mbd-macros and its dependencies) is built once; not the
//! outer build's, whose lock the running `cargo test` holds.
use std::process::Command;

#[test]
fn runtime_builds_without_std() {
    let target_dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/nested");
    // Without std, and without std but with a heap (`alloc`: the linearization and modes).
    for (package, features) in [("mbd-runtime", ""), ("mbd", ""), ("mbd", "alloc")] {
        let out = Command::new(env!("CARGO"))
            .args(["build", "--quiet", "-p", package, "--no-default-features", "--features", features, "--target-dir", target_dir])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "{package} without std (features: {features:?}) failed to build:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
