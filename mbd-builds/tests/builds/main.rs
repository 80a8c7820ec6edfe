//! Builds a user of mbd makes, each checked by running cargo as the user would:
//! - `ui`: every class of user mistake in `mechanism!` is a compile error with a span on the
//!   offending token (trybuild compares the compiler's messages with the committed `.stderr`
//!   files of `tests/ui/`);
//! - `runtime_builds_without_std`: `mbd-runtime` and the `mbd` facade build without the standard
//!   library (`--no-default-features`: `#![no_std]`, elementary functions from `libm`);
//! - `generated_types_document_their_tables_without_warnings`: `cargo doc` is warning-free, and
//!   the documentation of a generated type is one a user can live in: `doc-check/` (a crate
//!   outside the workspace holding a planar and a spatial mechanism, as a user's crate would) is
//!   documented with warnings as errors, alongside mbd, mbd-runtime and mbd-macros, and the
//!   generated pages are read back for their tables;
//! - `the_packaged_crates_build_the_readmes_program`: the crates as `cargo package` makes them
//!   for crates.io build a fresh crate's program (the README's) from their packaged files alone;
//! - `a_mechanism_builds_for_a_cortex_m4f`: the generated code runs on a microcontroller:
//!   `embedded/`, a `#![no_std]` crate holding the free slider-crank in `scalar f32`, is built for
//!   a Cortex-M4F (`thumbv7em-none-eabihf`, the target added by `.ci/ensure_embedded_target.sh`)
//!   and the size of its forward-dynamics function is read from the library's ELF symbol table
//!   and reported. The same library holds a modal analysis (`mbd::linearize` without std, feature
//!   `alloc`), compiled for the target. (Its f32 results against f64 on the host are
//!   `tests/scalar_f32.rs`'.)
//!
//! One test binary, so that its tests run side by side on the test threads. The nested builds
//! use trybuild's target directory, so that what they have in common with it and with each
//! other — mbd-macros and its dependencies — is built once where they can share it (one build
//! after another: cargo locks the directory); not the outer build's directory, whose lock the
//! running `cargo test` holds. Every nested build compiles mbd-macros unoptimized
//! ([`UNOPTIMIZED_MACRO`]; trybuild's and release host builds do by default): the workspace's
//! opt-level 3 for it pays where many or large mechanisms are expanded, and these builds expand
//! a few small ones. Optimized, each of its builds took 75 s of one core against 10 s
//! (2026-12-06, Intel Xeon), and it was built three times here.
mod elf;
mod html;

use std::path::{Path, PathBuf};
use std::process::Command;

use elf::symbol_sizes;
use html::{has_row, text};

/// `cargo --config` arguments that build the macro crate unoptimized (the module says why).
const UNOPTIMIZED_MACRO: [&str; 2] = ["--config", "profile.dev.package.mbd-macros.opt-level=0"];

/// The workspace's root (this package is one of its members).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("mbd-builds is in the workspace").to_path_buf()
}

/// The target directory the nested builds share: trybuild's, `<target>/tests/trybuild`.
fn nested_target() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root().join("target"), PathBuf::from).join("tests/trybuild")
}

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}

