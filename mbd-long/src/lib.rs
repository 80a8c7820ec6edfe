//! Long-run tests of mbd: `tests/` holds runs of 10⁶ steps and more. The crate exists so that
//! the root `Cargo.toml` can build it optimized under `cargo test` (`[profile.dev.package.mbd-long]`)
//! while every other test stays a fast-to-build debug binary; it has no code of its own.
