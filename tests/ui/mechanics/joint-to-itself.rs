use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        revolute bob[0.0, 0.0] ~ bob[0.0, 0.5];
    }
}
fn main() {}
