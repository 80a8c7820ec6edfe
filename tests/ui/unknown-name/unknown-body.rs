use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bobb[0.0, 0.5];
    }
}
fn main() {}
