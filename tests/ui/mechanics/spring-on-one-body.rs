use mbd::prelude::*;

// A spring between two points of one body stretches nothing.
mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[0.0, 0.5];
        spring bob[0.0, 0.0] ~ bob[0.0, 0.5] { k: 100.0, length: 0.5 };
    }
}
fn main() {}
