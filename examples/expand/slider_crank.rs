// The input whose expansion is `slider_crank.expanded.rs` beside this file: read the two side by
// side to see what `mechanism!` generates. A unit test of mbd-macros (`expand::snapshot`) expands
// this file and fails when the committed expansion is out of date; regenerate it with
// `MBD_BLESS=1 cargo test -p mbd-macros snapshot`.
use mbd::prelude::*;

mechanism! {
    /// Slider-crank driven at constant speed (Nikravesh, Planar Multibody Dynamics, ch. 7).
    pub SliderCrank {
        params { omega: 2.0 * PI, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = omega * t;
    }
}

fn main() {}
