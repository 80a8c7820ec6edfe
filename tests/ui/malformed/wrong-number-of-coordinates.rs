use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1, at: [0.0, -0.5] }
        revolute ground[0.0, 0.0] ~ bob[0.0, 0.5];
    }
}
fn main() {}
