use mbd::prelude::*;

mechanism! {
    Crank {
        params { omega: 6.0 }
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        drive crank.phi = omgea * t;
    }
}
fn main() {}
