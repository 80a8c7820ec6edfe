#!/usr/bin/env python3
"""The build-time column of the formulation table: each mechanism of
`mbd-bench/examples/formulations.rs`, in body and in joint coordinates, in a user's crate of its
own whose binary uses what the table times (the accelerations, an RK4 and a DOPRI5 simulation
after assembly), built with `cargo build --release` alone (dependencies built beforehand), the
macro optimized as guide/build-time.md recommends. Nothing under the checkout may change
while it runs: the crate depends on it by path, and a changed source would be rebuilt inside a
timing.

    python3 mbd-bench/build_scaling/formulations.py

The mechanisms' text is read from where the table reads it — the examples, the benchmark's
`mechanisms/` and the two `macro_rules!` of `formulations.rs` — and the joint-coordinate one is
that text with `joint_coordinates;` added, as `mbd-examples/build.rs` does. Prints a markdown
table: release build (s) and the peak resident memory of rustc (MB). About ten minutes on two
cores, most of it the ladder and the ball chain in joint coordinates.
"""
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from run import ROOT, build_time, prepare  # noqa: E402

CRATE = ROOT / "target" / "build-formulations"


def braced(text, start):
    """The text from `start` to the brace that closes the first `{` at or after it."""
    depth = 0
    for i in range(text.index("{", start), len(text)):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        if depth == 0:
            return text[start:i + 1]
    raise ValueError("unbalanced braces")


def example(path, name):
    """`(body text, joint text)` of the `mechanism!` declaring `pub name` in the file at `path`."""
    text = (ROOT / path).read_text()
    at = re.search(r"mechanism! \{\s*(///[^\n]*\n\s*)*pub " + name + r" \{", text)
    block = braced(text, at.start())
    open_at = block.index("pub " + name + " {") + len("pub " + name + " {")
    return block, block[:open_at] + "\n        joint_coordinates;" + block[open_at:]


def from_macro(name):
    """`(body text, joint text)` of the `macro_rules! name` of formulations.rs, its `$name` and
    optional `$joint;` filled in."""
    text = (ROOT / "mbd-bench/examples/formulations.rs").read_text()
    rules = text.index(f"macro_rules! {name} {{")
    block = braced(text, text.index("mbd::mechanism! {", rules))
    block = block.replace("$name", "Mechanism")
    return block.replace("$($joint;)?", ""), block.replace("$($joint;)?", "joint_coordinates;")


def renamed(block):
    """The mechanism declared as `pub Mechanism`, whatever its name was."""
    return re.sub(r"(mechanism! \{\s*(///[^\n]*\n\s*)*pub )\w+", r"\1Mechanism", block, count=1)


MAIN = """
fn main() {
    let m = Mechanism::default();
    let mut ws = Mechanism::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let v = [0.0; Mechanism::NV];
    let (mut vd, mut lambda) = ([0.0; Mechanism::NV], [0.0; Mechanism::NC]);
    m.accelerations(&q, &v, 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).expect("accelerations");
    let mut end = q;
    Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
        .start(0.0, &q, &v)
        .times(&[0.01])
        .run(&mut ws, |s| end = s.point.q)
        .expect("RK4");
    Simulation::new(&m, &mut Dopri5::new(Dopri5Options::default()))
        .start(0.0, &q, &v)
        .times(&[0.01])
        .run(&mut ws, |s| end = s.point.q)
        .expect("DOPRI5");
    println!("{}", end[0]);
}
"""


def main():
    mechanisms = [
        ("6-revolute arm", from_macro("arm")),
        ("16-link ball chain", example("mbd-bench/mechanisms/spatial_chain16.rs", "SpatialChain16")),
        ("slider-crank (driven)", example("examples/slider_crank.rs", "SliderCrank")),
        ("free four-bar", example("examples/free_four_bar.rs", "FreeFourBar")),
        ("double A-arm ride", example("examples/suspension_dynamics.rs", "DoubleAArmRide")),
        ("40-loop ladder", from_macro("ladder")),
    ]
    bins = {}
    for k, (_, texts) in enumerate(mechanisms):
        for coordinates, text in zip(["body", "joint"], texts):
            bins[f"m{k}_{coordinates}"] = "use mbd::prelude::*;\n\n" + renamed(text) + "\n" + MAIN
    env = prepare(CRATE, bins, optimized_macro=True)
    print("| mechanism | coordinates | release build (s) | peak memory (MB) |\n|---|---|---|---|")
    for k, (label, _) in enumerate(mechanisms):
        for coordinates in ["body", "joint"]:
            seconds, peak_mb = build_time(CRATE, f"m{k}_{coordinates}", env)
            print(f"| {label} | {coordinates} | {seconds:.1f} | {peak_mb:.0f} |", flush=True)


if __name__ == "__main__":
    main()
