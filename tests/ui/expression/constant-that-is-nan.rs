use mbd::prelude::*;

mechanism! {
    Crank {
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        drive crank.phi = 2.0 * t + sqrt(-1.0) * t;
    }
}
fn main() {}
