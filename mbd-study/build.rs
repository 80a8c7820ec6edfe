//! Writes the pendulum chains of 4, 16 and 64 links as `mechanism!` declarations (the DSL cannot
//! repeat structure yet, issue 12): each link 0.1 m and 0.1 kg, pinned end to end and to ground,
//! starting horizontal; and the 16-link chain again in f32.
use std::fmt::Write;

fn main() {
    let mut out = String::new();
    for (n, name, scalar) in [(4, "Chain4", ""), (16, "Chain16", ""), (64, "Chain64", ""), (16, "Chain16F32", "        scalar f32;\n")] {
        writeln!(out, "mbd::mechanism! {{\n    /// A free pendulum chain of {n} links, horizontal at the start.").unwrap();
        writeln!(out, "    pub {name} {{\n{scalar}        gravity [0.0, -9.81];").unwrap();
        for i in 0..n {
            let x = 0.05 + 0.1 * i as f64;
            writeln!(out, "        body l{i} {{ mass: 0.1, inertia: 8.3333e-5, at: [{x:.2}, 0.0, 0.0] }}").unwrap();
        }
        writeln!(out, "        revolute ground[0.0, 0.0] ~ l0[-0.05, 0.0];").unwrap();
        for i in 1..n {
            writeln!(out, "        revolute l{}[0.05, 0.0] ~ l{i}[-0.05, 0.0];", i - 1).unwrap();
        }
        writeln!(out, "    }}\n}}").unwrap();
    }
    let path = std::path::Path::new(&std::env::var("OUT_DIR").unwrap()).join("chains.rs");
    std::fs::write(path, out).unwrap();
    println!("cargo:rerun-if-changed=build.rs");
}
