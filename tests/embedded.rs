//! The generated code runs on a microcontroller: `embedded/`, a `#![no_std]` crate holding the
//! free slider-crank in `scalar f32`, is built for a Cortex-M4F (`thumbv7em-none-eabihf`, the
//! target added by `.ci/ensure_embedded_target.sh`) and the size of its forward-dynamics function
//! is read from the library's ELF symbol table and reported. The same library holds a modal
//! analysis (`mbd::linearize` without std, feature `alloc`), compiled for the target. (Its f32 results against f64 on the
//! host are `tests/scalar_f32.rs`'.) Runs cargo itself in `target/nested`, like `tests/no_std.rs`.
use std::path::Path;
use std::process::Command;

const TARGET: &str = "thumbv7em-none-eabihf";

#[test]
fn a_mechanism_builds_for_a_cortex_m4f() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
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
    let target_dir = root.join("target/nested");
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

/// (name, size) of every function symbol of the ELF32 little-endian objects of an `ar` archive.
/// A few lines for the one question the test asks, rather than an object-file crate.
fn symbol_sizes(archive: &[u8]) -> Vec<(String, u32)> {
    assert_eq!(&archive[..8], b"!<arch>\n", "not an ar archive");
    let u16_at = |b: &[u8], at: usize| u16::from_le_bytes([b[at], b[at + 1]]) as usize;
    let u32_at = |b: &[u8], at: usize| u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
    let mut out = Vec::new();
    let mut at = 8;
    while at + 60 <= archive.len() {
        let size: usize = std::str::from_utf8(&archive[at + 48..at + 58]).unwrap().trim().parse().unwrap();
        let elf = &archive[at + 60..at + 60 + size];
        at += 60 + size + size % 2;
        if elf.len() < 52 || &elf[..4] != b"\x7fELF" || elf[4] != 1 || elf[5] != 1 {
            continue;
        }
        let (shoff, shentsize, shnum) = (u32_at(elf, 0x20) as usize, u16_at(elf, 0x2e), u16_at(elf, 0x30));
        let section = |k: usize| &elf[shoff + k * shentsize..shoff + (k + 1) * shentsize];
        for k in 0..shnum {
            let sh = section(k);
            if u32_at(sh, 4) != 2 {
                continue; // not SHT_SYMTAB
            }
            let (offset, bytes) = (u32_at(sh, 16) as usize, u32_at(sh, 20) as usize);
            let strings = section(u32_at(sh, 24) as usize);
            let strtab = &elf[u32_at(strings, 16) as usize..][..u32_at(strings, 20) as usize];
            for sym in elf[offset..offset + bytes].chunks_exact(16) {
                if sym[12] & 0xf != 2 {
                    continue; // not STT_FUNC
                }
                let name = &strtab[u32_at(sym, 0) as usize..];
                let name = String::from_utf8_lossy(&name[..name.iter().position(|&c| c == 0).unwrap_or(0)]).into_owned();
                out.push((name, u32_at(sym, 8)));
            }
        }
    }
    out
}