/// Misuses of the runtime's API that must not compile (rustc's own messages, so outside the
/// catalogue above): an integrator wrapper that forwards only `step` and `interpolate`.
#[test]
fn api_misuse() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/api/*.rs");
}

/// The catalogue's messages, as committed: each says what was expected and what was found; the
/// catalogue covers at least 40 classes of mistake, grouped by topic; and each case's `main` uses
/// the mechanism's type (its constants, traits and solvers), so that its committed stderr shows
/// the mistake adds no follow-up error there.
#[test]
fn every_message_says_what_was_expected_and_what_was_found() {
    let mut cases = 0;
    let mut messages = Vec::new();
    for group in std::fs::read_dir("tests/ui").unwrap() {
        let group = group.unwrap().path();
        for file in std::fs::read_dir(&group).unwrap() {
            let file = file.unwrap().path();
            if file.extension().is_some_and(|e| e == "rs") {
                let program = std::fs::read_to_string(&file).unwrap();
                assert!(!program.contains("fn main() {}"), "{}: `main` does not use the mechanism", file.display());
            }
            if file.extension().is_some_and(|e| e == "stderr") {
                cases += 1;
                let text = std::fs::read_to_string(&file).unwrap();
                let errors: Vec<&str> = text.lines().filter(|l| l.starts_with("error:") || l.starts_with("error[")).collect();
                assert!(!errors.is_empty(), "{}: no error", file.display());
                messages.extend(errors.into_iter().map(|e| (file.clone(), e.to_string())));
            }
        }
    }
    assert!(cases >= 40, "{cases} cases in the catalogue");
    for (file, message) in &messages {
        let (expected, found) = (message.find("expected "), message.find(", found "));
        assert!(
            matches!((expected, found), (Some(e), Some(f)) if e < f),
            "{}: the message does not read \"expected … , found …\":\n{message}",
            file.display()
        );
    }
}

#[test]
fn runtime_builds_without_std() {
    let target_dir = nested_target();
    // Without std, and without std but with a heap (`alloc`: the linearization and modes).
    for (package, features) in [("mbd-runtime", ""), ("mbd", ""), ("mbd", "alloc")] {
        let out = Command::new(env!("CARGO"))
            .args(UNOPTIMIZED_MACRO)
            .args(["build", "--quiet", "-p", package, "--no-default-features", "--features", features, "--target-dir"])
            .arg(&target_dir)
            .current_dir(root())
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "{package} without std (features: {features:?}) failed to build:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn generated_types_document_their_tables_without_warnings() {
    let (root, target_dir) = (root(), nested_target());
    let out = Command::new(env!("CARGO"))
        .args(UNOPTIMIZED_MACRO)
        .args(["doc", "--quiet", "--no-deps", "-p", "mbd-doc-check", "-p", "mbd", "-p", "mbd-runtime", "-p", "mbd-macros"])
        .arg("--manifest-path")
        .arg(root.join("doc-check/Cargo.toml"))
        .arg("--target-dir")
        .arg(&target_dir)
        .env("RUSTDOCFLAGS", "-D warnings")
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "cargo doc failed or warned:\n{}", String::from_utf8_lossy(&out.stderr));
    let page = |name: &str| text(&std::fs::read_to_string(target_dir.join("doc/mbd_doc_check").join(name)).expect("the page"));

    let planar = page("struct.SliderCrank.html");
    for row in [
        // coordinates with their index and unit
        "| 2 | crank.phi | rad |",
        "| 6 | slider.x | m |",
        // points and their accessors
        "| crank.A | SliderCrank::crank_a |",
        // joints: index into JOINTS, name, kind, rows
        "| 0 | pin | revolute | 0–1 |",
        "| 3 | level | constraint | 6 |",
        // rows with the unit of their multiplier
        "| 1 | pin: y | N |",
        "| 7 | upright: user | J per unit of the row |",
        // force elements and the velocities they act on
        "| return_spring | 6, 7 |",
    ] {
        has_row(&planar, row);
    }
    assert!(planar.contains("3 planar bodies, 9 coordinates and velocities, 8 constraint rows (1 degree of freedom)"));
    // internals stay out: the Newton matrix's plumbing and the model JSON's text
    for internal in ["NewtonMatrix", "newton_storage", "sparse_position_solve", "\"bodies\":"] {
        assert!(!planar.contains(internal), "the planar page shows {internal}");
    }

    let spatial = page("struct.SpatialSliderCrank.html");
    for row in [
        "| 6 | crank.e3 | 1 |",
        "| 7 | slider.x | m |",
        "| 5 | crank.wz | rad/s |",
        "| 9 | guide: twist | N·m |",
        "| 10 | rod: length | N |",
    ] {
        has_row(&spatial, row);
    }
}

const TARGET: &str = "thumbv7em-none-eabihf";

#[test]
fn a_mechanism_builds_for_a_cortex_m4f() {
    let root = root();
    let ci = std::env::var("CI").is_ok_and(|v| v == "true");
    let added = Command::new("bash").arg(root.join(".ci/ensure_embedded_target.sh")).output();
    match added {
        Ok(out) if out.status.success() => {}
        other => {
            let why = match other {
                Ok(out) => String::from_utf8_lossy(&out.stderr).into_owned(),
                Err(e) => e.to_string(),
            };
            assert!(!ci, "CI=true: the target {TARGET} could not be added: {why}");
            eprintln!("SKIPPED: the target {TARGET} could not be added (no rustup or no network): {why}");
            return;
        }
    }
    let target_dir = nested_target();
    let out = Command::new(env!("CARGO"))
        .args(["build", "--quiet", "--release", "--target", TARGET, "--manifest-path"])
        .arg(root.join("embedded/Cargo.toml"))
        .arg("--target-dir")
        .arg(&target_dir)
        .output()
        .expect("cargo runs");
    assert!(out.status.success(), "the embedded crate failed to build for {TARGET}:\n{}", String::from_utf8_lossy(&out.stderr));
    let library = std::fs::read(target_dir.join(TARGET).join("release/libmbd_embedded.a")).expect("the static library");
    let sizes = symbol_sizes(&library);
    let size = |name: &str| sizes.iter().filter(|(n, _)| n == name || n.contains(&format!("{name}17h"))).map(|&(_, s)| s).max();
    let step = size("mbd_accelerations").expect("the library exports mbd_accelerations");
    let sincos = size("sincosf").unwrap_or(0);
    println!("{TARGET}: mbd_accelerations is {step} bytes of code; libm's sincosf, which it calls, {sincos} bytes");
    // The modal analysis without std: linearize and modes, monomorphized for a mechanism and
    // compiled to Cortex-M code (not only type-checked).
    let modal = size("mbd_pendulum_frequency").expect("the library exports mbd_pendulum_frequency");
    let schur = sizes.iter().filter(|(n, _)| n.contains("Schur") || n.contains("SymmetricEigen")).map(|&(_, s)| s).sum::<u32>();
    println!("{TARGET}: mbd_pendulum_frequency is {modal} bytes of code; nalgebra's eigensolvers {schur} bytes");
    assert!(schur > 0, "nalgebra's eigensolvers are not in the library: the modal analysis was not compiled");
    // Not a size target (those live in benchmarks): a bound that only a build gone wrong (an
    // unoptimized or std-linked one) would break.
    assert!(step > 0 && step < 64 * 1024, "mbd_accelerations is {step} bytes");
}

/// The crates a user depends on, as they would be published: `cargo package` makes each
/// `.crate` file (what crates.io would receive: the files the package holds, its manifest with
/// versions in place of paths), each within crates.io's 10 MB limit; then a fresh crate outside
/// the workspace, depending on `mbd = "0.1"` as a user would once it is published, builds and
/// runs the README's first program against the unpacked `.crate` files (`[patch.crates-io]`
/// resolves `mbd`, `mbd-macros` and `mbd-runtime` to them, crates.io everything else). That
/// build is the packages' verification: it compiles each one from its packaged files alone, so
/// anything a package needs from outside itself fails here. (`cargo package`'s own verification
/// would compile the same three crates once more.)
#[test]
fn the_packaged_crates_build_the_readmes_program() {
    let (root, target_dir) = (root(), nested_target());
    let crates = ["mbd-macros", "mbd-runtime", "mbd"];
    let mut package = Command::new(env!("CARGO"));
    package
        .args(UNOPTIMIZED_MACRO)
        .args(["package", "--quiet", "--no-verify", "--allow-dirty", "--target-dir"])
        .arg(&target_dir)
        .current_dir(&root);
    for name in crates {
        package.args(["-p", name]);
    }
    let out = package.output().expect("cargo runs");
    assert!(out.status.success(), "cargo package failed:\n{}", String::from_utf8_lossy(&out.stderr));

    let version = env!("CARGO_PKG_VERSION");
    let user = target_dir.join("packaged-user");
    let _ = std::fs::remove_dir_all(&user);
    std::fs::create_dir_all(user.join("src")).expect("a directory");
    let mut patches = String::new();
    for name in crates {
        let file = target_dir.join(format!("package/{name}-{version}.crate"));
        let size = std::fs::metadata(&file).expect("the .crate file").len();
        assert!(size < 10 * 1024 * 1024, "{name}: {size} bytes, above crates.io's 10 MB");
        let out = Command::new("tar").arg("-xzf").arg(&file).arg("-C").arg(&user).output().expect("tar runs");
        assert!(out.status.success(), "{name}: the .crate file does not unpack:\n{}", String::from_utf8_lossy(&out.stderr));
        patches.push_str(&format!("{name} = {{ path = \"{name}-{version}\" }}\n"));
    }
    std::fs::write(
        user.join("Cargo.toml"),
        format!(
            "[package]\nname = \"packaged-user\"\nversion = \"0.1.0\"\nedition = \"2021\"\npublish = false\n\n\
             [dependencies]\nmbd = \"{version}\"\n\n[patch.crates-io]\n{patches}\n[workspace]\n"
        ),
    )
    .expect("a manifest");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("the README");
    let program = readme.split("```rust\n").nth(1).and_then(|rest| rest.split("\n```").next()).expect("the README's first program");
    std::fs::write(user.join("src/main.rs"), program).expect("the program");
    let out = Command::new(env!("CARGO"))
        .args(UNOPTIMIZED_MACRO)
        .args(["run", "--quiet", "--manifest-path"])
        .arg(user.join("Cargo.toml"))
        .arg("--target-dir")
        .arg(&target_dir)
        .output()
        .expect("cargo runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "the README's program against the packaged crates failed:\n{}", String::from_utf8_lossy(&out.stderr));
    // Its last line: the slider of the README's slider-crank at 0.99 s.
    assert!(stdout.lines().last().is_some_and(|l| l.starts_with("0.99 s: slider at")), "{stdout}");
}
