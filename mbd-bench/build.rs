//! Compiles the CasADi-generated C of the benchmark mechanisms (`casadi/*.c`, made by
//! `python -m mbd_oracle.codegen`, see tests/oracle/README.md and the crate documentation) with -O3 -march=native, as the
//! comparison in the issues is stated.
fn main() {
    let files = ["casadi/slider_crank.c", "casadi/chain16.c", "casadi/free_slider_crank_dynamics.c", "casadi/pendulum_chain16_dynamics.c"];
    for f in files {
        println!("cargo:rerun-if-changed={f}");
    }
    cc::Build::new().files(files).opt_level(3).flag_if_supported("-march=native").warnings(false).compile("casadi_generated");
}
