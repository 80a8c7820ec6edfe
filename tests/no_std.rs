//! `mbd-runtime` and the `mbd` facade build without the standard library (`--no-default-features`:
//! `#![no_std]`, elementary functions from `libm`). Runs cargo itself, like trybuild does, in a
//! target directory of its own so it never waits on the build that runs this test.
use std::process::Command;

#[test]
fn runtime_builds_without_std() {
    let target_dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/no-std-check");
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
