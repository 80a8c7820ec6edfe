#!/usr/bin/env python3
"""Build time and peak memory of a user's crate holding one mechanism of N bodies.

    python3 mbd-bench/build_scaling/run.py            # N = 10, 30, 60, 120, 240
    python3 mbd-bench/build_scaling/run.py --driven   # the kinematic user's crate, below
    python3 mbd-bench/build_scaling/run.py --joint    # the same chain in joint coordinates

For each N it writes a crate under target/build-scaling/ whose binary declares a pendulum chain
of N links with a torsion spring at every pin, assembles it and simulates it with RK4, DOPRI5,
DOP853 and generalized-α, and solves its statics — every solver instantiated, as a user's
program would — then times `cargo build --release` of that binary alone (its dependencies built
beforehand) and reads the peak resident memory of the largest process of that build (rustc).
Prints a markdown table. Targets (issue 11): at most 30 s and 1 GB at 120 bodies, no cliff.

With --driven the chain has every joint angle driven (NV = NC) and no springs, and the binary
runs a kinematic sweep of 200 points and inverse dynamics at each, as a kinematic user's
program would; it also prints the microseconds per point of each, run once after the build.

With --joint the chain (not driven) is declared in joint coordinates (`joint_coordinates;`):
N coordinates and no rows, M(q) dense (issue 38's goal: the same 30 s and 1 GB at 120).

With --run (not with --driven) the binary is run once after the build: the microseconds per
RK4 step (1 ms, default drift control, 200 steps from the straight pose) and the iterations
(accepted and rejected) of the default statics from there.
"""
import os
import pathlib
import resource
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
CRATE = ROOT / "target" / "build-scaling"


def mechanism(n, doc, first, at_pin):
    """`mechanism! { Chain }` of n links of 0.1 m pinned end to end and to the ground, with the
    statement `first` after the ground pin and `at_pin(i)` after the pin of links i - 1 and i."""
    lines = ["use mbd::prelude::*;", "", "mechanism! {", f"    /// {doc}", "    pub Chain {", "        gravity [0.0, -9.81];"]
    for i in range(n):
        lines.append(f"        body l{i} {{ mass: 0.1, inertia: 8.3333e-5, at: [{0.05 + 0.1 * i:.2f}, 0.0, 0.0] }}")
    lines.append("        revolute ground[0.0, 0.0] ~ l0[-0.05, 0.0];")
    lines += [first] if first else []
    for i in range(1, n):
        lines.append(f"        revolute l{i - 1}[0.05, 0.0] ~ l{i}[-0.05, 0.0];")
        lines.append(at_pin(i))
    return lines + ["    }", "}", ""]


def chain(n):
    lines = mechanism(n, f"A pendulum chain of {n} links with torsion springs.", None,
                      lambda i: f"        rotational_spring l{i - 1} ~ l{i} {{ k: 1.0, angle: 0.0, c: 0.01 }};")
    lines += ["""fn main() {
    let m = Chain::default();
    let mut ws = Chain::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let v = [0.0; Chain::NV];
    let o: SimulationOptions<f64> = SimulationOptions::default();
    let times = [0.01];
    Simulation::new(&m, &mut Rk4::default()).start(0.0, &q, &v).times(&times).options(o).run(&mut ws, |_| {}).expect("RK4");
    Simulation::new(&m, &mut Dopri5::new(Dopri5Options::default())).start(0.0, &q, &v).times(&times).options(o).run(&mut ws, |_| {}).expect("DOPRI5");
    Simulation::new(&m, &mut Dop853::new(Dop853Options::default())).start(0.0, &q, &v).times(&times).options(o).run(&mut ws, |_| {}).expect("DOP853");
    let mut alpha = Chain::generalized_alpha(GeneralizedAlphaOptions::default());
    Simulation::new(&m, &mut alpha).start(0.0, &q, &v).times(&times).options(o).run(&mut ws, |_| {}).expect("generalized-α");
    // Timed (--run): 200 RK4 steps of 1 ms from the straight pose, and statics from there.
    let start = std::time::Instant::now();
    Simulation::new(&m, &mut Rk4::default()).start(0.0, &q, &v).times(&[0.2]).options(o).run(&mut ws, |_| {}).expect("RK4");
    let rk4 = start.elapsed().as_secs_f64() / 200.0 * 1e6;
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; Chain::NC]).expect("statics");
    println!("{rk4:.1} {}", report.iterations + report.rejected);
}
"""]
    return "\n".join(lines)


