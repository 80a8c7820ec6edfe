use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[0.0, 0.5]
        gravity [0.0, -9.81];
    }
}
fn main() {}
