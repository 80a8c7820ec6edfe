//! Compiles the CasADi-generated C of the benchmark mechanisms (`casadi/*.c`, made by
//! `python -m mbd_oracle.codegen`, see tests/oracle/README.md and the crate documentation). The
//! spatial files come from `casadi/generate_spatial.sh`.
//!
//! **The same instruction set on both sides** (issue 41): the C is compiled for the instruction
//! set Rust compiles mbd for, read from the target features cargo gives this script. A plain
//! `cargo bench` builds both for baseline x86-64 (SSE2: gcc `-march=x86-64`); with
//! `RUSTFLAGS="-C target-cpu=native"` both for this processor (gcc `-march=native`). Until
//! 2026-12-06 the C was always built `-march=native` (AVX2 and FMA) against mbd at baseline. gcc
//! also contracts a·b + c into one fused multiply-add where the target has one (its default
//! `-ffp-contract=fast`). Rustc never does on its own; since 2026-12-06 mbd's generated code
//! asks for it (`Real::fused_mul_add`), so at `native` both sides use the instruction (the
//! benchmark prints this build's setting).
//!
//! Only the release profile (`cargo bench`) is optimized: `cargo test` (tests/same_values.rs) needs
//! the same numbers, not the speed, and gcc -O3 of the largest file (the spatial chain's forward
//! dynamics, 57 k lines) takes 60–90 s here against 4 s at -O0. The same source is compiled both
//! ways; the benchmarks check again, at -O3, that both sides take the same RK4 step.
fn main() {
    let files = [
        "casadi/slider_crank.c",
        "casadi/chain16.c",
        "casadi/free_slider_crank_dynamics.c",
        "casadi/pendulum_chain16_dynamics.c",
        "casadi/spatial_slider_crank.c",
        "casadi/spatial_chain16.c",
        "casadi/free_spatial_slider_crank_dynamics.c",
        "casadi/spatial_chain16_dynamics.c",
    ];
    for f in files {
        println!("cargo:rerun-if-changed={f}");
    }
    println!("cargo:rerun-if-env-changed=CARGO_ENCODED_RUSTFLAGS");
    let release = std::env::var("PROFILE").is_ok_and(|p| p == "release");
    // Rust's target features for this build ("fxsr,sse,sse2" at baseline x86-64).
    let features = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let native = ["avx2", "fma"].iter().all(|f| features.split(',').any(|g| g == *f));
    let x86_64 = std::env::var("CARGO_CFG_TARGET_ARCH").is_ok_and(|a| a == "x86_64");
    let isa = match (x86_64, native) {
        (true, true) => "native",
        (true, false) => "x86-64",
        // Another architecture: gcc's default for it, as rustc's.
        (false, _) => "",
    };
    println!("cargo:rustc-env=MBD_BENCH_CASADI_MARCH={}", if isa.is_empty() { "default" } else { isa });
    let mut build = cc::Build::new();
    build.files(files).warnings(false);
    if release {
        build.opt_level(3);
        if !isa.is_empty() {
            build.flag(format!("-march={isa}"));
        }
    } else {
        build.opt_level(0);
    }
    build.compile("casadi_generated");
}
