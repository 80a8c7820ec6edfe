use mbd::prelude::*;

mechanism! {
    Crank {
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        drive crank.phi = atan2(t);
    }
}
fn main() {}
