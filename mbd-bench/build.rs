//! Compiles the CasADi-generated C of the benchmark mechanisms (`casadi/*.c`, made by
//! `python -m mbd_oracle.codegen`, see tests/oracle/README.md and the crate documentation) with -O3 -march=native, as the
//! comparison in the issues is stated. The spatial files come from `casadi/generate_spatial.sh`.
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
    let release = std::env::var("PROFILE").is_ok_and(|p| p == "release");
    let mut build = cc::Build::new();
    build.files(files).warnings(false);
    if release {
        build.opt_level(3).flag_if_supported("-march=native");
    } else {
        build.opt_level(0);
    }
    build.compile("casadi_generated");
}
