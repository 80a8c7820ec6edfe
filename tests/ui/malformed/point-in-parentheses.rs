use mbd::prelude::*;

// A point in body coordinates is written in brackets.
mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground(0.0, 0.0) ~ bob[0.0, 0.5];
    }
}
fn main() {}