def driven_chain(n):
    lines = mechanism(n, f"A chain of {n} links, every joint angle driven.", "        drive l0.phi = 0.1 * sin(t);",
                      lambda i: f"        drive angle(l{i - 1}, l{i}) = 0.1 * sin(t + {i}.0);")
    lines += ["""fn main() {
    let m = Chain::default();
    let mut ws = Chain::workspace();
    let mut q = m.initial_positions();
    let solver = KinematicSolver::default();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let times: Vec<f64> = (0..200).map(|k| k as f64 * 1e-3).collect();
    let mut states = Vec::new();
    let start = std::time::Instant::now();
    solver.sweep(&m, &mut ws, &mut q, &times, |t, q, v, vd| states.push((t, *q, *v, *vd))).expect("sweep");
    let sweep = start.elapsed().as_secs_f64() / 200.0 * 1e6;
    let mut lambda = [0.0; Chain::NC];
    let start = std::time::Instant::now();
    for (t, q, v, vd) in &states {
        InverseDynamics::default().solve(&m, &mut ws, q, v, vd, *t, &mut lambda).expect("inverse dynamics");
    }
    println!("{sweep:.1} {:.1}", start.elapsed().as_secs_f64() / 200.0 * 1e6);
}
"""]
    return "\n".join(lines)


def main():
    if sys.argv[1:2] == ["--measure"]:
        return measure(pathlib.Path(sys.argv[2]), sys.argv[3])
    driven = "--driven" in sys.argv[1:]
    joint = "--joint" in sys.argv[1:]
    run = "--run" in sys.argv[1:] and not driven
    sizes = [int(a) for a in sys.argv[1:] if not a.startswith("--")] or [10, 30, 60, 120, 240]
    bins = {}
    for n in sizes:
        text = driven_chain(n) if driven else chain(n)
        if joint:
            text = text.replace("gravity [0.0, -9.81];", "joint_coordinates;\n        gravity [0.0, -9.81];", 1)
        bins[f"chain{n}"] = text
    env = prepare(CRATE, bins)
    if driven:
        print("| bodies | release build (s) | peak memory (MB) | sweep (µs/point) | inverse dynamics (µs/point) |\n|---|---|---|---|---|")
    elif run:
        print("| bodies | release build (s) | peak memory (MB) | RK4 step (µs) | statics iterations |\n|---|---|---|---|---|")
    else:
        print("| bodies | release build (s) | peak memory (MB) |\n|---|---|---|")
    for n in sizes:
        seconds, peak_mb = build_time(CRATE, f"chain{n}", env)
        row = f"| {n} | {seconds:.1f} | {peak_mb:.0f} |"
        if driven or run:
            out = subprocess.run([str(CRATE / "target" / "release" / f"chain{n}")], check=True, capture_output=True, text=True)
            first, second = out.stdout.split()
            row += f" {first} | {second} |"
        print(row, flush=True)


def prepare(crate, bins, optimized_macro=False):
    """Writes a crate at `crate` depending on mbd with one binary per entry of `bins` (name: the
    source's text) and builds its dependencies (mbd, nalgebra, the macro crate) in release, so
    that each timing is the mechanism's binary alone. With `optimized_macro` the crate builds
    mbd-macros at opt-level 3, as guide/build-time.md recommends. Returns the environment
    to build it with."""
    (crate / "src" / "bin").mkdir(parents=True, exist_ok=True)
    profile = "\n[profile.release.package.mbd-macros]\nopt-level = 3\n" if optimized_macro else ""
    (crate / "Cargo.toml").write_text(f'[package]\nname = "{crate.name}"\nversion = "0.0.0"\nedition = "2021"\npublish = false\n\n'
                                      f'[dependencies]\nmbd = {{ path = "{ROOT}" }}\n\n[workspace]\n{profile}')
    for name, text in bins.items():
        (crate / "src" / "bin" / f"{name}.rs").write_text(text)
    env = dict(os.environ, CARGO_TARGET_DIR=str(crate / "target"))
    (crate / "src" / "bin" / "dependencies.rs").write_text("fn main() { let _ = mbd::prelude::PI; }\n")
    subprocess.run(["cargo", "build", "--release", "--bin", "dependencies"], cwd=crate, env=env, check=True)
    return env


def build_time(crate, name, env):
    """(seconds, peak MB) of `cargo build --release` of the binary `name` of `crate` alone: in a
    process of its own, so that its children's peak memory is this build's."""
    (crate / "src" / "bin" / f"{name}.rs").touch()
    out = subprocess.run([sys.executable, __file__, "--measure", str(crate), name], env=env, check=True, capture_output=True, text=True)
    seconds, peak_kb = out.stdout.split()
    return float(seconds), int(peak_kb) / 1024


def measure(crate, name):
    """Builds the binary `name`; prints the seconds and the largest child's peak resident memory (KB)."""
    start = time.monotonic()
    subprocess.run(["cargo", "build", "--release", "--bin", name], cwd=crate, check=True, capture_output=True)
    seconds = time.monotonic() - start
    print(seconds, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)


if __name__ == "__main__":
    main()
